"""Airtime and size budgets of each transport, computed from the model and the
codec's own encodings: how long a sentence, a sequence or a line takes, and
whether every frame fits the radio's FIFO."""
from __future__ import annotations

import types
from typing import Any, Optional

from ...model import Message, Protocol, Transport
from .layout import slots
from .text import cell, en, number, originals

# Serial characters are 8N1: a start bit, 8 data bits, a stop bit.
BITS_PER_CHAR = 10
# A rate for serial links whose schema names none: 9600 baud, the common default
# of UARTs and serial radio modules.
REFERENCE_BAUD = 9600
# The longest shortest-round-trip text of an IEEE-754 binary64 is 24 characters
# (-2.2250738585072014e-308); a double with no bound is counted at that.
LONGEST_DOUBLE = 24


def seconds(value: float) -> str:
    if value >= 1:
        return f"{value:.1f} s" if value % 1 else f"{int(value)} s"
    return f"{value * 1000:.1f} ms"


def _param(t: Transport, name: str) -> Any:
    return dict(t.params).get(name)


def _serial_time(chars: int, baud: int) -> float:
    return chars * BITS_PER_CHAR / baud


def _wire_digits(bits: int) -> int:
    return len(str((1 << bits) - 1))


def longest_text_line(p: Protocol, m: Message) -> Optional[int]:
    """Characters of the longest line a message can take, with its line end; None if unbounded."""
    fr = p.framing
    if fr.text_form is not None:  # bits protocol written as decimal wire values, each array element one
        values = m.wire.leaves
        return sum(_wire_digits(x.bits) for x in values) + len(values) - 1 + 1
    leaves = [s for s in slots(m) if s.field.kind != "group" and not s.field.prefix]
    total = len(fr.start) + len(str(m.ids[0])) + len(fr.prefix_separator) + len(fr.terminator)
    total += sum(s.field.length or 0 for s in slots(m) if s.field.prefix)  # before the id
    if fr.line_checksum:
        total += len(fr.line_checksum.suffix) + 2
    for i, s in enumerate(leaves):
        f = s.field
        if f.kind == "char":
            width = 1
        elif f.kind in ("uint", "int") and f.fixed_spelling:  # raw digits, a point, padding
            lo, hi = f.raw_range
            width = max(len(str(lo)), len(str(hi))) + 2 + (f.decimals or 0)
            width = max(width, f.width or 0)
        elif f.kind in ("uint", "int"):
            lo, hi = f.range if f.range is not None else f.raw_range
            width = max(len(number(lo)), len(number(hi)))
        elif f.kind == "float":
            width = LONGEST_DOUBLE
        elif f.kind == "str" and f.max_length is not None:
            width = f.max_length
        else:
            return None
        total += width + (len(fr.separator) if i else 0)
    return total


def _first_line(codec: types.ModuleType, p: Protocol, m: Message) -> Optional[str]:
    for ex in m.examples:
        if not ex.errors and not ex.decode_only and ex.values is not None:
            value = codec.from_dict(m.name, ex.values)
            return codec.encode(value) if p.framing.kind == "text" else codec.encode_text(value)
    return None


def _sequence_word(p: Protocol) -> str:
    """What the protocol's one sequence is called (its name), or "sequence"."""
    return p.sequences[0].name if len(p.sequences) == 1 else "sequence"


def _example_sequence_text(codec: types.ModuleType, p: Protocol) -> Optional[tuple[str, str, int]]:
    for s in p.sequences:
        for ex in s.examples:
            if ex.text is not None and not ex.errors:
                seq = getattr(codec, f"decode_{s.name}_text")(ex.text)
                text = getattr(codec, f"encode_{s.name}_text")(seq)
                return s.name, text, len(text.splitlines())
    return None


def repeated_words(p: Protocol, t: Transport, codec: types.ModuleType) -> list[tuple[str, str, str]]:
    """A word sent again and again for a time (an RC5 remote control sends so)."""
    word, repeat_s, rate = _param(t, "word_bits"), _param(t, "repeat_s"), _param(t, "rate_hz")
    typical = _param(t, "sentences_typical")
    largest = max(m.bits for m in p.messages)
    rows = [("word", f"{word} bits", f"largest message {largest} bits: "
             + ("fits" if largest <= word else "does NOT fit")),
            ("sends of each word", number(repeat_s * rate), f"{number(repeat_s)} s × {number(rate)} Hz"),
            ("time per sentence", seconds(repeat_s), f"{number(repeat_s * rate)} words ÷ {number(rate)} Hz")]
    if typical:
        rows.append((f"typical {_sequence_word(p)} ({number(typical)} sentences)", seconds(typical * repeat_s),
                     f"{number(typical)} × {number(repeat_s)} s"))
        rows.append((f"data in a typical {_sequence_word(p)}", f"{number(typical * word)} bits",
                     f"{number(typical)} × {word} bits"))
    example = _example_sequence_text(codec, p)
    if example:
        name, _, lines = example
        rows.append((f"the example {name} ({lines} sentences)", seconds(lines * repeat_s),
                     f"{lines} × {number(repeat_s)} s"))
    return rows


def serial_lines(p: Protocol, t: Transport, codec: types.ModuleType, baud: int, assumed: bool) -> list[tuple[str, str, str]]:
    """Text lines over a serial link: characters and time per message and per file."""
    rate = f"{baud} baud, 8N1 ({BITS_PER_CHAR} bits a character)"
    rows = [("line rate", rate, "no rate in the schema: a reference rate, not a spec value" if assumed
             else "from the transport's parameters")]
    for m in p.messages:
        longest = longest_text_line(p, m)
        line = _first_line(codec, p, m)
        if line is not None:
            chars = len(line) + (1 if p.framing.text_form is not None else 0)
            rows.append((f"`{m.name}` example line", f"{chars} chars, {seconds(_serial_time(chars, baud))}",
                         "codec output of the first example" + (" with its newline" if p.framing.text_form else "")))
        if longest is not None:
            how = "every field at its widest" + (f" (doubles at {LONGEST_DOUBLE} chars)"
                                                 if any(s.field.kind == "float" for s in slots(m)) else "")
            rows.append((f"`{m.name}` longest line", f"{longest} chars, {seconds(_serial_time(longest, baud))}", how))
    example = _example_sequence_text(codec, p)
    if example:
        name, text, lines = example
        chars = len(text.encode("utf-8"))
        rows.append((f"the example {name} file ({lines} lines)", f"{chars} bytes, {seconds(_serial_time(chars, baud))}",
                     "codec output of the sequence example"))
    typical = next((_param(x, "sentences_typical") for x in p.transports if _param(x, "sentences_typical")), None)
    if typical and p.framing.text_form is not None:
        widest = max(longest_text_line(p, m) for m in p.messages)
        chars = typical * widest
        rows.append((f"typical {_sequence_word(p)} file ({number(typical)} lines, at most)", f"{chars} bytes, "
                     f"{seconds(_serial_time(chars, baud))}", f"{number(typical)} × {widest} chars"))
    return rows


def serial_frames(p: Protocol, baud: int) -> list[tuple[str, str, str]]:
    """Binary frames over a serial link: bytes and time per message."""
    rows = [("line rate", f"{baud} baud, 8N1 ({BITS_PER_CHAR} bits a byte)", "from the transport's parameters")]
    for m in p.messages:
        if m.size is not None:
            rows.append((f"`{m.name}` frame", f"{m.size} bytes, {seconds(_serial_time(m.size, baud))}",
                         f"{m.size} × {BITS_PER_CHAR} bits"))
    return rows


def fifo(p: Protocol, t: Transport, size: int) -> list[tuple[str, str, str]]:
    rows = [("radio FIFO", f"{size} bytes", "from the transport's parameters")]
    for m in p.messages:
        if m.size is None:
            continue
        verdict = f"fits, {size - m.size} bytes spare" if m.size <= size else f"does NOT fit: {m.size - size} bytes over"
        rows.append((f"`{m.name}` frame", f"{m.size} bytes", verdict))
    for param in p.parameters:
        # A length parameter grows every frame by one byte per unit: its largest value must still fit.
        users = [m for m in p.messages if any(s.field.length_param == param.name for s in slots(m))]
        if users and param.default is not None:
            overhead = users[0].size - int(param.default)
            largest = size - overhead
            allowed = int(param.range[1]) if param.range else None
            rows.append((f"largest `{param.name}`", f"{largest} bytes",
                         f"{size} − {overhead} bytes of framing"
                         + (f"; the schema allows up to {allowed}" if allowed is not None else "")))
    return rows


def transport_views(p: Protocol, codec: types.ModuleType) -> list[dict]:
    out = []
    for t in p.transports:
        rows: list[tuple[str, str, str]] = []
        fifo_bytes = _param(t, "fifo_bytes")
        if _param(t, "word_bits") and _param(t, "repeat_s") and _param(t, "rate_hz"):
            rows = repeated_words(p, t, codec)
        elif _param(t, "baud") and p.framing.kind != "text" and p.framing.text_form is None:
            rows = serial_frames(p, int(_param(t, "baud")))
        elif _param(t, "baud"):
            rows = serial_lines(p, t, codec, int(_param(t, "baud")), assumed=False)
        elif fifo_bytes:
            rows = fifo(p, t, int(fifo_bytes))
        elif p.framing.kind == "text" and t.kind in ("serial", "uart", "radio"):
            rows = serial_lines(p, t, codec, REFERENCE_BAUD, assumed=True)
        same_as = next((o["name"] for o in out if rows and o["rows"] == rows), None)
        out.append({"name": t.name, "kind": t.kind, "doc": cell(en(t.doc)),
                    "originals": [(lang, cell(text)) for lang, text in originals(t.doc)], "same_as": same_as,
                    "params": [(k, cell(number(v))) for k, v in t.params], "rows": [] if same_as else rows})
    return out
