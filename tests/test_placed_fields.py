"""Fields placed by start_bit beyond the codecs: `codeword diff` calls a moved start bit
or a flipped byte order breaking, the fingerprint follows them, and the docs draw the
payload bit by bit as a DBC numbers it (hand-worked grid)."""
from __future__ import annotations

from codeword.build import compile_schema, render_protocol
from codeword.diff.compare import compare
from codeword.fingerprint import fingerprint

SCHEMA = """codeword: 1
protocol: placed
title: t
source: s
framing:
  kind: bytes
  layout:
    - {payload: true}
messages:
  m:
    payload_bytes: 2
    fields:
      - {name: gear, type: u3, start_bit: 0, byte_order: little}
      - {name: mode, type: u4, start_bit: 15, byte_order: big}
"""


def protocol(tmp_path, text: str, name: str = "placed.yaml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return compile_schema(path)


def test_a_moved_start_bit_or_a_flipped_order_breaks_the_wire(tmp_path):
    old = protocol(tmp_path, SCHEMA, "old.yaml")
    moved = protocol(tmp_path, SCHEMA.replace("start_bit: 15", "start_bit: 14"), "moved.yaml")
    flipped = protocol(tmp_path, SCHEMA.replace("start_bit: 15, byte_order: big", "start_bit: 12, byte_order: little"),
                       "flipped.yaml")
    for new, said in ((moved, "start_bit changed from 15 to 14"), (flipped, "byte_order changed from 'big' to 'little'")):
        diff = compare(old, new)
        assert diff.breaking
        assert any(said in change.what for change in diff.changes), [c.what for c in diff.changes]
        assert fingerprint(old) != fingerprint(new)


def test_the_docs_draw_the_payload_as_a_dbc_numbers_it(tmp_path):
    page = render_protocol(protocol(tmp_path, SCHEMA))["docs/placed.md"]
    # gear: Intel, start 0, 3 bits: byte 0 bits 0..2; mode: Motorola, start 15 (byte 1 bit 7), 4 bits down to bit 4
    assert "| **B0** | · | · | · | · | · | `gear` msb | `gear` | `gear` lsb |" in page
    assert "| **B1** | `mode` msb | `mode` | `mode` | `mode` lsb | · | · | · | · |" in page
    assert "| `mode` | 4 | start bit 15 | B1 bits 7–4 | u4 BE (Motorola) |" in page
