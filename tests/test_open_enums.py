"""Open enums (`open: true`): a value no member has is valid too, and decoders keep it
as its number, as MAVLink's enums and a DBC's value tables are read. Expected bytes
are worked out by hand from the layout: kind, mode (u8), s (i4) and 4 reserved bits,
two modes (u8 each)."""
from __future__ import annotations

import pytest

from codeword.build import compile_schema
from codeword.diff import BREAKING, COMPATIBLE, compare
from schema_in_a_test import conformance_on_host_and_avr, load, render

SCHEMA = """codeword: 1
protocol: openenum
title: open enums
source: hand
enums:
  mode:
    type: u8
    open: true
    values:
      - {name: idle, value: 0}
      - {name: run, value: 3}
  small:
    type: i4
    open: true
    values:
      - {name: minus, value: -2}
  shut:
    type: u8
    values:
      - {name: off, value: 0}
framing:
  kind: bytes
  layout:
    - {name: kind, type: u8, dispatch: true}
    - {payload: true}
messages:
  status:
    id: 1
    fields:
      - {name: mode, type: u8, enum: mode}
      - {name: s, type: i4, enum: small}
      - {name: pad, type: u4, reserved: true}
      - {name: modes, type: u8, enum: mode, count: 2}
      - {name: lock, type: u8, enum: shut}
    examples:
      - hex: "01 03 e0 07 00 00"
        values: {mode: run, s: -2, modes: [7, idle], lock: "off"}
"""


@pytest.fixture(scope="module")
def codec(tmp_path_factory):
    where = tmp_path_factory.mktemp("openenum")
    render(where, "openenum", SCHEMA)
    return load(where / "openenum.py")


def test_a_value_no_member_has_decodes_as_its_number(codec):
    m = codec.decode(bytes.fromhex("01 c8 70 ff 03 00"))
    assert m.mode == 200 and type(m.mode) is int
    assert m.s == 7 and type(m.s) is int
    assert m.modes == [255, codec.Mode.run] and m.modes[1] is codec.Mode.run
    assert m.encode() == bytes.fromhex("01 c8 70 ff 03 00")


def test_a_closed_enum_beside_it_still_refuses_other_values(codec):
    with pytest.raises(codec.DecodeError) as e:
        codec.decode(bytes.fromhex("01 00 00 00 00 01"))
    assert e.value.field == "lock" and e.value.rule == "enum"


def test_encoders_take_members_and_integers_of_the_width_only(codec):
    assert codec.Status(mode=codec.Mode.run, s=-8, modes=[0, 255], lock=codec.Shut.off).encode() == \
        bytes.fromhex("01 03 80 00 ff 00")
    for bad in (256, -1, True, 1.0, "run", codec.Shut.off):
        with pytest.raises(codec.EncodeError) as e:
            codec.Status(mode=bad, s=0, modes=[0, 0], lock=codec.Shut.off).encode()
        assert e.value.field == "mode" and e.value.rule == "enum"
    with pytest.raises(codec.EncodeError):
        codec.Status(mode=0, s=8, modes=[0, 0], lock=codec.Shut.off).encode()  # i4 holds -8..7


def test_plain_data_keeps_names_of_members_and_numbers_of_the_rest(codec):
    m = codec.decode(bytes.fromhex("01 03 70 07 00 00"))
    data = m.to_dict()
    assert data == {"mode": "run", "s": 7, "modes": [7, "idle"], "lock": "off"}
    assert codec.Status.from_dict(data) == m
    assert codec.Status.from_dict({**data, "mode": 3}).mode is codec.Mode.run  # a member's value is the member


def test_c_and_python_agree_on_the_host_and_on_avr(tmp_path):
    host, avr = conformance_on_host_and_avr(tmp_path, "openenum", SCHEMA)
    assert host > 50 and avr > 50


def test_vectors_hold_values_no_member_has(tmp_path):
    import json
    from codeword.build import build
    (tmp_path / "openenum.yaml").write_text(SCHEMA, encoding="utf-8")
    assert not build([tmp_path / "openenum.yaml"], tmp_path / "out", root=tmp_path).errors
    vectors = json.loads((tmp_path / "out" / "vectors" / "openenum.json").read_text(encoding="utf-8"))
    modes = [c["values"]["mode"] for c in vectors["valid"]]
    assert any(isinstance(x, int) for x in modes) and any(isinstance(x, str) for x in modes)
    assert 255 in modes  # the top of the width


def test_diff_opening_is_compatible_and_closing_breaks(tmp_path):
    closed = tmp_path / "closed.yaml"
    opened = tmp_path / "openenum.yaml"
    closed.write_text(SCHEMA.replace("    open: true\n    values:\n      - {name: idle", "    values:\n      - {name: idle"),
                      encoding="utf-8")
    opened.write_text(SCHEMA, encoding="utf-8")
    a, b = compile_schema(closed), compile_schema(opened)
    assert ("field mode", "enum mode now open: a value no member has decodes as its number") in \
        {(c.subject, c.what) for c in compare(a, b).of_kind(COMPATIBLE)}
    back = compare(b, a)
    assert back.breaking
    assert ("field mode", "enum mode now closed: a value no member has is refused") in \
        {(c.subject, c.what) for c in back.of_kind(BREAKING)}


def test_docs_say_the_enum_is_open(tmp_path):
    from codeword.build import render_protocol
    page = render_protocol(compile_schema(render(tmp_path, "openenum", SCHEMA) / "openenum.yaml"))["docs/openenum.md"]
    assert "Open: a value no member has is valid too, and decoders keep it as its number." in page
    assert "enum [mode](#enum-mode), other values kept as numbers" in page


def test_an_open_enums_default_may_be_any_value_of_its_width_but_a_constant_is_a_member(tmp_path):
    from codeword.diagnostics import SchemaError
    with_default = SCHEMA.replace("{name: mode, type: u8, enum: mode}", "{name: mode, type: u8, enum: mode, default: 9}")
    render(tmp_path, "openenum", with_default)
    codec = load(tmp_path / "openenum.py")
    assert codec.Status(s=0, modes=[0, 0], lock=codec.Shut.off).mode == 9
    (tmp_path / "const.yaml").write_text(SCHEMA.replace("{name: mode, type: u8, enum: mode}",
                                                        "{name: mode, type: u8, enum: mode, const: 9}"))
    with pytest.raises(SchemaError, match="const 9 is not a member of enum 'mode'"):
        compile_schema(tmp_path / "const.yaml")
