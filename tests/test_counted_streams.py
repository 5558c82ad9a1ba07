"""A stream decoder finds a counted frame's end from its count field when the
framing has no length field; a count over the most, or a count of bytes that is
not whole elements, is a length error as soon as it is read (not a wait for a
frame that cannot be, nor a dispatch error once it is taken whole), alike in
Python and C. Frames worked by hand: xor of 01 02 01 02 is 00."""
from __future__ import annotations

from schema_in_a_test import c_bytes, load, render, run_c

SCHEMA = """codeword: 1
protocol: counts
title: t
source: s
framing:
  kind: bytes
  layout:
    - {name: sync, type: u8, const: 0x55}
    - {name: kind, type: u8, dispatch: true}
    - {payload: true}
    - {name: check, type: u8, checksum: {algorithm: xor, covers: {from: kind, to: payload}}}
messages:
  samples:
    id: 1
    fields:
      - {name: n, type: u8}
      - {name: values, type: u16, count: {from: n, unit: bytes}, max_count: 4}
  other:        # 7 bytes, as a samples frame claiming 3 bytes would be
    id: 2
    fields: [{name: v, type: u32}]
"""
# 3 bytes is not whole u16s; 10 bytes is more than 4 u16s; then a good frame
STREAM = bytes.fromhex("55 01 03" "55 01 0a" "55 01 02 01 02 00")


def test_python_refuses_a_bad_count_when_it_reads_it(tmp_path):
    render(tmp_path, "counts", SCHEMA)
    mod = load(tmp_path / "counts.py")
    out = mod.StreamDecoder().feed(STREAM)
    assert [getattr(x, "rule", type(x).__name__) for x in out] == ["length", "Samples"]
    assert out[1].values == [0x0102]


def test_c_refuses_a_bad_count_when_it_reads_it(tmp_path):
    render(tmp_path, "counts", SCHEMA)
    driver = r"""
#include <stdio.h>
#include "counts.h"
static const uint8_t stream[] = {STREAM};
int main(void) {
    counts_parser_t p;
    counts_message_t m;
    size_t i;
    int rc;
    counts_parser_init(&p, COUNTS_DIR_ANY);
    for (i = 0; i < sizeof stream; i++) {
        counts_parser_feed(&p, stream[i]);
        while ((rc = counts_parser_next(&p, &m)) != 0) {
            if (rc == 1) printf("samples %u %04x\n", (unsigned)m.as.samples.values_count, (unsigned)m.as.samples.values[0]);
            else printf("error %d\n", rc == CW_ERR_LENGTH ? 1 : rc);
        }
    }
    return 0;
}
""".replace("STREAM", c_bytes(STREAM))
    assert run_c(tmp_path, driver) == ["error 1", "samples 1 0102"]
