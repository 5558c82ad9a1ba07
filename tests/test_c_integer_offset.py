"""An integer offset on a signed field: value = raw + offset, in C as in Python.
-104 with offset -100 is raw -4, four bits 1100, sent in the high half of the byte."""
from __future__ import annotations

from schema_in_a_test import load, render, run_c

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


NARROW = """codeword: 1
protocol: narrow
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
      - {name: level, type: i9, range: [-73, 92]}
      - {name: count, type: u7, range: [0, 100]}
"""


def test_range_is_checked_on_every_value_of_the_wire_type(tmp_path):
    """The members are int16_t and uint8_t (the wire types i9 and u7, not the ranges):
    -201 (1 0011 0111) would wrap to 55 in an int8_t and 0x7f is fine, but both must be
    range errors exactly as in Python."""
    render(tmp_path, "narrow", NARROW)
    mod = load(tmp_path / "narrow.py")
    frames = {"55 9b 80": "range",   # level -201: 1 0011 0111, count 0
              "55 00 e4": "ok",      # level 0, count 100 (0x64 = 110 0100)
              "55 00 e5": "range"}   # count 101
    for frame, want in frames.items():
        try:
            mod.decode(bytes.fromhex(frame))
            got = "ok"
        except mod.DecodeError as err:
            got = err.rule
        assert got == want, frame
    calls = "\n".join(f'    show((const uint8_t[]){{0x{f[0:2]}, 0x{f[3:5]}, 0x{f[6:8]}}});' for f in frames)
    driver = """#include <stdio.h>
#include "narrow.h"
static void show(const uint8_t *frame) {
    narrow_a_t m;
    int rc = narrow_a_decode(frame, 3u, &m);
    printf("%s\\n", rc == CW_OK ? "ok" : cw_error_name(rc));
}
int main(void) {
""" + calls + """
    return 0;
}
"""
    assert run_c(tmp_path, driver) == list(frames.values())
