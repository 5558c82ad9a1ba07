"""JSON text exactly as json.dumps(value, indent=1, ensure_ascii=True) writes it,
but a value at a time, so a large document can be written in pieces.

The standard encoder falls back to pure-Python generators whenever it indents;
this builds each piece with string joins instead, several times faster, which
matters for conformance vector files of thousands of messages.
"""
from __future__ import annotations

from json.encoder import encode_basestring_ascii
from typing import Any

_INFINITY = float("inf")


def _float(value: float) -> str:
    if value != value:
        return "NaN"
    if value == _INFINITY:
        return "Infinity"
    if value == -_INFINITY:
        return "-Infinity"
    return float.__repr__(value)


def _key(key: Any) -> str:
    if isinstance(key, str):
        return encode_basestring_ascii(key)
    if isinstance(key, float):
        return encode_basestring_ascii(_float(key))
    if key is True or key is False or key is None:
        return encode_basestring_ascii({True: "true", False: "false", None: "null"}[key])
    if isinstance(key, int):
        return encode_basestring_ascii(int.__repr__(key))
    raise TypeError(f"keys must be str, int, float, bool or None, not {type(key).__name__}")


_BOOLS = {True: "true", False: "false"}
# Exact types only: a subclass (an IntEnum, say) takes the general path below.
_LEAVES = {str: encode_basestring_ascii, int: int.__repr__, float: _float,
           bool: _BOOLS.__getitem__, type(None): lambda _: "null"}


def dumps(value: Any, level: int = 0) -> str:
    """The text of value when it starts at indentation `level` (its items one deeper)."""
    leaf = _LEAVES.get(type(value))
    if leaf is not None:
        return leaf(value)
    if isinstance(value, str):
        return encode_basestring_ascii(value)
    if value is None:
        return "null"
    if value is True:
        return "true"
    if value is False:
        return "false"
    if isinstance(value, int):
        return int.__repr__(value)
    if isinstance(value, float):
        return _float(value)
    inner = level + 1
    if isinstance(value, (list, tuple)):
        if not value:
            return "[]"
        parts = []
        for item in value:
            leaf = _LEAVES.get(type(item))
            parts.append(leaf(item) if leaf is not None else dumps(item, inner))
        pad = "\n" + " " * inner
        return "[" + pad + ("," + pad).join(parts) + "\n" + " " * level + "]"
    if isinstance(value, dict):
        if not value:
            return "{}"
        parts = []
        for key, item in value.items():
            leaf = _LEAVES.get(type(item))
            parts.append((encode_basestring_ascii(key) if type(key) is str else _key(key)) + ": "
                         + (leaf(item) if leaf is not None else dumps(item, inner)))
        pad = "\n" + " " * inner
        return "{" + pad + ("," + pad).join(parts) + "\n" + " " * level + "}"
    raise TypeError(f"Object of type {type(value).__name__} is not JSON serializable")


class ListWriter:
    """Writes a list member of an indented JSON object item by item: `open`,
    any number of `item`, `close`; the same text as dumps of the whole list."""

    def __init__(self, out, level: int):
        self.out, self.level, self.count = out, level, 0

    def item(self, value: Any) -> None:
        self.out.write(("[" if not self.count else ",") + "\n" + " " * (self.level + 1)
                       + dumps(value, self.level + 1))
        self.count += 1

    def close(self) -> None:
        self.out.write("\n" + " " * self.level + "]" if self.count else "[]")
