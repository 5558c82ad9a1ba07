"""How the C target moves a binary message between its raw values and its
bytes: the frame cut into spans that each start and end on a byte boundary,
so that every byte is written exactly once (no memset, no read-modify-write)
and fields sharing a byte are packed with one shift and mask each.

A span is one of
- "bytes": a `bytes` field, copied;
- "int": a byte-aligned field of 8, 16, 24 or 32 bits, in its own byte order;
- "pack": bit fields (and the frame's trailing padding) that together fill
  1 to 4 whole bytes, read and written as one big-endian integer, most
  significant bit first as the wire counts bits;
- "bits": bit fields filling more than 4 bytes together, moved bit by bit
  (cw_put_bits/cw_get_bits) in bytes zeroed first.
"""
from __future__ import annotations

from dataclasses import dataclass

from ..wire import Leaf


@dataclass(frozen=True)
class Piece:
    leaf: Leaf
    pos: int  # first bit in the frame
    bits: int


@dataclass(frozen=True)
class Span:
    kind: str  # "bytes", "int", "pack" or "bits"
    start: int  # first byte
    size: int  # bytes
    pieces: tuple[Piece, ...]

    def shift(self, piece: Piece) -> int:
        """Where `piece` sits in the span's big-endian integer, from bit 0."""
        return (self.start + self.size) * 8 - piece.pos - piece.bits


def spans(wired: list[tuple[Leaf, int]], frame_bytes: int) -> list[Span]:
    out: list[Span] = []
    pending: list[Piece] = []

    def close(end_bit: int) -> None:
        start = pending[0].pos // 8
        size = (end_bit + 7) // 8 - start
        out.append(Span("pack" if size <= 4 else "bits", start, size, tuple(pending)))
        pending.clear()

    for leaf, pos in wired:
        f = leaf.field
        aligned = pos % 8 == 0 and f.bits % 8 == 0
        if not pending and aligned:
            out.append(Span("bytes" if f.kind == "bytes" else "int", pos // 8, f.bits // 8,
                            (Piece(leaf, pos, f.bits),)))
            continue
        if f.kind == "bytes":
            raise ValueError(f"{f.name}: bytes fields must start on a byte boundary")
        pending.append(Piece(leaf, pos, f.bits))
        if (pos + f.bits) % 8 == 0:
            close(pos + f.bits)
    if pending:  # the frame's padding completes the last byte
        close(frame_bytes * 8)
    return out
