"""Integers of 33..64 bits: every bit and the byte order kept, in C as in Python.
Expected frames are written out by hand from the field widths below."""
from __future__ import annotations

from schema_in_a_test import load, render, run_c

BINARY = """codeword: 1
protocol: wide
title: t
source: s
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: kind, type: u8, dispatch: true}
    - {payload: true}
messages:
  big:
    id: 1
    fields:
      - {name: a, type: u64}
      - {name: b, type: i64, byte_order: little}
      - {name: c, type: u40}
      - {name: d, type: i36}
      - {name: pad, type: u4, reserved: true}
      - {name: f, type: u48, range: [1, 281474976710000]}
"""

# kind | a (8, big) | b (8, little) | c (5, big) | d: 36 bits, then 4 zero bits | f (6, big)
FRAMES = [
    ("01 0123456789abcdef feffffffffffffff ffeeddccbb fffffffff0 123456789abc",
     dict(a=0x0123456789ABCDEF, b=-2, c=0xFFEEDDCCBB, d=-1, f=0x123456789ABC)),
    ("01 ffffffffffffffff 0000000000000080 0000000000 8000000000 000000000001",
     dict(a=(1 << 64) - 1, b=-(1 << 63), c=0, d=-(1 << 35), f=1)),
    ("01 8000000000000000 ffffffffffffff7f 8000000001 7ffffffff0 fffffffffd70",
     dict(a=1 << 63, b=(1 << 63) - 1, c=(1 << 39) + 1, d=(1 << 35) - 1, f=281474976710000)),
]

TEXT = """codeword: 1
protocol: widetext
title: t
source: s
framing:
  kind: text
  prefix_separator: ':'
  separator: ','
  terminator: "\\n"
messages:
  w:
    id: W
    fields:
      - {name: a, type: u64}
      - {name: b, type: i64}
      - {name: c, type: u32}
      - {name: d, type: i40, range: [-500000000000, 500000000000]}
"""

LINES = [
    ("W:18446744073709551615,-9223372036854775808,4294967295,-500000000000\n",
     dict(a=(1 << 64) - 1, b=-(1 << 63), c=(1 << 32) - 1, d=-5 * 10**11)),
    ("W:0,9223372036854775807,2147483648,500000000000\n",
     dict(a=0, b=(1 << 63) - 1, c=1 << 31, d=5 * 10**11)),
]

# each refused by both decoders, with the error kind both name
BAD_LINES = [
    ("W:18446744073709551616,0,0,0\n", "range"),   # 2**64
    ("W:-1,0,0,0\n", "range"),
    ("W:0,9223372036854775808,0,0\n", "range"),    # 2**63
    ("W:0,0,4294967296,0\n", "range"),             # 2**32
    ("W:0,0,0,500000000001\n", "range"),
    ("W:0,0,0,99999999999999999999999\n", "range"),
    ("W:0,0,1x,0\n", "syntax"),
]


def c_hex(frame: str) -> str:
    return ", ".join(f"0x{b:02x}" for b in bytes.fromhex(frame))


def test_python_encodes_and_decodes_wide_integers(tmp_path):
    mod = load(render(tmp_path, "wide", BINARY) / "wide.py")
    for frame, values in FRAMES:
        assert mod.encode(mod.Big(**values)) == bytes.fromhex(frame)
        decoded = mod.decode(bytes.fromhex(frame))
        assert {k: getattr(decoded, k) for k in values} == values


def test_c_encodes_and_decodes_wide_integers(tmp_path):
    render(tmp_path, "wide", BINARY)
    calls = []
    for frame, v in FRAMES:
        calls.append(f"""    {{
        static const uint8_t frame[] = {{{c_hex(frame)}}};
        m.a = {v['a']}ULL; m.b = (int64_t)({v['b'] + (1 << 63)}ULL - 9223372036854775807ULL - 1ULL);
        m.c = {v['c']}ULL; m.d = {v['d']}LL; m.f = {v['f']}ULL;
        n = wide_big_encode(&m, out, sizeof out);
        for (i = 0; i < n; i++) printf("%02x", out[i]);
        printf(" %d\\n", memcmp(out, frame, sizeof frame) == 0);
        memset(&m, 0, sizeof m);
        n = wide_big_decode(frame, sizeof frame, &m);
        printf("%d %" PRIu64 " %" PRId64 " %" PRIu64 " %" PRId64 " %" PRIu64 "\\n", n, m.a, m.b, m.c, m.d, m.f);
    }}""")
    driver = """#include <inttypes.h>
#include <stdio.h>
#include <string.h>
#include "wide.h"
int main(void) {
    wide_big_t m;
    uint8_t out[64];
    int n, i;
""" + "\n".join(calls) + """
    m.a = 0; m.b = 0; m.c = 0; m.d = 0; m.f = 0;
    printf("%s\\n", cw_error_name(wide_big_encode(&m, out, sizeof out)));
    m.c = 1ULL << 40; m.f = 1;
    printf("%s\\n", cw_error_name(wide_big_encode(&m, out, sizeof out)));
    return 0;
}
"""
    lines = run_c(tmp_path, driver)
    expected = []
    for frame, v in FRAMES:
        expected.append(frame.replace(" ", "") + " 1")
        expected.append(f"0 {v['a']} {v['b']} {v['c']} {v['d']} {v['f']}")
    assert lines == expected + ["range", "range"]


def test_python_text_integers_of_64_bits(tmp_path):
    mod = load(render(tmp_path, "widetext", TEXT) / "widetext.py")
    for line, values in LINES:
        assert mod.encode(mod.W(**values)) == line
        decoded = mod.decode(line)
        assert {k: getattr(decoded, k) for k in values} == values
    for line, kind in BAD_LINES:
        try:
            mod.decode(line)
        except mod.DecodeError as err:
            assert err.rule == kind, (line, err)
        else:
            raise AssertionError(f"{line!r} decoded")


def test_c_text_integers_of_64_bits(tmp_path):
    render(tmp_path, "widetext", TEXT)
    calls = []
    for line, v in LINES:
        text = line.replace("\n", "\\n")
        calls.append(f"""    {{
        static const char line[] = "{text}";
        m.a = {v['a']}ULL; m.b = (int64_t)({v['b'] + (1 << 63)}ULL - 9223372036854775807ULL - 1ULL);
        m.c = {v['c']}UL; m.d = {v['d']}LL;
        n = widetext_w_encode(&m, out, sizeof out);
        printf("%d %d\\n", n, n > 0 && (size_t)n == strlen(line) && memcmp(out, line, (size_t)n) == 0);
        memset(&m, 0, sizeof m);
        n = widetext_w_decode(line, strlen(line), &m);
        printf("%d %" PRIu64 " %" PRId64 " %" PRIu32 " %" PRId64 "\\n", n, m.a, m.b, m.c, m.d);
    }}""")
    for line, _ in BAD_LINES:
        text = line.replace("\n", "\\n")
        calls.append(f'    printf("%s\\n", cw_error_name(widetext_w_decode("{text}", strlen("{text}"), &m)));')
    driver = """#include <inttypes.h>
#include <stdio.h>
#include <string.h>
#include "widetext.h"
int main(void) {
    widetext_w_t m;
    char out[128];
    int n;
""" + "\n".join(calls) + """
    return 0;
}
"""
    lines = run_c(tmp_path, driver)
    expected = []
    for line, v in LINES:
        expected.append(f"{len(line)} 1")
        expected.append(f"0 {v['a']} {v['b']} {v['c']} {v['d']}")
    assert lines == expected + [kind for _, kind in BAD_LINES]
