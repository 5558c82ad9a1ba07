"""The framing section's hand-worked streams: each stream's bytes and the events a
stream decoder gives on them, as the schema states them (the build has checked
them against the generated decoder)."""
from __future__ import annotations

from ...model import Protocol, StreamEvent
from .layout import shown
from .text import DecisionLinker, cell, code, en, link_msg


def stream_section(p: Protocol, linker: DecisionLinker) -> dict:
    """The rows, and what checks them: the build, and for byte framings every
    decoder that runs the conformance vectors."""
    rows = [{"name": cell(s.name), "doc": linker.link(cell(en(s.doc))) if s.doc else "",
             "data": code(shown(s.data.decode("latin-1"))) if s.text else code(s.data.hex(" ")),
             "events": [event_text(e) for e in s.events] or ["nothing: every byte is skipped"]}
            for s in p.streams]
    return {"rows": rows, "in_vectors": p.framing.kind == "bytes",
            "form": "text" if p.framing.kind == "text" else "bytes"}


def event_text(e: StreamEvent) -> str:
    if e.message is not None:
        return link_msg(e.message) + (f" (its frame ends at offset {e.end})" if e.end is not None else "")
    return f"error: {code(e.rule)}" if e.rule else "error (any rule)"
