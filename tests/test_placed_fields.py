"""Fields placed by start_bit beyond the codecs: `codeword diff` calls a moved start bit,
a flipped byte order or a change of the multiplexor values that carry a field breaking,
the fingerprint follows them, and the docs draw the payload bit by bit as a DBC numbers
it, a grid for each set of multiplexor values (hand-worked grids)."""
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


MUX = """codeword: 1
protocol: muxed
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
      - {name: page, type: u2, start_bit: 0, byte_order: little}
      - {name: a, type: u8, start_bit: 8, byte_order: little, multiplexed_by: {field: page, values: [0]}}
      - {name: b, type: u4, start_bit: 15, byte_order: big, multiplexed_by: {field: page, values: [1..2]}}
"""


def test_changing_which_values_carry_a_field_breaks_the_wire(tmp_path):
    old = protocol(tmp_path, MUX, "old.yaml")
    new = protocol(tmp_path, MUX.replace("values: [1..2]", "values: [1, 3]"), "new.yaml")
    plain = protocol(tmp_path, MUX.replace("start_bit: 15, byte_order: big, multiplexed_by: {field: page, values: [1..2]}",
                                           "start_bit: 2, byte_order: little"), "plain.yaml")
    for changed, said in ((new, "carried when page is 1..2, now page is 1, 3"), (plain, "now always")):
        diff = compare(old, changed)
        assert diff.breaking
        assert any(said in change.what for change in diff.changes), [c.what for c in diff.changes]
        assert fingerprint(old) != fingerprint(changed)


def test_the_docs_give_each_multiplexor_value_its_fields_and_bits(tmp_path):
    page = render_protocol(protocol(tmp_path, MUX))["docs/muxed.md"]
    assert "| `page` is 0 | `a` | `page`, `a` |" in page
    assert "| `page` is 1..2 | `b` | `page`, `b` |" in page
    # page 0: a (Intel, start 8) fills byte 1; pages 1..2: b (Motorola, start 15) takes byte 1 bits 7..4
    zero = page.split("Payload bits when `page` is 0:")[1]
    assert "| **B1** | `a` msb | `a` | `a` | `a` | `a` | `a` | `a` | `a` lsb |" in zero.split("Payload bits when")[0]
    ones = page.split("Payload bits when `page` is 1..2:")[1]
    assert "| **B1** | `b` msb | `b` | `b` | `b` lsb | · | · | · | · |" in ones
    assert "| `b` | 4 | start bit 15 | B1 bits 7–4 | u4 BE (Motorola), if `page` is 1..2 |" in page


def test_the_accelerator_serves_multiplexed_messages(tmp_path):
    """Its C reads each signal's presence from its multiplexors' raw values and gives None to
    the fields not carried, as Python does (tests/test_accelerator.py compares both on the
    multiplexed messages of examples/can_mixed.yaml, frame by frame)."""
    from codeword.targets.accelerator.encode import encodable
    from codeword.targets.accelerator.scope import servable
    muxed, placed = protocol(tmp_path, MUX, "muxed.yaml"), protocol(tmp_path, SCHEMA)
    assert servable(muxed, muxed.message("m")) and encodable(muxed, muxed.message("m"))
    assert servable(placed, placed.message("m"))
