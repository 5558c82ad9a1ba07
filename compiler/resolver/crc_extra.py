"""MAVLink's CRC_EXTRA derived from a message's definition
(https://mavlink.io/en/guide/serialization.html#crc_extra), for a CRC with
`extra: mavlink`: the X.25 CRC (CRC-16/MCRF4XX) of the message's MAVLink name and a
space, then of each base field in wire order, its MAVLink type and a space, its name
and a space, and for an array its length as one byte; the extension fields take no
part. The byte is the CRC's two bytes XORed.

A message's MAVLink name is its name in upper case and a field's its name, unless
`mavlink_name` says otherwise (a name codeword refuses, renamed on import)."""
from __future__ import annotations

from typing import Optional

from ..model import Field

# (kind, bits) → MAVLink's type; bytes are MAVLink's char (an array beyond one byte)
TYPES = {("uint", 8): "uint8_t", ("uint", 16): "uint16_t", ("uint", 32): "uint32_t", ("uint", 64): "uint64_t",
         ("int", 8): "int8_t", ("int", 16): "int16_t", ("int", 32): "int32_t", ("int", 64): "int64_t",
         ("float", 32): "float", ("float", 64): "double"}


def mavlink_type(f: Field) -> Optional[tuple[str, int]]:
    """(MAVLink type, array length or 0) of a field as MAVLink would declare it; None where
    MAVLink has no such field (a group, a bit field, a text, an array whose count varies)."""
    if f.varies or f.kind == "group" or f.start_bit is not None:
        return None
    if f.kind == "bytes":
        return ("char", 0 if f.length == 1 else f.length) if f.length else None
    e = f.element
    name = TYPES.get((e.kind, e.bits))
    if name is None or (f.count or 0) > 255:  # MAVLink writes an array's length in one byte
        return None
    return name, f.count or 0


def definition(message_name: str, fields: list[tuple[str, str, int]]) -> bytes:
    """The bytes MAVLink hashes: the message's name, then (type, name, array length) of
    each base field in wire order."""
    out = f"{message_name} ".encode("ascii")
    for type_name, name, length in fields:
        out += f"{type_name} {name} ".encode("ascii")
        if length:
            out += bytes([length])
    return out


def x25(data: bytes, crc: int = 0xFFFF) -> int:
    """MAVLink's crc_accumulate over `data` (CRC-16/MCRF4XX, a byte at a time)."""
    for byte in data:
        tmp = (byte ^ crc) & 0xFF
        tmp = (tmp ^ (tmp << 4)) & 0xFF
        crc = ((crc >> 8) ^ (tmp << 8) ^ (tmp << 3) ^ (tmp >> 4)) & 0xFFFF
    return crc


def derived(message_name: str, fields: list[tuple[str, str, int]]) -> int:
    value = x25(definition(message_name, fields))
    return (value & 0xFF) ^ (value >> 8)
