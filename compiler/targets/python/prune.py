"""Drop what a generated module does not use: imports and private module-level functions
that only some schemas need. Type checkers in strict mode report each unused one."""
from __future__ import annotations

import re

_DEF = re.compile(r"^def (_\w+)\(", re.M)
_FROM_IMPORT = re.compile(r"^from (?!__future__ )(\S+) import (.+)$", re.M)
_IMPORT = re.compile(r"^import (\w+)$", re.M)


def prune(source: str) -> str:
    """`source` without unused private top-level functions and imported names."""
    while True:
        pruned = _drop_unused_function(source)
        if pruned == source:
            break
        source = pruned
    return _drop_unused_imports(source)


# names that also serve as parameter names in every module: only a call counts as a use
_CALLED = {"field"}


def _uses(source: str, name: str) -> int:
    after = r"\(" if name in _CALLED else r"\b"
    return len(re.findall(rf"(?<![\w.]){re.escape(name)}{after}", source))


def _drop_unused_function(source: str) -> str:
    for match in _DEF.finditer(source):
        if _uses(source, match.group(1)) == 1:  # its own def line only
            end = re.compile(r"^\S", re.M).search(source, match.end())
            stop = end.start() if end else len(source)
            return source[:match.start()] + source[stop:].lstrip("\n")
    return source


def _drop_unused_imports(source: str) -> str:
    def from_line(m: re.Match[str]) -> str:
        rest = source[m.end():]
        names = [n.strip() for n in m.group(2).split(",")]
        kept = [n for n in names if _uses(rest, n.split(" as ")[-1])]
        return f"from {m.group(1)} import {', '.join(kept)}" if kept else ""

    def import_line(m: re.Match[str]) -> str:
        return m.group(0) if re.search(rf"\b{m.group(1)}\.", source[m.end():]) else ""
    source = _FROM_IMPORT.sub(from_line, source)
    return _IMPORT.sub(import_line, source)
