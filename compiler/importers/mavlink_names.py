"""MAVLink's UPPER_CASE names mapped to codeword names, deterministically: lower case;
a name codeword refuses (a keyword, a name the generated code or the framing uses,
too long, starting with a digit) gets a trailing `_` or is shortened with a hash, and
the schema says the original in a comment."""
from __future__ import annotations

import zlib

from ..names import GENERATED_CLASSES, MAX_NAME_LENGTH, camel, name_problem, protocol_name_problem


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


def protocol_name(dialect: str) -> str:
    """common.xml → common; a dialect whose name is a Python module or C header (test) → mavlink_test."""
    name = "".join(c if c.isalnum() else "_" for c in dialect.lower())
    return name if not protocol_name_problem(name) else usable(f"mavlink_{name}")


def member_name(entry: str, enum: str, taken: set) -> str:
    """An enum entry's name without its enum's prefix (MAV_TYPE_QUADROTOR → quadrotor), or
    its whole name where the rest would not do (GPS_FIX_TYPE_3D_FIX → gps_fix_type_3d_fix)."""
    prefix = enum + "_"
    short = entry[len(prefix):].lower() if entry.startswith(prefix) and len(entry) > len(prefix) else ""
    if short and not short[:1].isdigit() and not name_problem(short) and short not in taken:
        return short
    return usable(entry.lower(), taken)
