"""A text constant that a line may leave empty (NMEA's unit letter after a value
a sentence may omit): no member of the message; writers always write it,
readers take its place as written, empty, or left out at the end of the line,
and refuse anything else. Example checking used to read it from the message
(AttributeError)."""
from __future__ import annotations

import json

import pytest

from codeword.build import build, compile_schema
from codeword.diagnostics import SchemaError
from schema_in_a_test import load, render, run_c

SCHEMA = """codeword: 1
protocol: alts
title: t
source: s
framing: {kind: text, prefix_separator: ",", separator: ",", terminator: ";"}
messages:
  alt:
    id: ALT
    fields:
      - {name: height, type: u16, optional: true}
      - {name: unit, type: char, const: M, optional: true}
      - {name: version, type: u8, const: 7, optional: true}
      - {name: sep, type: i16, optional: true}
      - {name: label, type: str, max_length: 3, const: geo, optional: true}
    examples:
      - name: full
        values: {height: 12, sep: -3}
        text: "ALT,12,M,7,-3,geo;"
      - name: nothing known
        values: {}
        text: "ALT,,M,7,,geo;"
"""

# lines a reader takes, and the values they hold (written by hand)
READ = [
    ("ALT,12,M,7,-3,geo;", {"height": 12, "sep": -3}),
    ("ALT,12,,,-3,;", {"height": 12, "sep": -3}),
    ("ALT,12,M;", {"height": 12, "sep": None}),
    ("ALT,,,,5;", {"height": None, "sep": 5}),
    ("ALT,;", {"height": None, "sep": None}),
]
WRONG = ["ALT,12,K,7,-3,geo;", "ALT,12,M,8,-3,geo;", "ALT,12,M,7,-3,gps;"]


def test_python_writes_the_constants_always_and_reads_them_empty_or_left_out(tmp_path):
    render(tmp_path, "alts", SCHEMA)
    mod = load(tmp_path / "alts.py")
    assert mod.encode(mod.Alt(height=12, sep=-3)) == "ALT,12,M,7,-3,geo;"
    assert mod.encode(mod.Alt(height=None, sep=None)) == "ALT,,M,7,,geo;"
    for line, values in READ:
        assert mod.decode(line) == mod.Alt(**values), line
    for bad in WRONG:
        with pytest.raises(mod.DecodeError) as info:
            mod.decode(bad)
        assert info.value.rule == "const", bad


def test_c_writes_the_constants_always_and_reads_them_empty_or_left_out(tmp_path):
    render(tmp_path, "alts", SCHEMA)
    lines = [line for line, _ in READ] + WRONG
    calls = "\n".join(f'    show("{line}");' for line in lines)
    driver = r"""
#include <stdio.h>
#include <string.h>
#include "alts.h"
static void show(const char *line) {
    alts_alt_t m;
    int rc = alts_alt_decode(line, strlen(line), &m);
    if (rc != CW_OK) { printf("%d\n", rc == CW_ERR_CONST); return; }
    printf("%d %d %d %d\n", m.has_height, m.has_height ? m.height : 0, m.has_sep, m.has_sep ? m.sep : 0);
}
int main(void) {
    alts_alt_t m;
    char out[40];
    memset(&m, 0, sizeof m);
    m.has_height = true; m.height = 12u; m.has_sep = true; m.sep = -3;
    printf("%d %s\n", alts_alt_encode(&m, out, sizeof out), out);
    m.has_height = false; m.has_sep = false;
    printf("%d %s\n", alts_alt_encode(&m, out, sizeof out), out);
""" + calls + """
    return 0;
}
"""
    assert run_c(tmp_path, driver) == [
        "18 ALT,12,M,7,-3,geo;", "14 ALT,,M,7,,geo;",
        "1 12 1 -3", "1 12 1 -3", "1 12 0 0", "0 0 1 5", "0 0 0 0",
        "1", "1", "1"]


def test_docs_and_vectors_show_the_constant(tmp_path):
    path = tmp_path / "alts.yaml"
    path.write_text(SCHEMA, encoding="utf-8")
    result = build([path], tmp_path / "out")
    assert not result.errors
    doc = (tmp_path / "out" / "docs" / "alts.md").read_text(encoding="utf-8")
    assert "| `unit` | 2 | char | = M | optional: always written; a reader also takes it empty" in doc
    vectors = json.loads((tmp_path / "out" / "vectors" / "alts.json").read_text(encoding="utf-8"))
    full = next(v for v in vectors["valid"] if v["name"] == "full")
    assert full["text"] == "ALT,12,M,7,-3,geo;" and full["values"] == {"height": 12, "sep": -3}
    assert all(",M,7," in v["text"] for v in vectors["valid"])


def test_an_optional_str_before_a_constant_is_refused_at_its_line(tmp_path):
    path = tmp_path / "alts.yaml"
    path.write_text(SCHEMA.replace("{name: height, type: u16, optional: true}",
                                   "{name: height, type: str, max_length: 4, optional: true}"), encoding="utf-8")
    with pytest.raises(SchemaError) as info:
        compile_schema(path)
    assert any(d.loc.line == 11 and "constant 'unit'" in d.message and "optional str 'height'" in d.message
               for d in info.value.diagnostics), info.value.diagnostics


KINDS = """codeword: 1
protocol: kinds
title: t
source: s
framing: {kind: text, prefix_separator: ",", separator: ",", terminator: ";"}
messages:
  k:
    id: K
    fields:
      - {name: n, type: u8}
      - {name: level, type: i16, const: -20}
      - {name: unit, type: char, const: M}
      - {name: label, type: str, max_length: 3, const: geo}
"""
# a damaged constant and the error both codecs give for it, as each kind is read
DAMAGED = [("K,1,--20,M,geo;", "syntax"), ("K,1,-2a,M,geo;", "syntax"), ("K,1,-020,M,geo;", None),
           ("K,1,99999999999999999999,M,geo;", "const"), ("K,1,-21,M,geo;", "const"),
           ("K,1,-20,MM,geo;", "type"), ("K,1,-20,N,geo;", "const"),
           ("K,1,-20,M,geos;", "length"), ("K,1,-20,M,gps;", "const")]


def test_a_damaged_constant_gives_its_kinds_error_in_python_and_c(tmp_path):
    render(tmp_path, "kinds", KINDS)
    mod = load(tmp_path / "kinds.py")
    for line, rule in DAMAGED:
        if rule is None:
            assert mod.decode(line) == mod.K(n=1), line
            continue
        with pytest.raises(mod.DecodeError) as info:
            mod.decode(line)
        assert info.value.rule == rule, line
    codes = {None: "CW_OK", "syntax": "CW_ERR_SYNTAX", "const": "CW_ERR_CONST", "type": "CW_ERR_TYPE",
             "length": "CW_ERR_LENGTH"}
    checks = "\n".join(f'    printf("%d\\n", kinds_k_decode("{line}", {len(line)}u, &m) == {codes[rule]});'
                       for line, rule in DAMAGED)
    driver = '#include <stdio.h>\n#include "kinds.h"\nint main(void) {\n    kinds_k_t m;\n' + checks + "\n    return 0;\n}\n"
    assert run_c(tmp_path, driver) == ["1"] * len(DAMAGED)


def test_a_line_of_constants_alone_compiles_warning_free(tmp_path):
    render(tmp_path, "kinds", KINDS.replace("      - {name: n, type: u8}\n", ""))
    driver = r"""
#include <stdio.h>
#include "kinds.h"
int main(void) {
    kinds_k_t m;
    char out[32];
    printf("%d %s\n", kinds_k_encode(&m, out, sizeof out), out);
    printf("%d\n", kinds_k_decode("K,-20,M,geo;", 12u, &m));
    return 0;
}
"""
    assert run_c(tmp_path, driver) == ["12 K,-20,M,geo;", "0"]
