"""A constant char or str field of a text line is no member of the message: the
encoders write it as the schema spells it and the decoders check it. The Python
encoder used to read it from the message (AttributeError)."""
from __future__ import annotations

from schema_in_a_test import load, render, run_c

SCHEMA = """codeword: 1
protocol: units
title: t
source: s
framing: {kind: text, prefix_separator: ",", separator: ",", terminator: ";"}
messages:
  speed:
    id: SPD
    fields:
      - {name: value, type: u16}
      - {name: unit, type: char, const: K}
      - {name: label, type: str, max_length: 3, const: kmh}
"""


def test_python_writes_and_checks_text_constants(tmp_path):
    render(tmp_path, "units", SCHEMA)
    mod = load(tmp_path / "units.py")
    assert mod.encode(mod.Speed(value=12)) == "SPD,12,K,kmh;"
    assert mod.decode("SPD,12,K,kmh;") == mod.Speed(value=12)
    for bad in ("SPD,12,N,kmh;", "SPD,12,K,mph;"):
        try:
            mod.decode(bad)
        except mod.DecodeError as err:
            assert err.rule == "const"
        else:
            raise AssertionError(f"{bad} decoded")


def test_c_writes_and_checks_text_constants(tmp_path):
    render(tmp_path, "units", SCHEMA)
    driver = r"""
#include <stdio.h>
#include <string.h>
#include "units.h"
int main(void) {
    units_speed_t m;
    char out[32];
    m.value = 12u;
    printf("%d %s\n", units_speed_encode(&m, out, sizeof out), out);
    printf("%d\n", units_speed_decode("SPD,12,N,kmh;", 13u, &m) == CW_ERR_CONST);
    return 0;
}
"""
    assert run_c(tmp_path, driver) == ["13 SPD,12,K,kmh;", "1"]
