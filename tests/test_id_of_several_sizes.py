"""Frames with neither a sync nor a length field, two messages sharing an id at two
fixed sizes: the stream decoders try each size of the id, smallest first, and take
the first frame whose CRC holds. Frames are the Modbus specification's published
examples (read holding registers 40108..40110 of device 17, and the response with
three registers), CRC-16/MODBUS sent low byte first. Without a checksum nothing
tells the sizes apart, so the schema is refused."""
from __future__ import annotations

import pytest

from codeword.build import compile_schema
from codeword.diagnostics import SchemaError
from schema_in_a_test import load, render
from stream_events import accelerated, c_events, python_events, without_ends

SCHEMA = """codeword: 1
protocol: rtu
title: t
source: s
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: address, type: u8}
    - {name: function, type: u8, dispatch: true}
    - {payload: true}
    - {name: crc, type: u16, byte_order: little, checksum: {algorithm: CRC-16/MODBUS, covers: {from: address, to: payload}}}
messages:
  read_request:
    id: 0x03
    fields:
      - {name: start, type: u16}
      - {name: count, type: u16}
    examples:
      - {hex: "11 03 00 6b 00 03 76 87", values: {address: 17, start: 107, count: 3}}
  read_response:
    id: 0x03
    fields:
      - {name: byte_count, type: u8}
      - {name: registers, type: u16, count: 3}
    examples:
      - {hex: "11 03 06 ae 41 56 52 43 40 49 ad", values: {address: 17, byte_count: 6, registers: [0xAE41, 0x5652, 0x4340]}}
"""
REQUEST = bytes.fromhex("11 03 00 6b 00 03 76 87")
RESPONSE = bytes.fromhex("11 03 06 ae 41 56 52 43 40 49 ad")
DAMAGED = bytes.fromhex("11 03 06 ae 41 56 52 43 40 49 ae")  # the response with its CRC's high byte off by one
STREAM = REQUEST + RESPONSE + DAMAGED + RESPONSE + REQUEST
# The damaged response fails at 8 bytes and at 11 (its checksum: the error reported); then
# each byte after its first is tried and fails (no id 0x03 with a CRC that holds) until
# the second response, which decodes from offset 30.
EXPECTED = [("message", "read_request", 8), ("message", "read_response", 19), ("error", "checksum"),
            ("message", "read_response", 41), ("message", "read_request", 49)]


def test_python_tries_each_size_of_the_id(tmp_path):
    render(tmp_path, "rtu", SCHEMA)
    mod = load(tmp_path / "rtu.py")
    items = mod.StreamDecoder().feed(STREAM)
    assert [(m.start, m.count) for m in items if type(m).__name__ == "ReadRequest"] == [(107, 3), (107, 3)]
    assert [m.registers for m in items if type(m).__name__ == "ReadResponse"] == [[0xAE41, 0x5652, 0x4340]] * 2
    assert python_events(mod, STREAM) == EXPECTED
    assert python_events(mod, STREAM, piece=1) == EXPECTED


def test_accelerator_tries_each_size_of_the_id(tmp_path):
    render(tmp_path, "rtu", SCHEMA)
    fast = accelerated(tmp_path, "rtu")
    assert python_events(fast, STREAM) == EXPECTED
    assert python_events(fast, STREAM, piece=3) == EXPECTED


def test_c_tries_each_size_of_the_id(tmp_path):
    render(tmp_path, "rtu", SCHEMA)
    scan, parser = c_events(tmp_path, "rtu", ["read_request", "read_response"], STREAM)
    assert scan == EXPECTED
    assert parser == without_ends(EXPECTED)


def test_without_a_checksum_the_sizes_are_refused(tmp_path):
    path = tmp_path / "rtu.yaml"
    path.write_text(SCHEMA.replace("    - {name: crc, type: u16, byte_order: little, checksum: {algorithm: "
                                   "CRC-16/MODBUS, covers: {from: address, to: payload}}}\n", "")
                    .replace(" 76 87", "").replace(" 49 ad", ""), encoding="utf-8")
    with pytest.raises(SchemaError) as refused:
        compile_schema(path)
    (problem,) = [d for d in refused.value.diagnostics if "same id" in d.message]
    assert problem.loc.line == 20 and "no checksum" in problem.message
