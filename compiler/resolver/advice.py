"""Warnings on a schema that builds: things its author should look at, never a failure."""
from __future__ import annotations

from ..diagnostics import Diagnostic
from ..model import Message, Protocol


def warnings_of(p: Protocol) -> list[Diagnostic]:
    out = [Diagnostic(m.loc, f"message {m.name!r} has no example: nothing checks its wire bytes against a "
                             "frame worked out by hand", "add an example with hex from the specification or a "
                                                         "peer implementation", "warning")
           for m in p.messages if not m.examples]
    if p.framing.kind == "bytes":
        out.extend(shared_ids(p.messages))
    return sorted(out, key=lambda d: (d.loc, d.message))


def shared_ids(messages: tuple[Message, ...]) -> list[Diagnostic]:
    """Messages of one id (and direction) told apart by their frame's size alone: a frame
    cut or padded by a byte decodes as the other message, or is refused for its size."""
    out = []
    seen: dict[tuple, Message] = {}
    for m in messages:
        for key in (m.dispatch_key,) if m.dispatch_key else ():
            first = seen.setdefault(key, m)
            if first is m or first.direction and m.direction and first.direction != m.direction:
                continue
            out.append(Diagnostic(m.loc, f"message {m.name!r} has the id of {first.name!r} and is told apart "
                                         f"from it only by its size ({m.size} bytes, {first.size})",
                                  "give it an id of its own if the protocol allows; keep the sizes far apart "
                                  "otherwise", "warning"))
    return out
