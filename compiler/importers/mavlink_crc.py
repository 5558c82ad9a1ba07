"""CRC_EXTRA, MAVLink's hash of a message definition
(https://mavlink.io/en/guide/serialization.html#crc_extra): the X.25 CRC
(CRC-16/MCRF4XX) of the message name and a space, then of each base field in wire
order, its type and a space, its name and a space, and for an array its length as
one byte; the extension fields take no part. The byte is the CRC's two bytes XORed."""
from __future__ import annotations

from .mavlink_xml import XmlMessage


def x25_accumulate(crc: int, data: bytes) -> int:
    for byte in data:
        tmp = (byte ^ crc) & 0xFF
        tmp = (tmp ^ (tmp << 4)) & 0xFF
        crc = ((crc >> 8) ^ (tmp << 8) ^ (tmp << 3) ^ (tmp >> 4)) & 0xFFFF
    return crc


def crc_extra(message: XmlMessage) -> int:
    crc = x25_accumulate(0xFFFF, f"{message.name} ".encode("ascii"))
    for f in message.wire_fields:
        if f.extension:
            continue
        crc = x25_accumulate(crc, f"{f.type} {f.name} ".encode("ascii"))
        if f.array_length:
            crc = x25_accumulate(crc, bytes([f.array_length]))
    return (crc & 0xFF) ^ (crc >> 8)
