"""Arrays and bytes that fill the rest of the payload (`to_end: true` in a bytes
framing): the frame's size says how many elements were sent. Frames worked by hand:
sync 55, id, the length byte (payload bytes sent), payload (big-endian), end byte aa."""
from __future__ import annotations

import pytest

from schema_in_a_test import conformance_on_host_and_avr, load, render, run_c

SCHEMA = """codeword: 1
protocol: rest
title: t
source: s
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: sync, type: u8, const: 0x55}
    - {name: id, type: u8, dispatch: true}
    - {name: len, type: u8, length_of: {from: payload, to: payload}}
    - {payload: true}
    - {name: end, type: u8, const: 0xaa}
types:
  pair:
    type: group
    fields:
      - {name: a, type: u8, range: [0, 100]}
      - {name: b, type: i8}
messages:
  registers:
    id: 1
    fields:
      - {name: start, type: u16}
      - {name: values, type: u16, to_end: true, max_count: 4}
  blob:
    id: 2
    fields:
      - {name: tag, type: u8}
      - {name: data, type: bytes, to_end: true, max_length: 5}
  pairs:
    id: 3
    fields:
      - {name: pts, type: pair, to_end: true, max_count: 3}
"""


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    where = tmp_path_factory.mktemp("rest")
    render(where, "rest", SCHEMA)
    return where, load(where / "rest.py")


def test_python_sends_what_the_list_holds(built):
    mod = built[1]
    cases = [(mod.Registers(start=0x0102, values=[0x0A0B, 0x0C0D]), "55 01 06 0102 0a0b 0c0d aa"),
             (mod.Registers(start=7, values=[]), "55 01 02 0007 aa"),
             (mod.Blob(tag=9, data=b""), "55 02 01 09 aa"),
             (mod.Blob(tag=9, data=b"\x01\x02\x03\x04\x05"), "55 02 06 09 0102030405 aa"),
             (mod.Pairs(pts=[mod.PairsPts(a=100, b=-1)]), "55 03 02 64 ff aa")]
    for message, frame in cases:
        assert mod.encode(message) == bytes.fromhex(frame)
        assert mod.decode(bytes.fromhex(frame)) == message


@pytest.mark.parametrize("frame, rule", [
    ("55 01 03 0102 0a aa", "length"),  # half a register
    ("55 01 0c 0102 0001 0002 0003 0004 0005 aa", "length"),  # five registers, four at most
    ("55 03 02 65 00 aa", "range"),  # a = 101: the element sent is checked
])
def test_python_refuses_what_does_not_fill_whole_elements(built, frame, rule):
    """The message's decoder names the rule; the module's decoder, which finds the message
    by id and size, refuses a size the message never has as `dispatch`."""
    mod = built[1]
    message = {"01": mod.Registers, "03": mod.Pairs}[frame[3:5]]
    with pytest.raises(mod.DecodeError) as e:
        message.decode(bytes.fromhex(frame))
    assert e.value.rule == rule
    with pytest.raises(mod.DecodeError) as e:
        mod.decode(bytes.fromhex(frame))
    assert e.value.rule == (rule if rule == "range" else "dispatch")


def test_c_agrees(built):
    driver = r"""
#include <stdio.h>
#include "rest.h"
int main(void) {
    static const uint8_t two[] = {0x55, 0x01, 0x06, 0x01, 0x02, 0x0a, 0x0b, 0x0c, 0x0d, 0xaa};
    static const uint8_t half[] = {0x55, 0x01, 0x03, 0x01, 0x02, 0x0a, 0xaa};
    rest_registers_t m = {0};
    uint8_t out[16];
    int n, i;
    n = rest_registers_decode(two, sizeof two, &m);
    printf("%d %u %04x %04x\n", n, (unsigned)m.values_count, m.values[0], m.values[1]);
    m.values_count = 1;
    n = rest_registers_encode(&m, out, sizeof out);
    for (i = 0; i < n; i++) printf("%02x", out[i]);
    printf("\n%d\n", rest_registers_decode(half, sizeof half, &m));
    return 0;
}
"""
    assert run_c(built[0], driver) == ["0 2 0a0b 0c0d", "550104" "0102" "0a0b" "aa", "-2"]


def test_conformance_vectors_on_the_host_and_on_atmega32_under_simavr(tmp_path):
    host, avr = conformance_on_host_and_avr(tmp_path, "rest", SCHEMA)
    assert host > 50 and avr > 50
