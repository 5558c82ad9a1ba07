"""The stream decoders size a frame by its length field read whole and in the
field's byte order, for a two-byte length in either order and for frames
longer than 255 bytes; the Python StreamDecoder and the C parser find the
same frames, written out by hand below, in a stream with garbage around them."""
from __future__ import annotations

from pathlib import Path

import pytest

import schema_in_a_test as scratch


SCHEMA = """\
codeword: 1
protocol: lenf
title: frames sized by a two-byte length
source: hand-written
framing:
  kind: bytes
  byte_order: {order}
  layout:
    - {{name: sync, type: u8, const: 0x7E}}
    - {{name: length, type: u16, length_of: {{from: kind, to: payload}}}}
    - {{name: kind, type: u8, dispatch: true}}
    - {{payload: true}}
messages:
  small:
    id: 1
    fields:
      - {{name: a, type: u8}}
  large:
    id: 2
    fields:
      - {{name: b, type: u32}}
      - {{name: blob, type: bytes, length: 295}}
"""

# length counts kind .. end of payload: small 1 + 1 = 2 = 0x0002; large 1 + 4 + 295 = 300 = 0x012c
BLOB = bytes(range(256)) + bytes(range(39))
FRAMES = {
    "little": (bytes.fromhex("7e 02 00 01 42"),
               bytes.fromhex("7e 2c 01 02 44 33 22 11") + BLOB),
    "big": (bytes.fromhex("7e 00 02 01 42"),
            bytes.fromhex("7e 01 2c 02 11 22 33 44") + BLOB),
}
GARBAGE = bytes.fromhex("00 13 7e ff 7e")  # two stray sync bytes whose length is no known size


def stream(order: str) -> bytes:
    small, large = FRAMES[order]
    return GARBAGE + small + large + GARBAGE[:2] + small


DRIVER = """\
#include <stdio.h>
#include "lenf.h"

static const uint8_t stream[] = {STREAM};

int main(void)
{
    lenf_parser_t p;
    lenf_message_t m;
    size_t i;
    int rc;
    lenf_parser_init(&p, 0);
    for (i = 0; i < sizeof stream; i++) {
        if (lenf_parser_feed(&p, stream[i]) != CW_OK) {
            printf("full\\n");
            return 1;
        }
        while ((rc = lenf_parser_next(&p, &m)) != 0) {
            if (rc < 0) {
                continue;
            }
            if (m.kind == LENF_MSG_SMALL) {
                printf("small %02x\\n", (unsigned)m.as.small.a);
            } else {
                printf("large %08lx %u\\n", (unsigned long)m.as.large.b, (unsigned)m.as.large.blob[294]);
            }
        }
    }
    printf("skipped %lu\\n", (unsigned long)p.scan.skipped);
    return 0;
}
"""


@pytest.fixture(params=sorted(FRAMES))
def built(request, tmp_path: Path):
    return request.param, scratch.render(tmp_path, "lenf", SCHEMA.format(order=request.param))


def test_python_stream_decoder_reads_the_two_byte_length(built):
    order, where = built
    lenf = scratch.load(where / "lenf.py")
    small, large = FRAMES[order]
    assert lenf.encode(lenf.Small(a=0x42)) == small
    assert lenf.encode(lenf.Large(b=0x11223344, blob=BLOB)) == large
    decoder = lenf.StreamDecoder()
    data = stream(order)
    events = [e for k in range(0, len(data), 7) for e in decoder.feed(data[k:k + 7])]
    messages = [e for e in events if not isinstance(e, lenf.CodecError)]
    assert messages == [lenf.Small(a=0x42), lenf.Large(b=0x11223344, blob=BLOB), lenf.Small(a=0x42)]
    assert decoder.finish() == []
    assert decoder.skipped == len(GARBAGE) + 2


def test_c_parser_reads_the_two_byte_length(built):
    order, where = built
    driver = DRIVER.replace("{STREAM}", "{" + ", ".join(f"0x{b:02x}" for b in stream(order)) + "}")
    assert scratch.run_c(where, driver) == ["small 42", "large 11223344 38", "small 42",
                                            f"skipped {len(GARBAGE) + 2}"]
