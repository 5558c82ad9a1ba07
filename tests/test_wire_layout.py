"""The wire layout is computed once, in the model: every field's first bit and
the frame cut into runs of whole bytes. Python and C spell the same runs, so a
frame mixing every kind of run comes out of both as the bytes worked out by hand."""
from __future__ import annotations

from codeword.build import compile_schema

from schema_in_a_test import load, render, run_c

SCHEMA = """codeword: 1
protocol: runs
title: t
source: s
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: sync, type: u8, const: 0x55}
    - {payload: true}
messages:
  mixed:
    fields:
      - {name: a, type: u4}
      - {name: b, type: u4}
      - {name: c, type: u24}
      - {name: d, type: u16, byte_order: little}
      - {name: e, type: u3}
      - {name: f, type: u13}
      - {name: g, type: bytes, length: 2}
      - {name: h, type: u5}
      - {name: pad, type: u3, reserved: true}
"""

# By hand: 55 | a=1 b=2: 12 | c=0x030405: 03 04 05 | d=0x0607 little: 07 06
# | e=5 f=0x123: 101 0000100100011 = a1 23 | g: 68 69 | h=0x1f pad=0: 11111 000 = f8
FRAME = "55 12 03 04 05 07 06 a1 23 68 69 f8"
VALUES = dict(a=1, b=2, c=0x030405, d=0x0607, e=5, f=0x123, g=b"hi", h=0x1F)


def test_runs_are_cut_once_in_the_model(tmp_path):
    path = tmp_path / "runs.yaml"
    path.write_text(SCHEMA, encoding="utf-8")
    m = compile_schema(path).messages[0]
    runs = [(r.kind, r.start, r.size, [leaf.dotted for leaf in r.leaves]) for r in m.wire.runs]
    assert runs == [("number", 0, 1, ["sync"]), ("packed", 1, 1, ["a", "b"]), ("number", 2, 3, ["c"]),
                    ("number", 5, 2, ["d"]), ("packed", 7, 2, ["e", "f"]), ("bytes", 9, 2, ["g"]),
                    ("packed", 11, 1, ["h", "pad"])]
    assert [leaf.pos for leaf in m.wire.leaves] == [0, 8, 12, 16, 40, 56, 59, 72, 88, 93]
    packed = m.wire.runs[4]
    assert [packed.shift(leaf) for leaf in packed.leaves] == [13, 0]


def test_python_and_c_write_and_read_the_hand_worked_frame(tmp_path):
    render(tmp_path, "runs", SCHEMA)
    mod = load(tmp_path / "runs.py")
    frame = bytes.fromhex(FRAME)
    assert mod.encode(mod.Mixed(**VALUES)) == frame
    assert mod.decode(frame) == mod.Mixed(**VALUES)
    driver = r"""
#include <stdio.h>
#include <string.h>
#include "runs.h"
int main(void) {
    runs_mixed_t m, back;
    uint8_t out[12];
    int n, i;
    memset(&m, 0, sizeof m);
    m.a = 1; m.b = 2; m.c = 0x030405ul; m.d = 0x0607u; m.e = 5; m.f = 0x123u;
    memcpy(m.g, "hi", 2); m.h = 0x1f;
    n = runs_mixed_encode(&m, out, sizeof out);
    printf("%d", n);
    for (i = 0; i < n; i++) printf(" %02x", out[i]);
    printf("\n");
    n = runs_mixed_decode(out, sizeof out, &back);
    printf("%d %d %d %lx %x %d %x %c%c %x\n", n, back.a, back.b, (unsigned long)back.c, (unsigned)back.d,
           back.e, (unsigned)back.f, back.g[0], back.g[1], back.h);
    return 0;
}
"""
    assert run_c(tmp_path, driver) == ["12 " + FRAME, "0 1 2 30405 607 5 123 hi 1f"]
