"""A small YAML writer for imported schemas: block mappings a person reads and edits,
comments where the source said something the schema has no key for, long texts
folded at a readable width. Every scalar is written so that YAML reads back exactly
the value given (plain when that is safe, else double-quoted with JSON's escapes)."""
from __future__ import annotations

import json
import re
import textwrap

WIDTH = 100
# plain scalars that YAML reads back as the same string
_PLAIN = re.compile(r"[A-Za-z_][A-Za-z0-9_ ./%()-]*\Z")
_SPECIAL = frozenset("y n yes no on off true false null ~".split())


def number(value: float) -> str:
    """A finite number as YAML reads it back exactly: an integer plainly, a float with a
    point (PyYAML takes 1e-05 for a string, 1.0e-05 for a float)."""
    if isinstance(value, int):
        return str(value)
    mantissa, e, exponent = repr(float(value)).partition("e")
    if e and "." not in mantissa:
        mantissa += ".0"
    return mantissa + (f"e{'-' if exponent.startswith('-') else '+'}{exponent.lstrip('+-')}" if e else "")


def scalar(value) -> str:
    """One scalar, as YAML text that reads back as `value`."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return number(value)
    text = str(value)
    if _PLAIN.match(text) and text.lower() not in _SPECIAL and not text.endswith(" ") and ": " not in text \
            and " #" not in text:
        return text
    return json.dumps(text, ensure_ascii=False)


def flow(mapping: dict) -> str:
    """`{key: value, …}` on one line."""
    return "{" + ", ".join(f"{k}: {scalar(v)}" for k, v in mapping.items()) + "}"


class Writer:
    """Lines of a YAML document, written top to bottom."""

    def __init__(self) -> None:
        self.lines: list[str] = []

    def text(self) -> str:
        return "\n".join(self.lines) + "\n"

    def raw(self, block: str) -> None:
        """Lines written as they are (a fixed part of the schema)."""
        self.lines += block.rstrip("\n").split("\n")

    def blank(self) -> None:
        self.lines.append("")

    def comment(self, text: str, indent: int = 0) -> None:
        """`# text`, wrapped; a comment holds anything, so nothing needs escaping but newlines."""
        pad = " " * indent
        flat = " ".join(text.split())
        for line in textwrap.wrap(flat, WIDTH - indent - 2, break_long_words=False, break_on_hyphens=False) or [""]:
            self.lines.append(f"{pad}# {line}".rstrip())

    def key(self, key: str, indent: int) -> None:
        self.lines.append(f"{' ' * indent}{key}:")

    def item(self, key: str, value, indent: int, first: bool = False) -> None:
        """`key: value`; `first` starts a sequence item (`- key: value`)."""
        self.lines.append(f"{' ' * indent}{'- ' if first else ''}{key}: {scalar(value)}")

    def prose(self, key: str, text: str, indent: int, first: bool = False) -> None:
        """`key: text`, folded over several lines (`>-`) when it is long."""
        lead = f"{' ' * indent}{'- ' if first else ''}{key}: "
        one_line = lead + scalar(text)
        if len(one_line) <= WIDTH or not text.strip() or text != " ".join(text.split()):
            self.lines.append(one_line)
            return
        inner = " " * (indent + 2 + (2 if first else 0))
        self.lines.append(lead + ">-")
        # a folded scalar joins its lines with single spaces: the text's own words back
        self.lines += [inner + line for line in textwrap.wrap(text, WIDTH - len(inner), break_long_words=False,
                                                              break_on_hyphens=False)]

    def code(self, key: str, text: str, indent: int) -> None:
        """`key: text`, the text written as it is (a hex number, a flow list of numbers)."""
        self.lines.append(f"{' ' * indent}{key}: {text}")

    def flow_item(self, mapping: dict, indent: int) -> None:
        self.lines.append(f"{' ' * indent}- {flow(mapping)}")
