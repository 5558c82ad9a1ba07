"""Length fields that count a range of the frame rather than the payload alone, in
frames whose size changes. CRSF counts from the type byte to the CRC (the payload
and the two bytes around it); another link counts from the length byte itself to
the end, and a third counts the payload less one (`adjust: -1`). In each a counted
field makes the size vary, and the length field says the bytes sent. Frames worked
by hand; CRC-8/DVB-S2 (polynomial 0xD5) computed below bit by bit and checked on
the catalogue's check value."""
from __future__ import annotations

import pytest

from schema_in_a_test import conformance_on_host_and_avr, load, render, run_c

CRSF = """codeword: 1
protocol: crsfish
title: t
source: s
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: sync, type: u8, const: 0xc8}
    - {name: len, type: u8, length_of: {from: type, to: crc}}
    - {name: type, type: u8, dispatch: true}
    - {payload: true}
    - {name: crc, type: u8, checksum: {algorithm: CRC-8/DVB-S2, covers: {from: type, to: payload}}}
messages:
  battery:
    id: 0x08
    fields:
      - {name: voltage, type: u16}
      - {name: current, type: u16}
      - {name: used, type: u24}
      - {name: remaining, type: u8}
  text:
    id: 0x21
    fields:
      - {name: n, type: u8}
      - {name: chars, type: bytes, length: {from: n}, max_length: 16}
"""

SELF = """codeword: 1
protocol: selfish
title: t
source: s
framing:
  kind: bytes
  byte_order: little
  layout:
    - {name: sync, type: u8, const: 0x7e}
    - {name: len, type: u16, length_of: {from: len, to: sum}}
    - {name: id, type: u8, dispatch: true}
    - {payload: true}
    - {name: sum, type: u8, checksum: {algorithm: sum, covers: {from: len, to: payload}}}
messages:
  samples:
    id: 1
    fields:
      - {name: n, type: u8}
      - {name: v, type: i16, count: {from: n}, max_count: 3}
"""

LESS_ONE = """codeword: 1
protocol: lessone
title: t
source: s
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: id, type: u8, dispatch: true}
    - {name: len, type: u8, length_of: {from: payload, to: payload, adjust: -1}}
    - {payload: true}
messages:
  note:
    id: 2
    fields:
      - {name: flags, type: u8}
      - {name: code, type: u16, present_if: {field: flags, equals: 1}}
"""


def crc8_dvb_s2(data: bytes) -> int:
    crc = 0
    for byte in data:
        crc ^= byte
        for _ in range(8):
            crc = ((crc << 1) ^ 0xD5) & 0xFF if crc & 0x80 else (crc << 1) & 0xFF
    return crc


def crsf(body: str) -> bytes:
    data = bytes.fromhex(body)  # type and payload
    return bytes([0xC8, len(data) + 1]) + data + bytes([crc8_dvb_s2(data)])


def test_the_crc_matches_the_catalogue_check_value():
    assert crc8_dvb_s2(b"123456789") == 0xBC


@pytest.fixture(scope="module")
def modules(tmp_path_factory):
    out = {}
    for name, schema in (("crsfish", CRSF), ("selfish", SELF), ("lessone", LESS_ONE)):
        where = tmp_path_factory.mktemp(name)
        render(where, name, schema)
        out[name] = (where, load(where / f"{name}.py"))
    return out


def test_crsf_counts_type_payload_and_crc(modules):
    mod = modules["crsfish"][1]
    battery = mod.Battery(voltage=0x00A8, current=0x000F, used=0x0004D2, remaining=100)
    assert mod.encode(battery) == crsf("08 00a8 000f 0004d2 64")  # len 0x0a, as CRSF sends it
    assert mod.encode(mod.Text(chars=b"hi")) == crsf("21 02 6869")  # len 5
    assert mod.encode(mod.Text(chars=b"")) == crsf("21 00")  # len 3
    assert mod.decode(crsf("21 02 6869")) == mod.Text(chars=b"hi")
    with pytest.raises(mod.DecodeError) as e:  # the length byte says one more than was sent
        frame = bytearray(crsf("21 02 6869"))
        frame[1] += 1
        mod.decode(bytes(frame))
    assert e.value.rule == "length"


def test_a_length_that_counts_itself_and_the_sum(modules):
    mod = modules["selfish"][1]
    # len (2) + id + n + 2 × 2 + sum = 9: 09 00; the sum covers len .. payload
    body = bytes.fromhex("0900 01 02 ffff 0200")
    assert mod.encode(mod.Samples(v=[-1, 2])) == b"\x7e" + body + bytes([sum(body) & 0xFF])
    empty = bytes.fromhex("0500 01 00")
    assert mod.encode(mod.Samples(v=[])) == b"\x7e" + empty + bytes([sum(empty) & 0xFF])


def test_an_adjusted_length(modules):
    mod = modules["lessone"][1]
    assert mod.encode(mod.Note(flags=1, code=0x1234)) == bytes.fromhex("02 02 01 1234")  # 3 bytes, less one
    assert mod.encode(mod.Note(flags=0)) == bytes.fromhex("02 00 00")
    assert mod.decode(bytes.fromhex("02 00 00")) == mod.Note(flags=0)


def test_c_agrees(modules):
    where = modules["crsfish"][0]
    driver = r"""
#include <stdio.h>
#include "crsfish.h"
int main(void) {
    crsfish_text_t m = {0};
    uint8_t out[32];
    int n, i;
    m.chars[0] = 0x68; m.chars[1] = 0x69; m.chars_count = 2;
    n = crsfish_text_encode(&m, out, sizeof out);
    for (i = 0; i < n; i++) printf("%02x", out[i]);
    printf("\n%d\n", crsfish_text_decode(out, (size_t)n, &m));
    return 0;
}
"""
    assert run_c(where, driver) == [crsf("21 02 6869").hex(), "0"]


@pytest.mark.parametrize("name, schema", [("crsfish", CRSF), ("selfish", SELF), ("lessone", LESS_ONE)])
def test_conformance_vectors_on_the_host_and_on_atmega32_under_simavr(tmp_path, name, schema):
    host, avr = conformance_on_host_and_avr(tmp_path, name, schema)
    assert host > 50 and avr > 50
