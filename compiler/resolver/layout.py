"""The wire layout of a message, computed once for every target: each field with
a wire value of its own and its first bit, and the frame cut into runs of whole
bytes. Targets choose only how to spell a run (a struct code, a C access helper,
a row of a table)."""
from __future__ import annotations

from typing import Optional

from ..model import Field, Leaf, Run, Wire, shift_in
from .repeats import repeats_of


def leaves_of(layout: tuple[Field, ...], prefix: tuple[str, ...] = (), start: Optional[int] = 0) -> list[Leaf]:
    """Every field with a wire value, groups flattened, with its first bit while
    the widths before it are known."""
    out: list[Leaf] = []
    pos = start
    for f in layout:
        if f.is_payload:  # a payload placed by start_bit takes its bytes here
            if pos is not None and f.length:
                pos += 8 * f.length
            continue
        if f.start_bit is not None and f.bit_offset is not None:  # where its start bit puts it, in its own order
            out.append(Leaf(f, prefix + (f.name,), f.bit_offset, f.byte_order))
            continue
        if f.count is None:
            out.extend(leaves_of_one(f, prefix + (f.name,), pos))
        else:  # an array: each element where the one before it ends, its index in the path
            element = f.element
            for i in range(f.count):
                at = None if pos is None or element.bits is None else pos + i * element.bits
                out.extend(leaves_of_one(element, prefix + (f.name, i), at))
        pos = None if pos is None or f.bits is None else pos + f.bits
    return out


def leaves_of_one(f: Field, path: tuple, pos: Optional[int]) -> list[Leaf]:
    """The leaves of one field (or one array element) at `path`: a group's flattened."""
    if f.kind == "group":
        return leaves_of(f.fields, path, pos)
    return [Leaf(f, path, pos)]


def runs_of(leaves: list[Leaf], frame_bytes: int, order: str = "big") -> tuple[Run, ...]:
    """A field of whole bytes that starts on a byte boundary, with no bit field
    waiting before it, is a run of its own; bit fields gather until they end on a
    byte boundary (or the frame's padding completes the last byte), into an integer
    read in `order`, the frame's bit order."""
    out: list[Run] = []
    pending: list[Leaf] = []

    def close(end_bit: int) -> None:
        start = pending[0].pos // 8
        out.append(Run("packed", start, (end_bit + 7) // 8 - start, tuple(pending), order))
        pending.clear()

    for leaf in leaves:
        if not leaf.bits:
            continue
        if not pending and leaf.pos % 8 == 0 and leaf.bits % 8 == 0:
            kind = "bytes" if leaf.field.kind == "bytes" else "number"
            out.append(Run(kind, leaf.pos // 8, leaf.bits // 8, (leaf,)))
            continue
        pending.append(leaf)
        if (leaf.pos + leaf.bits) % 8 == 0:
            close(leaf.pos + leaf.bits)
    if pending:
        close(frame_bytes * 8)
    return tuple(out)


def wire_of(layout: tuple[Field, ...], bits: Optional[int], order: str = "big",
            looped: frozenset[str] = frozenset()) -> Wire:
    """The layout of a message; runs only when the frame's size is known (binary).
    `order`: the frame's bit stream order (Framing.wire_order). A payload placed by
    start_bit is one packed run of its bytes, whatever it leaves unused. `looped`: the
    arrays that may become Repeats."""
    leaves = leaves_of(layout, start=0 if bits is not None else None)
    if bits is None:
        return Wire(tuple(leaves), (), order)
    marker = next((f for f in layout if f.is_payload), None)
    if marker is None or not marker.length:
        runs = runs_of(leaves, (bits + 7) // 8, order)
        return Wire(tuple(leaves), runs, order, repeats_of(layout, leaves, runs, looped))
    start = marker.bit_offset // 8 - marker.length
    placed = [x for x in leaves if x.field.start_bit is not None]
    before = [x for x in leaves if x.field.start_bit is None and x.pos < 8 * start]
    after = [x for x in leaves if x.field.start_bit is None and x.pos >= 8 * start]
    orders = [x.order for x in placed]  # the payload's integer is read in its fields' usual order
    most = max(("big", "little"), key=lambda o: (orders.count(o), o == order))
    payload = Run("packed", start, marker.length, tuple(placed), most, free=True)
    runs = runs_of(before, start, order) + (payload,) + runs_of(after, (bits + 7) // 8, order)
    return Wire(tuple(leaves), runs, order)


def key_read(leaves: list[Leaf] | tuple[Leaf, ...], default_order: str, wire_order: str = "big") -> Optional[dict]:
    """How a decoder reads the dispatch key of a bytes frame: bytes first..last as
    one integer in `byte_order`, shifted right by `shift` and masked with `mask`;
    `places` gives each dispatch field's (shift, bits) inside that key. With one
    dispatch field the key is its value; with several (UBX's class and id) it is
    their values side by side, as the bytes hold them. Fields of whole bytes set
    the read's byte order; otherwise it is the frame's bit order (`wire_order`)."""
    fields = [leaf for leaf in leaves if leaf.field.dispatch and leaf.pos is not None]
    if not fields:
        return None
    first = min(leaf.pos for leaf in fields) // 8
    last = max((leaf.pos + leaf.bits - 1) // 8 + 1 for leaf in fields)
    orders = {leaf.field.byte_order or default_order for leaf in fields if whole_bytes(leaf) and leaf.bits > 8}
    order = orders.pop() if len(orders) == 1 else wire_order

    def shift(leaf: Leaf) -> int:
        if whole_bytes(leaf) or order == wire_order:
            return shift_in(order, first, last - first, leaf.pos, leaf.bits)
        byte = leaf.pos // 8  # part of one byte (the resolver sees to it), read in the frame's bit order
        index = byte - first if order == "little" else last - 1 - byte
        return 8 * index + shift_in(wire_order, byte, 1, leaf.pos, leaf.bits)

    shifts = {leaf.field.name: shift(leaf) for leaf in fields}
    low = min(shifts.values())
    places = {leaf.field.name: (shifts[leaf.field.name] - low, leaf.bits) for leaf in fields}
    mask = sum(((1 << bits) - 1) << at for at, bits in places.values())
    return {"first": first, "last": last, "bytes": last - first, "shift": low, "mask": mask,
            "byte_order": order, "places": places}


def whole_bytes(leaf: Leaf) -> bool:
    return leaf.pos % 8 == 0 and leaf.bits % 8 == 0


def key_of(read: dict, values: dict[str, int]) -> int:
    """The dispatch key of a message whose dispatch fields hold `values`."""
    key = 0
    for name, (at, bits) in read["places"].items():
        key |= (values[name] & ((1 << bits) - 1)) << at
    return key
