"""Text framing with a constant field and an optional char: Python and C write
the same line, read it back, and refuse a wrong constant."""
from __future__ import annotations

import pytest

from schema_in_a_test import load, render, run_c

SCHEMA = """codeword: 1
protocol: {name}
title: t
source: s
framing:
  kind: text
  prefix_separator: ":"
  separator: ","
  terminator: ";"
messages:
  ping:
    id: "P"
    fields:
      - {{name: v, type: u8, const: 7}}
      - {{name: a, type: u8}}
      - {{name: c, type: char, optional: true}}
"""


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    where = tmp_path_factory.mktemp("textconst")
    render(where, "textconst", SCHEMA.format(name="textconst"))
    return where


def test_python_writes_the_constant_and_checks_it(built):
    mod = load(built / "textconst.py")
    assert mod.encode(mod.Ping(a=5, c="x")) == "P:7,5,x;"  # the line, written out by hand
    assert mod.encode(mod.Ping(a=5)) == "P:7,5;"
    assert mod.decode("P:7,5,x;") == mod.Ping(a=5, c="x")
    with pytest.raises(mod.DecodeError) as bad:
        mod.decode("P:8,5;")
    assert bad.value.rule == "const" and bad.value.field == "v"
    with pytest.raises(mod.DecodeError) as wide:
        mod.decode("P:7,296;")  # a u8 written in text can hold more than 8 bits
    assert wide.value.rule == "range"


def test_c_agrees(built):
    driver = r"""
#include <stdio.h>
#include <string.h>
#include "textconst.h"
int main(void) {
    textconst_ping_t m;
    char buf[64];
    int n;
    memset(&m, 0, sizeof m);
    m.a = 5; m.has_c = true; m.c = 'x';
    n = textconst_ping_encode(&m, buf, sizeof buf);
    printf("%.*s\n", n, buf);
    m.has_c = false;
    n = textconst_ping_encode(&m, buf, sizeof buf);
    printf("%.*s\n", n, buf);
    memset(&m, 0, sizeof m);
    n = textconst_ping_decode("P:7,5,x;", 8u, &m);
    printf("%d %u %d %c\n", n, m.a, m.has_c, m.c);
    printf("%d\n", textconst_ping_decode("P:8,5;", 6u, &m) == CW_ERR_CONST);
    printf("%d\n", textconst_ping_decode("P:7,296;", 8u, &m) == CW_ERR_RANGE);
    return 0;
}
"""
    assert run_c(built, driver) == ["P:7,5,x;", "P:7,5;", "0 5 1 x", "1", "1"]


def test_a_newline_terminator_builds_and_agrees(tmp_path):
    schema = SCHEMA.format(name="lines").replace('terminator: ";"', 'terminator: "\\n"')
    render(tmp_path, "lines", schema)
    mod = load(tmp_path / "lines.py")
    assert mod.encode(mod.Ping(a=5)) == "P:7,5\n"
    decoder = mod.StreamDecoder()
    assert decoder.feed("P:7,5\nP:7,6") == [mod.Ping(a=5)]
    (cut,) = decoder.finish()
    assert cut.allowed == "a message ending in \n before the end"
    driver = r"""
#include <stdio.h>
#include <string.h>
#include "lines.h"
int main(void) {
    lines_ping_t m;
    char buf[32];
    int n;
    memset(&m, 0, sizeof m);
    m.a = 5;
    n = lines_ping_encode(&m, buf, sizeof buf);
    printf("%d %.*s|\n", n, n - 1, buf);
    return 0;
}
"""
    assert run_c(tmp_path, driver) == ["6 P:7,5|"]


def test_an_absent_optional_value_before_a_present_one_is_an_empty_value(tmp_path):
    schema = SCHEMA.format(name="gaps").replace(
        "      - {name: c, type: char, optional: true}",
        "      - {name: b, type: u8, optional: true}\n      - {name: c, type: char, optional: true}")
    render(tmp_path, "gaps", schema)
    mod = load(tmp_path / "gaps.py")
    assert mod.encode(mod.Ping(a=5, b=6, c="x")) == "P:7,5,6,x;"
    assert mod.encode(mod.Ping(a=5, c="x")) == "P:7,5,,x;"  # b's place kept, empty
    assert mod.decode("P:7,5,,x;") == mod.Ping(a=5, c="x")
    driver = r"""
#include <stdio.h>
#include <string.h>
#include "gaps.h"
int main(void) {
    gaps_ping_t m;
    char buf[32];
    int n;
    memset(&m, 0, sizeof m);
    m.a = 5; m.has_c = true; m.c = 'x';
    n = gaps_ping_encode(&m, buf, sizeof buf);
    printf("%.*s\n", n, buf);
    memset(&m, 0, sizeof m);
    n = gaps_ping_decode("P:7,5,,x;", 9u, &m);
    printf("%d %d %d %c\n", n, m.has_b, m.has_c, m.c);
    return 0;
}
"""
    assert run_c(tmp_path, driver) == ["P:7,5,,x;", "0 0 1 x"]


ALL_OPTIONAL = """codeword: 1
protocol: allopt
title: t
source: s
framing: {kind: text, prefix_separator: ':', separator: '|', terminator: '#'}
messages:
  a:
    id: A
    fields:
      - {name: c, type: char, optional: true}
      - {name: n, type: i8, optional: true}
"""


def test_a_message_of_optional_values_only_reads_an_empty_body_as_none(tmp_path):
    """`A:#` holds no value (not one empty value), in Python and in C; `A:x|5#` both."""
    from schema_in_a_test import load, render, run_c
    render(tmp_path, "allopt", ALL_OPTIONAL)
    mod = load(tmp_path / "allopt.py")
    assert mod.encode(mod.A()) == "A:#"
    got = mod.decode("A:#")
    assert (got.c, got.n) == (None, None)
    assert (mod.decode("A:x|5#").c, mod.decode("A:x|5#").n) == ("x", 5)
    driver = r"""
#include <stdio.h>
#include <string.h>
#include "allopt.h"
static void show(const char *line) {
    allopt_a_t m;
    int rc = allopt_a_decode(line, strlen(line), &m);
    printf("%s %d %d\n", cw_error_name(rc), (int)m.has_c, (int)m.has_n);
}
int main(void) {
    show("A:#");
    show("A:x|5#");
    return 0;
}
"""
    assert run_c(tmp_path, driver) == ["ok 0 0", "ok 1 1"]
