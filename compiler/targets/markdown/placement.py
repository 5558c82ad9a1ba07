"""The payload of a message whose fields are placed by start_bit (CAN DBC signals),
drawn as a grid: one row per payload byte, bits 7 (MSB) to 0, each cell naming the
field that holds the bit and marking its most and least significant bits, so a
big-endian (Motorola) field reads from its `msb` down and on into the next byte."""
from __future__ import annotations

from typing import Optional

from ...model import Message



def dbc_bit(order: str, pos: int) -> int:
    """A bit counted in `order` (see Leaf.order) as DBC numbers it: 8 × byte + bit (0 = LSB)."""
    return pos if order == "little" else 8 * (pos // 8) + 7 - pos % 8


def payload_grid(m: Message, only: Optional[set[str]] = None) -> Optional[dict]:
    """Rows of the grid (byte label, then 8 cells for bits 7..0), or None without placed fields.
    `only`: the fields drawn (multiplexed ones share bits: each value set has its grid)."""
    if not m.payload_bytes:
        return None
    run = next(r for r in m.wire.runs if r.free)
    owner: dict[int, str] = {}
    for leaf in run.leaves:
        if only is not None and leaf.field.name not in only:
            continue
        order = run.order_of(leaf)
        bits = [dbc_bit(order, leaf.pos + k) - 8 * run.start for k in range(leaf.bits)]  # MSB first when big
        msb, lsb = (bits[0], bits[-1]) if order == "big" else (bits[-1], bits[0])
        for b in bits:
            mark = "" if leaf.bits == 1 else " msb" if b == msb else " lsb" if b == lsb else ""
            owner[b] = f"`{leaf.dotted}`{mark}"
    rows = [{"byte": f"{i} (B{run.start + i})" if run.start else f"B{i}", "cells": [owner.get(8 * i + bit, "·") for bit in range(7, -1, -1)]}
            for i in range(run.size)]
    return {"rows": rows, "first": f"B{run.start}"}


def placed_type(order: str) -> str:
    """How the field table names a placed field's byte order."""
    return "BE (Motorola)" if order == "big" else "LE (Intel)"



