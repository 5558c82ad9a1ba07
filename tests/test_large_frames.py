"""Frames over 65,535 bytes: the language allows them (fields of up to 4 KiB, as
many as a message holds), so the C stream parser counts its buffered bytes in a
type as wide as the largest frame needs. The frame below is put together by hand
(sync, id, the payload, CRC-16/XMODEM from binascii); Python and C both write it,
and both find it in a stream, fed whole and one byte at a time."""
from __future__ import annotations

import binascii
import struct

import pytest

from schema_in_a_test import c_bytes, firmware_warnings, load, render, run_c

BLOCKS = 17  # 17 fields of 4096 bytes: a payload of 69,634 bytes with the tail

LARGE = """codeword: 1
protocol: large
title: Frames over 64 KiB
source: hand-written
framing:
  kind: bytes
  byte_order: little
  layout:
    - {name: sync, type: u8, const: 0xA5}
    - {name: id, type: u8, dispatch: true}
    - {payload: true}
    - {name: check, type: u16, checksum: {algorithm: CRC-16/XMODEM, covers: {from: id, to: payload}}}
messages:
  small:
    id: 1
    fields:
      - {name: v, type: u8}
  blob:
    id: 2
    fields:
""" + "".join(f"      - {{name: d{i}, type: bytes, length: 4096}}\n" for i in range(BLOCKS)) + """      - {name: tail, type: u16}
"""


def block(i: int) -> bytes:
    return bytes((i * 31 + k * 7) & 0xFF for k in range(4096))


def frame(ident: int, payload: bytes) -> bytes:
    body = bytes((ident,)) + payload
    return b"\xa5" + body + struct.pack("<H", binascii.crc_hqx(body, 0))  # XMODEM: poly 0x1021, init 0


BLOB = frame(2, b"".join(block(i) for i in range(BLOCKS)) + struct.pack("<H", 0xBEEF))
SMALL = frame(1, b"\x5a")


def test_the_hand_made_frame_is_over_64_kib():
    assert len(BLOB) == 2 + BLOCKS * 4096 + 2 + 2 > 65535


def test_python_writes_and_finds_the_large_frame(tmp_path):
    mod = load(render(tmp_path, "large", LARGE) / "large.py")
    blob = mod.Blob(**{f"d{i}": block(i) for i in range(BLOCKS)}, tail=0xBEEF)
    assert mod.encode(blob) == BLOB
    found = mod.StreamDecoder().feed(SMALL + BLOB + SMALL)
    assert found == [mod.Small(v=0x5A), blob, mod.Small(v=0x5A)]


C_DRIVER = """#include <stdio.h>
#include <string.h>
#include "large.h"

static const uint8_t blob[] = {%(blob)s};
static const uint8_t small[] = {%(small)s};
static uint8_t stream[sizeof small + sizeof blob + sizeof small];
static uint8_t out[sizeof blob];
static large_blob_t want;
static large_message_t got;
static large_parser_t parser;
static large_scan_state_t scanner;

static int is_blob(const large_message_t *m)
{
    return m->kind == LARGE_MSG_BLOB && memcmp(&m->as.blob, &want, sizeof want) == 0;
}

int main(void)
{
    size_t i, used = 0, at = 0;
    unsigned k, found = 0, blobs = 0;
    int rc, n;
    for (k = 0; k < %(blocks)du; k++) {  /* the blocks as the test writes them */
        uint8_t *d = (uint8_t *)&want + offsetof(large_blob_t, d0) + k * sizeof want.d0;
        for (i = 0; i < 4096u; i++) {
            d[i] = (uint8_t)((k * 31u + i * 7u) & 0xFFu);
        }
    }
    want.tail = 0xBEEFu;
    n = large_blob_encode(&want, out, sizeof out);
    printf("encode %%d %%d\\n", n == (int)sizeof blob, n > 0 && memcmp(out, blob, sizeof blob) == 0);
    memcpy(stream, small, sizeof small);
    memcpy(stream + sizeof small, blob, sizeof blob);
    memcpy(stream + sizeof small + sizeof blob, small, sizeof small);
    large_parser_init(&parser, LARGE_DIR_ANY);
    for (i = 0; i < sizeof stream; i++) {
        if (large_parser_feed(&parser, stream[i]) != CW_OK) {
            printf("feed refused at %%lu\\n", (unsigned long)i);
            return 1;
        }
        while ((rc = large_parser_next(&parser, &got)) != 0) {
            found += rc == 1;
            blobs += rc == 1 && is_blob(&got);
        }
    }
    printf("parser %%u %%u\\n", found, blobs);
    found = blobs = 0;
    large_scan_start(&scanner, LARGE_DIR_ANY);
    while (at < sizeof stream && (rc = large_scan(&scanner, stream + at, sizeof stream - at, &used, &got)) != 0) {
        at += used;
        found += rc == 1;
        blobs += rc == 1 && is_blob(&got);
    }
    printf("scan %%u %%u\\n", found, blobs);
    return 0;
}
"""


def test_c_writes_and_finds_the_large_frame_fed_whole_and_byte_by_byte(tmp_path):
    """The byte parser once counted its buffer in 16 bits: past 65,535 bytes the count
    wrapped and every large frame the scan decodes was lost."""
    render(tmp_path, "large", LARGE)
    lines = run_c(tmp_path, C_DRIVER % {"blob": c_bytes(BLOB), "small": c_bytes(SMALL), "blocks": BLOCKS})
    assert lines == ["encode 1 1", "parser 3 1", "scan 3 1"]


@pytest.mark.parametrize("compiler", ["gcc", "clang"])
def test_the_large_frame_header_compiles_without_warnings(tmp_path, compiler):
    """-Wtype-limits (in -Wextra) saw the 16-bit count compared with the buffer's size."""
    render(tmp_path, "large", LARGE)
    assert firmware_warnings(tmp_path, "large", compiler, "-O2") == ""


# Least significant bit first, 16 channels of 11 bits after 12 KiB of bytes: the
# channels lie past bit 65,535 of the frame. Each channel at 1024 sets stream bit
# 11k + 10 (tests/test_lsb_first.py works it out), the same 11 bytes for every 8.
FAR_BITS = """codeword: 1
protocol: farbits
title: Bit fields past bit 65535
source: hand-written
framing:
  kind: bytes
  bit_order: lsb_first
  layout:
    - {name: sync, type: u8, const: 0xA5}
    - {payload: true}
messages:
  m:
    fields:
      - {name: a, type: bytes, length: 4096}
      - {name: b, type: bytes, length: 4096}
      - {name: c, type: bytes, length: 4096}
      - {name: ch, type: u11, count: 16}
      - {name: end, type: u8}
"""
FAR_FRAME = b"\xa5" + bytes(3 * 4096) + bytes.fromhex("00 04 20 00 01 08 40 00 02 10 80" * 2) + b"\x7e"


def test_bit_fields_past_bit_65535_are_written_and_read_where_they_lie(tmp_path):
    """The bit helpers take a 16-bit offset; the encoder once passed the field's bit
    from the frame's start (98,312 here): wrapped, or refused by -Wconversion."""
    mod = load(render(tmp_path, "farbits", FAR_BITS) / "farbits.py")
    assert mod.encode(mod.M(a=bytes(4096), b=bytes(4096), c=bytes(4096), ch=[1024] * 16, end=0x7E)) == FAR_FRAME
    driver = """#include <stdio.h>
#include <string.h>
#include "farbits.h"
static const uint8_t frame[] = {%s};
static farbits_m_t want, got;
static uint8_t out[sizeof frame];
int main(void)
{
    unsigned i;
    int n;
    for (i = 0; i < 16u; i++) {
        want.ch[i] = 1024u;
    }
    want.end = 0x7Eu;
    n = farbits_m_encode(&want, out, sizeof out);
    printf("%%d %%d\\n", n == (int)sizeof frame, n > 0 && memcmp(out, frame, sizeof frame) == 0);
    n = farbits_m_decode(frame, sizeof frame, &got);
    printf("%%d %%d\\n", n, memcmp(&got, &want, sizeof got) == 0);
    return 0;
}
""" % c_bytes(FAR_FRAME)
    assert run_c(tmp_path, driver, ("-Wconversion",)) == ["1 1", "0 1"]
    assert firmware_warnings(tmp_path, "farbits", "gcc", "-O2") == ""


def crc8_smbus(data: bytes) -> int:
    """CRC-8/SMBUS bit by bit, as its catalogue entry defines it: poly 0x07, init 0, no reflection."""
    crc = 0
    for byte in data:
        crc ^= byte
        for _ in range(8):
            crc = (crc << 1 ^ 0x07) & 0xFF if crc & 0x80 else crc << 1
    return crc


def test_a_crc_over_a_large_frame_is_a_loop_not_a_line_per_byte(tmp_path):
    """A CRC without a standard-library routine gets code written for each fixed span
    it covers, which is only sized by the schema while the span is short: over a
    69,635-byte frame it was a line per byte, 7.7 MB of Python that does not compile
    (RecursionError). The module stays small and writes the frame worked out here."""
    schema = LARGE.replace("type: u16, checksum: {algorithm: CRC-16/XMODEM", "type: u8, checksum: {algorithm: CRC-8/SMBUS")
    assert schema != LARGE
    path = render(tmp_path, "large", schema) / "large.py"
    assert path.stat().st_size < 300_000, path.stat().st_size
    mod = load(path)
    body = bytes((2,)) + b"".join(block(i) for i in range(BLOCKS)) + struct.pack("<H", 0xBEEF)
    wire = b"\xa5" + body + bytes((crc8_smbus(body),))
    blob = mod.Blob(**{f"d{i}": block(i) for i in range(BLOCKS)}, tail=0xBEEF)
    assert mod.encode(blob) == wire
    assert mod.decode(wire) == blob
