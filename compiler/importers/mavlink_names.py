"""MAVLink's UPPER_CASE names mapped to codeword names, deterministically: lower case;
a name codeword refuses (a keyword, a name the generated code or the framing uses,
too long, starting with a digit) gets a trailing `_` or is shortened with a hash, and
the schema says the original in a comment."""
from __future__ import annotations

from ..names import name_problem, protocol_name_problem
from .naming import usable


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
