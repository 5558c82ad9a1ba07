"""The schema fingerprint: a hash of everything in a protocol model that affects
the wire, and nothing that only documents it.

Two schemas with the same fingerprint produce and accept the same bytes, so a
host that reads a firmware's fingerprint can tell whether both were built from
the same protocol. Docs, titles, user-facing messages, examples, hand-worked
streams, notes, history, the version string, source locations and the delivery
section (which machines the simulator drives, which notes the docs cite) are left out; names
stay in, because they are the API of the generated codecs and what `codeword
diff` matches on.
"""
from __future__ import annotations

import dataclasses
import enum
import hashlib
import json
from functools import lru_cache
from typing import Any

from .model import Protocol, Text

# Model attributes that describe a protocol to people, not to a decoder.
DOC_ONLY = frozenset({
    "doc", "title", "message", "examples", "notes", "history", "version", "source",
    "file", "sha256", "loc", "delivery", "streams",
})
# Model attributes computed from others: hashing them again adds nothing.
DERIVED = frozenset({"wire", "text_places", "line_max"})


@lru_cache(maxsize=None)
def _wire_fields(cls: type) -> tuple[tuple[str, Any], ...]:
    """(name, default) of each wire attribute; `_NONE` when it has no default."""
    return tuple((f.name, f.default if f.default is not dataclasses.MISSING else _NONE)
                 for f in dataclasses.fields(cls) if f.name not in DOC_ONLY | DERIVED)


_NONE = object()


def wire_model(value: Any) -> Any:
    """The model as plain JSON data without its documentation. An attribute at its
    default is left out, so a model that grows (a new option, off by default)
    keeps the fingerprints of the protocols that do not use it."""
    if isinstance(value, Text):
        return None
    if hasattr(type(value), "__dataclass_fields__") and not isinstance(value, type):
        return {name: wire_model(attr) for name, default in _wire_fields(type(value))
                if (attr := getattr(value, name)) is not default and not (default is not _NONE and attr == default)}
    if isinstance(value, (tuple, list)):
        return [wire_model(x) for x in value]
    if isinstance(value, dict):
        return {str(k): wire_model(v) for k, v in sorted(value.items(), key=lambda kv: str(kv[0]))}
    if isinstance(value, enum.Enum):
        return wire_model(value.value)
    if isinstance(value, bytes):
        return value.hex()
    if value is None or isinstance(value, (bool, int, float, str)):
        return value
    return repr(value)


def canonical_json(p: Protocol) -> str:
    return json.dumps(wire_model(p), sort_keys=True, separators=(",", ":"), ensure_ascii=True)


def fingerprint_digest(p: Protocol) -> str:
    """SHA-256 (hex) of the canonical wire model."""
    # Every target asks; the model is immutable, so the digest is kept on it.
    memo = getattr(p, "__dict__", {})
    digest = memo.get("_wire_digest")
    if digest is None:
        digest = memo["_wire_digest"] = hashlib.sha256(canonical_json(p).encode("ascii")).hexdigest()
    return digest


def fingerprint(p: Protocol) -> str:
    """The fingerprint as 16 hex digits (the first 64 bits of the digest): what
    generated code exposes as FINGERPRINT and the docs show."""
    return fingerprint_digest(p)[:16]


def fingerprint32(p: Protocol) -> int:
    """The first 32 bits of the digest, for firmware that reports it as one word."""
    return int(fingerprint_digest(p)[:8], 16)
