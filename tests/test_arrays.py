"""Fields of a fixed count (`count: N`): an array of a scalar or of a group, each
element where the one before it ends. The expected bytes are worked out by hand
below; Python and C both write them and read them back."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from codeword.build import compile_schema
from codeword.cli import main
from codeword.diff import BREAKING, compare
from codeword.fingerprint import canonical_json, fingerprint
from codeword.targets.markdown.layout import diagram, slots, type_text

from schema_in_a_test import c_bytes, conformance_on_host_and_avr, firmware_warnings, load, render, run_c

ROOT = Path(__file__).resolve().parent.parent

ARRAYS = """codeword: 1
protocol: arrays
title: Arrays
source: hand-written
framing:
  kind: bytes
  byte_order: little
  layout:
    - {name: id, type: u8, dispatch: true}
    - {payload: true}
types:
  pair:
    type: group
    fields:
      - {name: hi, type: u4}
      - {name: lo, type: u4}
messages:
  words:
    id: 1
    fields:
      - {name: w, type: u16, count: 4}
  fives:
    id: 2
    fields:
      - {name: v, type: u5, count: 3}
      - {name: pad, type: u1, reserved: true}
  pairs:
    id: 3
    fields:
      - {name: p, type: pair, count: 2}
  limited:
    id: 4
    fields:
      - {name: ch, type: u8, count: 3, range: [0, 200]}
"""

# (message, values, frame), each frame worked out by hand:
FRAMES = [
    # id 1, then four u16 little-endian: 1, 2, 0x1234, 0xFFFF
    ("words", {"w": [1, 2, 0x1234, 0xFFFF]}, "01 0100 0200 3412 ffff"),
    # id 2, then 00001 00010 11111 and a zero pad bit, most significant bit first:
    # 0000 1000 | 1011 1110 = 08 be
    ("fives", {"v": [1, 2, 31]}, "02 08 be"),
    # id 3, then {hi 1, lo 2} {hi 3, lo 4}: one byte each, hi in the high nibble
    ("pairs", {"p": [{"hi": 1, "lo": 2}, {"hi": 3, "lo": 4}]}, "03 12 34"),
]

SBUS = """codeword: 1
protocol: sbus16
title: SBUS frame with its channels as one array
source: hand-written
framing:
  kind: bytes
  bit_order: lsb_first
  layout:
    - {name: header, type: u8, const: 0x0F}
    - {payload: true}
    - {name: footer, type: u8, const: 0x00}
messages:
  channels:
    fields:
      - {name: ch, type: u11, count: 16}
      - {name: ch17, type: bool}
      - {name: ch18, type: bool}
      - {name: frame_lost, type: bool}
      - {name: failsafe, type: bool}
      - {name: spare, type: u4, reserved: true}
"""

# As in tests/test_lsb_first.py (worked out there bit by bit): every channel at 1024
# sets stream bit 11k + 10, giving 00 04 20 00 01 08 40 00 02 10 80 for eight channels.
CENTRED = "0f" + "00 04 20 00 01 08 40 00 02 10 80" * 2 + "00 00"
# Channel 1 at 0x7FF, others 0: stream bits 0..10 = ff 07; ch17 (bit 0) and failsafe (bit 3) = 09.
FIRST_FULL = "0f ff 07" + " 00" * 20 + " 09 00"
SBUS_FRAMES = [
    (dict(ch=[1024] * 16, ch17=False, ch18=False, frame_lost=False, failsafe=False), CENTRED),
    (dict(ch=[0x7FF] + [0] * 15, ch17=True, ch18=False, frame_lost=False, failsafe=True), FIRST_FULL),
]


def c_init(values: dict) -> str:
    """A C initialiser of plain integers, lists and nested dicts."""
    def one(v):
        if isinstance(v, dict):
            return "{" + ", ".join(f".{k} = {one(x)}" for k, x in v.items()) + "}"
        if isinstance(v, list):
            return "{" + ", ".join(one(x) for x in v) + "}"
        if isinstance(v, bool):
            return "true" if v else "false"
        return f"{v}u"
    return one(values)


def test_python_writes_and_reads_the_hand_worked_frames(tmp_path):
    mod = load(render(tmp_path, "arrays", ARRAYS) / "arrays.py")
    for name, values, frame in FRAMES:
        obj = mod.from_dict(name, values)
        assert mod.encode(obj) == bytes.fromhex(frame)
        assert mod.decode(bytes.fromhex(frame)) == obj
    decoded = mod.decode(bytes.fromhex("03 12 34"))
    assert decoded.p == [mod.PairsP(hi=1, lo=2), mod.PairsP(hi=3, lo=4)]
    assert type(mod.decode(bytes.fromhex("01 0100 0200 3412 ffff")).w) is list


def test_python_refuses_a_wrong_length_or_element_naming_it(tmp_path):
    mod = load(render(tmp_path, "arrays", ARRAYS) / "arrays.py")
    with pytest.raises(mod.EncodeError) as short:
        mod.encode(mod.Words(w=[1, 2, 3]))
    assert (short.value.field, short.value.rule) == ("w", "count")
    with pytest.raises(mod.EncodeError) as wrong:
        mod.encode(mod.Words(w=[1, 2, 3, "4"]))
    assert (wrong.value.field, wrong.value.rule) == ("w[3]", "type")
    with pytest.raises(mod.EncodeError) as outside:
        mod.encode(mod.Fives(v=[1, 32, 0]))
    assert (outside.value.field, outside.value.rule) == ("v[1]", "range")
    with pytest.raises(mod.EncodeError) as member:
        mod.encode(mod.Pairs(p=[mod.PairsP(hi=1, lo=2), mod.PairsP(hi=3, lo=16)]))
    assert member.value.field == "p[1].lo"
    with pytest.raises(mod.EncodeError):
        mod.encode(mod.Words(w=7))
    assert mod.encode(mod.Words(w=(1, 2, 0x1234, 0xFFFF))) == bytes.fromhex("01 0100 0200 3412 ffff")  # a tuple too
    with pytest.raises(mod.DecodeError) as plain:
        mod.from_dict("words", {"w": 5})
    assert plain.value.field == "w"


def test_c_writes_and_reads_the_hand_worked_frames(tmp_path):
    render(tmp_path, "arrays", ARRAYS)
    checks = []
    for name, values, frame in FRAMES:
        checks.append(f"""    {{
        static const uint8_t frame[] = {{{c_bytes(bytes.fromhex(frame))}}};
        const arrays_{name}_t want = {c_init(values)};
        arrays_{name}_t got;
        uint8_t out[16];
        int n = arrays_{name}_encode(&want, out, sizeof out);
        printf("{name} %d %d", n == (int)sizeof frame, n > 0 && memcmp(out, frame, sizeof frame) == 0);
        memset(&got, 0xAA, sizeof got);
        n = arrays_{name}_decode(frame, sizeof frame, &got);
        printf(" %d %d\\n", n, memcmp(&got, &want, sizeof got) == 0);
    }}""")
    driver = """#include <stdio.h>
#include <string.h>
#include "arrays.h"
int main(void) {
""" + "\n".join(checks) + """
    {
        arrays_fives_t m = {{1u, 32u, 0u}};
        uint8_t out[8];
        printf("%s\\n", cw_error_name(arrays_fives_encode(&m, out, sizeof out)));
    }
    return 0;
}
"""
    lines = run_c(tmp_path, driver)
    assert lines == [f"{name} 1 1 0 1" for name, _, _ in FRAMES] + ["range"]


def test_the_sbus_channels_as_one_array_give_the_hand_worked_frames(tmp_path):
    mod = load(render(tmp_path, "sbus16", SBUS) / "sbus16.py")
    for values, frame in SBUS_FRAMES:
        assert mod.Channels(**values).encode() == bytes.fromhex(frame)
        assert mod.decode(bytes.fromhex(frame)) == mod.Channels(**values)
    checks = []
    for i, (values, frame) in enumerate(SBUS_FRAMES):
        checks.append(f"""    {{
        static const uint8_t frame[] = {{{c_bytes(bytes.fromhex(frame))}}};
        const sbus16_channels_t want = {c_init(values)};
        sbus16_channels_t got;
        uint8_t out[32];
        int n = sbus16_channels_encode(&want, out, sizeof out);
        printf("{i} %d %d", n, n > 0 && memcmp(out, frame, sizeof frame) == 0);
        memset(&got, 0, sizeof got);
        n = sbus16_channels_decode(frame, sizeof frame, &got);
        printf(" %d %d %u\\n", n, memcmp(&got, &want, sizeof got) == 0, (unsigned)got.ch[0]);
    }}""")
    driver = """#include <stdio.h>
#include <string.h>
#include "sbus16.h"
int main(void) {
""" + "\n".join(checks) + """
    return 0;
}
"""
    lines = run_c(tmp_path, driver)
    assert lines == ["0 25 1 0 1 1024", "1 25 1 0 1 2047"]


# Least significant bit first, elements crossing bytes: wide ones, narrow ones and
# whole little-endian integers in an array of groups, as the raw array holds them.
WIDE_LSB = """codeword: 1
protocol: widelsb
title: Wide elements packed least significant bit first
source: hand-written
framing:
  kind: bytes
  bit_order: lsb_first
  byte_order: little
  layout:
    - {name: sync, type: u8, const: 0xA5}
    - {payload: true}
    - {name: check, type: u8, checksum: {algorithm: xor, covers: {from: payload, to: payload}}}
messages:
  samples:
    fields:
      - name: sample
        type: group
        count: 4
        fields:
          - {name: wide, type: u43}
          - {name: narrow, type: u5}
          - {name: whole, type: u64}
          - {name: half, type: u16}
      - {name: tail, type: u3}
      - {name: more, type: u5}
"""


@pytest.mark.parametrize("level", ["-O0", "-O1", "-O2", "-Os", "-O3"])
@pytest.mark.parametrize("compiler", ["gcc", "clang"])
@pytest.mark.parametrize("name,schema", [("sbus16", SBUS), ("widelsb", WIDE_LSB)], ids=["sbus16", "widelsb"])
def test_lsb_first_arrays_compile_without_warnings_where_firmware_inlines_them(tmp_path, name, schema,
                                                                                compiler, level):
    """The encoder keeps every raw value in a local array before it packs them; gcc
    could not tell raw had set them all, and warned (-Wmaybe-uninitialized) at -O1
    where firmware encodes into a buffer on its stack."""
    render(tmp_path, name, schema)
    assert firmware_warnings(tmp_path, name, compiler, level) == ""


def test_each_element_is_a_leaf_with_its_index(tmp_path):
    path = tmp_path / "arrays.yaml"
    path.write_text(ARRAYS, encoding="utf-8")
    p = compile_schema(path)
    fives = p.message("fives")
    assert [(x.dotted, x.var, x.pos, x.bits) for x in fives.wire.leaves] == [
        ("id", "r_id", 0, 8), ("v[0]", "r_1v_0", 8, 5), ("v[1]", "r_1v_1", 13, 5), ("v[2]", "r_1v_2", 18, 5),
        ("pad", "r_pad", 23, 1)]
    pairs = p.message("pairs")
    assert [x.dotted for x in pairs.wire.leaves] == ["id", "p[0].hi", "p[0].lo", "p[1].hi", "p[1].lo"]
    w = p.message("words").layout[1]
    assert (w.count, w.bits, w.element.bits, w.element.count) == (4, 64, 16, None)


def test_the_docs_show_an_array_as_one_row(tmp_path):
    path = tmp_path / "sbus16.yaml"
    path.write_text(SBUS, encoding="utf-8")
    p = compile_schema(path)
    m = p.messages[0]
    ch = next(s for s in slots(m) if s.field.name == "ch")
    assert (ch.path, ch.offset, ch.field.bits) == ("ch[16]", 8, 176)
    assert type_text(p, ch.field) == "16 × u11 LE"  # the element type, read little-endian (lsb_first)
    column = next(c for c in diagram(p, m)["columns"] if c["name"] == "ch[0..15]")
    assert column["offset"] == "8–183"


def test_a_changed_count_is_breaking_and_arrays_leave_other_fingerprints_alone(tmp_path):
    def model(text: str, name: str):
        path = tmp_path / f"{name}.yaml"
        path.write_text(text, encoding="utf-8")
        return compile_schema(path)
    old = model(SBUS, "old")
    new = model(SBUS.replace("count: 16", "count: 15").replace("u4, reserved", "u15, reserved"), "new")
    changes = [(c.kind, c.subject, c.what) for c in compare(old, new).changes]
    assert (BREAKING, "field ch", "count changed from 16 to 15") in changes
    assert not any(c[1].startswith("field ch[") for c in changes)  # not element by element
    assert fingerprint(old) != fingerprint(new)
    plain = compile_schema(ROOT / "schemas" / "tank.yaml")  # no arrays: no trace of them in the wire model
    assert '"count"' not in canonical_json(plain)


def test_check_names_the_element_that_breaks_a_range(tmp_path, capsys):
    schema = tmp_path / "arrays.yaml"
    schema.write_text(ARRAYS, encoding="utf-8")
    data = tmp_path / "frames.hex"
    data.write_text("04 01 02 c8\n04 01 02 c9\n", encoding="utf-8")  # 200, then 201 in ch[2]
    status = main(["check", "--format", "json", str(schema), str(data)])
    doc = json.loads(capsys.readouterr().out)
    assert status == 1
    assert [(f["line"], f["field"], f["rule"], f["actual"]) for f in doc["findings"]] == [(2, "ch[2]", "range", 201)]




WORDS = """codeword: 1
protocol: bitarrays
title: An array in a bit record with a text form
source: hand-written
framing:
  kind: bits
  max_bits: 56
  byte_order: big
  text_form: {separator: " ", comment: "#"}
messages:
  levels:
    bits: 56
    fields:
      - {name: tag, type: u2, const: 1, dispatch: true}
      - {name: v, type: u3, count: 4}
      - {name: pad, type: u2, reserved: true}
      - {name: wide, type: u20, count: 2}
"""


def test_a_bit_record_holds_an_array_and_its_text_form_one_value_per_element(tmp_path):
    mod = load(render(tmp_path, "bitarrays", WORDS) / "bitarrays.py")
    obj = mod.Levels(v=[1, 2, 3, 7], wide=[0xFFFFF, 1])
    # 01 | 001 010 011 111 | 00 | 20 ones | 19 zeros and a one: 0100 1010 0111 1100, ff ff f0 00 01
    assert mod.encode(obj) == bytes.fromhex("4a7c fffff00001")
    assert mod.encode_text(obj) == "1 1 2 3 7 0 1048575 1"  # each element a raw value of its own
    assert mod.decode_text("1 1 2 3 7 0 1048575 1") == obj


@pytest.mark.parametrize("name,schema", [("arrays", ARRAYS), ("sbus16", SBUS), ("bitarrays", WORDS)])
def test_conformance_vectors_on_the_host_and_on_atmega32_under_simavr(tmp_path, name, schema):
    """Edge values in every element, random arrays, damaged frames (and, for the bit
    record, its text form): C agrees with Python on the host and on an 8-bit AVR."""
    host, avr = conformance_on_host_and_avr(tmp_path, name, schema)
    assert host > 100 and avr > 100


NESTED = """codeword: 1
protocol: nested
title: t
source: s
framing:
  kind: bytes
  layout:
    - {name: sync, type: u8, const: 0x55}
    - {payload: true}
types:
  pair: {type: group, fields: [{name: x, type: u4}, {name: y, type: u4}]}
messages:
  m:
    fields:
      - name: outer
        type: group
        count: 2
        fields:
          - {name: a, type: u8}
          - {name: inner, type: pair, count: 3}
"""
# by hand: outer[0] = a 01, pairs 12 34 56; outer[1] = a 02, pairs 78 9a bc
NESTED_FRAME = "55 01 12 34 56 02 78 9a bc"


def test_an_array_inside_an_array_has_its_own_count(tmp_path):
    """Python checked the inner array against the outer one's count (3 pairs refused as not 2)."""
    render(tmp_path, "nested", NESTED)
    mod = load(tmp_path / "nested.py")
    frame = bytes.fromhex(NESTED_FRAME)
    m = mod.decode(frame)
    assert [(o.a, [(p.x, p.y) for p in o.inner]) for o in m.outer] == \
        [(1, [(1, 2), (3, 4), (5, 6)]), (2, [(7, 8), (9, 10), (11, 12)])]
    assert mod.encode(m) == frame
    driver = r"""
#include <stdio.h>
#include "nested.h"
int main(void) {
    static const uint8_t frame[] = {0x55, 0x01, 0x12, 0x34, 0x56, 0x02, 0x78, 0x9a, 0xbc};
    nested_m_t m;
    uint8_t out[9];
    int i, n, rc = nested_m_decode(frame, sizeof frame, &m);
    n = nested_m_encode(&m, out, sizeof out);
    printf("%d %d %u %u", rc, n, (unsigned)m.outer[1].a, (unsigned)m.outer[1].inner[2].y);
    for (i = 0; i < n; i++) printf(" %02x", out[i]);
    printf("\n");
    return 0;
}
"""
    assert run_c(tmp_path, driver) == ["0 9 2 12 " + NESTED_FRAME]
