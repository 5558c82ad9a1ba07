"""Text for the Markdown specs: table-safe cells, translations, decision links,
anchors and the display of decoded values."""
from __future__ import annotations

import dataclasses
import enum
import re
from typing import Any, Optional

from ...model import Protocol, Text
from ..escape import md_code, md_text

LANGUAGES = {"ru": "Russian", "zh": "Chinese", "pl": "Polish", "en": "English"}


# Schema prose in a paragraph or table cell, and inline code: escape.py's Markdown context.
cell = md_text
code = md_code


def en(text: Optional[Text]) -> str:
    return " ".join(text.en.split()) if text else ""


def originals(text: Optional[Text]) -> list[tuple[str, str]]:
    """(language code, text) of every translation a schema gives, in its order."""
    if text is None:
        return []
    return [(lang, " ".join(value.split())) for lang, value in text.translations]


def with_original(text: Optional[Text]) -> str:
    """English, then the original-language wording in parentheses: `Header (头位串)`."""
    out = en(text)
    extra = [value for _, value in originals(text) if value and value != out]
    return f"{out} ({'; '.join(extra)})" if extra else out


def anchor(kind: str, name: str) -> str:
    """A stable HTML id: the same on GitHub, in MkDocs and in the tests."""
    return f"{kind}-" + re.sub(r"[^a-z0-9]+", "-", name.lower()).strip("-")


def link_msg(name: str) -> str:
    """A link to a message's section."""
    return f"[{name}](#{anchor('msg', name)})"


class DecisionLinker:
    """Turns the note ids a text cites (such as ABC-D1) into links to the notes."""

    def __init__(self, p: Protocol):
        ids = sorted((n.id for n in p.notes), key=len, reverse=True)
        self.ids = {n.id for n in p.notes}
        self.pattern = re.compile(r"(?<![\w-])(" + "|".join(map(re.escape, ids)) + r")(?![\w-])") if ids else None

    def link(self, text: str) -> str:
        if not self.pattern:
            return text
        return self.pattern.sub(lambda m: f"[{m.group(1)}](#{anchor('note', m.group(1))})", text)

    def cited(self, text: str) -> list[str]:
        return sorted(set(self.pattern.findall(text))) if self.pattern else []

    def ref(self, note_id: Optional[str]) -> str:
        """A link to a note if the protocol has it, else the id as plain text."""
        if not note_id:
            return ""
        shown = md_text(note_id)
        return f"[{shown}](#{anchor('note', note_id)})" if note_id in self.ids else shown


def number(value: Any) -> str:
    """Numbers as a reader writes them: 4095.875, 100, -0.125; never 1e+02 for integers."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float) and value.is_integer() and abs(value) < 1e15:
        return str(int(value))
    return str(value)


def shown(value: Any) -> str:
    """A decoded value as the docs show it: enum names, flag names, hex bytes, nested groups."""
    if value is None:
        return "absent"
    if isinstance(value, enum.Flag):
        names = [m.name for m in type(value) if m.value and (value & m) == m and m.name]
        return " + ".join(names) if names else "none"
    if isinstance(value, enum.Enum):
        return str(value.name)
    if isinstance(value, (bytes, bytearray)):
        return bytes(value).hex(" ")
    if isinstance(value, str):
        return '"' + value + '"'
    if dataclasses.is_dataclass(value):
        inner = ", ".join(f"{f.name} = {shown(getattr(value, f.name))}" for f in dataclasses.fields(value) if f.compare)
        return "{" + inner + "}"
    if isinstance(value, list):
        return "[" + ", ".join(shown(v) for v in value) + "]"
    return number(value)


def decoded_fields(obj: Any) -> list[tuple[str, str]]:
    """(field, shown value) for a decoded message object, in declaration order."""
    return [(f.name, shown(getattr(obj, f.name))) for f in dataclasses.fields(obj) if f.compare]
