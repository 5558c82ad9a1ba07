"""A text line as other receivers write it: its numbers spelled with leading zeros,
more or fewer decimals, a `+`; or its later values left off, as an older writer
does; the line checksum made again. Readers take every such line (decode-only
inputs of the conformance vectors)."""
from __future__ import annotations

import random
import re
from typing import Optional

from .model import Field, Framing, Message

_PLAIN = re.compile(r"(-?)([0-9]+)(?:\.([0-9]+))?\Z")  # what writers emit (no exponent)


def respelled(fr: Framing, m: Message, line: str, rng: random.Random) -> Optional[str]:
    """`line` (as the encoder wrote it) with some numbers spelled otherwise, or None
    when it holds no number to respell."""
    head = fr.start + m.ids[0] + fr.prefix_separator
    if not line.startswith(head) or not line.endswith(fr.terminator):
        return None
    tail = len(fr.terminator) + (len(fr.line_checksum.suffix) + 2 if fr.line_checksum else 0)
    leaves = [leaf.field for leaf in m.wire.leaves]
    tokens = line[len(head):len(line) - tail].split(fr.separator, max(0, len(leaves) - 1))
    changed = False
    for n, (f, token) in enumerate(zip(leaves, tokens)):
        spelling = _respell(f, token, rng) if rng.random() < 0.7 else None
        if spelling is not None:
            tokens[n], changed = spelling, True
    if not changed:
        return None
    body = m.ids[0] + fr.prefix_separator + fr.separator.join(tokens)
    if fr.line_checksum:
        body += fr.line_checksum.suffix + format(line_sum(fr.line_checksum.algorithm, body), "02X")
    return fr.start + body + fr.terminator


def with_values(fr: Framing, m: Message, line: str, n: int) -> str:
    """`line` (as the encoder wrote it) ended after its first `n` values, as a writer that
    leaves off the values after them writes it; the line checksum made again."""
    tail = len(fr.terminator) + (len(fr.line_checksum.suffix) + 2 if fr.line_checksum else 0)
    content = line[len(fr.start):len(line) - tail]
    pf = m.prefix_field
    head = (pf.length if pf is not None else 0) + len(m.ids[0]) + len(fr.prefix_separator)
    values = content[head:].split(fr.separator, max(0, m.text_places.total - 1)) if content[head:] else []
    content = content[:head] + fr.separator.join(values[:n])
    if fr.line_checksum:
        content += fr.line_checksum.suffix + format(line_sum(fr.line_checksum.algorithm, content), "02X")
    return fr.start + content + fr.terminator


def line_sum(algorithm: str, text: str) -> int:
    acc = 0
    for ch in text:
        acc = acc ^ ord(ch) if algorithm == "xor" else acc + ord(ch)
    return acc & 0xFF


def _respell(f: Field, token: str, rng: random.Random) -> Optional[str]:
    """Another spelling of one value's number, for a field whose readers take it."""
    plain = f.kind in ("uint", "int") and f.enum is None and f.flags is None and not f.one_hot
    if f.const is not None or not (plain or f.kind == "float"):
        return None
    match = _PLAIN.match(token)
    if match is None:
        return None
    sign, whole, fraction = match[1] or rng.choice(["", "+"]), match[2], match[3]
    whole = "0" * rng.randint(0, 3) + whole
    if not (f.fixed_spelling or f.kind == "float"):  # a plain integer: no point
        return sign + whole
    if fraction is None:
        fraction = "0" * rng.randint(0, 2)
    elif rng.random() < 0.5:
        fraction += "0" * rng.randint(1, 2)
    else:
        fraction = fraction.rstrip("0")
    return sign + whole + ("." + fraction if fraction or rng.random() < 0.3 else "")
