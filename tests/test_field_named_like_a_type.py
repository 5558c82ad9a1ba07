"""A field may be named like a Python type (`bytes`, `str`): the generated module
still reads the other fields' types right."""
from __future__ import annotations

from schema_in_a_test import load, render

SCHEMA = """codeword: 1
protocol: typenames
title: t
source: s
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: sync, type: u8, const: 0x55}
    - {name: kind, type: u8, dispatch: true}
    - {payload: true}
messages:
  a:
    id: 1
    fields:
      - {name: bytes, type: u8}
      - {name: str, type: u8}
      - {name: data, type: bytes, length: 2}
"""


def test_from_dict_reads_hex_into_a_bytes_field_beside_one_named_bytes(tmp_path):
    render(tmp_path, "typenames", SCHEMA)
    mod = load(tmp_path / "typenames.py")
    message = mod.from_dict("a", {"bytes": 3, "str": 4, "data": "6162"})
    assert message.data == b"ab"
    assert mod.encode(message) == bytes.fromhex("55 01 03 04 61 62")
