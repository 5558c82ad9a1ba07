"""IEEE 754 binary32 values as the f32 codecs see them: the floats nearest a range's
bound on its inner side (an integer or decimal bound may fall between two), which C
compares a float member with exactly, as Python compares the decoded value with the
bound itself."""
from __future__ import annotations

import math
import struct
from typing import Union

LARGEST = 3.4028234663852886e38


def bits_of(value: float) -> int:
    """The bit pattern of `value` as a binary32 (rounded to the nearest one)."""
    return struct.unpack(">I", struct.pack(">f", value))[0]


def nearest(value: float) -> float:
    """The binary32 value nearest `value` (`value` within the finite range)."""
    return struct.unpack(">f", struct.pack(">f", value))[0]


def _below(value: float) -> float:
    """The float just below the float `value`."""
    bits = struct.unpack(">I", struct.pack(">f", value))[0]
    if value > 0:
        bits -= 1
    elif value == 0:
        bits = 0x80000001  # the negative subnormal nearest zero
    else:
        bits += 1
    return struct.unpack(">f", struct.pack(">I", bits))[0]


def at_most(value: Union[int, float]) -> float:
    """The largest float not above `value` (-inf when no finite one is)."""
    if value >= LARGEST:
        return LARGEST
    if value < -LARGEST:
        return -math.inf
    near = nearest(float(value))  # one of the two floats around value (the int may round twice)
    return near if near <= value else _below(near)


def at_least(value: Union[int, float]) -> float:
    """The smallest float not below `value` (+inf when no finite one is)."""
    return -at_most(-value) + 0.0  # +0.0, not -0.0, for a bound of 0


def literal(value: float) -> str:
    """A C float literal of exactly the float `value`: its shortest double spelling
    rounds to the same float, being far nearer to it than half a float's step."""
    return repr(value) + "f"
