"""Example values of scaled and f32 fields are compared as the wire carries them:
12.6 on a field of scale 0.1 is raw 126, however the decoder's float spells it
(12.600000000000001). A value another step away is still wrong."""
from __future__ import annotations

import pytest

from codeword.build import compile_schema, render_protocol, verify
from codeword.diagnostics import SchemaError

SCHEMA = """codeword: 1
protocol: scaled
title: t
source: s
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: code, type: u8, dispatch: true}
    - {payload: true}
types:
  cell:
    type: group
    fields:
      - {name: volts, type: u8, scale: 0.1}
messages:
  reading:
    id: 1
    fields:
      - {name: v, type: u16, scale: 0.1, unit: V}
      - {name: t, type: i16, scale: 0.01, offset: -40}
      - {name: f, type: f32}
      - {name: cells, type: cell, count: 2}
      - {name: trims, type: u8, scale: 0.1, count: 2}
    examples:
      - name: as a person writes them
        values: {v: V, t: T, f: F, cells: [{volts: 0.3}, {volts: 0.7}], trims: [0.3, 0.6]}
        # 126 = 0x007e; (21.3 + 40) / 0.01 = 6130 = 0x17f2; 1.1 in single precision is 0x3f8ccccd
        hex: 01 007e 17f2 3f8ccccd 03 07 03 06
"""


def check(tmp_path, v="12.6", t="21.3", f="1.1"):
    path = tmp_path / "scaled.yaml"
    path.write_text(SCHEMA.replace("V,", v + ",").replace("T,", t + ",").replace("F,", f + ","), encoding="utf-8")
    protocol = compile_schema(path)
    verify(protocol, render_protocol(protocol))


def test_values_as_written_match_the_wire(tmp_path):
    check(tmp_path)


def test_a_value_within_the_step_the_wire_carries_matches(tmp_path):
    check(tmp_path, v="12.63", f="1.10000002")


@pytest.mark.parametrize("wrong", [{"v": "12.7"}, {"v": "12.5"}, {"t": "21.31"}, {"f": "1.1000001"}])
def test_a_value_a_step_away_still_fails(tmp_path, wrong):
    with pytest.raises(SchemaError) as info:
        check(tmp_path, **wrong)
    assert any("decodes to" in d.message for d in info.value.diagnostics), info.value.diagnostics
