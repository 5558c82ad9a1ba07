"""A checksum over bytes that is narrower than a byte (a parity bit, a 4-bit sum)
and shares its byte with other fields: the codecs put it into its own bits and
compute it over the covered bytes only. Frames below are worked out by hand."""
from __future__ import annotations

from pathlib import Path

import scratch

SCHEMA = """\
codeword: 1
protocol: bcb
title: narrow checksums over bytes
source: hand-written
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: sync, type: u8, const: 0x57}
    - {name: kind, type: u8, dispatch: true}
    - {payload: true}
messages:
  odd:
    id: 2
    fields:
      - {name: x, type: u8}
      - {name: flag, type: u1}
      - {name: p, type: u1, checksum: {algorithm: parity, over: bytes, covers: {from: kind, to: x}}}
      - {name: pad, type: u6, reserved: true}
  nibble:
    id: 3
    fields:
      - {name: x, type: u8}
      - {name: s, type: u4, checksum: {algorithm: sum, over: bytes, covers: {from: kind, to: x}}}
      - {name: y, type: u4}
"""

# odd: parity over kind, x (sync 0x57 has five ones and is not covered):
#   x=0x0f: 02 0f hold 1 + 4 = 5 ones, even parity bit 1 -> byte 3 = flag<<7 | 1<<6
#   x=0x0e: 4 ones, bit 0
# nibble: s = (03 + x) % 16 in the high nibble, y in the low one:
#   x=0x10: 0x13 % 16 = 3 -> 0x3y
FRAMES = [
    ("Odd", dict(x=0x0F, flag=0), "57 02 0f 40"),
    ("Odd", dict(x=0x0F, flag=1), "57 02 0f c0"),
    ("Odd", dict(x=0x0E, flag=1), "57 02 0e 80"),
    ("Nibble", dict(x=0x10, y=9), "57 03 10 39"),
    ("Nibble", dict(x=0xFF, y=0), "57 03 ff 20"),
]

def test_python_puts_a_narrow_checksum_into_its_bits(tmp_path: Path):
    bcb = scratch.load(scratch.render(tmp_path, "bcb", SCHEMA) / "bcb.py")
    for cls, values, wire in FRAMES:
        obj = getattr(bcb, cls)(**values)
        assert bcb.encode(obj).hex(" ") == wire
        assert bcb.decode(bytes.fromhex(wire)) == obj
    bad = bytearray.fromhex("57 02 0f 00")  # parity bit cleared
    try:
        bcb.decode(bytes(bad))
    except bcb.DecodeError as exc:
        assert (exc.field, exc.rule) == ("p", "checksum")
    else:
        raise AssertionError("a wrong parity bit was accepted")
