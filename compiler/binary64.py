"""IEEE 754 binary64 values as the f64 codecs see them: bit patterns, their
order as unsigned integers (cw_f64_order in codeword.h), and the doubles nearest
a range's bound on its inner side (an integer bound may fall between two)."""
from __future__ import annotations

import math
import struct
from typing import Union

LARGEST = 1.7976931348623157e308


def bits_of(value: float) -> int:
    """The bit pattern of `value`."""
    return struct.unpack(">Q", struct.pack(">d", value))[0]


def order_of(value: float) -> int:
    """`value`'s bits as an unsigned integer ordered as the values are (-0 as +0)."""
    bits = bits_of(value)
    if bits == 1 << 63:
        bits = 0
    return (~bits & ((1 << 64) - 1)) if bits >> 63 else bits | 1 << 63


def at_most(value: Union[int, float]) -> float:
    """The largest double not above `value` (-inf when no finite one is)."""
    if value > LARGEST:
        return LARGEST
    if value < -LARGEST:
        return -math.inf
    nearest = float(value)
    return nearest if nearest <= value else math.nextafter(nearest, -math.inf)


def at_least(value: Union[int, float]) -> float:
    """The smallest double not below `value` (+inf when no finite one is)."""
    return -at_most(-value) + 0.0  # +0.0, not -0.0, for a bound of 0
