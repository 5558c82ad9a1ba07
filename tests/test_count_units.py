"""A count in units other than elements or bytes: Modbus reads a float as two 16-bit
registers, so a quantity of registers counts 2-byte units (`unit: 2`); an array of
bytes counted in 2-byte words takes two elements per unit. Frames worked by hand
(big-endian; 1.0 is 3f800000 and -2.5 is c0200000 in binary32)."""
from __future__ import annotations

import pytest

from schema_in_a_test import conformance_on_host_and_avr, load, render, run_c

SCHEMA = """codeword: 1
protocol: units
title: t
source: s
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: id, type: u8, dispatch: true}
    - {payload: true}
messages:
  floats:
    id: 3
    fields:
      - {name: registers, type: u8}
      - {name: values, type: f32, count: {from: registers, unit: 2}, max_count: 4}
  words:
    id: 4
    fields:
      - {name: words, type: u8}
      - {name: data, type: u8, count: {from: words, unit: 2}, max_count: 6}
"""


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    where = tmp_path_factory.mktemp("units")
    render(where, "units", SCHEMA)
    return where, load(where / "units.py")


def test_python_counts_in_units(built):
    mod = built[1]
    cases = [(mod.Floats(values=[1.0]), "03 02 3f800000"),  # one float: two registers
             (mod.Floats(values=[1.0, -2.5]), "03 04 3f800000 c0200000"),
             (mod.Words(data=[1, 2, 3, 4]), "04 02 01020304"),  # four bytes: two words
             (mod.Words(data=[]), "04 00")]
    for message, frame in cases:
        assert mod.encode(message) == bytes.fromhex(frame)
        assert mod.decode(bytes.fromhex(frame)) == message


def test_python_refuses_counts_that_split_an_element_or_a_unit(built):
    mod = built[1]
    with pytest.raises(mod.EncodeError) as e:
        mod.encode(mod.Words(data=[1, 2, 3]))  # three bytes are not whole words
    assert (e.value.field, e.value.rule) == ("data", "count")
    with pytest.raises(mod.DecodeError) as e:
        mod.Floats.decode(bytes.fromhex("03 03 3f800000 0000"))  # three registers: half a float
    assert (e.value.field, e.value.rule) == ("registers", "length")


def test_c_agrees(built):
    driver = r"""
#include <stdio.h>
#include "units.h"
int main(void) {
    static const uint8_t two[] = {0x03, 0x04, 0x3f, 0x80, 0x00, 0x00, 0xc0, 0x20, 0x00, 0x00};
    static const uint8_t half[] = {0x03, 0x03, 0x3f, 0x80, 0x00, 0x00, 0x00, 0x00};
    units_floats_t f = {0};
    units_words_t w = {0};
    uint8_t out[16];
    int n, i;
    n = units_floats_decode(two, sizeof two, &f);
    printf("%d %u %g %g\n", n, (unsigned)f.values_count, (double)f.values[0], (double)f.values[1]);
    printf("%d\n", units_floats_decode(half, sizeof half, &f));
    w.data[0] = 1; w.data[1] = 2; w.data_count = 2;
    n = units_words_encode(&w, out, sizeof out);
    for (i = 0; i < n; i++) printf("%02x", out[i]);
    w.data_count = 3;
    printf("\n%d\n", units_words_encode(&w, out, sizeof out));
    return 0;
}
"""
    assert run_c(built[0], driver) == ["0 2 1 -2.5", "-2", "04010102", "-4"]


def test_conformance_vectors_on_the_host_and_on_atmega32_under_simavr(tmp_path):
    host, avr = conformance_on_host_and_avr(tmp_path, "units", SCHEMA)
    assert host > 50 and avr > 50
