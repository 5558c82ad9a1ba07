"""Results a build would compute again unchanged, kept between builds.

A result is stored under a hash of everything it depends on (the caller names
each input: schema and generated code hashes, parameters, the source of the
code that computes it, the Python version), so a stale entry is never found,
only left behind. The folder is $CODEWORD_CACHE, else $XDG_CACHE_HOME/codeword,
else ~/.cache/codeword; CODEWORD_CACHE=off keeps nothing. A cache that cannot be
read or written only costs the computation.
"""
from __future__ import annotations

import contextlib
import hashlib
import json
import os
import sys
import tempfile
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


def key(kind: str, *inputs: Any) -> str:
    text = json.dumps([kind, list(sys.version_info[:2]), *inputs], sort_keys=True)
    return f"{kind}-{hashlib.sha256(text.encode('utf-8')).hexdigest()[:32]}"


def remembered(name: str, compute: Callable[[], Any]) -> Any:
    """compute()'s JSON-able result, from the cache when a build has stored it."""
    where = folder()
    path = where / f"{name}.json" if where is not None else None
    if path is not None:
        try:
            return json.loads(path.read_text(encoding="utf-8"))["value"]
        except (OSError, ValueError, KeyError, TypeError):  # absent or damaged: compute it
            pass
    value = compute()
    if path is not None:
        _store(path, value)
    return value


def _store(path: Path, value: Any) -> None:
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=path.parent, suffix=".tmp")
    except OSError:
        return
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as out:
            json.dump({"value": value}, out)
        os.replace(tmp, path)  # whole or not at all, even with builds running side by side
    except OSError:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
