"""Conditional fields and a counted array of groups in the middle of a payload. `gps`
is sent when `parts` has its gps flag, `volts` when it has battery, `extra` when `kind`
is run; `pts` holds `n` points (0..3) and fields follow it. A frame leaves out what
is absent, the length byte counts the payload bytes sent and the CRC covers them.
Frames worked by hand: sync a5, id 01, length, payload (little-endian), CRC-16/MODBUS
computed below by the standard bitwise algorithm (checked on a published frame)."""
from __future__ import annotations

import dataclasses

import pytest

from schema_in_a_test import conformance_on_host_and_avr, load, render, run_c

SCHEMA = """codeword: 1
protocol: tele
title: t
source: s
framing:
  kind: bytes
  byte_order: little
  layout:
    - {name: sync, type: u8, const: 0xa5}
    - {name: id, type: u8, dispatch: true}
    - {name: len, type: u8, length_of: {from: payload, to: payload}}
    - {payload: true}
    - {name: crc, type: u16, checksum: {algorithm: CRC-16/MODBUS, covers: {from: id, to: payload}}}
flags:
  parts:
    type: u8
    bits:
      - {name: gps, bit: 0}
      - {name: battery, bit: 2}
enums:
  mode:
    type: u8
    values:
      - {name: idle, value: 0}
      - {name: run, value: 3}
types:
  fix:
    type: group
    fields:
      - {name: lat, type: i16}
      - {name: lon, type: i16}
  point:
    type: group
    fields:
      - {name: x, type: i8, range: [-100, 100]}
      - {name: m, type: u8, enum: mode}
messages:
  status:
    id: 1
    fields:
      - {name: parts, type: u8, flags: parts}
      - {name: n, type: u8}
      - {name: gps, type: fix, present_if: {field: parts, has: gps}}
      - {name: pts, type: point, count: {from: n}, max_count: 3}
      - {name: volts, type: u16, present_if: {field: parts, has: battery}, range: [0, 20000]}
      - {name: kind, type: u8, enum: mode}
      - {name: extra, type: u8, present_if: {field: kind, equals: run}}
      - {name: tail, type: u8}
"""


def crc16_modbus(data: bytes) -> int:
    """CRC-16/MODBUS, bit by bit: reflected polynomial 0xA001, initial 0xFFFF."""
    crc = 0xFFFF
    for byte in data:
        crc ^= byte
        for _ in range(8):
            crc = (crc >> 1) ^ 0xA001 if crc & 1 else crc >> 1
    return crc


def frame(payload: str) -> bytes:
    body = bytes([0x01, len(bytes.fromhex(payload))]) + bytes.fromhex(payload)
    return b"\xa5" + body + crc16_modbus(body).to_bytes(2, "little")


# parts, n, [gps lat lon], [pts: x m]*, [volts], kind, [extra], tail
FULL = "05 01  fe ff 2c 01  ff 03  e0 2e  03 07  09"  # gps, one point, battery, run
EMPTY = "00 00  00  09"  # nothing optional, no point, idle
MIDDLE = "04 02  9c 00 64 03  10 27  00  09"  # battery only, two points, idle


def test_the_crc_matches_a_published_modbus_frame():
    assert crc16_modbus(bytes.fromhex("11 03 06 AE 41 56 52 43 40")) == 0xAD49


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    where = tmp_path_factory.mktemp("tele")
    render(where, "tele", SCHEMA)
    return where, load(where / "tele.py")


def messages(mod):
    Parts, Mode, Pt = mod.Parts, mod.Mode, mod.StatusPts
    return [
        (FULL, mod.Status(parts=Parts.gps | Parts.battery, gps=mod.StatusGps(lat=-2, lon=300),
                          pts=[Pt(x=-1, m=Mode.run)], volts=12000, kind=Mode.run, extra=7, tail=9)),
        (EMPTY, mod.Status(parts=Parts(0), gps=None, pts=[], volts=None, kind=Mode.idle, extra=None, tail=9)),
        (MIDDLE, mod.Status(parts=Parts.battery, gps=None, pts=[Pt(x=-100, m=Mode.idle), Pt(x=100, m=Mode.run)],
                            volts=10000, kind=Mode.idle, extra=None, tail=9)),
    ]


def test_python_sends_only_what_is_present(built):
    mod = built[1]
    for payload, message in messages(mod):
        assert mod.encode(message) == frame(payload)
        assert mod.decode(frame(payload)) == message


def test_python_refuses_a_value_its_condition_does_not_allow(built):
    mod = built[1]
    _, message = messages(mod)[1]
    with pytest.raises(mod.EncodeError) as e:
        mod.encode(dataclasses.replace(message, volts=5))  # battery flag not set
    assert (e.value.field, e.value.rule) == ("volts", "present")
    _, message = messages(mod)[0]
    with pytest.raises(mod.EncodeError) as e:
        mod.encode(dataclasses.replace(message, gps=None))  # gps flag set
    assert (e.value.field, e.value.rule) == ("gps", "present")


@pytest.mark.parametrize("payload, field, rule", [
    ("00 04  00  09", "n", "range"),  # four points, three at most
    ("00 01  96 00  00  09", "pts[0].x", "range"),  # a point sent is checked: x = -106
    ("00 01  00 05  00  09", "pts[0].m", "enum"),
    ("04 00  00  09", "volts", "length"),  # battery says two bytes follow: the frame is short
    ("00 00  00  09 09", "volts", "length"),  # a byte too many
])
def test_python_refuses_frames_that_break_the_counts_and_checks(built, payload, field, rule):
    mod = built[1]
    with pytest.raises(mod.DecodeError) as e:
        mod.decode(frame(payload))
    assert e.value.rule == rule
    assert e.value.field in (field, "len", "extra")


def test_an_absent_point_is_not_checked(built):
    """Points past the count read as zeros, which m = 0 (idle) and x = 0 pass anyway; the
    condition on them is tested by the point whose enum a zero would break: none here,
    so this checks the one-point frame reads one point back."""
    mod = built[1]
    assert len(mod.decode(frame(FULL)).pts) == 1


def test_c_agrees(built):
    cases = "".join(f"    {{ static const uint8_t f[] = {{{', '.join(f'0x{b:02x}' for b in frame(p))}}}; check(f, sizeof f); }}\n"
                    for p in (FULL, EMPTY, MIDDLE))
    driver = r"""
#include <stdio.h>
#include <string.h>
#include "tele.h"
static void check(const uint8_t *f, size_t len) {
    tele_status_t m;
    uint8_t out[64];
    int n, i;
    memset(&m, 0xee, sizeof m);
    n = tele_status_decode(f, len, &m);
    printf("%d %u %u", n, (unsigned)m.parts, (unsigned)m.pts_count);
    n = tele_status_encode(&m, out, sizeof out);
    printf(" %d %d\n", n, n == (int)len && memcmp(out, f, len) == 0);
    (void)i;
}
int main(void) {
""" + cases + r"""    return 0;
}
"""
    assert run_c(built[0], driver) == ["0 5 1 18 1", "0 0 0 9 1", "0 4 2 15 1"]


def test_c_fields_read_back(built):
    driver = r"""
#include <stdio.h>
#include "tele.h"
int main(void) {
    tele_status_t m = {0};
    uint8_t out[64];
    int n, i;
    m.parts = 5; m.gps.lat = -2; m.gps.lon = 300;
    m.pts_count = 1; m.pts[0].x = -1; m.pts[0].m = TELE_MODE_RUN;
    m.volts = 12000; m.kind = TELE_MODE_RUN; m.extra = 7; m.tail = 9;
    n = tele_status_encode(&m, out, sizeof out);
    for (i = 0; i < n; i++) printf("%02x", out[i]);
    printf("\n");
    return 0;
}
"""
    assert run_c(built[0], driver) == [frame(FULL).hex()]


def test_conformance_vectors_on_the_host_and_on_atmega32_under_simavr(tmp_path):
    """Every combination the vectors hold, damaged frames and streams: C agrees with
    Python on the host and on an 8-bit AVR."""
    host, avr = conformance_on_host_and_avr(tmp_path, "tele", SCHEMA)
    assert host > 50 and avr > 50


def test_an_error_names_the_bit_offset_in_the_frame_as_sent(built):
    """`kind` is byte 17 of the largest frame; with nothing optional sent it is byte 5."""
    mod = built[1]
    with pytest.raises(mod.DecodeError) as e:
        mod.decode(frame("00 00  05  09"))  # kind = 5: no such mode
    assert (e.value.field, e.value.rule, e.value.offset) == ("kind", "enum", 40)
