"""Byte framings without a length field: the stream decoders take a frame's size
from its id (and a protocol of one message needs no id at all). Frames are
worked out by hand: xor checksums over every byte before them."""
from __future__ import annotations


import pytest

from codeword.build import compile_schema
from codeword.diagnostics import SchemaError
from schema_in_a_test import load, render, run_c

HEAD = """codeword: 1
protocol: {name}
title: t
source: s
"""
BY_ID = HEAD + """framing:
  kind: bytes
  byte_order: little
  layout:
    - {{name: kind, type: u8, dispatch: true}}
    - {{payload: true}}
    - {{name: crc, type: u8, checksum: {{algorithm: xor, covers: {{from: kind, to: payload}}}}}}
messages:
  a:
    id: 1
    fields:
      - {{name: x, type: u8}}
  b:
    id: 2
    fields:
      - {{name: x, type: u16}}
      - {{name: y, type: u16}}
"""
ONE = HEAD + """framing:
  kind: bytes
  byte_order: little
  layout:
    - {{name: sync, type: u8, const: 0x55}}
    - {{payload: true}}
    - {{name: crc, type: u8, checksum: {{algorithm: xor, covers: {{from: sync, to: payload}}}}}}
messages:
  a:
    fields:
      - {{name: x, type: u8}}
"""
A5 = "01 05 04"  # kind 1, x 5, 01^05
B = "02 02 01 04 03 06"  # kind 2, x 0x0102 and y 0x0304 low byte first, 02^02^01^04^03
STREAM = bytes.fromhex("09" + A5 + B + A5)  # 09: no message has that id

DRIVER = r"""
#include <stdio.h>
#include "{name}.h"
int main(void) {{
    static const uint8_t stream[] = {{ {bytes} }};
    {name}_parser_t p;
    {name}_message_t m;
    size_t i;
    int rc;
    {name}_parser_init(&p, 0);
    for (i = 0; i < sizeof stream; i++) {{
        if ({name}_parser_feed(&p, stream[i]) != CW_OK) return 1;
        while ((rc = {name}_parser_next(&p, &m)) != 0) {{
            if (rc < 0) printf("error %s\n", rc == CW_ERR_DISPATCH ? "dispatch" : "other");
            {show}
        }}
    }}
    printf("skipped %u\n", (unsigned)p.scan.skipped);
    return 0;
}}
"""


def c_bytes(data: bytes) -> str:
    return ", ".join(f"0x{b:02x}" for b in data)


def test_frames_of_two_sizes_without_sync_or_length(tmp_path):
    render(tmp_path, "byid", BY_ID.format(name="byid"))
    mod = load(tmp_path / "byid.py")
    items = mod.StreamDecoder().feed(STREAM)
    assert isinstance(items[0], mod.DecodeError) and items[0].rule == "dispatch"
    assert items[1:] == [mod.A(x=5), mod.B(x=0x0102, y=0x0304), mod.A(x=5)]
    show = ('else if (m.kind == BYID_MSG_A) printf("a %u\\n", m.as.a.x); '
            'else printf("b %u %u\\n", m.as.b.x, m.as.b.y);')
    out = run_c(tmp_path, DRIVER.format(name="byid", bytes=c_bytes(STREAM), show=show))
    assert out == ["error dispatch", "a 5", "b 258 772", "a 5", "skipped 1"]


def test_one_message_needs_no_id(tmp_path):
    render(tmp_path, "one", ONE.format(name="one"))
    mod = load(tmp_path / "one.py")
    assert mod.decode(bytes.fromhex("55 05 50")) == mod.A(x=5)  # 55^05 = 50
    decoder = mod.StreamDecoder()
    assert decoder.feed(bytes.fromhex("00 55 05 50 55 07 52")) == [mod.A(x=5), mod.A(x=7)]
    assert decoder.skipped == 1
    show = 'else printf("a %u\\n", m.as.a.x);'
    out = run_c(tmp_path, DRIVER.format(name="one", bytes="0x00, 0x55, 0x05, 0x50, 0x55, 0x07, 0x52", show=show))
    assert out == ["a 5", "a 7", "skipped 1"]


def test_one_id_of_two_sizes_without_length_or_checksum_is_refused(tmp_path):
    # with a checksum the stream decoders try each size (tests/test_id_of_several_sizes.py)
    text = BY_ID.format(name="twosizes").replace("id: 2", "id: 1")
    text = "\n".join(line for line in text.splitlines() if "checksum" not in line) + "\n"
    path = tmp_path / "twosizes.yaml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(SchemaError) as refused:
        compile_schema(path)
    (problem,) = [d for d in refused.value.diagnostics if "same id" in d.message]
    assert problem.loc.line == text.splitlines().index("  b:") + 1
