"""HDLC's async control character map (RFC 1662 §7.1) against frames worked by hand
from the RFC's rules, in Python, in C (host with sanitizers; the conformance driver on
an ATmega32 under simavr) and in the compiled accelerator.

The rules (RFC 1662 §4.2 and §7.1): bit n of the 32-bit map stands for the control
character n (bit 0: NUL). A sender escapes 7E, 7D and every mapped character: 7D,
then the byte XOR 20. A receiver first drops every mapped character that arrives as it
is (equipment on the way may have added it, e.g. XON/XOFF), then takes 7D as the
escape of the next byte, whatever it is.
"""
from __future__ import annotations

import shutil

import pytest

from codeword import accelerate as accel
from schema_in_a_test import conformance_on_host_and_avr, load, render, run_c

SCHEMA = """codeword: 1
protocol: {name}
title: HDLC with a control character map
source: RFC 1662
framing:
  kind: bytes
  encoding: hdlc
  accm: {accm}
  layout:
    - {{name: kind, type: u8, dispatch: true}}
    - {{payload: true}}
    - {{name: check, type: u8, checksum: {{algorithm: sum, modulo: 256, covers: {{from: kind, to: payload}}}}}}
messages:
  flow:
    id: 0x11
    fields:
      - {{name: x, type: u16}}
{examples}
"""

# XON (11) and XOFF (13) mapped: bits 17 and 19, 0x000A0000.
XONXOFF = SCHEMA.format(name="xonxoff", accm="0x000A0000", examples="""    examples:
      - hex: "7e 7d 31 7d 33 7d 5e a2 7e"
        values: {x: 0x137e}""")
# PPP's default map: every control character.
PPP = SCHEMA.format(name="pppmap", accm="0xFFFFFFFF", examples="")

# kind 11, x 137E, check 11 + 13 + 7E = A2: every byte but the check is escaped.
FLOW = bytes.fromhex("11 13 7e a2")
FLOW_WIRE = bytes.fromhex("7e 7d 31 7d 33 7d 5e a2 7e")
# An XON added before the escaped 11's second byte and before the check: both dropped.
FLOW_WITH_XON = bytes.fromhex("7e 7d 11 31 7d 33 7d 5e 11 a2 7e")
# 13 as it is (unescaped, so added on the way) and the unmapped 41 escaped: 7D 61.
FLOW_MIXED = bytes.fromhex("7e 7d 31 13 7d 33 7d 5e 7d 61 7e")  # frame 11 13 7e 41: check A2 expected, so bad


def test_python_escapes_and_drops_the_mapped_characters(tmp_path):
    render(tmp_path, "xonxoff", XONXOFF)
    mod = load(tmp_path / "xonxoff.py")
    assert mod.stuff(FLOW) == FLOW_WIRE
    assert mod.encode(mod.Flow(x=0x137E)) == FLOW_WIRE
    assert mod.unstuff(FLOW_WITH_XON) == FLOW
    assert mod.decode(FLOW_WITH_XON) == mod.Flow(x=0x137E)
    assert mod.unstuff(FLOW_MIXED) == bytes.fromhex("11 13 7e 41")
    # unmapped control characters are data, as they are: 01 and 12 go unescaped
    assert mod.stuff(bytes.fromhex("01 12 11")) == bytes.fromhex("7e 01 12 7d 31 7e")
    # an escape followed only by dropped characters: a bad escape at the escape's offset
    with pytest.raises(mod.DecodeError) as err:
        mod.decode(bytes.fromhex("7e 11 13 a2 7d 11 7e"))
    assert err.value.rule == "escape" and "at byte 4 " in str(err.value)
    # a stream: the frame with XONs, then one with an added XOFF inside an escape
    decoder = mod.StreamDecoder()
    items = decoder.feed(FLOW_WITH_XON + bytes.fromhex("7d 13 31 7d 33 7d 5e a2 7e"))
    assert items == [mod.Flow(x=0x137E), mod.Flow(x=0x137E)] and decoder.skipped == 0


def test_ppp_default_map_escapes_every_control_character(tmp_path):
    render(tmp_path, "pppmap", PPP)
    mod = load(tmp_path / "pppmap.py")
    # 00 → 7D 20, 1F → 7D 3F, 20 is not a control character, 7D → 7D 5D, 7F stays
    assert mod.stuff(bytes.fromhex("00 1f 20 7d 7f")) == bytes.fromhex("7e 7d 20 7d 3f 20 7d 5d 7f 7e")
    everything = bytes(range(256))
    wire = mod.stuff(everything)
    assert not any(b < 0x20 for b in wire) and wire.count(0x7E) == 2
    for i in range(0, 256, 4):  # frames of up to 4 bytes: each byte value once
        assert mod.unstuff(mod.stuff(everything[i:i + 4])) == everything[i:i + 4]
    # kind 11, x 0102, check 14: all four bytes are control characters
    assert mod.encode(mod.Flow(x=0x0102)) == bytes.fromhex("7e 7d 31 7d 21 7d 22 7d 34 7e")


C_DRIVER = r"""
#include <stdio.h>
#include "xonxoff.h"
static void show(const uint8_t *data, int n)
{
    int i;
    if (n < 0) {
        printf("error %d\n", n);
        return;
    }
    for (i = 0; i < n; i++) {
        printf(i ? " %02x" : "%02x", (unsigned)data[i]);
    }
    printf("\n");
}
int main(void)
{
    static const uint8_t flow[] = {0x11, 0x13, 0x7e, 0xa2};
    static const uint8_t with_xon[] = {0x7e, 0x7d, 0x11, 0x31, 0x7d, 0x33, 0x7d, 0x5e, 0x11, 0xa2, 0x7e};
    uint8_t wire[XONXOFF_WIRE_MAX];
    uint8_t frame[XONXOFF_FRAME_MAX];
    xonxoff_message_t m;
    int rc;
    show(wire, xonxoff_stuff(flow, sizeof flow, wire, sizeof wire));
    show(frame, xonxoff_unstuff(with_xon, sizeof with_xon, frame, sizeof frame));
    rc = xonxoff_decode(with_xon, sizeof with_xon, 0, &m);
    printf("decode %d x %x\n", rc, (unsigned)m.as.flow.x);
    return 0;
}
"""


def test_c_escapes_and_drops_the_mapped_characters(tmp_path):
    render(tmp_path, "xonxoff", XONXOFF)
    lines = run_c(tmp_path, C_DRIVER)
    assert lines == [FLOW_WIRE.hex(" "), FLOW.hex(" "), "decode 0 x 137e"]


@pytest.mark.parametrize("name,schema", [("xonxoff", XONXOFF), ("pppmap", PPP)])
def test_conformance_on_host_and_atmega32(tmp_path, name, schema):
    host, avr = conformance_on_host_and_avr(tmp_path, name, schema)
    assert host > 10 and avr == host


def test_the_accelerator_decodes_as_python(tmp_path):
    from fuzz.schema.accelerated import difference, load as load_module
    import io
    import json
    from codeword.build import compile_schema
    from codeword.vectors import write_vectors
    if shutil.which("gcc") is None or accel.python_headers() is None:
        pytest.fail("gcc and Python's headers are needed (scripts/install-toolchains installs them)")
    render(tmp_path, "xonxoff", XONXOFF)
    out = io.StringIO()
    write_vectors(compile_schema(tmp_path / "xonxoff.yaml"), load(tmp_path / "xonxoff.py"), out)
    vectors = json.loads(out.getvalue())
    folder = tmp_path / "accel"
    accel.accelerate([tmp_path / "xonxoff.yaml"], folder)
    fast = load_module(tmp_path / "xonxoff.py", "_xonxoff_fast", folder)
    pure = load_module(tmp_path / "xonxoff.py", "_xonxoff_pure", None)
    problem, compared = difference(fast, pure, vectors, [FLOW_WITH_XON * 3 + FLOW_MIXED + FLOW_WIRE])
    assert not problem, problem
    assert compared > len(vectors["valid"])


def test_a_changed_map_breaks_and_changes_the_fingerprint(tmp_path):
    from codeword.build import compile_schema
    from codeword.diff import BREAKING, compare
    from codeword.fingerprint import fingerprint
    protocols = []
    for name, schema in [("a", XONXOFF), ("b", PPP.replace("protocol: pppmap", "protocol: xonxoff"))]:
        (tmp_path / name).mkdir()
        (tmp_path / name / "xonxoff.yaml").write_text(schema, encoding="utf-8")
        protocols.append(compile_schema(tmp_path / name / "xonxoff.yaml"))
    assert fingerprint(protocols[0]) != fingerprint(protocols[1])
    assert {c.what for c in compare(*protocols).of_kind(BREAKING)} == {"accm changed from 655360 to 4294967295"}


@pytest.mark.parametrize("compiler", ["gcc", "clang"])
@pytest.mark.parametrize("level", ["-O0", "-O2", "-Os"])
def test_strict_warnings(tmp_path, compiler, level):
    from schema_in_a_test import firmware_warnings
    render(tmp_path, "pppmap", PPP)
    assert firmware_warnings(tmp_path, "pppmap", compiler, level) == ""


# An XOFF (13) while idle, between two frames: a stretch of mapped characters alone.
IDLE_XOFF = FLOW_WIRE + bytes.fromhex("13 13 7e 11 7e") + FLOW_WIRE
# A stretch that holds no frame, an XON inside it: its two kept bytes are skipped.
GARBAGE_WITH_XON = bytes.fromhex("7e 41 11 42 7e") + FLOW_WIRE
# An escape followed only by mapped characters, at stream offset 4.
LOST_ESCAPE = bytes.fromhex("7e 11 13 a2 7d 11 7e") + FLOW_WIRE


def test_mapped_characters_alone_are_an_empty_stretch(tmp_path):
    """RFC 1662 4.2: receivers drop mapped characters before anything else, so a stretch
    of them alone holds nothing, as the idle flags between frames: no error, no skipped
    byte. A stretch that holds no frame skips only the bytes it keeps."""
    render(tmp_path, "xonxoff", XONXOFF)
    mod = load(tmp_path / "xonxoff.py")
    for step in (1, 3, len(IDLE_XOFF)):
        decoder = mod.StreamDecoder()
        items = [x for at in range(0, len(IDLE_XOFF), step) for x in decoder.feed(IDLE_XOFF[at:at + step])]
        assert items == [mod.Flow(x=0x137E)] * 2 and decoder.skipped == 0 and decoder.finish() == []
    decoder = mod.StreamDecoder()
    items = decoder.feed(GARBAGE_WITH_XON)
    assert items[0].rule == "dispatch" and items[1:] == [mod.Flow(x=0x137E)]
    assert decoder.skipped == 2 and decoder.spans[0] == (1, 3)  # 41 11 42: three bytes on the stream
    decoder = mod.StreamDecoder()
    items = decoder.feed(LOST_ESCAPE)
    assert items[0].rule == "escape" and items[0].offset == 4 * 8 and items[1:] == [mod.Flow(x=0x137E)]
    assert decoder.skipped == 2  # the bytes kept: a2 7d
    assert decoder.feed(bytes.fromhex("11 13 11")) == [] and decoder.finish() == []


def test_a_flood_of_mapped_characters_keeps_the_buffer_bounded(tmp_path):
    """A megabyte of XON/XOFF in the middle of a frame: the decoder drops each as it
    comes, holds no more than one encoded frame, and decodes the frame after it."""
    render(tmp_path, "xonxoff", XONXOFF)
    mod = load(tmp_path / "xonxoff.py")
    decoder = mod.StreamDecoder()
    assert decoder.feed(FLOW_WIRE[:4]) == []
    flood = b"\x11\x13" * 2048
    most = 0
    for _ in range(256):  # 1 MiB
        assert decoder.feed(flood) == []
        most = max(most, len(decoder._buffer))
    assert most <= mod.WIRE_MAX
    assert decoder.feed(FLOW_WIRE[4:]) == [mod.Flow(x=0x137E)] and decoder.skipped == 0
    assert decoder.spans == [(1, len(FLOW_WIRE) - 2 + len(flood) * 256)]  # the frame's extent on the stream


STREAM_DRIVER = r"""
#include <stdio.h>
#include "xonxoff.h"
static void scan(const char *name, const uint8_t *data, size_t len, unsigned repeat_flood)
{
    xonxoff_scan_state_t s;
    xonxoff_message_t m;
    size_t used, at = 0;
    unsigned k;
    int rc;
    xonxoff_scan_start(&s, 0);
    printf("%s:", name);
    for (k = 0; k < repeat_flood; k++) {  /* XON/XOFF after the first 4 bytes */
        static const uint8_t flood[] = {0x11, 0x13};
        size_t i;
        for (i = 0; i < 4u && k == 0u; i++) {
            rc = xonxoff_scan(&s, data + i, 1u, &used, &m);
            if (rc != 0) { printf(" early %d", rc); }
        }
        rc = xonxoff_scan(&s, flood, sizeof flood, &used, &m);
        if (rc != 0) { printf(" flood %d", rc); }
        at = 4u;
    }
    while (at < len) {
        rc = xonxoff_scan(&s, data + at, len - at, &used, &m);
        at += used;
        if (rc > 0) {
            printf(" x=%x", (unsigned)m.as.flow.x);
        } else if (rc < 0) {
            printf(" %s", rc == CW_ERR_ESCAPE ? "escape" : cw_error_name(rc));
        }
    }
    printf(" skipped %lu\n", (unsigned long)s.skipped);
}
int main(void)
{
    static const uint8_t idle[] = {IDLE};
    static const uint8_t garbage[] = {GARBAGE};
    static const uint8_t lost[] = {LOST};
    static const uint8_t flow[] = {FLOW};
    scan("idle", idle, sizeof idle, 0u);
    scan("garbage", garbage, sizeof garbage, 0u);
    scan("lost", lost, sizeof lost, 0u);
    scan("flood", flow, sizeof flow, 524288u);
    return 0;
}
"""


def test_c_drops_mapped_characters_as_python_does(tmp_path):
    from schema_in_a_test import c_bytes
    render(tmp_path, "xonxoff", XONXOFF)
    driver = STREAM_DRIVER
    for key, data in (("IDLE", IDLE_XOFF), ("GARBAGE", GARBAGE_WITH_XON), ("LOST", LOST_ESCAPE), ("FLOW", FLOW_WIRE)):
        driver = driver.replace("{" + key + "}", "{" + c_bytes(data) + "}")
    assert run_c(tmp_path, driver) == ["idle: x=137e x=137e skipped 0", "garbage: dispatch x=137e skipped 2",
                                       "lost: escape x=137e skipped 2", "flood: x=137e skipped 0"]
