"""Text floats: the Python codec (binary64 floats) and the C codec (cw_decimal_t,
digits as written) read and write the same lines. A text float holds at most 15
significant digits and is 0 or at least 1e-307 in magnitude: within that, every
decimal survives a double digit for digit, so both sides agree on every value."""
from __future__ import annotations

import pytest

from schema_in_a_test import load, render, run_c

SCHEMA = """codeword: 1
protocol: tf
title: t
source: s
framing:
  kind: text
  prefix_separator: ':'
  separator: ','
  terminator: ";"
  trim: true
messages:
  r:
    id: R
    fields:
      - {name: x, type: f64}
      - {name: n, type: i16}
"""

# (body of x, what both decoders give: the value's text as written back, or the error)
LINES = [
    ("1.5", "1.5"),
    ("-0.25", "-0.25"),
    ("123456789012345", "123456789012345"),          # 15 digits
    ("1234567890.12345", "1234567890.12345"),
    ("0.000123456789012345", "0.000123456789012345"),
    ("1e-307", "1e-307"),
    ("-1.79769313486231e308", "-1.79769313486231e+308"),
    ("000000000000000000001.5000000000000", "1.5"),  # zeros are not significant
    ("1e-400", "precision"),                          # a double reads it as 0
    ("4.9e-324", "precision"),                        # subnormal: digits not kept
    ("9.99999999999999e-308", "precision"),
    ("1234567890123456", "precision"),                # 16 digits
    ("-361669.46998275385", "precision"),             # 17 digits; a double writes ...386
    ("1.79769313486232e308", "finite"),
    ("1e309", "finite"),
    ("1.5x", "syntax"),
]


def python_result(mod, line: str) -> str:
    try:
        m = mod.decode(line)
    except mod.DecodeError as err:
        return err.rule
    return mod.encode(m)[2:].split(",")[0]


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    where = tmp_path_factory.mktemp("tf")
    render(where, "tf", SCHEMA)
    return where


def test_python_reads_text_floats_within_the_rule(built):
    mod = load(built / "tf.py")
    assert [python_result(mod, f"R:{x},7;") for x, _ in LINES] == [want for _, want in LINES]


def test_c_reads_text_floats_like_python(built):
    lines = "\n".join(f'    show("R:{x},7;");' for x, _ in LINES)
    driver = """#include <stdio.h>
#include <string.h>
#include "tf.h"
static void show(const char *line) {
    tf_r_t m;
    char out[64];
    int rc = tf_r_decode(line, strlen(line), &m);
    int n;
    if (rc != CW_OK) {
        printf("%s\\n", cw_error_name(rc));
        return;
    }
    n = tf_r_encode(&m, out, sizeof out);
    if (n < 0) {
        printf("encode %s\\n", cw_error_name(n));
        return;
    }
    printf("%.*s\\n", (int)strcspn(out + 2, ","), out + 2);
}
int main(void) {
""" + lines + """
    return 0;
}
"""
    assert run_c(built, driver) == [want for _, want in LINES]


def test_python_encoder_refuses_what_a_decoder_would(built):
    mod = load(built / "tf.py")
    for value, rule in [(0.1 + 0.2, "precision"), (1e-310, "precision"), (-5e-324, "precision"),
                        (10 ** 400, "finite"), (-(10 ** 400), "finite"), (float("nan"), "finite")]:
        with pytest.raises(mod.EncodeError) as err:
            mod.encode(mod.R(x=value, n=1))
        assert err.value.rule == rule, value
    assert mod.encode(mod.R(x=10 ** 20, n=1)) == "R:1e+20,1;"
    assert mod.encode(mod.R(x=0.3, n=1)) == "R:0.3,1;"


def test_c_encoder_refuses_what_a_decoder_would(built):
    cases = [("8u, 14446", "finite"), ("179769313486232ULL, 294", "finite"),
             ("179769313486231ULL, 294", "ok"), ("1234567890123456ULL, 0", "precision"),
             ("1u, -308", "precision"), ("1u, -307", "ok"), ("0u, 0", "ok")]
    calls = "\n".join(f"    show({args});" for args, _ in cases)
    driver = """#include <stdio.h>
#include "tf.h"
static void show(uint64_t digits, int16_t exp10) {
    tf_r_t m;
    char out[64];
    int n;
    m.x.digits = digits;
    m.x.exp10 = exp10;
    m.x.negative = false;
    m.n = 1;
    n = tf_r_encode(&m, out, sizeof out);
    printf("%s\\n", n < 0 ? cw_error_name(n) : "ok");
}
int main(void) {
""" + calls + """
    return 0;
}
"""
    assert run_c(built, driver) == [want for _, want in cases]


def test_only_ascii_text_is_read(built):
    """str.strip() and float() take Unicode spaces and digits; the C decoder reads bytes."""
    mod = load(built / "tf.py")
    for line in ["R:\u00a01.5,7;", "R:1.5\u3000,7;", "R:\u0661,7;", "R:1.5,7;\u0085"]:
        with pytest.raises(mod.DecodeError) as err:
            mod.decode(line)
        assert err.value.rule == "text", line


def test_c_refuses_the_same_bytes(built):
    mod = load(built / "tf.py")
    lines = [b"R:\xc2\xa01.5,7;", b"R:1.5\xe3\x80\x80,7;", b"R:\xd9\xa1,7;", b"R:1.5,7\x85;"]
    for line in lines:
        with pytest.raises(mod.DecodeError) as err:
            mod.decode(line)
        assert err.value.rule == "text", line
    calls = "\n".join('    show("' + "".join(f"\\x{b:02x}" for b in line) + f'", {len(line)}u);' for line in lines)
    driver = """#include <stdio.h>
#include "tf.h"
static void show(const char *line, size_t n) {
    tf_r_t m;
    printf("%s\\n", cw_error_name(tf_r_decode(line, n, &m)));
}
int main(void) {
""" + calls + """
    return 0;
}
"""
    assert run_c(built, driver) == ["text"] * len(lines)
