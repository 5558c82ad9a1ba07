"""Integers with fixed decimals and zero padding in text lines (NMEA 0183's
`4807.038`, `01131.000`, `092750.000`, `08`): the raw integer is written with
`decimals` digits after the point, zero-padded to `width`; readers accept exactly
that spelling and give the value the text shows. Lines are written by hand."""
from __future__ import annotations

import pytest

from schema_in_a_test import load, render, run_c

SCHEMA = """codeword: 1
protocol: fixedsp
title: t
source: s
framing: {kind: text, prefix_separator: ",", separator: ",", terminator: ";"}
messages:
  p:
    id: P
    fields:
      - {name: lat, type: i32, decimals: 3, width: 8, range: [0, 9000]}
      - {name: time, type: i32, decimals: 3, width: 10}
      - {name: sats, type: u8, width: 2}
      - {name: neg, type: i16, decimals: 1, width: 5, optional: true}
"""

GOOD = "P,4807.038,092750.000,08,-01.5;"
BAD = ["P,4807.03,092750.000,08;", "P,04807.038,092750.000,08;", "P,4807.038,92750.000,08;",
       "P,4807.038,092750.000,8;", "P,4807.038,092750.000,08,-00.0;", "P,+4807.038,092750.000,08;"]


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    where = tmp_path_factory.mktemp("fixedsp")
    render(where, "fixedsp", SCHEMA)
    return where


def test_python_writes_and_reads_the_exact_spelling(built):
    mod = load(built / "fixedsp.py")
    m = mod.P(lat=4807.038, time=92750.0, sats=8, neg=-1.5)
    assert mod.encode(m) == GOOD
    assert mod.decode(GOOD) == m  # 4807.038 exactly: raw 4807038 / 1000
    assert mod.encode(mod.P(lat=0.005, time=0.0, sats=12)) == "P,0000.005,000000.000,12;"
    for line in BAD:
        with pytest.raises(mod.DecodeError) as bad:
            mod.decode(line)
        assert bad.value.rule == "syntax", line
    with pytest.raises(mod.DecodeError) as high:
        mod.decode("P,9000.001,092750.000,08;")
    assert high.value.rule == "range"


def test_c_agrees(built):
    calls = "\n".join(f'    dec("{line}");' for line in [GOOD, *BAD, "P,9000.001,092750.000,08;"])
    driver = r"""
#include <stdio.h>
#include <string.h>
#include "fixedsp.h"
static void dec(const char *s) {
    fixedsp_p_t m;
    int rc;
    memset(&m, 0, sizeof m);
    rc = fixedsp_p_decode(s, strlen(s), &m);
    printf("%d %ld %ld %u %d\n", rc, (long)m.lat, (long)m.time, m.sats, m.neg);
}
int main(void) {
    fixedsp_p_t m;
    char buf[80];
    memset(&m, 0, sizeof m);
    m.lat = 4807038; m.time = 92750000; m.sats = 8; m.has_neg = true; m.neg = -15;
    printf("%d %s\n", fixedsp_p_encode(&m, buf, sizeof buf), buf);
    m.lat = 5; m.time = 0; m.sats = 12; m.has_neg = false;
    printf("%d %s\n", fixedsp_p_encode(&m, buf, sizeof buf), buf);
CALLS
    return 0;
}
""".replace("CALLS", calls)
    out = run_c(built, driver)
    assert out[:3] == [f"{len(GOOD)} {GOOD}", "25 P,0000.005,000000.000,12;", "0 4807038 92750000 8 -15"]
    assert [line.split()[0] for line in out[3:]] == ["-13"] * len(BAD) + ["-4"]  # CW_ERR_SYNTAX, CW_ERR_RANGE


DECIMALS_ZERO = """codeword: 1
protocol: zerodec
title: t
source: s
framing: {kind: text, prefix_separator: ",", separator: ",", terminator: ";"}
messages:
  q:
    id: Q
    fields:
      - {name: count, type: i16, decimals: 0}
"""


def test_decimals_zero_is_a_fixed_spelling_too(tmp_path):
    """`decimals: 0` writes the integer as it is and reads only that: `07` is not `7`
    (Python took `decimals: 0` for no option and read `07`; C refused it)."""
    render(tmp_path, "zerodec", DECIMALS_ZERO)
    mod = load(tmp_path / "zerodec.py")
    assert mod.encode(mod.Q(count=7)) == "Q,7;"
    assert mod.decode("Q,7;") == mod.Q(count=7)
    with pytest.raises(mod.DecodeError) as err:
        mod.decode("Q,07;")
    assert err.value.rule == "syntax"
    driver = r"""
#include <stdio.h>
#include "zerodec.h"
int main(void) {
    zerodec_q_t m;
    printf("%d %d\n", zerodec_q_decode("Q,7;", 4u, &m), zerodec_q_decode("Q,07;", 5u, &m) == CW_ERR_SYNTAX);
    return 0;
}
"""
    assert run_c(tmp_path, driver) == ["0 1"]
