"""`finite: false`: a binary float that may hold NaN and the infinities (MAVLink sends NaN
for "no value" or "no change"). Any NaN decodes; every encoder sends the quiet NaN,
0x7FC00000 in an f32 and 0x7FF8000000000000 in an f64, whatever NaN it holds, so that
Python and C write the same bytes; an infinity is sent as it is. Expected frames are
worked by hand from IEEE 754: a frame `A5 01 | a f32 LE | b f64 LE | c f32 LE` with
CRC-16/MCRF4XX over the bytes after the sync, checked against pymavlink's x25crc."""
import math
import struct

import pytest
from pymavlink.mavutil import x25crc

from codeword.build import compile_schema
from codeword.diff.compare import compare
from codeword.fingerprint import fingerprint
from schema_in_a_test import c_bytes, conformance_on_host_and_avr, load, render, run_c

SCHEMA = """\
codeword: 1
protocol: nanp
title: floats that may be NaN
source: tests/test_nonfinite_floats.py
framing:
  kind: bytes
  byte_order: little
  layout:
    - {name: sync, type: u8, const: 0xA5}
    - {name: id, type: u8, dispatch: true}
    - {payload: true}
    - name: crc
      type: u16
      checksum: {algorithm: CRC-16/MCRF4XX, covers: {from: id, to: payload}}
messages:
  sample:
    id: 1
    fields:
      - {name: a, type: f32, finite: false}
      - {name: b, type: f64, finite: false}
      - {name: c, type: f32}
"""


def frame(a: bytes, b: bytes, c: bytes) -> bytes:
    body = b"\x01" + a + b + c
    return b"\xa5" + body + struct.pack("<H", x25crc(body).crc)


QUIET32, QUIET64 = bytes.fromhex("0000c07f"), bytes.fromhex("000000000000f87f")  # 0x7FC00000, 0x7FF8000000000000
MINUS_INF64 = bytes.fromhex("000000000000f0ff")  # 0xFFF0000000000000
ONE_AND_A_HALF = bytes.fromhex("0000c03f")  # 1.5 = 0x3FC00000
# NaNs no encoder sends: negative, with a payload (0xFFC00001; 0xFFF0000000000001, signalling)
ODD32, ODD64 = bytes.fromhex("0100c0ff"), bytes.fromhex("010000000000f0ff")


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    where = tmp_path_factory.mktemp("nanp")
    render(where, "nanp", SCHEMA)
    return where


def test_python_sends_any_nan_as_the_quiet_nan_and_an_infinity_as_it_is(built):
    mod = load(built / "nanp.py")
    odd = struct.unpack("<d", ODD64)[0]
    assert math.isnan(odd)
    wire = mod.encode(mod.Sample(a=odd, b=-math.inf, c=1.5))
    assert wire == frame(QUIET32, MINUS_INF64, ONE_AND_A_HALF)
    back = mod.decode(frame(ODD32, ODD64, ONE_AND_A_HALF))  # any NaN is read
    assert math.isnan(back.a) and math.isnan(back.b) and back.c == 1.5
    assert mod.encode(back) == frame(QUIET32, QUIET64, ONE_AND_A_HALF)


def test_a_float_left_finite_still_refuses_nan(built):
    mod = load(built / "nanp.py")
    with pytest.raises(mod.EncodeError) as err:
        mod.encode(mod.Sample(a=1.0, b=2.0, c=math.nan))
    assert (err.value.field, err.value.rule) == ("c", "finite")
    with pytest.raises(mod.DecodeError) as derr:
        mod.decode(frame(QUIET32, QUIET64, QUIET32))
    assert (derr.value.field, derr.value.rule) == ("c", "finite")
    with pytest.raises(mod.EncodeError) as err:  # a value that is no float is no NaN either
        mod.encode(mod.Sample(a="nan", b=2.0, c=1.0))
    assert (err.value.field, err.value.rule) == ("a", "type")


def test_c_reads_any_nan_and_sends_the_quiet_nan_as_python_does(built):
    odd = frame(ODD32, ODD64, ONE_AND_A_HALF)
    driver = f"""
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "nanp.h"
static const uint8_t odd[] = {{{c_bytes(odd)}}};
static void show(const uint8_t *b, int n)
{{
    int i;
    for (i = 0; i < n; i++) {{
        printf("%02x", b[i]);
    }}
    printf("\\n");
}}
int main(void)
{{
    nanp_sample_t m;
    uint8_t out[32];
    int rc = nanp_sample_decode(odd, sizeof odd, &m);
    printf("%d %d %d\\n", rc, isnan(m.a) != 0, isnan(m.b) != 0);
    show(out, nanp_sample_encode(&m, out, sizeof out));
    m.a = -INFINITY;
    m.b = INFINITY;
    show(out, nanp_sample_encode(&m, out, sizeof out));
    m.c = NAN;
    printf("%d\\n", nanp_sample_encode(&m, out, sizeof out));
    return 0;
}}
"""
    lines = run_c(built, driver)
    assert lines[0] == "0 1 1"
    assert lines[1] == frame(QUIET32, QUIET64, ONE_AND_A_HALF).hex()
    assert lines[2] == frame(bytes.fromhex("000080ff"), bytes.fromhex("000000000000f07f"), ONE_AND_A_HALF).hex()
    assert lines[3] == "-17"  # CW_ERR_FINITE: c is finite


def test_the_conformance_vectors_hold_nan_and_the_infinities_on_the_host_and_on_avr(tmp_path):
    """The vectors draw NaN and the infinities for such fields; C passes them, and on AVR
    (32-bit double: the f64 member is its bits) too."""
    host, avr = conformance_on_host_and_avr(tmp_path, "nanp", SCHEMA, parts=1)
    assert host > 100 and avr > 100


def test_the_schema_says_it_in_the_docs_the_fingerprint_and_diff(tmp_path):
    finite = SCHEMA.replace("{name: a, type: f32, finite: false}", "{name: a, type: f32}")
    (tmp_path / "old.yaml").write_text(finite, encoding="utf-8")
    (tmp_path / "new.yaml").write_text(SCHEMA, encoding="utf-8")
    old, new = compile_schema(tmp_path / "old.yaml"), compile_schema(tmp_path / "new.yaml")
    assert fingerprint(old) != fingerprint(new)
    widened = {(c.subject, c.what, c.kind) for c in compare(old, new).changes}
    narrowed = {(c.subject, c.what, c.kind) for c in compare(new, old).changes}
    assert ("field a", "now holds NaN and the infinities too (widened)", "compatible") in widened
    assert ("field a", "NaN and the infinities now refused", "breaking") in narrowed
    from codeword.targets import markdown
    docs = markdown.render(new, load(render(tmp_path, "nanp", SCHEMA) / "nanp.py"))["docs/nanp.md"]
    assert "| IEEE-754 binary32 or NaN, ±∞ |" in docs and "| IEEE-754 binary64 or NaN, ±∞ |" in docs
    assert "a sender sends every NaN as the quiet NaN, `0x7FC00000` in 32 bits and `0x7FF8000000000000` in 64" in docs
