"""A field that crosses bytes in the other byte order than the frame's bits run is
refused with advice that works: the advice, applied as it is written, gives a
schema that builds and puts the bytes where a hand calculation puts them."""
from __future__ import annotations

import re

import pytest
import yaml

from codeword.build import compile_schema, render_protocol, verify
from codeword.diagnostics import SchemaError

SCHEMA = """codeword: 1
protocol: lsb
title: t
source: s
framing:
  kind: bytes
  bit_order: lsb_first
  byte_order: big
  layout:
    - {name: code, type: u8, dispatch: true}
    - {payload: true}
messages:
  ch:
    id: 1
    fields:
      - {name: a, type: u11}
      - {name: b, type: u5}
      - {name: big, type: u16}
    examples:
      # a = 0x5A5: its low 8 bits fill byte 1 (a5), its high 3 bits (101) bits 0-2 of
      # byte 2, b = 0x13 bits 3-7 (0x13 << 3 = 0x98): 9d; big = 0x1234 big-endian: 12 34
      - values: {a: 0x5A5, b: 0x13, big: 0x1234}
        hex: 01 a5 9d 12 34
"""


def refusal(tmp_path, text: str):
    path = tmp_path / "lsb.yaml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(SchemaError) as info:
        compile_schema(path)
    return info.value.diagnostics


def builds(tmp_path, doc: dict) -> None:
    path = tmp_path / "lsb.yaml"
    path.write_text(yaml.safe_dump(doc, sort_keys=False), encoding="utf-8")
    protocol = compile_schema(path)
    verify(protocol, render_protocol(protocol))  # the example's hand-made bytes included


def apply(doc: dict, hint: str) -> dict:
    """The hint's advice done as it says: the framing's byte order, and the named
    whole-byte fields given the other."""
    framing = re.search(r"set the framing's `byte_order: (\w+)`", hint)
    assert framing, hint
    doc["framing"]["byte_order"] = framing.group(1)
    keep = re.search(r"give `byte_order: (\w+)` to the whole-byte fields .*?\(here: ([^)]*)\)", hint)
    assert keep, hint
    for name in re.findall(r"`(\w+)`", keep.group(2)):
        field = next(f for f in doc["messages"]["ch"]["fields"] if f["name"] == name)
        field["byte_order"] = keep.group(1)
    return doc


def test_the_hint_for_a_field_crossing_bytes_gives_a_schema_that_builds(tmp_path):
    d, = refusal(tmp_path, SCHEMA)
    assert "must be byte-aligned" in d.message and "padding" not in d.hint
    builds(tmp_path, apply(yaml.safe_load(SCHEMA), d.hint))


def test_a_byte_order_on_a_field_crossing_bytes_points_to_the_same_advice(tmp_path):
    d, = refusal(tmp_path, SCHEMA.replace("{name: a, type: u11}", "{name: a, type: u11, byte_order: little}"))
    assert d.loc.line == 16 and "whole bytes" in d.message
    assert "drop it" in d.hint and "set the framing's" in d.hint
