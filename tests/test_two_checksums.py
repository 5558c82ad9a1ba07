"""Two checksums in one frame: a CRC-8 over the header and a CRC-16 over the whole
frame, header CRC included (the codecs fill checksums in wire order). Expected
values come from the standard library's CRC-16/XMODEM (binascii.crc_hqx) and a
bitwise CRC-8/SMBUS written out below, not from codeword."""
from __future__ import annotations

import binascii

from schema_in_a_test import load, render, run_c

SCHEMA = """codeword: 1
protocol: twocrc
title: t
source: s
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: sync, type: u8, const: 0xAA}
    - {name: kind, type: u8, dispatch: true}
    - {name: header_crc, type: u8, checksum: {algorithm: CRC-8/SMBUS, covers: {from: sync, to: kind}}}
    - {payload: true}
    - {name: crc, type: u16, checksum: {algorithm: CRC-16/XMODEM, covers: {from: sync, to: payload}}}
messages:
  reading:
    id: 1
    fields:
      - {name: value, type: u16}
"""


def crc8_smbus(data: bytes) -> int:
    crc = 0
    for byte in data:
        crc ^= byte
        for _ in range(8):
            crc = (crc << 1 ^ 0x07) & 0xFF if crc & 0x80 else crc << 1 & 0xFF
    return crc


def expected_frame(value: int) -> bytes:
    header = bytes([0xAA, 0x01])
    head = header + bytes([crc8_smbus(header)]) + value.to_bytes(2, "big")
    return head + binascii.crc_hqx(head, 0).to_bytes(2, "big")


def test_python_fills_and_checks_both(tmp_path):
    render(tmp_path, "twocrc", SCHEMA)
    mod = load(tmp_path / "twocrc.py")
    frame = expected_frame(0x1234)
    assert mod.encode(mod.Reading(value=0x1234)) == frame
    assert mod.decode(frame).value == 0x1234
    for at, field in ((2, "header_crc"), (5, "crc")):
        bad = bytearray(frame)
        bad[at] ^= 1
        try:
            mod.decode(bytes(bad))
        except mod.DecodeError as err:
            assert (err.rule, err.field) == ("checksum", field)
        else:
            raise AssertionError(f"a damaged {field} decoded")


def test_c_fills_and_checks_both(tmp_path):
    render(tmp_path, "twocrc", SCHEMA)
    driver = r"""
#include <stdio.h>
#include "twocrc.h"
int main(void) {
    twocrc_reading_t m;
    uint8_t out[7];
    int i, n;
    m.value = 0x1234u;
    n = twocrc_reading_encode(&m, out, sizeof out);
    printf("%d", n);
    for (i = 0; i < n; i++) printf(" %02x", out[i]);
    printf("\n");
    out[2] ^= 1u;
    printf("%d\n", twocrc_reading_decode(out, sizeof out, &m) == CW_ERR_CHECKSUM);
    return 0;
}
"""
    assert run_c(tmp_path, driver) == ["7 " + expected_frame(0x1234).hex(" "), "1"]
