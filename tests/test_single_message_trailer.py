"""A protocol of one message without an id, sized by a length field, whose flag puts a
trailer after the frame: the module's decode reads the trailer as the message's own decode
does, and every stream decoder refuses a length as soon as it is read, before the flag
byte arrives. Frames worked out by hand: AA, the length (1), the flags, x, then the tag
when flag 0 is set."""
from __future__ import annotations

import pytest

from schema_in_a_test import load, render
from stream_events import accelerated, c_events, python_events, without_ends

SCHEMA = """codeword: 1
protocol: flagged
title: one message with a trailer
source: hand-written
flags:
  link_flags:
    type: u8
    bits:
      - {name: tagged, bit: 0}
framing:
  kind: bytes
  layout:
    - {name: sync, type: u8, const: 0xAA}
    - {name: len, type: u8, length_of: {from: payload, to: payload}}
    - {name: flags, type: u8, flags: link_flags}
    - {payload: true}
  trailer:
    present_if: {field: flags, has: tagged}
    fields:
      - {name: tag, type: u8}
messages:
  reading:
    fields:
      - {name: x, type: u8}
"""
PLAIN = bytes.fromhex("aa 01 00 05")
TAGGED = bytes.fromhex("aa 01 01 05 09")
# two frames, then a sync whose length (7: a frame of 10 bytes) no frame has, and no flag byte yet
STREAM = PLAIN + TAGGED + bytes.fromhex("aa 07")
EXPECTED = [("message", "reading", 4), ("message", "reading", 9), ("error", "length")]


@pytest.fixture
def mod(tmp_path):
    render(tmp_path, "flagged", SCHEMA)
    return load(tmp_path / "flagged.py")


def test_decode_reads_the_trailer(mod):
    plain, tagged = mod.decode(PLAIN), mod.decode(TAGGED)
    assert (plain.x, plain.tag) == (5, None)
    assert (tagged.x, tagged.tag, tagged.flags) == (5, 9, mod.LinkFlags.tagged)
    assert mod.encode(tagged) == TAGGED


def test_decode_refuses_a_trailer_the_flag_leaves_out(mod):
    with pytest.raises(mod.DecodeError) as caught:
        mod.decode(PLAIN + b"\x09")
    assert caught.value.rule == "length"


def test_python_refuses_the_length_before_the_flag_byte(mod):
    assert python_events(mod, STREAM) == EXPECTED
    assert python_events(mod, STREAM, piece=1) == EXPECTED


def test_accelerated_module_agrees(tmp_path):
    render(tmp_path, "flagged", SCHEMA)
    assert python_events(accelerated(tmp_path, "flagged"), STREAM, piece=1) == EXPECTED


def test_c_agrees(tmp_path):
    render(tmp_path, "flagged", SCHEMA)
    scan, parser = c_events(tmp_path, "flagged", ["reading"], STREAM)
    assert scan == EXPECTED
    assert parser == without_ends(EXPECTED)
