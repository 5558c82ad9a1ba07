"""A checksum over bytes that is narrower than a byte (a parity bit, a 4-bit sum)
and shares its byte with other fields: the codecs put it into its own bits and
compute it over the covered bytes only. Frames below are worked out by hand."""
from __future__ import annotations

from pathlib import Path

import schema_in_a_test as scratch

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

DRIVER = """\
#include <stdio.h>
#include "bcb.h"

static void show(bcb_message_t *m)
{
    uint8_t buf[8] = {0};
    int n = bcb_encode(m, buf, sizeof buf);
    int i;
    for (i = 0; i < n; i++) {
        printf("%s%02x", i ? " " : "", (unsigned)buf[i]);
    }
    printf(" %s\\n", bcb_decode(buf, (size_t)n, 0, m) == CW_OK ? "ok" : "bad");
}

int main(void)
{
    bcb_message_t m;
    m.kind = BCB_MSG_ODD;
    m.as.odd.x = 0x0f; m.as.odd.flag = 0; show(&m);
    m.kind = BCB_MSG_ODD;
    m.as.odd.x = 0x0f; m.as.odd.flag = 1; show(&m);
    m.kind = BCB_MSG_ODD;
    m.as.odd.x = 0x0e; m.as.odd.flag = 1; show(&m);
    m.kind = BCB_MSG_NIBBLE;
    m.as.nibble.x = 0x10; m.as.nibble.y = 9; show(&m);
    m.kind = BCB_MSG_NIBBLE;
    m.as.nibble.x = 0xff; m.as.nibble.y = 0; show(&m);
    return 0;
}
"""


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


def test_c_agrees(tmp_path: Path):
    where = scratch.render(tmp_path, "bcb", SCHEMA)
    assert scratch.run_c(where, DRIVER) == [f"{wire} ok" for _, _, wire in FRAMES]


# A wrong checksum field is refused with the checksum error, in C as in Python.
REJECTED = ["57 02 0f 00",  # parity bit cleared
            "57 02 0e c0",  # parity bit set over four ones
            "57 03 10 49"]  # sum 4 instead of 3

REJECT_DRIVER = """\
#include <stdio.h>
#include "bcb.h"

int main(void)
{
    static const uint8_t frames[][4] = {{0x57, 0x02, 0x0f, 0x00}, {0x57, 0x02, 0x0e, 0xc0},
                                        {0x57, 0x03, 0x10, 0x49}};
    bcb_message_t m;
    size_t i;
    for (i = 0; i < sizeof frames / sizeof frames[0]; i++) {
        int rc = bcb_decode(frames[i], 4u, 0, &m);
        printf("%s\\n", rc == CW_ERR_CHECKSUM ? "checksum" : rc == CW_OK ? "ok" : "other");
    }
    return 0;
}
"""


def test_a_wrong_narrow_checksum_is_refused(tmp_path: Path):
    where = scratch.render(tmp_path, "bcb", SCHEMA)
    assert scratch.run_c(where, REJECT_DRIVER) == ["checksum"] * len(REJECTED)
    bcb = scratch.load(where / "bcb.py")
    for wire in REJECTED:
        try:
            bcb.decode(bytes.fromhex(wire))
        except bcb.DecodeError as exc:
            assert exc.rule == "checksum", wire
        else:
            raise AssertionError(f"{wire} was accepted")


# Frames over 4 bytes, a narrow CRC and a whole-byte sum, an odd parity beside an even one.
LONG = """\
codeword: 1
protocol: bcl
title: narrow checksums over bytes in longer frames
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
    id: 4
    fields:
      - {name: x, type: u16}
      - {name: z, type: u16}
      - {name: flag, type: u1}
      - {name: p, type: u1, checksum: {algorithm: parity, parity: odd, over: bytes, covers: {from: kind, to: z}}}
      - {name: pad, type: u6, reserved: true}
  even:
    id: 5
    fields:
      - {name: x, type: u16}
      - {name: z, type: u16}
      - {name: e, type: u1, checksum: {algorithm: parity, over: bytes, covers: {from: kind, to: z}}}
      - {name: flag, type: u1}
      - {name: pad, type: u6, reserved: true}
  check:
    id: 6
    fields:
      - {name: data, type: bytes, length: 9}
      - name: c
        type: u4
        checksum: {algorithm: crc, width: 4, poly: 0x3, init: 0, refin: true, refout: true, xorout: 0,
                   covers: {from: data, to: data}}
      - {name: y, type: u4}
  small:
    id: 8
    fields:
      - {name: x, type: u8}
      - name: c
        type: u4
        checksum: {algorithm: crc, width: 4, poly: 0x3, init: 0, refin: true, refout: true, xorout: 0,
                   covers: {from: x, to: x}}
      - {name: y, type: u4}
  total:
    id: 7
    fields:
      - {name: x, type: u8}
      - {name: s, type: u8, checksum: {algorithm: sum, over: bytes, covers: {from: kind, to: x}}}
"""

# odd: odd parity over kind, x, z: 04 01 02 03 04 hold 1+1+1+2+1 = 6 ones -> p = 1;
#   z = 0x0307: 8 ones -> p = 1; z = 0x0305: 7 ones -> p = 0. Last byte flag<<7 | p<<6.
# even: 05 01 02 03 04 hold 7 ones -> e = 1; 05 00 00 00 00: 2 ones -> e = 0. e<<7 | flag<<6.
# check: CRC-4/G-704 (the parameters above) of "123456789" is its catalogue check value 7.
# small: CRC-4/G-704 of the one byte 01: reflected poly 0xC, eight shifts of 01 end at 7.
# total: 07 + f0 = 0xf7; 07 + fa = 0x101, mod 256 = 0x01.
LONG_FRAMES = [
    ("Odd", dict(x=0x0102, z=0x0304, flag=1), "57 04 01 02 03 04 c0"),
    ("Odd", dict(x=0x0102, z=0x0307, flag=0), "57 04 01 02 03 07 40"),
    ("Odd", dict(x=0x0102, z=0x0305, flag=1), "57 04 01 02 03 05 80"),
    ("Even", dict(x=0x0102, z=0x0304, flag=1), "57 05 01 02 03 04 c0"),
    ("Even", dict(x=0, z=0, flag=1), "57 05 00 00 00 00 40"),
    ("Check", dict(data=b"123456789", y=5), "57 06 31 32 33 34 35 36 37 38 39 75"),
    ("Small", dict(x=1, y=0xA), "57 08 01 7a"),
    ("Total", dict(x=0xF0), "57 07 f0 f7"),
    ("Total", dict(x=0xFA), "57 07 fa 01"),
]

LONG_DRIVER = """\
#include <stdio.h>
#include <string.h>
#include "bcl.h"

static void show(bcl_message_t *m)
{
    uint8_t buf[16] = {0};
    int n = bcl_encode(m, buf, sizeof buf);
    int i;
    for (i = 0; i < n; i++) {
        printf("%s%02x", i ? " " : "", (unsigned)buf[i]);
    }
    printf(" %s", bcl_decode(buf, (size_t)n, 0, m) == CW_OK ? "ok" : "bad");
    /* one bit of the checksum flipped */
    buf[n - 1] = (uint8_t)(buf[n - 1] ^ (m->kind == BCL_MSG_TOTAL ? 0x01u
                                         : m->kind == BCL_MSG_EVEN ? 0x80u : 0x40u));
    printf(" %s\\n", bcl_decode(buf, (size_t)n, 0, m) == CW_ERR_CHECKSUM ? "checksum" : "missed");
}

int main(void)
{
    bcl_message_t m;
    m.kind = BCL_MSG_ODD;
    m.as.odd.x = 0x0102; m.as.odd.z = 0x0304; m.as.odd.flag = 1; show(&m);
    m.kind = BCL_MSG_ODD;
    m.as.odd.x = 0x0102; m.as.odd.z = 0x0307; m.as.odd.flag = 0; show(&m);
    m.kind = BCL_MSG_ODD;
    m.as.odd.x = 0x0102; m.as.odd.z = 0x0305; m.as.odd.flag = 1; show(&m);
    m.kind = BCL_MSG_EVEN;
    m.as.even.x = 0x0102; m.as.even.z = 0x0304; m.as.even.flag = 1; show(&m);
    m.kind = BCL_MSG_EVEN;
    m.as.even.x = 0; m.as.even.z = 0; m.as.even.flag = 1; show(&m);
    m.kind = BCL_MSG_CHECK;
    memcpy(m.as.check.data, "123456789", 9); m.as.check.y = 5; show(&m);
    m.kind = BCL_MSG_SMALL;
    m.as.small.x = 1; m.as.small.y = 0xa; show(&m);
    m.kind = BCL_MSG_TOTAL;
    m.as.total.x = 0xf0; show(&m);
    m.kind = BCL_MSG_TOTAL;
    m.as.total.x = 0xfa; show(&m);
    return 0;
}
"""


def test_python_long_frames(tmp_path: Path):
    bcl = scratch.load(scratch.render(tmp_path, "bcl", LONG) / "bcl.py")
    for cls, values, wire in LONG_FRAMES:
        obj = getattr(bcl, cls)(**values)
        assert bcl.encode(obj).hex(" ") == wire
        assert bcl.decode(bytes.fromhex(wire)) == obj


def test_c_long_frames(tmp_path: Path):
    where = scratch.render(tmp_path, "bcl", LONG)
    assert scratch.run_c(where, LONG_DRIVER) == [f"{wire} ok checksum" for _, _, wire in LONG_FRAMES]
