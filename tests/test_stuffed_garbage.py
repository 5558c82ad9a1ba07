"""Garbage in byte-stuffed framings (SLIP, COBS, HDLC): a run of stretches between
delimiters that hold no frame gives one error, not one per stretch, in the Python
StreamDecoder, the C scan and byte parser, and `codeword check`; memory stays bounded.
The frame is worked out by hand: id 1, x = 5, xor check 01^05 = 04, between HDLC
flags 7E (none of its bytes needs escaping)."""
from __future__ import annotations

import tracemalloc

from codeword.cli import main
from schema_in_a_test import load, render
from stream_events import c_events, python_events, without_ends

SCHEMA = """codeword: 1
protocol: flagged
title: t
source: s
framing:
  kind: bytes
  encoding: hdlc
  layout:
    - {name: kind, type: u8, dispatch: true}
    - {payload: true}
    - {name: check, type: u8, checksum: {algorithm: xor, covers: {from: kind, to: payload}}}
messages:
  a:
    id: 1
    fields:
      - {name: x, type: u8}
    examples:
      - {hex: "7e 01 05 04 7e", values: {x: 5}}
"""
FRAME = bytes.fromhex("7e 01 05 04 7e")
SHORT = bytes.fromhex("01 7e")  # a stretch of one byte: no frame is that short


def test_python_gives_one_error_per_run_in_bounded_memory(tmp_path):
    render(tmp_path, "flagged", SCHEMA)
    mod = load(tmp_path / "flagged.py")
    garbage = SHORT * 1_000_000  # 2 MB
    d = mod.StreamDecoder()
    tracemalloc.start()
    items = d.feed(garbage)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    assert [x.rule for x in items] == ["dispatch"]  # id 1 with a frame of 1 byte
    assert peak < 16 * len(garbage)  # the input and its copy, not an error per stretch
    assert d.skipped == len(garbage) // 2  # the stretches' bytes; the delimiters are no frame's
    assert [type(x).__name__ for x in d.feed(FRAME + garbage[:1000] + FRAME)] == ["A", "DecodeError", "A"]


def test_python_and_c_agree_on_runs_of_short_garbage(tmp_path):
    render(tmp_path, "flagged", SCHEMA)
    mod = load(tmp_path / "flagged.py")
    data = SHORT * 50 + FRAME + SHORT * 3 + bytes.fromhex("7e 01 05 05 7e") + FRAME + FRAME + SHORT
    # a frame's span ends before its closing flag: at 104, 120 and 125; the damaged frame
    # (check 05) is part of the second run of garbage
    expected = [("error", "dispatch"), ("message", "a", 104), ("error", "dispatch"), ("message", "a", 120),
                ("message", "a", 125), ("error", "dispatch")]
    assert python_events(mod, data) == expected
    assert python_events(mod, data, piece=1) == expected
    scan, parser = c_events(tmp_path, "flagged", ["a"], data, stuffed=True)
    assert scan == expected
    assert parser == without_ends(expected)


def test_check_reports_a_run_once(tmp_path, capsys):
    render(tmp_path, "flagged", SCHEMA)
    capture = tmp_path / "noise.bin"
    capture.write_bytes(SHORT * 5000 + FRAME)
    assert main(["check", str(tmp_path / "flagged.yaml"), str(capture)]) == 1
    out = capsys.readouterr().out
    assert len([line for line in out.splitlines() if ": error: " in line]) <= 2, out[:2000]
