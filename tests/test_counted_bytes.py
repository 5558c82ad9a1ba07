"""A bytes field whose length an earlier field gives: `data` holds 0..4 bytes, `n`
says how many, and a frame carries only those. Frames worked by hand: sync 55, id 07,
the length byte (payload bytes sent: tag, n and the n bytes of data), then the end
byte aa."""
from __future__ import annotations

import pytest

from schema_in_a_test import conformance_on_host_and_avr, load, render, run_c

SCHEMA = """codeword: 1
protocol: blob
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
messages:
  chunk:
    id: 7
    fields:
      - {name: tag, type: u8}
      - {name: n, type: u8}
      - {name: data, type: bytes, length: {from: n}, max_length: 4}
"""

FRAMES = [(b"", "55 07 02 09 00 aa"), (b"\x01", "55 07 03 09 01 01 aa"),
          (b"\x01\x02\x03\x04", "55 07 06 09 04 01 02 03 04 aa")]


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    where = tmp_path_factory.mktemp("blob")
    render(where, "blob", SCHEMA)
    return where, load(where / "blob.py")


def test_python_sends_only_the_bytes_given(built):
    mod = built[1]
    for data, frame in FRAMES:
        assert mod.encode(mod.Chunk(tag=9, data=data)) == bytes.fromhex(frame)
        assert mod.decode(bytes.fromhex(frame)) == mod.Chunk(tag=9, data=data)
    with pytest.raises(mod.EncodeError, match="chunk.data.*0..4"):
        mod.encode(mod.Chunk(tag=9, data=b"12345"))


@pytest.mark.parametrize("frame, rule", [("55 07 04 09 05 aa bb aa", "range"),  # n over the most
                                         ("55 07 05 09 02 aa bb cc aa", "length"),  # n says 2, 3 sent
                                         ("55 07 03 09 02 aa bb aa", "length")])  # len disagrees
def test_python_refuses_a_count_the_frame_does_not_hold(built, frame, rule):
    mod = built[1]
    with pytest.raises(mod.DecodeError) as e:
        mod.decode(bytes.fromhex(frame))
    assert e.value.rule == rule


def test_c_agrees(built):
    driver = r"""
#include <stdio.h>
#include "blob.h"
int main(void) {
    static const uint8_t frame[] = {0x55, 0x07, 0x04, 0x09, 0x02, 0xaa, 0xbb, 0xaa};
    static const uint8_t over[] = {0x55, 0x07, 0x04, 0x09, 0x05, 0xaa, 0xbb, 0xaa};
    static const uint8_t disagree[] = {0x55, 0x07, 0x05, 0x09, 0x02, 0xaa, 0xbb, 0xcc, 0xaa};
    blob_chunk_t m = {0};
    uint8_t out[16];
    int n, i;
    m.tag = 9; m.data[0] = 1; m.data_count = 1;
    n = blob_chunk_encode(&m, out, sizeof out);
    printf("%d", n);
    for (i = 0; i < n; i++) printf(" %02x", out[i]);
    printf("\n");
    m.data_count = 5;
    printf("%d\n", blob_chunk_encode(&m, out, sizeof out));
    n = blob_chunk_decode(frame, sizeof frame, &m);
    printf("%d %u %u %02x %02x %02x\n", n, m.tag, m.data_count, m.data[0], m.data[1], m.data[2]);
    printf("%d %d\n", blob_chunk_decode(over, sizeof over, &m), blob_chunk_decode(disagree, sizeof disagree, &m));
    return 0;
}
"""
    assert run_c(built[0], driver) == ["7 55 07 03 09 01 01 aa", "-4", "0 9 2 aa bb 00", "-4 -2"]


NO_LENGTH = """codeword: 1
protocol: rtu
title: t
source: s
framing:
  kind: bytes
  byte_order: little
  layout:
    - {name: id, type: u8, dispatch: true}
    - {payload: true}
    - {name: crc, type: u16, checksum: {algorithm: CRC-16/MODBUS, covers: {from: id, to: payload}}}
messages:
  small:
    id: 1
    fields:
      - {name: n, type: u8}
      - {name: data, type: bytes, length: {from: n}, max_length: 5}
  large:
    id: 2
    fields:
      - {name: tag, type: u16}
      - {name: n, type: u16}
      - {name: data, type: bytes, length: {from: n}, max_length: 40}
"""


@pytest.mark.parametrize("name, schema", [("blob", SCHEMA), ("rtu", NO_LENGTH)])
def test_conformance_vectors_on_the_host_and_on_atmega32_under_simavr(tmp_path, name, schema):
    """Empty, one-byte, fullest and random data, damaged frames and streams (where
    there is no length field the count gives a frame's size): C agrees with Python on
    the host and on an 8-bit AVR."""
    host, avr = conformance_on_host_and_avr(tmp_path, name, schema)
    assert host > 50 and avr > 50
