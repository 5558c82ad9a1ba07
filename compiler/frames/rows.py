"""Decoded messages and codec errors as rows: what every frame command prints."""
from __future__ import annotations

import dataclasses
import enum
import json
from dataclasses import dataclass, field
from typing import Any, Optional, Union

from ..model import Field, Protocol


@dataclass
class Row:
    """One frame or line: where it starts, its bytes, and its message or error."""

    offset: Optional[int]
    raw: Union[bytes, str]  # a frame's bytes, or a text protocol's line
    message: Optional[str] = None
    values: list[tuple[str, str, Any]] = field(default_factory=list)  # (name, shown, JSON value)
    error: Optional[str] = None
    time: Optional[str] = None
    skipped: int = 0  # bytes between frames this row stands for (not a frame itself)

    def as_json(self) -> dict:
        out: dict[str, Any] = {}
        if self.time is not None:
            out["time"] = self.time
        out["offset"] = self.offset
        out["frame"] = self.frame
        if self.error is not None:
            out["error"] = self.error
        else:
            out["message"] = self.message
            out["values"] = {name: value for name, _, value in self.values}
        return out

    @property
    def frame(self) -> str:
        return self.raw if isinstance(self.raw, str) else self.raw.hex(" ")

    def summary(self) -> str:
        """The message and its values on one line."""
        if self.error is not None:
            return f"error: {self.error}"
        return f"{self.message} " + " ".join(f"{name}={shown}" for name, shown, _ in self.values)


def units_of(protocol: Protocol) -> dict[str, dict[str, Field]]:
    """Per message name, its declared fields by name (for units and nesting)."""
    return {m.name: {f.name: f for f in m.members} for m in protocol.messages}


def message_row(obj, fields: dict[str, Field], offset: Optional[int], raw, name: Optional[str] = None) -> Row:
    row = Row(offset, raw, message=name or obj.NAME)
    _flatten(obj, fields, "", row.values)
    return row


def error_row(exc: Exception, offset: Optional[int], raw: bytes) -> Row:
    return Row(offset, raw, error=str(exc))


def _flatten(obj, fields: dict[str, Field], prefix: str, out: list) -> None:
    for attr in dataclasses.fields(obj):
        if not attr.compare:  # not a value: the text numbers were read from
            continue
        value = getattr(obj, attr.name)
        model = fields.get(attr.name)
        name = prefix + attr.name
        if dataclasses.is_dataclass(value) and not isinstance(value, type):
            _flatten(value, {f.name: f for f in model.fields} if model else {}, name + ".", out)
            continue
        if isinstance(value, (list, tuple)):  # the items of a sequence
            for i, item in enumerate(value):
                _flatten(item, {}, f"{name}[{i}].", out)
            continue
        shown, plain = _show(value)
        unit = model.unit if model is not None else None
        out.append((name, f"{shown} {unit}" if unit and value is not None else shown, plain))


def _show(value) -> tuple[str, Any]:
    """How a value is shown, and how it is written as JSON."""
    if isinstance(value, enum.Flag):
        names = [m.name for m in type(value) if m.value and m in value]
        return "|".join(names) or "0", names
    if isinstance(value, enum.Enum):
        return str(value.name), value.name
    if isinstance(value, (bytes, bytearray)):
        return value.hex(" ") or "''", value.hex()
    if value is None:
        return "-", None
    if isinstance(value, str):
        return json.dumps(value), value
    return repr(value), value
