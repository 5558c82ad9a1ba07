"""An enum with negative values on a signed field of a bit-packed protocol:
its members travel as two's complement in the field's bits. The generated
Python and C encoders write the frames worked out by hand below, and both
decoders read them back, refusing bit patterns that are no member (and a
negative constant that does not match).

`probe` is coded as one word in C; `wide`, with a little-endian field, as
raw values in an array: both C paths are exercised."""
from __future__ import annotations

from pathlib import Path

import pytest

import schema_in_a_test as scratch


SCHEMA = """\
codeword: 1
protocol: senum
title: signed enums
source: hand-written
enums:
  trend:
    type: i2
    values: [{name: down, value: -1}, {name: flat, value: 0}, {name: up, value: 1}]
  level:
    type: i8
    values: [{name: low, value: -100}, {name: mid, value: 5}, {name: high, value: 100}]
  far:
    type: i16
    values: [{name: west, value: -300}, {name: here, value: 0}, {name: east, value: 300}]
framing:
  kind: bits
  max_bits: 32
  byte_order: big
messages:
  probe:
    fields:
      - {name: head, type: u2, dispatch: true, const: 1}
      - {name: t, type: i2, enum: trend}
      - {name: k, type: i4, const: -2}
      - {name: b, type: i8, enum: level}
      - {name: cs, type: u8, checksum: {algorithm: sum, over: fields}}
  wide:
    fields:
      - {name: head, type: u2, dispatch: true, const: 2}
      - {name: t, type: i2, enum: trend}
      - {name: pad, type: u4, reserved: true}
      - {name: w, type: i16, enum: far, byte_order: little}
      - {name: cs, type: u8, checksum: {algorithm: sum, over: fields}}
"""

# Bits MSB first; cs = (sum of the other fields' raw wire values) mod 256.
# probe: head 01, t, k = -2 = 1110, then b and cs bytes.
#   down/low:  01 11 1110 = 7e, -100 = 9c, cs 1+3+14+156 = 174 = ae
#   up/high:   01 01 1110 = 5e, 100 = 64,  cs 1+1+14+100 = 116 = 74
#   flat/mid:  01 00 1110 = 4e, 5 = 05,    cs 1+0+14+5 = 20 = 14
# wide: head 10, t, pad 0000, w (16 bits, low byte first), cs.
#   down/west: 10 11 0000 = b0, -300 = fed4 sent d4 fe,
#              cs 2+3+0+65236 = 65241 = 254*256 + 217 -> d9
#   up/east:   10 01 0000 = 90, 300 = 012c sent 2c 01, cs 2+1+300 = 303 -> 2f
GOOD = {
    "7e 9c ae": ("probe", "down", "low"),
    "5e 64 74": ("probe", "up", "high"),
    "4e 05 14": ("probe", "flat", "mid"),
    "b0 d4 fe d9": ("wide", "down", "west"),
    "90 2c 01 2f": ("wide", "up", "east"),
}
# Each with a correct checksum, so the named check is what fails.
BAD = {
    "6e 05 16": "enum",  # t = 10 = -2: no trend; cs 1+2+14+5 = 22
    "7e 9d af": "enum",  # b = 9d = -99: no level; cs 1+3+14+157 = 175
    "72 9c a2": "const",  # k = 0010 = 2, not -2; cs 1+3+2+156 = 162
    "7e 9c ad": "checksum",
    "b0 d5 fe da": "enum",  # w = fed5 = -299: no far; cs 65242 mod 256 = 218
}

DRIVER = """\
#include <stdio.h>
#include "senum.h"

static void show(const char *hex, const uint8_t *frame, size_t len)
{
    senum_message_t m;
    int rc = senum_decode(frame, len, &m);
    if (rc != CW_OK) {
        printf("%s error %s\\n", hex, cw_error_name(rc));
    } else if (m.kind == SENUM_MSG_PROBE) {
        printf("%s probe %d %d\\n", hex, (int)m.as.probe.t, (int)m.as.probe.b);
    } else {
        printf("%s wide %d %d\\n", hex, (int)m.as.wide.t, (int)m.as.wide.w);
    }
}

static void encode(const senum_message_t *m)
{
    uint8_t buf[SENUM_MAX_FRAME];
    int n = senum_encode(m, buf, sizeof buf);
    int i;
    printf("encoded");
    for (i = 0; i < n; i++) {
        printf(" %02x", (unsigned)buf[i]);
    }
    if (n < 0) {
        printf(" error %s", cw_error_name(n));
    }
    printf("\\n");
}

int main(void)
{
    senum_message_t m;
FRAMES
    m.kind = SENUM_MSG_PROBE;
    m.as.probe.t = SENUM_TREND_DOWN;
    m.as.probe.b = SENUM_LEVEL_LOW;
    encode(&m);
    m.as.probe.t = -2;
    encode(&m);
    m.kind = SENUM_MSG_WIDE;
    m.as.wide.t = SENUM_TREND_DOWN;
    m.as.wide.w = SENUM_FAR_WEST;
    encode(&m);
    m.as.wide.w = -299;
    encode(&m);
    return 0;
}
"""

VALUES = {"down": -1, "flat": 0, "up": 1, "low": -100, "mid": 5, "high": 100,
          "west": -300, "here": 0, "east": 300}


@pytest.fixture(scope="module")
def built(tmp_path_factory) -> Path:
    return scratch.render(tmp_path_factory.mktemp("senum"), "senum", SCHEMA)


@pytest.fixture(scope="module")
def senum(built):
    return scratch.load(built / "senum.py")


def test_python_encodes_and_decodes_negative_members(senum):
    for hex_, (kind, *names) in GOOD.items():
        frame = bytes.fromhex(hex_)
        got = senum.decode(frame)
        if kind == "probe":
            want = senum.Probe(t=senum.Trend[names[0]], b=senum.Level[names[1]])
        else:
            want = senum.Wide(t=senum.Trend[names[0]], w=senum.Far[names[1]])
        assert got == want, hex_
        assert [m.value for m in (got.t, got.b if kind == "probe" else got.w)] == \
            [VALUES[n] for n in names]
        assert senum.encode(want) == frame, hex_


def test_python_refuses_what_is_no_member(senum):
    for hex_, rule in BAD.items():
        with pytest.raises(senum.DecodeError) as err:
            senum.decode(bytes.fromhex(hex_))
        assert err.value.rule == rule, hex_


def test_c_encodes_and_decodes_negative_members(built):
    frames = scratch.show_calls([*GOOD, *BAD])
    lines = scratch.run_c(built, DRIVER.replace("FRAMES", frames), ("-Wtype-limits",))
    want = []
    for hex_, (kind, *names) in GOOD.items():
        want.append(f"{hex_} {kind} {VALUES[names[0]]} {VALUES[names[1]]}")
    want += [f"{hex_} error {rule}" for hex_, rule in BAD.items()]
    want += ["encoded 7e 9c ae", "encoded error enum",
             "encoded b0 d4 fe d9", "encoded error enum"]
    assert lines == want
