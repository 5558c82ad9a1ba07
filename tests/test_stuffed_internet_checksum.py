"""An internet checksum (RFC 1071) in place before a pattern-stuffed payload: it covers
itself and the bytes as sent, so the encoder counts its own field as zero while it sums
the stuffed bytes, and a decoder applies RFC 1071's receiver check to them. The frame is
worked out by hand: A5, the length of the payload as sent (5), the checksum, then the
payload 7E 01 02 03 with 7D inserted after 7E. Big-endian words 0005 0000 7E7D 0102 0300
sum to 8284, whose one's complement is 7D7B; rfc1071 in tests/test_internet_checksum.py
agrees."""
from __future__ import annotations

from schema_in_a_test import c_bytes, conformance_on_host_and_avr, load, render, run_c
from test_internet_checksum import rfc1071

SCHEMA = """codeword: 1
protocol: sealed
title: an internet checksum before a stuffed payload
source: hand-written
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: sync, type: u8, const: 0xA5}
    - {name: len, type: u16, length_of: {from: payload, to: payload}}
    - {name: check, type: u16, checksum: {algorithm: internet, covers: {from: len, to: payload}}}
    - {payload: true}
  stuffing: {after: 7E, insert: 0x7D, covers: {from: payload, to: payload}}
messages:
  blob:
    fields:
      - {name: data, type: bytes, length: 4}
"""

SENT = bytes.fromhex("a5 00 05 7d 7b 7e 7d 01 02 03")
DATA = bytes.fromhex("7e 01 02 03")


def test_the_hand_worked_checksum_is_rfc_1071s():
    zeroed = SENT[1:3] + b"\x00\x00" + SENT[5:]
    assert rfc1071(zeroed) == 0x7D7B


def test_python_sends_and_reads_the_frame(tmp_path):
    render(tmp_path, "sealed", SCHEMA)
    mod = load(tmp_path / "sealed.py")
    assert mod.encode(mod.Blob(data=DATA)) == SENT
    assert mod.decode(SENT).data == DATA
    damaged = SENT[:-1] + b"\x04"
    try:
        mod.decode(damaged)
    except mod.DecodeError as e:
        assert (e.rule, e.field) == ("checksum", "check")
    else:
        raise AssertionError("a damaged frame decoded")


def test_c_sends_and_reads_the_frame(tmp_path):
    render(tmp_path, "sealed", SCHEMA)
    driver = f"""#include <stdio.h>
#include <string.h>
#include "sealed.h"
int main(void) {{
    static const uint8_t sent[] = {{ {c_bytes(SENT)} }};
    sealed_blob_t m;
    uint8_t out[32];
    int n, i, rc = sealed_blob_decode(sent, sizeof sent, &m);
    printf("%s %02x %02x %02x %02x\\n", cw_error_name(rc < 0 ? rc : 0), m.data[0], m.data[1], m.data[2], m.data[3]);
    n = sealed_blob_encode(&m, out, sizeof out);
    for (i = 0; i < n; i++) printf("%02x", out[i]);
    printf("\\n");
    memcpy(out, sent, sizeof sent);
    out[sizeof sent - 1] = 4;
    printf("%s\\n", cw_error_name(sealed_blob_decode(out, sizeof sent, &m)));
    return 0;
}}
"""
    assert run_c(tmp_path, driver) == ["ok 7e 01 02 03", SENT.hex(), "checksum"]


def test_c_agrees_with_python_on_host_and_avr(tmp_path):
    host, avr = conformance_on_host_and_avr(tmp_path, "sealed", SCHEMA)
    assert host > 0 and avr == host


# Two four-bit fields share the byte before the length: every field after them sits one
# byte further on than a count of whole-byte fields makes it. Covered from the sync, the
# bytes A5 12 0005 0000 7E7D 0102 03(00) sum to 2797 (folded), whose complement is D868.
NIBBLES = SCHEMA.replace("protocol: sealed", "protocol: nibbled").replace(
    "    - {name: len, type: u16, length_of: {from: payload, to: payload}}\n"
    "    - {name: check, type: u16, checksum: {algorithm: internet, covers: {from: len, to: payload}}}",
    "    - {name: version, type: u4, const: 1}\n"
    "    - {name: kind, type: u4, const: 2}\n"
    "    - {name: len, type: u16, length_of: {from: payload, to: payload}}\n"
    "    - {name: check, type: u16, checksum: {algorithm: internet, covers: {from: sync, to: payload}}}")
NIBBLED = bytes.fromhex("a5 12 00 05 d8 68 7e 7d 01 02 03")


def test_the_hand_worked_checksum_after_two_nibbles_is_rfc_1071s():
    assert "version" in NIBBLES and rfc1071(NIBBLED[:4] + b"\x00\x00" + NIBBLED[6:]) == 0xD868


def test_fields_after_a_shared_byte_are_placed_in_the_next_byte(tmp_path):
    render(tmp_path, "nibbled", NIBBLES)
    mod = load(tmp_path / "nibbled.py")
    assert mod.encode(mod.Blob(data=DATA)) == NIBBLED
    assert mod.decode(NIBBLED).data == DATA
    (tmp_path / "c").mkdir()
    host, avr = conformance_on_host_and_avr(tmp_path / "c", "nibbled", NIBBLES)
    assert host > 0 and avr == host
