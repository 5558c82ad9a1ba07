"""A serial transport's baud rate on a binary protocol gives a time per frame
(8N1: ten bits a byte), also for a message without an id."""
from __future__ import annotations

from codeword.build import compile_schema, render_with_codec

SCHEMA = """codeword: 1
protocol: budget
title: t
source: s
transports:
  - {name: uart, kind: serial, params: {baud: 9600}}
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: sync, type: u8, const: 0x55}
    - {payload: true}
messages:
  a:
    fields:
      - {name: x, type: u32}
"""


def test_binary_frames_over_a_serial_link(tmp_path):
    path = tmp_path / "budget.yaml"
    path.write_text(SCHEMA, encoding="utf-8")
    page = render_with_codec(compile_schema(path))[0]["docs/budget.md"]
    assert "| line rate | **9600 baud, 8N1 (10 bits a byte)** |" in page
    # 5 bytes × 10 bits / 9600 baud = 5.2 ms
    assert "| `a` frame | **5 bytes, 5.2 ms** | 5 × 10 bits |" in page
