"""The locals generated code keeps each leaf's raw value in (`r_…`, Python's group
objects `g_…`) are spelt from the leaf's path: one spelling per path, so a group
member `a.b` and a field `a_b` keep their own values, and no `__`, which C++
reserves (the headers must compile as C++ too). Expected frames are worked out by
hand below; clang's -Wreserved-identifier and a scan of the text check the names."""
from __future__ import annotations

import itertools
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from codeword.model import path_name
from conftest import PROTOCOLS, ROOT
from schema_in_a_test import load, render, run_c

NESTED = """\
codeword: 1
protocol: nested
title: Local names of nested fields
source: hand-written
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: id, type: u8, dispatch: true}
    - {payload: true}
types:
  point:
    type: group
    fields:
      - {name: x, type: u4}
      - {name: v, type: u4, count: 3}
  tiny:
    type: group
    fields:
      - {name: x, type: u2}
      - {name: v, type: u1, count: 2}
messages:
  flat_names:
    id: 1
    fields:
      - {name: a_b, type: u8}
      - {name: a, type: group, fields: [{name: b, type: u8}]}
      - {name: ch_3, type: u8}
      - {name: ch, type: u4, count: 4}
      - {name: q_, type: group, fields: [{name: b, type: u4}, {name: c, type: u4}]}
      - {name: pts, type: point, count: 2}
    examples:
      - name: every value its own
        values: {a_b: 1, a: {b: 2}, ch_3: 3, ch: [4, 5, 6, 7], q_: {b: 8, c: 9},
                 pts: [{x: 1, v: [2, 3, 4]}, {x: 5, v: [6, 7, 8]}]}
        hex: 01 01 02 03 45 67 89 12 34 56 78
  word_names:
    id: 2
    fields:
      - {name: a_b, type: u4}
      - {name: a, type: group, fields: [{name: b, type: u4}]}
      - {name: ch, type: u4, count: 2}
      - {name: pts, type: tiny, count: 2}
    examples:
      - name: every value its own
        values: {a_b: 1, a: {b: 2}, ch: [3, 4], pts: [{x: 1, v: [0, 1]}, {x: 2, v: [1, 1]}]}
        hex: 02 12 34 5B
"""
# By hand: one byte each for id, a_b, a.b and ch_3, then 4-bit values first bit
# first (ch 4 5 6 7 → 45 67, q_ 8 9 → 89, pts[i] x then v[0..2] → 12 34, 56 78).
# word_names fits one 32-bit word, whose C keeps every leaf in a local: a_b 1 and
# a.b 2 → 12, ch → 34, pts[0] x=01 v=0,1 → 0101 and pts[1] x=10 v=1,1 → 1011: 5B.
FLAT = "01 01 02 03 45 67 89 12 34 56 78"
WORD = "02 12 34 5B"

NAMES = ["a", "b", "a_b", "b_c", "a_", "ch", "ch_3", "x1", "q_"]
INDEXES = [0, 1, 3, 11]


def paths(depth: int):
    for first in NAMES:
        for rest in itertools.product(NAMES + INDEXES, repeat=depth - 1):
            yield (first, *rest)


def test_each_path_has_its_own_spelling_without_a_double_underscore():
    spelt: dict[str, tuple] = {}
    for path in (p for depth in (1, 2, 3, 4) for p in paths(depth)):
        name = path_name(path)
        assert re.fullmatch(r"[A-Za-z0-9]+(_[A-Za-z0-9]+)*_?", name) and "__" not in name, path
        assert spelt.setdefault(name, path) == path, (name, path, spelt[name])
    assert (path_name(("speed",)), path_name(("ch", 3)), path_name(("pts", 1, "x"))) == ("speed", "2ch_3", "3pts_1_1x")


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    where = tmp_path_factory.mktemp("nested")
    render(where, "nested", NESTED)  # the schema's hand-worked examples must hold in Python
    return where


def test_python_keeps_a_member_apart_from_a_field_of_its_flat_name(built):
    mod = load(built / "nested.py")
    flat = mod.decode(bytes.fromhex(FLAT))
    assert (flat.a_b, flat.a.b, flat.ch_3, flat.ch, flat.q_.b, flat.q_.c) == (1, 2, 3, [4, 5, 6, 7], 8, 9)
    assert [(p.x, p.v) for p in flat.pts] == [(1, [2, 3, 4]), (5, [6, 7, 8])]
    word = mod.decode(bytes.fromhex(WORD))
    assert (word.a_b, word.a.b, word.ch, [(p.x, p.v) for p in word.pts]) == (1, 2, [3, 4], [(1, [0, 1]), (2, [1, 1])])
    assert mod.encode(flat).hex(" ").upper() == FLAT and mod.encode(word).hex(" ").upper() == WORD


DRIVER = r"""
#include <stdio.h>
#include "nested.h"
static void again(const nested_message_t *m) {
    uint8_t out[NESTED_MAX_FRAME];
    int i, n = nested_encode(m, out, sizeof out);
    for (i = 0; i < n; i++) printf(" %02X", out[i]);
    printf("\n");
}
int main(void) {
    static const uint8_t flat[] = {FLAT};
    static const uint8_t word[] = {WORD};
    nested_message_t m;
    const nested_flat_names_t *f = &m.as.flat_names;
    const nested_word_names_t *w = &m.as.word_names;
    int rc = nested_decode(flat, sizeof flat, NESTED_DIR_ANY, &m);
    printf("%d %u %u %u %u %u %u %u %u\n", rc, f->a_b, f->a.b, f->ch_3, f->ch[3], f->q_.b, f->q_.c, f->pts[1].x,
           f->pts[1].v[2]);
    again(&m);
    rc = nested_decode(word, sizeof word, NESTED_DIR_ANY, &m);
    printf("%d %u %u %u %u %u %u\n", rc, w->a_b, w->a.b, w->ch[1], w->pts[0].v[1], w->pts[1].x, w->pts[1].v[0]);
    again(&m);
    return 0;
}
"""


def c_array(frame: str) -> str:
    return ", ".join(f"0x{b}" for b in frame.split())


def test_c_keeps_a_member_apart_from_a_field_of_its_flat_name(built):
    lines = run_c(built, DRIVER.replace("{FLAT}", "{" + c_array(FLAT) + "}").replace("{WORD}", "{" + c_array(WORD) + "}"))
    assert lines == ["0 1 2 3 7 8 9 5 8", " " + FLAT, "0 1 2 4 1 2 1", " " + WORD]


def header_groups(built: Path) -> list[list[Path]]:
    """The five protocols' headers, the examples' and the nested schema's: each a
    folder that also holds codeword.h."""
    return [[ROOT / "generated" / "c" / f"{p}.h" for p in PROTOCOLS],
            sorted(h for h in (ROOT / "generated" / "examples" / "c").glob("*.h") if h.name != "codeword.h"),
            [built / "nested.h"]]


# Names the compiler and the C library define, which the headers may use but never declare.
IMPLEMENTATION = re.compile(r"__[A-Za-z0-9_]+__|__builtin_[a-z0-9_]+|__cplusplus")


def test_no_generated_identifier_holds_a_double_underscore(built):
    found = {}
    for header in (h for group in header_groups(built) for h in group + [group[0].parent / "codeword.h"]):
        code = re.sub(r'/\*.*?\*/|"(?:\\.|[^"\\])*"', " ", header.read_text(encoding="utf-8"), flags=re.S)
        names = {n for n in re.findall(r"\b[A-Za-z_][A-Za-z0-9_]*", code) if "__" in n and not IMPLEMENTATION.fullmatch(n)}
        if names:
            found[header.name] = sorted(names)[:5]
    assert not found, found
    assert "r_3pts_1_1v_0" in (built / "nested.h").read_text(encoding="utf-8")  # C keeps nested leaves in locals


def compile_as_cpp17(compiler: str, built: Path, tmp: Path, extra: list[str]) -> None:
    path = shutil.which(compiler)
    assert path, f"{compiler} is not installed (.ci/run installs it)"
    for group in header_groups(built):
        src = tmp / f"{group[0].stem}.cpp"
        src.write_text("".join(f'#include "{h.name}"\n' for h in group) + "int main() { return 0; }\n",
                       encoding="utf-8")
        made = subprocess.run([path, "-std=c++17", "-Wall", "-Wextra", "-Werror", "-pedantic", *extra,
                               "-I", str(group[0].parent), "-c", str(src), "-o", str(src.with_suffix(".o"))],
                              capture_output=True, text=True, timeout=300)
        assert made.returncode == 0, made.stderr[-3000:]


def test_headers_compile_as_cpp17_with_gcc(built, tmp_path):
    compile_as_cpp17("g++", built, tmp_path, [])


def test_headers_declare_no_reserved_identifier_for_clang(built, tmp_path):
    """clang names each identifier the C++ standard reserves (`__` anywhere, `_` and a capital)."""
    compile_as_cpp17("clang++", built, tmp_path, ["-Wreserved-identifier"])
