"""Conformance vectors for text stream readers: streams of valid lines with the
characters the framing skips between them, garbage lines, damaged and cut lines,
a line too long for the readers' bound and an unterminated line at the end, with
the events the Python StreamDecoder gives when fed one character at a time and
then told the stream ended. Each event carries where its line lies (`at`,
`length`), so the C readers are held to the offsets as well as the order."""
from __future__ import annotations

import random
import string
from typing import Any, Callable

from .model import Protocol

STREAMS = 6
PRINTABLE = string.ascii_letters + string.digits + ",.:;*$-+ "


def text_stream_vectors(p: Protocol, mod: Any, rng: random.Random, lines: list[str],
                        plain: Callable[[Any], Any]) -> list[dict]:
    """The schema's hand-worked streams, then random ones cut from `lines` (valid, canonical)."""
    out = [stream_events(mod, f"worked by hand: {s.name}", s.data, plain) for s in p.streams]
    if not lines:
        return out
    fr = p.framing
    for n in range(STREAMS):
        parts: list[str] = []
        for _ in range(rng.randint(2, 5)):  # few: a stream and its events fit an ATmega32 with its share of vectors
            line = rng.choice(lines)
            shape = rng.random()
            if shape < 0.15:  # a garbage line
                parts.append("".join(rng.choices(PRINTABLE.replace(fr.terminator[0], ""), k=rng.randint(1, 12)))
                             + fr.terminator)
            elif shape < 0.3:  # a character changed
                at = rng.randrange(len(line) - len(fr.terminator)) if len(line) > len(fr.terminator) else 0
                parts.append(line[:at] + rng.choice(PRINTABLE.replace(fr.terminator[0], "")) + line[at + 1:])
            elif shape < 0.4:  # cut short: it runs on into the next line
                parts.append(line[:rng.randint(1, len(line) - 1)])
            if fr.ignore_between and rng.random() < 0.5:
                parts.append("".join(rng.choices(fr.ignore_between, k=rng.randint(1, 4))))
            parts.append(line)
        if n == 0:  # a line too long: one error, then the next line reads
            parts.insert(1, "x" * (fr.line_max + rng.randint(0, 3)) + fr.terminator)
        if n % 2:  # an unterminated line at the end: finish() reports it
            parts.append(rng.choice(lines)[:-len(fr.terminator)])
        out.append(stream_events(mod, f"stream {n}", "".join(parts).encode("latin-1"), plain))
    return out


def stream_events(mod: Any, name: str, stream: bytes, plain: Callable[[Any], Any]) -> dict:
    """The stream with the events of a StreamDecoder fed one character at a time, then finish()."""
    decoder = mod.StreamDecoder()
    events = []

    def take(items: list) -> None:
        for item, (at, length) in zip(items, decoder.spans):
            if isinstance(item, mod.DecodeError):
                events.append({"error": item.rule, "at": at, "length": length})
            else:
                events.append({"message": type(item).NAME, "values": plain(item), "at": at, "length": length})
    for at in range(len(stream)):
        take(decoder.feed(stream[at:at + 1]))
    take(decoder.finish())
    return {"name": name, "text": stream.decode("latin-1"), "events": events}

