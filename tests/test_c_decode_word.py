"""The C word form of a bits protocol whose words are over 32 bits: `<proto>_decode_word`
and `<msg>_to_word` take a uint64_t and reach every message, including those over 4
bytes. Words below are worked out by hand."""
from __future__ import annotations

from pathlib import Path

import schema_in_a_test as scratch

SCHEMA = """\
codeword: 1
protocol: wide
title: a bits protocol with a 5-byte message
source: hand-written
framing: {kind: bits, max_bits: 40, byte_order: big}
messages:
  small:
    fields:
      - {name: tag, type: u2, const: 1, dispatch: true}
      - {name: a, type: u6}
  big:
    fields:
      - {name: tag, type: u2, const: 2, dispatch: true}
      - {name: b, type: u14}
      - {name: c, type: u16}
      - {name: d, type: u6}
"""

# big, b=0x1234 c=0xbeef d=42: 10 | 01 0010 0011 0100 | 1011 1110 1110 1111 | 101010 | 00
#   = 1001 0010  0011 0100  1011 1110  1110 1111  1010 1000 = 0x9234beefa8 (38 bits, 2 zero)
# small, a=21: 01 | 010101 = 0x55, left-aligned in 40 bits: 0x5500000000
WORDS = [
    (0x9234BEEFA8, "big b=0x1234 c=0xbeef d=42"),
    (0x5500000000, "small a=21"),
]
REFUSED = [
    (0x10000000000, "range"),     # 41 bits
    (0x5500000001, "reserved"),   # small: a bit below its byte
    (0x9234BEEFA9, "reserved"),   # big: one of its 2 padding bits
    (0x0000000000, "dispatch"),   # tag 0 is no message
]

DRIVER = """\
#include <stdio.h>
#include "wide.h"

static const char *why(int rc)
{
    return rc == CW_ERR_RANGE ? "range" : rc == CW_ERR_RESERVED ? "reserved"
         : rc == CW_ERR_DISPATCH ? "dispatch" : "other";
}

static void show(uint64_t word)
{
    wide_message_t m;
    uint64_t back = 0;
    int rc = wide_decode_word(word, &m);
    if (rc != CW_OK) {
        printf("%s\\n", why(rc));
    } else if (m.kind == WIDE_MSG_BIG) {
        rc = wide_big_to_word(&m.as.big, &back);
        printf("big b=0x%x c=0x%x d=%u %010llx %d\\n", (unsigned)m.as.big.b, (unsigned)m.as.big.c,
               (unsigned)m.as.big.d, (unsigned long long)back, rc);
    } else {
        rc = wide_small_to_word(&m.as.small, &back);
        printf("small a=%u %010llx %d\\n", (unsigned)m.as.small.a, (unsigned long long)back, rc);
    }
}

int main(void)
{
    show(0x9234BEEFA8ULL);
    show(0x5500000000ULL);
    show(0x10000000000ULL);
    show(0x5500000001ULL);
    show(0x9234BEEFA9ULL);
    show(0x0ULL);
    return 0;
}
"""

# Every message 5 bytes: the dispatch head the C reads stays within 32 bits.
# one, v=0x12345 w=0x6789: 1001 | 0001 0010 0011 0100 0101 | 0110 0111 1000 1001 = 0x9123456789
ONE = """\
codeword: 1
protocol: one
title: a bits protocol of 5-byte messages only
source: hand-written
framing: {kind: bits, max_bits: 40, byte_order: big}
messages:
  one:
    fields:
      - {name: tag, type: u4, const: 9, dispatch: true}
      - {name: v, type: u20}
      - {name: w, type: u16}
"""

ONE_DRIVER = """\
#include <stdio.h>
#include "one.h"

int main(void)
{
    static const uint8_t bytes[5] = {0x91, 0x23, 0x45, 0x67, 0x89};
    one_message_t m;
    uint64_t back = 0;
    int rc = one_decode_word(0x9123456789ULL, &m);
    printf("%d v=0x%lx w=0x%x\\n", rc, (unsigned long)m.as.one.v, (unsigned)m.as.one.w);
    rc = one_one_to_word(&m.as.one, &back);
    printf("%d %010llx\\n", rc, (unsigned long long)back);
    rc = one_decode(bytes, sizeof bytes, &m);
    printf("%d v=0x%lx w=0x%x\\n", rc, (unsigned long)m.as.one.v, (unsigned)m.as.one.w);
    return 0;
}
"""


def test_python_words_over_32_bits(tmp_path: Path):
    wide = scratch.load(scratch.render(tmp_path, "wide", SCHEMA) / "wide.py")
    assert wide.encode_word(wide.Big(b=0x1234, c=0xBEEF, d=42)) == 0x9234BEEFA8
    assert wide.decode_word(0x9234BEEFA8) == wide.Big(b=0x1234, c=0xBEEF, d=42)
    assert wide.decode_word(0x5500000000) == wide.Small(a=21)


def test_c_decode_word_over_32_bits(tmp_path: Path):
    where = scratch.render(tmp_path, "wide", SCHEMA)
    assert scratch.run_c(where, DRIVER) == (
        [f"{text} {word:010x} 0" for word, text in WORDS] + [why for _, why in REFUSED])


def test_c_messages_all_over_32_bits(tmp_path: Path):
    where = scratch.render(tmp_path, "one", ONE)
    assert scratch.run_c(where, ONE_DRIVER) == ["0 v=0x12345 w=0x6789", "0 9123456789",
                                                "0 v=0x12345 w=0x6789"]
