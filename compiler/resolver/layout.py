"""The wire layout of a message, computed once for every target: each field with
a wire value of its own and its first bit, and the frame cut into runs of whole
bytes. Targets choose only how to spell a run (a struct code, a C access helper,
a row of a table)."""
from __future__ import annotations

from typing import Optional

from ..model import Field, Leaf, Run, Wire


def leaves_of(layout: tuple[Field, ...], prefix: tuple[str, ...] = (), start: Optional[int] = 0) -> list[Leaf]:
    """Every field with a wire value, groups flattened, with its first bit while
    the widths before it are known."""
    out: list[Leaf] = []
    pos = start
    for f in layout:
        if f.is_payload:
            continue
        if f.kind == "group":
            inner = leaves_of(f.fields, prefix + (f.name,), pos)
            out.extend(inner)
        else:
            out.append(Leaf(f, prefix + (f.name,), pos))
        pos = None if pos is None or f.bits is None else pos + f.bits
    return out


def runs_of(leaves: list[Leaf], frame_bytes: int) -> tuple[Run, ...]:
    """A field of whole bytes that starts on a byte boundary, with no bit field
    waiting before it, is a run of its own; bit fields gather until they end on a
    byte boundary (or the frame's padding completes the last byte)."""
    out: list[Run] = []
    pending: list[Leaf] = []

    def close(end_bit: int) -> None:
        start = pending[0].pos // 8
        out.append(Run("packed", start, (end_bit + 7) // 8 - start, tuple(pending)))
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


def wire_of(layout: tuple[Field, ...], bits: Optional[int]) -> Wire:
    """The layout of a message; runs only when the frame's size is known (binary)."""
    leaves = leaves_of(layout, start=0 if bits is not None else None)
    runs = runs_of(leaves, (bits + 7) // 8) if bits is not None else ()
    return Wire(tuple(leaves), runs)


def key_read(leaves: list[Leaf] | tuple[Leaf, ...], default_order: str) -> Optional[dict]:
    """How a decoder reads the dispatch key of a bytes frame: bytes first..last as
    one integer in `byte_order`, shifted right by `shift` and masked with `mask`;
    `places` gives each dispatch field's (shift, bits) inside that key. With one
    dispatch field the key is its value; with several (UBX's class and id) it is
    their values side by side, as the bytes hold them."""
    fields = [leaf for leaf in leaves if leaf.field.dispatch and leaf.pos is not None]
    if not fields:
        return None
    first = min(leaf.pos for leaf in fields) // 8
    last = max((leaf.pos + leaf.bits - 1) // 8 + 1 for leaf in fields)
    orders = {leaf.field.byte_order or default_order for leaf in fields if leaf.bits > 8}
    order = "little" if orders == {"little"} else "big"

    def shift(leaf: Leaf) -> int:
        if order == "big":
            return last * 8 - (leaf.pos + leaf.bits)
        byte = 8 * (leaf.pos // 8 - first)  # the integer's bytes are read least significant first
        return byte if leaf.bits % 8 == 0 else byte + 8 - leaf.pos % 8 - leaf.bits

    shifts = {leaf.field.name: shift(leaf) for leaf in fields}
    low = min(shifts.values())
    places = {leaf.field.name: (shifts[leaf.field.name] - low, leaf.bits) for leaf in fields}
    mask = sum(((1 << bits) - 1) << at for at, bits in places.values())
    return {"first": first, "last": last, "bytes": last - first, "shift": low, "mask": mask,
            "byte_order": order if last - first > 1 else "big", "places": places}


def key_of(read: dict, values: dict[str, int]) -> int:
    """The dispatch key of a message whose dispatch fields hold `values`."""
    key = 0
    for name, (at, bits) in read["places"].items():
        key |= (values[name] & ((1 << bits) - 1)) << at
    return key
