"""CAN identifiers and data lengths, as every part of codeword names them."""
from __future__ import annotations

EXTENDED_FLAG = 1 << 31  # SocketCAN's CAN_EFF_FLAG
MAX_STANDARD_ID = 0x7FF
MAX_EXTENDED_ID = 0x1FFFFFFF
CLASSIC_LENGTHS = tuple(range(9))
# CAN FD data lengths: the DLC codes 9..15 stand for 12..64 bytes
FD_LENGTHS = CLASSIC_LENGTHS + (12, 16, 20, 24, 32, 48, 64)
HEADER_BYTES = 5  # the identifier and the data length before the data


def lengths(can: str) -> tuple[int, ...]:
    """The data lengths a CAN frame may have."""
    return FD_LENGTHS if can == "fd" else CLASSIC_LENGTHS


def identifier(can_id: int) -> tuple[int, bool]:
    """The arbitration identifier and whether it is extended, from a 32-bit can_id."""
    return can_id & MAX_EXTENDED_ID, bool(can_id & EXTENDED_FLAG)

