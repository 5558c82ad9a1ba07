"""An integer offset on a signed field: value = raw + offset, in C as in Python.
-104 with offset -100 is raw -4, four bits 1100, sent in the high half of the byte."""
from __future__ import annotations

from scratch import load, render, run_c

SCHEMA = """codeword: 1
protocol: shifted
title: t
source: s
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: sync, type: u8, const: 0x55}
    - {payload: true}
messages:
  a:
    fields:
      - {name: level, type: i4, offset: -100}
      - {name: pad, type: u4, reserved: true}
"""


def test_signed_field_with_an_integer_offset(tmp_path):
    render(tmp_path, "shifted", SCHEMA)
    mod = load(tmp_path / "shifted.py")
    assert mod.encode(mod.A(level=-104)) == bytes.fromhex("55 c0")
    assert mod.decode(bytes.fromhex("55 70")).level == -93  # raw 7
    driver = r"""
#include <stdio.h>
#include "shifted.h"
int main(void) {
    static const uint8_t frame[] = {0x55, 0x70};
    shifted_a_t m;
    uint8_t out[2];
    int n;
    m.level = -104;
    n = shifted_a_encode(&m, out, sizeof out);
    printf("%d %02x %02x\n", n, out[0], out[1]);
    n = shifted_a_decode(frame, sizeof frame, &m);
    printf("%d %d\n", n, m.level);
    return 0;
}
"""
    assert run_c(tmp_path, driver) == ["2 55 c0", "0 -93"]
