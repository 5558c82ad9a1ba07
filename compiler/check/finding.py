"""One violation found in checked data, built from the generated codec's error."""
from __future__ import annotations

import enum
from dataclasses import dataclass
from typing import Any, Optional


@dataclass
class Finding:
    file: str
    unit: Optional[int]  # 1-based frame, line or word number within the input
    rule: str  # the codec's check kind: range, const, checksum, length, grammar, …
    text: str  # one-line description; the schema's user message where it has one
    line: Optional[int] = None  # text inputs
    column: Optional[int] = None  # text inputs, 1-based
    offset: Optional[int] = None  # binary inputs: byte offset in the file
    message: Optional[str] = None  # message (or sequence) name
    field: Optional[str] = None
    actual: Any = None
    allowed: Optional[str] = None
    decision: Optional[str] = None
    user_message: Optional[str] = None

    def location(self) -> str:
        if self.line is not None:
            where = f"{self.file}:{self.line}"
            return f"{where}:{self.column}" if self.column else where
        if self.offset is not None:
            return f"{self.file}:@{self.offset}"
        return self.file

    def as_json(self) -> dict:
        return {"file": self.file, "line": self.line, "column": self.column, "offset": self.offset,
                "unit": self.unit, "message": self.message, "field": self.field, "rule": self.rule,
                "decision": self.decision, "actual": plain(self.actual), "allowed": self.allowed or None,
                "user_message": self.user_message, "text": self.text}

    def as_text(self, unit_name: str) -> str:
        unit = f" ({unit_name} {self.unit})" if self.unit is not None else ""
        return f"{self.location()}{unit}: error: {self.text}"


def plain(value: Any) -> Any:
    """A JSON-safe form of a decoded or raw value."""
    if isinstance(value, enum.Enum):
        return plain(value.value)
    if isinstance(value, (bytes, bytearray)):
        return bytes(value).hex()
    if isinstance(value, (list, tuple)):
        return [plain(x) for x in value]
    if value is None or isinstance(value, (bool, int, str)):
        return value
    if isinstance(value, float):
        return value if value == value and value not in (float("inf"), float("-inf")) else repr(value)
    return repr(value)


def describe(error) -> str:
    """The codec's own one-line wording of an error, without its offset (the
    finding's location says where) and with the spec's user message first."""
    where = ".".join(x for x in (error.message, error.field) if x)
    value = error.value
    shown = bytes(value).hex(" ") if isinstance(value, (bytes, bytearray)) else repr(plain(value))
    named = error.rule == "rule" and error.decision  # a schema rule: its id says which
    text = f"{where + ': ' if where else ''}{shown} breaks rule {error.decision if named else error.rule}"
    if error.allowed:
        text += f" (expected {error.allowed})"
    if error.decision and not named:
        text += f" [{error.decision}]"
    if error.user_message:
        text = f"{error.user_message} — {text}"
    return text


def from_error(error, file: str, unit: Optional[int], **where) -> Finding:
    """A finding from a codec CodecError; `where` gives line/column/offset."""
    return Finding(file=file, unit=unit, rule=str(error.rule), text=describe(error),
                   message=error.message, field=error.field, actual=error.value,
                   allowed=str(error.allowed) if error.allowed else None, decision=error.decision,
                   user_message=error.user_message, **where)
