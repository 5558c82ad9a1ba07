"""A scaled field whose top value is no double: `u53` scaled by 0.125 from 1000 reaches
1000 + 0.125 * (2**53 - 1) = 1125899906843623.875, between the doubles ...623.75 and
...624.0 (doubles of that size are 0.25 apart). The encoder takes every double up to
...623.75 and refuses ...624.0 (whose raw value, 2**53, the width cannot hold) with a
range error, never an internal one. Found by the schema fuzzer (seed 658016)."""
from __future__ import annotations

import pytest

from schema_in_a_test import load, render

SCHEMA = """codeword: 1
protocol: wide
title: t
source: s
framing:
  kind: bytes
  byte_order: big
  layout:
    - {payload: true}
messages:
  reading:
    fields:
      - {name: level, type: u53, scale: 0.125, offset: 1000}
      - {name: pad, type: u3, reserved: true}
"""


def test_the_largest_double_the_width_holds_encodes_and_the_next_is_refused(tmp_path):
    mod = load(render(tmp_path, "wide", SCHEMA) / "wide.py")
    top = 1125899906843623.75  # raw (top - 1000) / 0.125 = 2**53 - 2, then 3 zero bits
    assert mod.Reading(level=top).encode() == bytes.fromhex("ff ff ff ff ff ff f0")
    assert mod.decode(bytes.fromhex("ff ff ff ff ff ff f0")).level == top
    with pytest.raises(mod.EncodeError) as err:
        mod.Reading(level=1125899906843624.0).encode()
    assert err.value.rule == "range"
    bottom = mod.Reading(level=1000.0).encode()
    assert bottom == bytes(7)
    with pytest.raises(mod.EncodeError) as err:
        mod.Reading(level=999.875).encode()
    assert err.value.rule == "range"
