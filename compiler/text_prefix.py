"""A text message's prefix as a pattern: the prefix field's values (NMEA's talker: any
uppercase letters of its length, or a listed set) followed by the message's id; and
whether two patterns read one same prefix (then a decoder could not tell the messages apart)."""
from __future__ import annotations

from typing import Optional

LETTERS = "ABCDEFGHIJKLMNOPQRSTUVWXYZ"


def is_prefix_value(text: str, length: int) -> bool:
    """A prefix field's value: `length` uppercase letters A-Z."""
    return len(text) == length and all(ch in LETTERS for ch in text)


class Pattern:
    """Prefixes `<value><id>`: a value of `length` letters (any, or one of `values`), then `id`."""

    def __init__(self, ident: str, length: int = 0, values: Optional[tuple[str, ...]] = None) -> None:
        self.ident, self.length, self.values = ident, length, values

    def takes(self, value: str) -> bool:
        if self.values is not None:
            return value in self.values
        return is_prefix_value(value, self.length)

    def example(self) -> str:
        return (self.values[0] if self.values else "A" * self.length) + self.ident


def pattern_of(ident: str, prefix_field) -> Pattern:
    if prefix_field is None:
        return Pattern(ident)
    return Pattern(ident, prefix_field.length or 0, tuple(prefix_field.values) if prefix_field.values else None)


def common_prefix(a: Pattern, b: Pattern) -> Optional[str]:
    """A prefix both patterns read, or None when there is none."""
    if a.length > b.length:
        a, b = b, a
    if a.length + len(a.ident) != b.length + len(b.ident):
        return None
    d = b.length - a.length  # b's value covers a's value and the first d characters of a's id
    if a.ident[d:] != b.ident:
        return None
    middle = a.ident[:d]
    if b.values is not None:
        candidates = [v for v in b.values if v[a.length:] == middle]
    elif all(ch in LETTERS for ch in middle):
        heads = list(a.values) if a.values is not None else ["A" * a.length]
        candidates = [h + middle for h in heads]
    else:
        candidates = []
    for v in candidates:
        if a.takes(v[:a.length]):
            return v + b.ident
    return None
