"""Empty values in the middle of a text line (NMEA 0183's `,,`): an optional field
may be absent anywhere; absent, it is written as nothing between its separators and
an empty value reads back as absent (None, `has_<name>` false). Optional values at
the end are left out with their separators; an optional str, whose empty value is
an empty str, may be absent only there. Lines are written out by hand."""
from __future__ import annotations

import pytest

from schema_in_a_test import load, render, run_c

SCHEMA = """codeword: 1
protocol: empties
title: t
source: s
framing: {kind: text, prefix_separator: ",", separator: ",", terminator: ";", trim: true}
messages:
  fix:
    id: FIX
    fields:
      - {name: age, type: f64, optional: true}
      - {name: sats, type: u8}
      - {name: hemi, type: char, optional: true}
      - {name: mode, type: u8, optional: true}
      - {name: height, type: i16}
      - {name: station, type: u16, optional: true}
      - {name: note, type: str, max_length: 6, optional: true}
      - {name: last, type: char, optional: true}
"""


@pytest.fixture(scope="module")
def mod(tmp_path_factory):
    where = tmp_path_factory.mktemp("empties")
    render(where, "empties", SCHEMA)
    return load(where / "empties.py"), where


CASES = [
    ("FIX,,8,,,-3;", dict(sats=8, height=-3)),
    ("FIX,1.5,8,N,2,-3,12;", dict(age=1.5, sats=8, hemi="N", mode=2, height=-3, station=12)),
    ("FIX,,8,,2,-3,,ok;", dict(sats=8, mode=2, height=-3, note="ok")),
    ("FIX,,8,N,,-3,,ok,z;", dict(sats=8, hemi="N", height=-3, note="ok", last="z")),
]


@pytest.mark.parametrize("line,values", CASES)
def test_python_both_ways(mod, line, values):
    m, _ = mod
    assert m.encode(m.Fix(**values)) == line
    assert m.decode(line) == m.Fix(**values)


def test_empty_values_read_as_absent_and_required_ones_stay_required(mod):
    m, _ = mod
    assert m.decode("FIX, ,8, , ,-3, ;") == m.Fix(sats=8, height=-3)  # trimmed: blank is empty
    with pytest.raises(m.DecodeError) as bad:
        m.decode("FIX,,,,,-3;")
    assert bad.value.field == "sats"
    with pytest.raises(m.EncodeError) as gap:
        m.encode(m.Fix(sats=8, height=-3, last="z"))  # note absent before a present value
    assert gap.value.field == "note" and gap.value.rule == "count"


def test_c_agrees(mod):
    _, where = mod
    lines = "\n".join(f'    show("{line}");' for line, _ in CASES)
    driver = r"""
#include <stdio.h>
#include <string.h>
#include "empties.h"
static void show(const char *line) {
    empties_fix_t m;
    char buf[64];
    int rc, n;
    memset(&m, 0, sizeof m);
    rc = empties_fix_decode(line, strlen(line), &m);
    n = empties_fix_encode(&m, buf, sizeof buf);
    printf("%d %d%d%d%d%d%d %.*s\n", rc, m.has_age, m.has_hemi, m.has_mode, m.has_station, m.has_note,
           m.has_last, n, buf);
}
int main(void) {
    empties_fix_t m;
    char buf[64];
LINES
    memset(&m, 0, sizeof m);
    m.sats = 8; m.height = -3; m.has_last = true; m.last = 'z';
    printf("%d\n", empties_fix_encode(&m, buf, sizeof buf) == CW_ERR_COUNT);
    printf("%d\n", empties_fix_decode("FIX,,,,,-3;", 11u, &m) != CW_OK);
    return 0;
}
""".replace("LINES", lines)
    assert run_c(where, driver) == [
        "0 000000 FIX,,8,,,-3;", "0 111100 FIX,1.5,8,N,2,-3,12;", "0 001010 FIX,,8,,2,-3,,ok;",
        "0 010011 FIX,,8,N,,-3,,ok,z;", "1", "1"]
