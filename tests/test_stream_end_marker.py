"""A constant after the payload (an end marker, as 0x55 here) closes the frame; it is
no part of the sync, which is only the constants before the payload. Frames worked
out by hand: start byte AA, the value, end marker 55."""
from __future__ import annotations

from schema_in_a_test import load, render
from stream_events import accelerated, c_events, python_events, without_ends

SCHEMA = """codeword: 1
protocol: marked
title: t
source: s
framing:
  kind: bytes
  layout:
    - {name: start, type: u8, const: 0xAA}
    - {payload: true}
    - {name: stop, type: u8, const: 0x55}
messages:
  reading:
    fields:
      - {name: x, type: u8}
    examples:
      - {hex: "aa 05 55", values: {x: 5}}
"""
# x = 5, x = 0x55 (the only value the end marker taken as sync would let through), x = 7
STREAM = bytes.fromhex("aa 05 55" "aa 55 55" "aa 07 55")
EXPECTED = [("message", "reading", 3), ("message", "reading", 6), ("message", "reading", 9)]


def test_python_finds_every_frame(tmp_path):
    render(tmp_path, "marked", SCHEMA)
    mod = load(tmp_path / "marked.py")
    d = mod.StreamDecoder()
    assert [m.x for m in d.feed(STREAM)] == [5, 0x55, 7]
    assert python_events(mod, STREAM, piece=1) == EXPECTED


def test_accelerator_finds_every_frame(tmp_path):
    render(tmp_path, "marked", SCHEMA)
    assert python_events(accelerated(tmp_path, "marked"), STREAM, piece=2) == EXPECTED


def test_c_finds_every_frame(tmp_path):
    render(tmp_path, "marked", SCHEMA)
    scan, parser = c_events(tmp_path, "marked", ["reading"], STREAM)
    assert scan == EXPECTED
    assert parser == without_ends(EXPECTED)
