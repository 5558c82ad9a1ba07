"""Drop what a generated module does not use: imports and private module-level functions
that only some schemas need. Type checkers in strict mode report each unused one."""
from __future__ import annotations

import re
from collections import Counter

_DEF = re.compile(r"^def (_\w+)\(", re.M)
_TOP_LEVEL = re.compile(r"^\S", re.M)
_FROM_IMPORT = re.compile(r"^from (?!__future__ )(\S+) import (.+)$", re.M)
_IMPORT = re.compile(r"^import (\w+)$", re.M)
# names that also serve as parameter names in every module: only a call counts as a use
_CALLED = {"field"}
_NAME = re.compile(r"(?<![\w.])[A-Za-z_]\w*")


def prune(source: str) -> str:
    """`source` without unused private top-level functions and imported names. The
    module's names are counted once; a function dropped takes its own uses with it."""
    uses = _counts(source)
    while True:  # a function dropped may leave others unused
        source, dropped = _drop_unused_functions(source, uses)
        if not dropped:
            break
        uses.subtract(_counts("".join(dropped)))
    return _drop_unused_imports(source, uses)


def _counts(source: str) -> Counter[str]:
    """How often each name is used in `source`: where no word character or dot comes
    before it (an attribute is not a use), and for _CALLED names only in a call."""
    uses = Counter(_NAME.findall(source))
    for name in _CALLED:
        uses[name] = len(re.findall(rf"(?<![\w.]){name}\(", source))
    return uses


def _drop_unused_functions(source: str, uses: Counter[str]) -> tuple[str, list[str]]:
    """`source` without the private functions named only on their own def line, and
    the text of those dropped."""
    kept, dropped, at = [], [], 0
    for match in _DEF.finditer(source):
        if uses[match.group(1)] == 1:  # its own def line only
            end = _TOP_LEVEL.search(source, match.end())
            stop = end.start() if end else len(source)
            kept.append(source[at:match.start()])
            dropped.append(source[match.start():stop])
            at = stop
            while source.startswith("\n", at):
                at += 1
    return "".join(kept) + source[at:], dropped


def _drop_unused_imports(source: str, uses: Counter[str]) -> str:
    def from_line(m: re.Match[str]) -> str:
        before = _counts(source[:m.end()])  # the imports come first: every other use is after
        names = [n.strip() for n in m.group(2).split(",")]
        kept = [n for n in names if uses[n.split(" as ")[-1]] - before[n.split(" as ")[-1]] > 0]
        return f"from {m.group(1)} import {', '.join(kept)}" if kept else ""

    def import_line(m: re.Match[str]) -> str:
        at = source.find(m.group(1) + ".", m.end())  # a use is the module's name and a dot
        while at >= 0 and (source[at - 1].isalnum() or source[at - 1] == "_"):
            at = source.find(m.group(1) + ".", at + 1)
        return m.group(0) if at >= 0 else ""
    source = _FROM_IMPORT.sub(from_line, source)
    return _IMPORT.sub(import_line, source)
