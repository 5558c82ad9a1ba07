"""How the Python target packs a frame's runs with `struct`: each run is one item (a
Chunk: a lone field, or bit fields packed in one integer), and consecutive items of one
byte order are one struct (a Segment)."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Optional

from ...model import Repeat, Run


def access(obj: str, step) -> str:
    """Python for one step down a path: an attribute, or an array's element."""
    return f"{obj}[{step}]" if isinstance(step, int) else f"{obj}.{step}"


@dataclass
class Chunk:
    """Bytes of the frame packed by one struct code: a lone byte-aligned field or a run of bit fields."""

    start: int  # byte offset
    nbytes: int
    leaves: list  # [(Leaf, shift)]
    code: str  # struct code, or "s" for an odd-sized run converted with int.to_bytes
    order: Optional[str]  # byte order it needs, None when any will do
    lone: bool  # a single field stored as is (float, bytes, whole integer)
    signed: bool = False
    other: list = field(default_factory=list)  # [(Leaf, shift)] in the bytes read in the other byte order
    free: bool = False  # bits no leaf holds read as anything (a payload placed by start_bit)
    repeat: Optional[Repeat] = None  # the bytes of an array read and written in a loop

    @property
    def other_order(self) -> str:
        return "little" if self.order == "big" else "big"


def chunks_of(runs: tuple[Run, ...], default_order: str) -> list[Chunk]:
    """The struct code of each run of the wire layout."""
    out: list[Chunk] = []
    for run in runs:
        n = run.size
        if run.kind == "packed":
            pairs = [(leaf, run.shift(leaf)) for leaf in run.leaves]
            own = [(leaf, at) for leaf, at in pairs if not run.mixed or run.order_of(leaf) == run.order]
            other = [(leaf, at) for leaf, at in pairs if run.mixed and run.order_of(leaf) != run.order]
            out.append(Chunk(run.start, n, own, STRUCT_CODES.get(n, "s"), run.order if n > 1 else None, False,
                             other=other, free=run.free))
            continue
        leaf = run.leaves[0]
        f = leaf.field
        if f.kind == "float":
            code = "f" if n == 4 else "d"
        elif f.kind == "bytes":
            code = f"{n}s"
        else:
            code = STRUCT_CODES.get(n, "s")
            code = code.lower() if f.kind == "int" else code
        order = f.byte_order or default_order
        out.append(Chunk(run.start, n, [(leaf, 0)], code, order if n > 1 else None, True, f.kind == "int"))
    return out


STRUCT_CODES = {1: "B", 2: "H", 4: "I", 8: "Q"}


@dataclass
class Segment:
    start: int
    chunks: list

    @property
    def fmt(self) -> str:
        order = next((c.order for c in self.chunks if c.order), "big")
        codes = "".join(f"{c.nbytes}s" if c.code == "s" else c.code for c in self.chunks)
        return ("<" if order == "little" else ">") + codes


def segments_of(chunks: list[Chunk]) -> list[Segment]:
    out: list[Segment] = []
    for chunk in chunks:
        if out:
            current = out[-1]
            order = next((c.order for c in current.chunks if c.order), None)
            if chunk.order is None or order is None or chunk.order == order:
                current.chunks.append(chunk)
                continue
        out.append(Segment(chunk.start, [chunk]))
    return out
