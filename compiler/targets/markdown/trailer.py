"""The framing section's words on a trailer: when a flag puts it after the frame, its
fields, and what its signature hashes."""
from __future__ import annotations

from ...model import Protocol
from .text import cell, code, en


def trailer_lines(p: Protocol) -> list[str]:
    t = p.framing.trailer
    if t is None:
        return []
    lines = [f"**Trailer.** When {code(t.presence.field)} has {code(t.presence.has)} (bit mask "
             f"`{t.flag_mask:#04x}` of byte B{t.flag_byte}), {t.size} more bytes follow the frame's last byte; "
             "the length and the checksum do not count them. " + (cell(en(t.doc)) if t.doc else "")]
    rows = []
    at = 0
    for f in t.fields:
        size = f.bits // 8
        kind = f"bytes[{size}]" if f.kind == "bytes" else f"u{f.bits}"
        rows.append(f"T{at}" + (f"–T{at + size - 1}" if size > 1 else "") + f": {code(f.name)} ({kind})"
                    + (f", {cell(en(f.doc))}" if f.doc else ""))
        at += size
    lines.append("Trailer bytes, from the first after the frame: " + "; ".join(rows) + ".")
    sig = t.signature
    if sig is not None:
        s = sig.signature
        lines.append(f"{code(sig.name)} is the first {sig.length} bytes of {s.algorithm} over a secret key of "
                     f"{s.key_length} bytes and then the bytes from {code(s.covers[0])} through {code(s.covers[1])}. "
                     "Decoders read it without a key; given the key, they refuse a frame without the trailer "
                     "(error `unsigned`) and one whose signature the key does not make (error `signature`). "
                     "Encoders given the key compute it.")
    return lines
