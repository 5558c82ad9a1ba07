"""Text lines with longer marks and a checksum: a start marker, ids of several
characters, separators and terminators of several characters, and NMEA 0183's
`*hh` (the XOR of the characters between `$` and `*`). Python and C write the
same lines, read them back and refuse a wrong checksum, start or terminator.
Expected checksums come from functools.reduce over the characters, or from a
published sentence."""
from __future__ import annotations

from functools import reduce

import pytest

from schema_in_a_test import load, render, run_c

NMEA_LIKE = """codeword: 1
protocol: marked
title: t
source: s
framing:
  kind: text
  start: "$"
  prefix_separator: ","
  separator: ","
  terminator: "\\r\\n"
  checksum: {algorithm: xor, over: line, suffix: "*"}
messages:
  vtg:
    id: GPVTG
    fields:
      - {name: track, type: f64}
      - {name: t, type: char}
      - {name: track_m, type: f64}
      - {name: m, type: char}
      - {name: knots, type: f64}
      - {name: n, type: char}
      - {name: kmh, type: f64}
      - {name: k, type: char}
  wx:
    id: PCWX
    fields:
      - {name: count, type: u8}
      - {name: flag, type: char}
      - {name: temp, type: i16}
      - {name: note, type: str, max_length: 8, optional: true}
"""

LONG_MARKS = """codeword: 1
protocol: longmarks
title: t
source: s
framing:
  kind: text
  prefix_separator: "::"
  separator: "||"
  terminator: ";;"
  checksum: {algorithm: sum, over: line, suffix: "#"}
messages:
  set:
    id: SET
    fields:
      - {name: name, type: str, max_length: 8}
      - {name: level, type: u16}
      - {name: mode, type: char}
"""


def xor_hex(text: str) -> str:
    return format(reduce(lambda acc, ch: acc ^ ord(ch), text, 0), "02X")


def sum_hex(text: str) -> str:
    return format(sum(map(ord, text)) % 256, "02X")


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    where = tmp_path_factory.mktemp("marks")
    render(where, "marked", NMEA_LIKE)
    render(where, "longmarks", LONG_MARKS)
    return where


def test_python_reads_a_published_sentence_and_checks_its_checksum(built):
    mod = load(built / "marked.py")
    vtg = mod.decode("$GPVTG,054.7,T,034.4,M,005.5,N,010.2,K*48\r\n")  # gpsd's NMEA reference
    assert (vtg.track, vtg.track_m, vtg.knots, vtg.kmh) == (54.7, 34.4, 5.5, 10.2)
    with pytest.raises(mod.DecodeError) as bad:
        mod.decode("$GPVTG,054.7,T,034.4,M,005.5,N,010.2,K*49\r\n")
    assert bad.value.rule == "checksum" and bad.value.offset == 38  # the '*'
    with pytest.raises(mod.DecodeError) as lower:
        mod.decode("$GPVTG,1,T,1,M,1,N,1,K*" + xor_hex("GPVTG,1,T,1,M,1,N,1,K").lower() + "\r\n")
    assert lower.value.rule == "checksum"  # writers write uppercase hex; readers take only that


def test_python_writes_start_checksum_and_terminator(built):
    mod = load(built / "marked.py")
    body = "PCWX,12,A,-7,hi"
    assert mod.encode(mod.Wx(count=12, flag="A", temp=-7, note="hi")) == f"${body}*{xor_hex(body)}\r\n"
    assert mod.decode(f"${body}*{xor_hex(body)}\r\n") == mod.Wx(count=12, flag="A", temp=-7, note="hi")
    for line, rule in [(f"{body}*{xor_hex(body)}\r\n", "prefix"), (f"${body}*{xor_hex(body)}\n", "terminator"),
                       (f"${body}{xor_hex(body)}\r\n", "checksum"), (f"${body}\r\n", "checksum")]:
        with pytest.raises(mod.DecodeError) as bad:
            mod.decode(line)
        assert bad.value.rule == rule, line
    stream = mod.StreamDecoder()
    good, bad = stream.feed(f"${body}*{xor_hex(body)}\r\n${body}*00\r\n$PC")
    assert good == mod.Wx(count=12, flag="A", temp=-7, note="hi")
    assert (bad.rule, bad.offset) == ("checksum", len(body) + 6 + len(body) + 1)


def test_python_longer_separators(built):
    mod = load(built / "longmarks.py")
    body = "SET::lamp||300||x"
    line = f"{body}#{sum_hex(body)};;"
    assert mod.encode(mod.Set(name="lamp", level=300, mode="x")) == line
    assert mod.decode(line) == mod.Set(name="lamp", level=300, mode="x")
    with pytest.raises(mod.EncodeError) as bar:
        mod.encode(mod.Set(name="a|b", level=1, mode="x"))  # a character of the separator
    assert bar.value.rule == "text"
    bad = "SET::a|b||1||x"
    with pytest.raises(mod.DecodeError) as read:
        mod.decode(f"{bad}#{sum_hex(bad)};;")
    assert read.value.rule == "text"


def test_c_agrees(built):
    wx = "PCWX,12,A,-7,hi"
    vtg = "GPVTG,054.7,T,034.4,M,005.5,N,010.2,K"
    bar = "SET::a|b||1||x"
    driver = r"""
#include <stdio.h>
#include <string.h>
#include "marked.h"
#include "longmarks.h"
static int dec(const char *s) {
    marked_message_t out;
    return marked_decode(s, strlen(s), MARKED_DIR_ANY, &out);
}
int main(void) {
    char buf[96];
    int n;
    marked_wx_t m;
    longmarks_set_t s;
    marked_message_t out;
    memset(&m, 0, sizeof m);
    m.count = 12; m.flag = 'A'; m.temp = -7; m.has_note = true; strcpy(m.note, "hi");
    n = marked_wx_encode(&m, buf, sizeof buf);
    printf("%d %.*s|\n", n, n - 2, buf);
    printf("%d\n", marked_wx_encode(&m, buf, (size_t)n) == CW_ERR_CAPACITY);
    memset(&out, 0, sizeof out);
    n = marked_decode(buf, (size_t)n, MARKED_DIR_ANY, &out);
    printf("%d %d %u %c %d %s\n", n, out.kind == MARKED_MSG_WX, out.as.wx.count, out.as.wx.flag, out.as.wx.temp, out.as.wx.note);
    printf("%d\n", dec("$GPVTG,054.7,T,034.4,M,005.5,N,010.2,K*48\r\n"));
    printf("%d\n", dec("$GPVTG,054.7,T,034.4,M,005.5,N,010.2,K*49\r\n") == CW_ERR_CHECKSUM);
    printf("%d\n", dec("GPVTG,054.7,T,034.4,M,005.5,N,010.2,K*48\r\n") == CW_ERR_PREFIX);
    printf("%d\n", dec("$GPVTG,054.7,T,034.4,M,005.5,N,010.2,K*48\n") == CW_ERR_TERMINATOR);
    printf("%d\n", dec("$GPVTG,054.7,T,034.4,M,005.5,N,010.2,K\r\n") == CW_ERR_CHECKSUM);
    memset(&s, 0, sizeof s);
    strcpy(s.name, "lamp"); s.level = 300; s.mode = 'x';
    n = longmarks_set_encode(&s, buf, sizeof buf);
    printf("%d %s|\n", n, buf);
    memset(&s, 0, sizeof s);
    n = longmarks_set_decode(buf, (size_t)n, &s);
    printf("%d %s %u %c\n", n, s.name, s.level, s.mode);
    strcpy(s.name, "a|b");
    printf("%d\n", longmarks_set_encode(&s, buf, sizeof buf) == CW_ERR_TEXT);
    printf("%d\n", longmarks_set_decode(BAR, strlen(BAR), &s) == CW_ERR_TEXT);
    return 0;
}
""".replace("BAR", f'"{bar}#{sum_hex(bar)};;"')
    out = run_c(built, driver)
    line = "SET::lamp||300||x"
    assert out == [f"{len(wx) + 6} ${wx}*{xor_hex(wx)}|", "1", "0 1 12 A -7 hi", "0", "1", "1", "1", "1",
                   f"{len(line) + 5} {line}#{sum_hex(line)};;|", "0 lamp 300 x", "1", "1"]
    assert xor_hex(vtg) == "48"
