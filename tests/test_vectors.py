"""Conformance vectors of a schema built in a temporary directory: each valid
vector decodes to its values and its values encode to its bytes in the
generated Python."""
from __future__ import annotations

import json
from pathlib import Path

import schema_in_a_test as scratch
from codeword.build import build, schema_files

SCALED = """\
codeword: 1
protocol: scaled
title: scaled integers without a range
source: hand-written
framing:
  kind: bytes
  byte_order: little
  layout:
    - {name: sync, type: u8, const: 0x55}
    - {name: kind, type: u8, dispatch: true}
    - {payload: true}
messages:
  reading:
    id: 1
    fields:
      - {name: v, type: i16, scale: 0.5}
      - {name: w, type: u8, scale: 0.25, offset: -10}
"""


def built(tmp_path: Path, name: str, text: str):
    """Build one schema into tmp_path/generated; its vectors and generated module."""
    (tmp_path / "schemas").mkdir()
    (tmp_path / "schemas" / f"{name}.yaml").write_text(text, encoding="utf-8")
    out = tmp_path / "generated"
    result = build(schema_files(tmp_path / "schemas"), out, root=tmp_path)
    assert not result.errors, "\n".join(map(str, result.errors))
    vectors = json.loads((out / "vectors" / f"{name}.json").read_text(encoding="utf-8"))
    return vectors, scratch.load(out / "python" / f"{name}.py")


def test_scaled_fields_without_range_take_their_limits_from_the_width(tmp_path):
    vectors, mod = built(tmp_path, "scaled", SCALED)
    cases = {c["name"]: c for c in vectors["valid"]}
    # v: i16 raw -32768..32767 times 0.5; w: u8 raw 0..255 times 0.25 minus 10.
    # Frame: 55 | 01 | v little-endian | w.
    assert cases["reading v min"]["values"]["v"] == -16384.0
    assert cases["reading v min"]["hex"][4:8] == "0080"
    assert cases["reading v max"]["values"]["v"] == 16383.5
    assert cases["reading v max"]["hex"][4:8] == "ff7f"
    assert cases["reading w min"]["values"]["w"] == -10.0
    assert cases["reading w min"]["hex"][8:] == "00"
    assert cases["reading w max"]["values"]["w"] == 53.75
    assert cases["reading w max"]["hex"][8:] == "ff"
    assert len(vectors["valid"]) > 200
    for case in vectors["valid"]:
        data = bytes.fromhex(case["hex"])
        assert data[:2] == b"\x55\x01", case["name"]
        decoded = mod.decode(data)
        assert {"v": decoded.v, "w": decoded.w} == case["values"], case["name"]
        assert mod.encode(mod.from_dict("reading", case["values"])) == data, case["name"]
