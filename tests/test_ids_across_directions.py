"""One id used by a message of each direction (a request and its reply under one
command number, a text sentence sent both ways): given its direction, a decoder
reads each frame as that direction's message; without one, it refuses the frame
with error `dispatch` rather than pick one. Python and C alike.

Binary frames worked by hand: sync a5, id, the payload, and an 8-bit sum of the id
and payload bytes. Text lines: `<prefix>:<values>;`."""
from __future__ import annotations

import pytest

from schema_in_a_test import conformance_on_host_and_avr, load, render

BINARY = """codeword: 1
protocol: {name}
title: t
source: s
roles:
  host: {{}}
  device: {{}}
directions:
  down: {{from: host, to: device}}
  up: {{from: device, to: host}}
framing:
  kind: bytes
  byte_order: little
  layout:
    - {{name: sync, type: u8, const: 0xa5}}
    - {{name: id, type: u8, dispatch: true}}
    - {{payload: true}}
    - {{name: sum, type: u8, checksum: {{algorithm: sum, covers: {{from: id, to: payload}}}}}}
messages:
  ask:
    id: 7
    direction: down
    fields:
      - {{name: what, type: u8}}
  answer:
    id: 7
    direction: up
    fields:
      - {{name: value, type: u8}}
  other:
    id: 8
    direction: up
    fields:
      - {{name: level, type: u8}}
"""

TEXT = """codeword: 1
protocol: {name}
title: t
source: s
roles:
  host: {{}}
  device: {{}}
directions:
  down: {{from: host, to: device}}
  up: {{from: device, to: host}}
framing:
  kind: text
  prefix_separator: ":"
  separator: ","
  terminator: ";"
messages:
  ask:
    id: "Q"
    direction: down
    fields:
      - {{name: what, type: u8}}
  answer:
    id: "Q"
    direction: up
    fields:
      - {{name: value, type: u8}}
      - {{name: unit, type: u8}}
"""


def test_binary_frames_of_one_id_decode_by_their_direction(tmp_path):
    mod = load(render(tmp_path, "shared_bin", BINARY.format(name="shared_bin")) / "shared_bin.py")
    wire = bytes.fromhex("a5 07 2a 31")  # 0x07 + 0x2a = 0x31
    assert mod.decode(wire, "down") == mod.Ask(what=42)
    assert mod.decode(wire, "up") == mod.Answer(value=42)
    assert mod.Ask.decode(wire) == mod.Ask(what=42)
    with pytest.raises(mod.DecodeError) as exc:
        mod.decode(wire)
    assert exc.value.rule == "dispatch"
    assert mod.decode(bytes.fromhex("a5 08 05 0d")) == mod.Other(level=5)  # not shared: no direction needed


def test_text_lines_of_one_prefix_decode_by_their_direction(tmp_path):
    mod = load(render(tmp_path, "shared_txt", TEXT.format(name="shared_txt")) / "shared_txt.py")
    assert mod.decode("Q:3;", "down") == mod.Ask(what=3)
    assert mod.decode("Q:3,4;", "up") == mod.Answer(value=3, unit=4)
    with pytest.raises(mod.DecodeError) as exc:
        mod.decode("Q:3;")
    assert exc.value.rule == "dispatch"
    with pytest.raises(mod.DecodeError) as exc:
        mod.decode("Q:3;", "up")  # the answer's line holds two values
    assert exc.value.rule != "dispatch"


@pytest.mark.parametrize("schema", [BINARY, TEXT], ids=["binary", "text"])
def test_c_agrees_on_every_direction_and_on_none(tmp_path, schema):
    """The vectors hold each message's frames with their direction and, for a shared id,
    without one (refused): the C decoder gives the same on the host and on AVR."""
    name = "shared_c"
    host, avr = conformance_on_host_and_avr(tmp_path, name, schema.format(name=name))
    assert host > 0 and host == avr
