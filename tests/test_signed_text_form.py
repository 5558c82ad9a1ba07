"""The exchange-file text form carries each raw wire value in decimal; a signed
field is written as its bit pattern, in Python as in C, and read back signed.
Lines below are worked out by hand."""
from __future__ import annotations

from pathlib import Path

import pytest

import schema_in_a_test as scratch

SCHEMA = """\
codeword: 1
protocol: sgnt
title: a signed field in the text form
source: hand-written
framing:
  kind: bits
  word_bits: 8
  byte_order: big
  text_form: {separator: " ", comment: "#", checksum_unfilled: 0}
messages:
  level:
    fields:
      - {name: tag, type: u2, const: 1, dispatch: true}
      - {name: v, type: i6}
"""

# v = -1 in 6 bits is 111111 = 63; v = -32 is 100000 = 32; v = 5 is 5
LINES = {-1: "1 63", -32: "1 32", 5: "1 5"}

DRIVER = """\
#include <stdio.h>
#include <string.h>
#include "sgnt.h"

int main(void)
{
    static const char *lines[] = {"1 63", "1 32", "1 5", "1 64"};
    static const int values[] = {-1, -32, 5};
    char buf[32];
    sgnt_message_t out;
    sgnt_level_t m;
    size_t i;
    for (i = 0; i < 3; i++) {
        int n;
        m.v = (int8_t)values[i];
        n = sgnt_level_to_text(&m, buf, sizeof buf);
        printf("%d -> %.*s\\n", values[i], n, buf);
    }
    for (i = 0; i < 4; i++) {
        int rc = sgnt_decode_text(lines[i], strlen(lines[i]), &out);
        if (rc == CW_OK) {
            printf("%s <- %d\\n", lines[i], (int)out.as.level.v);
        } else {
            printf("%s error %s\\n", lines[i], cw_error_name(rc));
        }
    }
    return 0;
}
"""


def test_python_writes_the_bit_pattern_and_reads_it_back_signed(tmp_path: Path):
    sgnt = scratch.load(scratch.render(tmp_path, "sgnt", SCHEMA) / "sgnt.py")
    for value, line in LINES.items():
        assert sgnt.encode_text(sgnt.Level(v=value)) == line
        assert sgnt.decode_text(line) == sgnt.Level(v=value)
    with pytest.raises(sgnt.DecodeError) as err:
        sgnt.decode_text("1 64")  # seven bits
    assert (err.value.field, err.value.rule) == ("v", "range")


def test_c_agrees(tmp_path: Path):
    where = scratch.render(tmp_path, "sgnt", SCHEMA)
    assert scratch.run_c(where, DRIVER) == ["-1 -> 1 63", "-32 -> 1 32", "5 -> 1 5",
                                           "1 63 <- -1", "1 32 <- -32", "1 5 <- 5", "1 64 error range"]


WIDE = """\
codeword: 1
protocol: widet
title: a 32-bit value in the text form
source: hand-written
framing:
  kind: bits
  max_bits: 40
  byte_order: big
  text_form: {separator: " ", comment: "#"}
messages:
  big:
    fields:
      - {name: tag, type: u8, const: 7, dispatch: true}
      - {name: v, type: u32}
"""

# the largest values read back whole; one past 2**32 - 1 is out of range, not clamped to it
WIDE_LINES = [("7 4294967294", "ok 4294967294"), ("7 4294967295", "ok 4294967295"),
              ("7 4294967296", "range"), ("7 99999999999999999999999", "range")]


def test_a_32_bit_text_form_value_is_read_whole_or_refused(tmp_path):
    where = scratch.render(tmp_path, "widet", WIDE)
    mod = scratch.load(where / "widet.py")
    for line, want in WIDE_LINES:
        try:
            got = f"ok {mod.decode_text(line).v}"
        except mod.DecodeError as err:
            got = err.rule
        assert got == want, line
    calls = "\n".join(f'    show("{line}");' for line, _ in WIDE_LINES)
    driver = """#include <inttypes.h>
#include <stdio.h>
#include <string.h>
#include "widet.h"
static void show(const char *line) {
    widet_message_t m;
    int rc = widet_decode_text(line, strlen(line), &m);
    if (rc == CW_OK) printf("ok %" PRIu32 "\\n", m.as.big.v); else printf("%s\\n", cw_error_name(rc));
}
int main(void) {
""" + calls + """
    return 0;
}
"""
    assert scratch.run_c(where, driver) == [want for _, want in WIDE_LINES]


LONG = """\
codeword: 1
protocol: longt
title: a text form line longer than 64 chars
source: hand-written
framing:
  kind: bits
  max_bits: 64
  byte_order: big
  text_form: {separator: " ", comment: "#"}
messages:
  flags:
    fields:
      - {name: tag, type: u2, const: 1, dispatch: true}
      - {name: bits, type: bool, count: 40}
      - {name: level, type: u10}
      - {name: trim, type: i12}
"""

# tag 1, forty 0/1 values, level at most 1023, trim's bit pattern at most 4095:
# 1 + 40 + 4 + 4 digits and 42 spaces = 91 chars, 92 with the NUL
LONG_LINE = "1 " + " ".join("1" * 40) + " 1023 2048"  # level 1023, trim -2048 (bit pattern 2048)


def test_the_longest_text_form_line_has_a_buffer_size_in_the_header(tmp_path):
    where = scratch.render(tmp_path, "longt", LONG)
    assert "#define LONGT_FLAGS_MAX_TEXT_FORM 92u" in (where / "longt.h").read_text(encoding="utf-8")
    mod = scratch.load(where / "longt.py")
    message = mod.Flags(bits=[True] * 40, level=1023, trim=-2048)
    assert mod.encode_text(message) == LONG_LINE and len(LONG_LINE) == 91
    driver = """#include <stdio.h>
#include "longt.h"
int main(void) {
    char buf[LONGT_FLAGS_MAX_TEXT_FORM];
    longt_flags_t m;
    int i;
    for (i = 0; i < 40; i++) m.bits[i] = true;
    m.level = 1023;
    m.trim = -2048;
    printf("%d %s\\n", longt_flags_to_text(&m, buf, sizeof buf), buf);
    printf("%s\\n", cw_error_name(longt_flags_to_text(&m, buf, sizeof buf - 1)));
    return 0;
}
"""
    assert scratch.run_c(where, driver) == [f"91 {LONG_LINE}", "capacity"]
