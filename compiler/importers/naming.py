"""Names from another format's specification mapped to names codeword accepts,
deterministically: a name codeword refuses (a keyword, a name the generated code or the
framing uses, too long, starting with a digit) gets a trailing `_` or is shortened with
a hash; importers say the original in a comment or a title."""
from __future__ import annotations

import re
import zlib

from ..names import GENERATED_CLASSES, MAX_NAME_LENGTH, camel, name_problem

_WORD_BREAK = re.compile(r"(?<=[a-z0-9])(?=[A-Z])|(?<=[A-Z])(?=[A-Z][a-z])")


def shortened(name: str) -> str:
    """A name cut to the length codeword allows, a hash of the whole keeping it unique."""
    tag = f"{zlib.crc32(name.encode()) & 0xFFFF:04x}"
    return f"{name[:MAX_NAME_LENGTH - 5].rstrip('_')}_{tag}"


def usable(name: str, taken: frozenset | set = frozenset()) -> str:
    """`name` (lower case already) or the nearest name codeword accepts and that is not taken."""
    if len(name) > MAX_NAME_LENGTH:
        name = shortened(name)
    if name[:1].isdigit():
        name = "n" + name
    while name_problem(name) or name in taken or camel(name) in GENERATED_CLASSES:
        name = name + "_" if len(name) < MAX_NAME_LENGTH else shortened(name + "x")
    return name


def snake(name: str) -> str:
    """CamelCase and other spellings in snake_case: EngineSpeed → engine_speed,
    ABSActive → abs_active, Sig-1 → sig_1."""
    words = _WORD_BREAK.sub("_", name)
    cleaned = "".join(c if c.isalnum() else "_" for c in words).lower()
    return re.sub("_+", "_", cleaned).strip("_") or "x"


def distinct(name: str, taken: set[str], classes: set[str]) -> str:
    """`name` (snake_case already) as a usable name not taken whose Python class name
    (CamelCase: s5 and s5_ are both S5) no other message or enum has; both recorded."""
    found = usable(name, taken)
    n = 2
    while camel(found) in classes:
        found = usable(f"{name}{n}", taken)
        n += 1
    taken.add(found)
    classes.add(camel(found))
    return found
