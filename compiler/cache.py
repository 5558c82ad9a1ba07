"""Results a build would compute again unchanged, kept between builds.

Each result has a slot, named by what it is and for which protocol, and a key,
a hash of everything it depends on (the caller names each input: schema and
generated code hashes, parameters, the source of the code that computes it; the
Python version is always part of it). A slot holds the last result stored in
it with its key; a result is used only when its key is the one asked for, so a
stale one is never used, only replaced, and the cache holds one result per
slot. The folder is $CODEWORD_CACHE, else $XDG_CACHE_HOME/codeword, else
~/.cache/codeword; CODEWORD_CACHE=off keeps nothing. A cache that cannot be
read or written only costs the computation.
"""
from __future__ import annotations

import contextlib
import hashlib
import importlib.util
import json
import os
import re
import sys
import tempfile
from functools import lru_cache
from pathlib import Path
from typing import Any, Callable, Optional

OFF = "off"


def folder() -> Optional[Path]:
    chosen = os.environ.get("CODEWORD_CACHE")
    if chosen == OFF:
        return None
    if chosen:
        return Path(chosen)
    base = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(base) / "codeword"


def source_hash(*files: Path) -> str:
    """The hash of the code that computes a result: a change to it is a new key."""
    h = hashlib.sha256()
    for path in files:
        h.update(path.read_bytes())
    return h.hexdigest()


@lru_cache(maxsize=1)
def compiler_hash() -> str:
    """The hash of codeword's own code and data (its templates show in what they render):
    for a result that depends on more of it than a caller can name."""
    package = Path(__file__).resolve().parent
    files = sorted(p for suffix in ("*.py", "*.json", "*.yaml") for p in package.rglob(suffix)
                   if "__pycache__" not in p.parts)
    h = hashlib.sha256()
    for path in files:
        h.update(path.relative_to(package).as_posix().encode("utf-8") + b"\0" + path.read_bytes() + b"\0")
    return h.hexdigest()


def key(*inputs: Any) -> str:
    """The hash of a result's inputs (JSON data), with the Python version and bytecode format."""
    text = json.dumps([list(sys.version_info[:3]), importlib.util.MAGIC_NUMBER.hex(), *inputs], sort_keys=True)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def slot(kind: str, name: str) -> str:
    return kind + "-" + re.sub(r"[^A-Za-z0-9_.-]", "_", name)[:80]


def load(place: str, wanted: str) -> Optional[bytes]:
    """The bytes stored in slot `place` under key `wanted`, or None."""
    where = folder()
    if where is None:
        return None
    try:
        data = (where / place).read_bytes()
    except OSError:
        return None
    stored, _, value = data.partition(b"\n")
    return value if stored == wanted.encode("ascii") else None


def store(place: str, wanted: str, value: bytes) -> None:
    where = folder()
    if where is None:
        return
    try:
        where.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=where, prefix=place, suffix=".tmp")
    except OSError:
        return
    try:
        with os.fdopen(fd, "wb") as out:
            out.write(wanted.encode("ascii") + b"\n" + value)
        os.replace(tmp, where / place)  # whole or not at all, even with builds running side by side
    except OSError:
        with contextlib.suppress(OSError):
            os.unlink(tmp)


def remembered(place: str, wanted: str, compute: Callable[[], Any]) -> Any:
    """compute()'s JSON-able result, from the cache when a build has stored it."""
    data = load(place, wanted)
    if data is not None:
        try:
            return json.loads(data)
        except ValueError:  # damaged: compute it
            pass
    value = compute()
    store(place, wanted, json.dumps(value).encode("utf-8"))
    return value
