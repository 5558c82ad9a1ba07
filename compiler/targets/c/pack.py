"""How the C target moves a binary message between its raw values and its
bytes: each run of the model's wire layout becomes one span, so that every
byte is written exactly once (no memset, no read-modify-write) and fields
sharing a byte are packed with one shift and mask each.

A span is one of
- "bytes": a `bytes` field, copied;
- "int": a byte-aligned number of whole bytes, in its own byte order;
- "pack": bit fields (and the frame's trailing padding) that together fill
  1 to 4 whole bytes, read and written as one integer in the run's byte order
  (big-endian most significant bit first, little-endian least significant first);
- "bits": bit fields filling more than 4 bytes together, or fields of both bit
  orders sharing bytes (a payload placed by start_bit), each moved with a
  constant shift per byte it touches, in its own bit order (bitbytes.py), in
  bytes zeroed first.
"""
from __future__ import annotations

from dataclasses import dataclass

from ...model import Leaf, Run, shift_in


@dataclass(frozen=True)
class Span:
    kind: str  # "bytes", "int", "pack" or "bits"
    start: int  # first byte
    size: int  # bytes
    pieces: tuple[Leaf, ...]
    order: str = "big"  # "pack" and "bits": the byte order of the span's integer

    def order_of(self, piece: Leaf) -> str:
        """The bit order `piece` counts in: its own (placed by start_bit), or the span's."""
        return piece.order or self.order

    def shift(self, piece: Leaf) -> int:
        """Where `piece` sits in the span's integer, from bit 0 (pieces of a "pack" span share its order)."""
        return shift_in(self.order_of(piece), self.start, self.size, piece.pos, piece.bits)


def span_kind(run: Run) -> str:
    if run.kind == "packed":
        return "pack" if run.size <= 4 and not run.mixed else "bits"
    return "bytes" if run.kind == "bytes" else "int"


def spans(runs: tuple[Run, ...]) -> list[Span]:
    return [Span(span_kind(run), run.start, run.size, run.leaves, run.order) for run in runs]
