"""Drop what a generated module does not use: imports and private module-level functions
that only some schemas need. Type checkers in strict mode report each unused one."""
from __future__ import annotations

import re

_DEF = re.compile(r"^def (_\w+)\(", re.M)
_FROM_IMPORT = re.compile(r"^from (?!__future__ )(\S+) import (.+)$", re.M)
_IMPORT = re.compile(r"^import (\w+)$", re.M)


def prune(source: str) -> str:
    """`source` without unused private top-level functions and imported names."""
    while True:  # a function dropped may leave others unused
        pruned = _drop_unused_functions(source)
        if pruned == source:
            break
        source = pruned
    return _drop_unused_imports(source)


# names that also serve as parameter names in every module: only a call counts as a use
_CALLED = {"field"}
_NAME = re.compile(r"(?<![\w.])([A-Za-z_]\w*)(\()?")


def _counts(source: str) -> dict[str, int]:
    """How often each name is used in `source`, in one pass: where no word character or
    dot comes before it (an attribute is not a use), and for _CALLED names only in a call."""
    uses: dict[str, int] = {}
    for match in _NAME.finditer(source):
        name = match.group(1)
        if name not in _CALLED or match.group(2):
            uses[name] = uses.get(name, 0) + 1
    return uses


def _drop_unused_functions(source: str) -> str:
    """`source` without the private functions named only on their own def line."""
    uses = _counts(source)
    kept, at = [], 0
    for match in _DEF.finditer(source):
        if uses.get(match.group(1)) == 1:  # its own def line only
            end = re.compile(r"^\S", re.M).search(source, match.end())
            stop = end.start() if end else len(source)
            kept.append(source[at:match.start()])
            at = stop
            while source.startswith("\n", at):
                at += 1
    return "".join(kept) + source[at:]


def _drop_unused_imports(source: str) -> str:
    def from_line(m: re.Match[str]) -> str:
        rest = _counts(source[m.end():])
        names = [n.strip() for n in m.group(2).split(",")]
        kept = [n for n in names if rest.get(n.split(" as ")[-1])]
        return f"from {m.group(1)} import {', '.join(kept)}" if kept else ""

    def import_line(m: re.Match[str]) -> str:
        return m.group(0) if re.search(rf"\b{m.group(1)}\.", source[m.end():]) else ""
    source = _FROM_IMPORT.sub(from_line, source)
    return _IMPORT.sub(import_line, source)
