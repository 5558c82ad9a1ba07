"""Integers with fixed decimals and zero padding in text lines (NMEA 0183's
`4807.038`, `01131.000`, `092750.000`, `08`): the raw integer is written with
`decimals` digits after the point, zero-padded to `width`; readers take any
spelling a receiver writes (NMEA 0183: "optional leading and trailing zeros;
decimal point and associated decimal-fraction are optional", `73.10 = 73.1 =
073.1 = 73`), rounding decimals beyond the field's to its step, halves away
from zero. Lines and raw values are worked by hand."""
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
# receiver spellings -> raw (lat, time, sats, neg or None), worked by hand
RESPELLED = {
    "P,4807.03,92750,8,-1.5;": (4807030, 92750000, 8, -15),
    "P,+4807.0384,092750.0004,008,-1.55;": (4807038, 92750000, 8, -16),  # 4 drops, 5 rounds away from 0
    "P,4807.0385,.5,8.,-00.0;": (4807039, 500, 8, 0),
    "P,00000000000000000004807.038,0,08.4,+1;": (4807038, 0, 8, 10),
    "P,9000.0004,1.9999,8.5,;": (9000000, 2000, 9, None),
}
BAD = ["P,4807.0.38,092750.000,08;", "P,48e2,092750.000,08;", "P,.,092750.000,08;", "P,-,092750.000,08;",
       "P,4807.038 ,092750.000,08;", "P,0x10,092750.000,08;", "P,++1,092750.000,08;", "P,4807.038,+-1,08;"]
OUT_OF_RANGE = ["P,9000.001,092750.000,08;", "P,9000.0005,092750.000,08;",
                "P,4807.038,99999999999999999999,08;", "P,4807.038,2147483.648,08;", "P,1,0,256;"]


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    where = tmp_path_factory.mktemp("fixedsp")
    render(where, "fixedsp", SCHEMA)
    return where


def test_python_writes_its_spelling_and_reads_any(built):
    mod = load(built / "fixedsp.py")
    m = mod.P(lat=4807.038, time=92750.0, sats=8, neg=-1.5)
    assert mod.encode(m) == GOOD
    assert mod.decode(GOOD) == m  # 4807.038 exactly: raw 4807038 / 1000
    assert mod.encode(mod.P(lat=0.005, time=0.0, sats=12)) == "P,0000.005,000000.000,12;"
    for line, (lat, time, sats, neg) in RESPELLED.items():
        got = mod.decode(line)
        assert (got.lat, got.time, got.sats, got.neg) == (
            lat / 1000, time / 1000, sats, None if neg is None else neg / 10), line
    for line in BAD:
        with pytest.raises(mod.DecodeError) as bad:
            mod.decode(line)
        assert bad.value.rule == "syntax", line
        assert bad.value.field in ("lat", "time"), line
    with pytest.raises(mod.DecodeError) as where:
        mod.decode("P,4807.038,+-1,08;")
    assert (where.value.field, where.value.offset) == ("time", 11)
    for line in OUT_OF_RANGE:
        with pytest.raises(mod.DecodeError) as high:
            mod.decode(line)
        assert high.value.rule == "range", line


def test_c_agrees(built):
    lines = [GOOD, *RESPELLED, *BAD, *OUT_OF_RANGE]
    calls = "\n".join(f'    dec("{line}");' for line in lines)
    driver = r"""
#include <stdio.h>
#include <string.h>
#include "fixedsp.h"
static void dec(const char *s) {
    fixedsp_p_t m;
    int rc;
    memset(&m, 0, sizeof m);
    rc = fixedsp_p_decode(s, strlen(s), &m);
    printf("%d %ld %ld %u %d %d\n", rc, (long)m.lat, (long)m.time, m.sats, m.has_neg, m.neg);
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
    assert out[:3] == [f"{len(GOOD)} {GOOD}", "25 P,0000.005,000000.000,12;", "0 4807038 92750000 8 1 -15"]
    respelled = [f"0 {lat} {time} {sats} {int(neg is not None)} {neg or 0}" for lat, time, sats, neg in RESPELLED.values()]
    assert out[3:3 + len(RESPELLED)] == respelled
    codes = [line.split()[0] for line in out[3 + len(RESPELLED):]]
    assert codes == ["-13"] * len(BAD) + ["-4"] * len(OUT_OF_RANGE)  # CW_ERR_SYNTAX, CW_ERR_RANGE


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
    """`decimals: 0` writes the integer as it is and reads any spelling of it, as
    Python and C alike: `07` and `7.0` are 7, `7.5` rounds to 8."""
    render(tmp_path, "zerodec", DECIMALS_ZERO)
    mod = load(tmp_path / "zerodec.py")
    assert mod.encode(mod.Q(count=7)) == "Q,7;"
    assert mod.decode("Q,7;") == mod.Q(count=7)
    assert mod.decode("Q,07;") == mod.decode("Q,7.0;") == mod.Q(count=7)
    assert mod.decode("Q,7.5;") == mod.Q(count=8)
    assert mod.decode("Q,-7.5;") == mod.Q(count=-8)
    driver = r"""
#include <stdio.h>
#include "zerodec.h"
int main(void) {
    zerodec_q_t m;
    int a = zerodec_q_decode("Q,07;", 5u, &m);
    int b = m.count;
    int c = zerodec_q_decode("Q,-7.5;", 7u, &m);
    printf("%d %d %d %d\n", a, b, c, m.count);
    return 0;
}
"""
    assert run_c(tmp_path, driver) == ["0 7 0 -8"]
