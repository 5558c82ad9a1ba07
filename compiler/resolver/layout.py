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


def wire_of(layout: tuple[Field, ...], bits: Optional[int], order: str = "big") -> Wire:
    """The layout of a message; runs only when the frame's size is known (binary).
    `order`: the frame's bit stream order (Framing.wire_order)."""
    leaves = leaves_of(layout, start=0 if bits is not None else None)
    runs = runs_of(leaves, (bits + 7) // 8, order) if bits is not None else ()
    return Wire(tuple(leaves), runs, order)
