"""Structural validation of a schema document against the language's JSON Schema.

A document found valid is remembered in the build cache (cache.py) under the
hash of its text, the JSON Schema and the code that reads and checks it: the
next build of the same schema neither validates it again nor imports jsonschema.
"""
from __future__ import annotations

import hashlib
import json
from functools import lru_cache
from pathlib import Path
from typing import TYPE_CHECKING

from . import cache, loader
from .diagnostics import Diagnostic
from .loader import Document

if TYPE_CHECKING:
    import jsonschema

SCHEMA_FILE = Path(__file__).parent / "schema" / "codeword.schema.json"
VALID = b"valid"


@lru_cache(maxsize=1)
def _validator() -> jsonschema.Draft202012Validator:
    import jsonschema  # only when a document is checked: importing it is a fair share of a small build
    base = jsonschema.Draft202012Validator
    # an integer is written as one: JSON Schema 2020-12 counts 5.0 (a float in YAML) as an
    # integer too, which would reach the resolver as a float
    strict = base.TYPE_CHECKER.redefine("integer", lambda _, x: isinstance(x, int) and not isinstance(x, bool))
    return jsonschema.validators.extend(base, type_checker=strict)(json.loads(SCHEMA_FILE.read_text(encoding="utf-8")))


def _deepest(error: jsonschema.ValidationError) -> jsonschema.ValidationError:
    """For oneOf/anyOf failures, the alternative that got furthest explains best."""
    best = error
    for sub in error.context or ():
        candidate = _deepest(sub)
        if len(candidate.absolute_path) > len(best.absolute_path):
            best = candidate
    return best


def _hint(error: jsonschema.ValidationError) -> str:
    if isinstance(error.instance, float) and error.instance.is_integer() and _takes(error, "integer"):
        return "write a whole number without a point or an exponent (5, not 5.0)" + (
            ", or quote it where a string is meant" if _takes(error, "string") else "")
    if error.validator == "additionalProperties":
        allowed = sorted(error.schema.get("properties", {}))
        return "allowed keys here: " + ", ".join(allowed) if allowed else ""
    if error.validator == "required":
        return "add the missing key"
    if error.validator == "pattern" and "A-Za-z_" in str(error.validator_value):
        return "names are identifiers: letters, digits and _, not starting with a digit"
    if error.validator in ("oneOf", "anyOf") and isinstance(error.instance, dict):
        return "a text is a string or a map of language codes with `en`; quote values that contain ', ' or ': '"
    return "see docs/schema-language.md"


def _takes(error: jsonschema.ValidationError, kind: str) -> bool:
    """Whether the schema at the error's place takes a value of JSON type `kind`, itself or
    as one of its alternatives."""
    spec = error.schema if isinstance(error.schema, dict) else {}
    return spec.get("type") == kind or any(
        isinstance(x, dict) and x.get("type") == kind for x in spec.get("oneOf", []) + spec.get("anyOf", []))


def structure_errors(doc: Document) -> list[Diagnostic]:
    place = cache.slot("valid", doc.file)
    wanted = cache.key("valid", hashlib.sha256(doc.text.encode("utf-8", "surrogatepass")).hexdigest(),
                       cache.source_hash(SCHEMA_FILE, Path(loader.__file__), Path(__file__)))
    if cache.load(place, wanted) == VALID:
        return []
    found = _errors(doc)
    if not found:
        cache.store(place, wanted, VALID)
    return found


def _errors(doc: Document) -> list[Diagnostic]:
    found: list[Diagnostic] = []
    seen: set[tuple] = set()
    for error in _validator().iter_errors(doc.data):
        error = _deepest(error)
        path = tuple(error.absolute_path)
        message = error.message
        if isinstance(error.instance, float) and error.instance.is_integer() and _takes(error, "integer"):
            message = f"{error.instance!r} is not an integer"
        if len(message) > 200:
            message = message[:200] + "…"
        where = ".".join(str(p) for p in path) or "top level"
        key = (path, message)
        if key in seen:
            continue
        seen.add(key)
        found.append(Diagnostic(doc.loc(path), f"{where}: {message}", _hint(error)))
    return found
