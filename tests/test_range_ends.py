"""A range's ends as stored integers, computed exactly (Field.range_bounds), so that the
C checks and the conformance vectors take the same ends. In floats 1.1 / 0.1 is
11.000000000000002 and 1.2 / 0.1 is 11.999999999999998: their ceiling and floor cross,
and the vector generator once stopped with an internal error on such a range (the long
fuzzing run at da374f0, seeds 772076 and 772492); at 1 decimal, 99999.9 / 0.1 floors to
999998, so the vectors never reached the range's top."""
from __future__ import annotations

import json

import schema_in_a_test as scratch
from codeword.build import build, compile_schema
from conftest import ROOT

SCHEMA = """codeword: 1
protocol: ends
title: t
source: s
framing:
  kind: bytes
  layout:
    - {name: sync, type: u8, const: 0xA5}
    - {name: kind, type: u8, dispatch: true}
    - {payload: true}
messages:
  level:
    id: 1
    fields:
      - {name: gain, type: u8, scale: 0.1, range: [1.1, 1.2]}
"""


def test_the_ends_are_exact(tmp_path):
    p = compile_schema(scratch.render(tmp_path, "ends", SCHEMA) / "ends.yaml")
    gain, = p.message("level").fields
    # the doubles 1.1 and 1.2 over the double 0.1: 10.99999999999999967 and 11.99999999999999989
    assert gain.range_bounds == (11, 11)
    nmea = compile_schema(ROOT / "examples" / "nmea0183.yaml")
    altitude = next(f for f in nmea.message("gga").fields if f.name == "altitude")
    assert altitude.range_bounds == (-99999, 999999)  # [-9999.9, 99999.9] at 1 decimal


def test_the_vectors_reach_each_end(tmp_path):
    out = tmp_path / "out"
    result = build([scratch.render(tmp_path, "ends", SCHEMA) / "ends.yaml"], out, root=tmp_path)
    assert not result.errors, result.errors
    cases = {c["name"]: c for c in json.loads((out / "vectors" / "ends.json").read_text())["valid"]}
    assert cases["level gain min"]["hex"][4:6] == cases["level gain max"]["hex"][4:6] == "0b"  # raw 11
    assert cases["level gain max"]["values"]["gain"] == 11 * 0.1
    nmea = json.loads((ROOT / "generated" / "examples" / "vectors" / "nmea0183.json").read_text())
    by_name = {c["name"]: c["values"] for c in nmea["valid"]}
    assert by_name["gga altitude min"]["altitude"] == -9999.9 and by_name["gga altitude max"]["altitude"] == 99999.9
