"""Byte stuffing around frames (`framing.encoding`): SLIP (RFC 1055), COBS and
HDLC-like framing (RFC 1662), in Python and in C. Expected bytes are the COBS
examples of the Wikipedia article (from Cheshire and Baker's paper), the escape
rules of the RFCs applied by hand, and, where installed, the PyPI `cobs`
package; never the encoder under test."""
from __future__ import annotations

import random

import pytest

from conftest import needs
from schema_in_a_test import load, render, run_c

SCHEMA = """codeword: 1
protocol: {name}
title: t
source: s
framing:
  kind: bytes
  encoding: {encoding}
  layout:
    - {{name: kind, type: u8, dispatch: true}}
    - {{name: len, type: u16, length_of: {{from: payload, to: payload}}}}
    - {{payload: true}}
    - {{name: check, type: u8, checksum: {{algorithm: sum, modulo: 256, covers: {{from: kind, to: payload}}}}}}
messages:
  ping:
    id: 0xC0
    fields:
      - {{name: a, type: u16}}
      - {{name: b, type: u8}}
  blob:
    id: 0x7E
    fields:
      - {{name: data, type: bytes, length: 300}}
"""

# ping a=0xDBC0 b=0x7E: kind C0, len 00 03, payload DB C0 7E, sum C0+00+03+DB+C0+7E = 0x2DC -> DC
PING = bytes.fromhex("C0 00 03 DB C0 7E DC")
PING_WIRE = {
    # END, C0 -> DB DC, DB -> DB DD, END
    "slip": "C0 DB DC 00 03 DB DD DB DC 7E DC C0",
    # flag, 7E -> 7D 5E, flag
    "hdlc": "7E C0 00 03 DB C0 7D 5E DC 7E",
    # block [C0] ended by the zero, last block [03 DB C0 7E DC], delimiter
    "cobs": "02 C0 06 03 DB C0 7E DC 00",
}

# Wikipedia, "Consistent Overhead Byte Stuffing", examples 1-11 (the delimiter added)
RUN = bytes(range(1, 255))
COBS_EXAMPLES = [
    ("00", "01 01 00"),
    ("00 00", "01 01 01 00"),
    ("00 11 00", "01 02 11 01 00"),
    ("11 22 00 33", "03 11 22 02 33 00"),
    ("11 22 33 44", "05 11 22 33 44 00"),
    ("11 00 00 00", "02 11 01 01 01 00"),
    (RUN.hex(), "FF" + RUN.hex() + "00"),
    ("00" + RUN.hex(), "01 FF" + RUN.hex() + "00"),
    (RUN.hex() + "FF", "FF" + RUN.hex() + "02 FF 00"),
    (bytes(range(2, 256)).hex() + "00", "FF" + bytes(range(2, 256)).hex() + "01 01 00"),
    (bytes(range(3, 256)).hex() + "00 01", "FE" + bytes(range(3, 256)).hex() + "02 01 00"),
]

# By hand from RFC 1055 and RFC 1662: the delimiter and the escape escaped, all else as is
SLIP_EXAMPLES = [("01 C0 02 DB 03", "C0 01 DB DC 02 DB DD 03 C0"), ("DB DC", "C0 DB DD DC C0"),
                 ("7E 7D 00", "C0 7E 7D 00 C0")]
HDLC_EXAMPLES = [("7E 7D 01", "7E 7D 5E 7D 5D 01 7E"), ("C0 DB 00", "7E C0 DB 00 7E"),
                 ("5E 5D 7E", "7E 5E 5D 7D 5E 7E")]
EXAMPLES = {"slip": SLIP_EXAMPLES, "hdlc": HDLC_EXAMPLES, "cobs": COBS_EXAMPLES}

# Encoded frames with a bad escape (or a COBS block past the end) and the byte it starts at
BAD_ESCAPES = {
    "slip": [("C0 DB 41 C0", 1), ("C0 01 DB C0", 2)],  # DB only before DC or DD; DB at the end
    "hdlc": [("7E 01 7D 7E", 2)],  # 7D 7E: the escape at the end (RFC 1662's abort)
    "cobs": [("05 11 22 00", 0), ("02 11 04 22 00", 2)],  # a code byte that runs past the delimiter
}


def hx(text: str) -> bytes:
    return bytes.fromhex(text)


def build(tmp_path, encoding: str):
    name = f"stuff_{encoding}"
    render(tmp_path, name, SCHEMA.format(name=name, encoding=encoding))
    return load(tmp_path / f"{name}.py")


@pytest.mark.parametrize("encoding", ["slip", "hdlc", "cobs"])
def test_python_stuffs_published_and_hand_worked_frames(tmp_path, encoding):
    mod = build(tmp_path, encoding)
    for frame, wire in EXAMPLES[encoding]:
        assert mod.stuff(hx(frame)) == hx(wire), frame
        assert mod.unstuff(hx(wire)) == hx(frame), wire
    assert mod.Ping(a=0xDBC0, b=0x7E).encode() == hx(PING_WIRE[encoding])
    assert mod.encode(mod.Ping(a=0xDBC0, b=0x7E)) == hx(PING_WIRE[encoding])
    assert mod.unstuff(hx(PING_WIRE[encoding])) == PING
    assert mod.decode(hx(PING_WIRE[encoding])) == mod.Ping(a=0xDBC0, b=0x7E)
    assert mod.Ping.decode(hx(PING_WIRE[encoding])) == mod.Ping(a=0xDBC0, b=0x7E)
    if encoding != "cobs":  # the leading delimiter may be left out
        assert mod.decode(hx(PING_WIRE[encoding])[1:]) == mod.Ping(a=0xDBC0, b=0x7E)


def test_hdlc_accepts_any_escaped_byte(tmp_path):
    """RFC 1662: a peer's async control character map escapes control characters too."""
    mod = build(tmp_path, "hdlc")
    assert mod.unstuff(hx("7E 7D 20 7D 21 41 7E")) == hx("00 01 41")


@pytest.mark.parametrize("encoding", ["slip", "hdlc", "cobs"])
def test_bad_escapes_are_typed_errors_with_their_offset(tmp_path, encoding):
    mod = build(tmp_path, encoding)
    for wire, at in BAD_ESCAPES[encoding]:
        with pytest.raises(mod.DecodeError) as caught:
            mod.decode(hx(wire))
        assert (caught.value.rule, caught.value.offset) == ("escape", 8 * at), wire
    with pytest.raises(mod.DecodeError) as caught:
        mod.decode(hx(PING_WIRE[encoding])[:-1])
    assert caught.value.rule == "delimiter"


def test_cobs_agrees_with_the_cobs_package(tmp_path):
    try:
        from cobs import cobs
    except ImportError:
        needs("the cobs package", "pip install cobs (the test extra)")
    mod = build(tmp_path, "cobs")
    rng = random.Random(1055)
    for _ in range(500):
        frame = bytes(rng.choice([0, 0, 1, 0x7E, 0xC0, rng.randrange(256)]) for _ in range(rng.randrange(1, 300)))
        assert mod.stuff(frame) == cobs.encode(frame) + b"\0"
        assert mod.unstuff(cobs.encode(frame) + b"\0") == frame


# a frame cut short, then a whole one: SLIP and HDLC cut inside an escape, whose delimiter
# is the next frame's leading one; COBS runs on into the next frame (13 bytes: no such frame)
CUT_SHORT = {
    "slip": lambda good: (good[:-4] + good, ["escape", "ping"]),
    "hdlc": lambda good: (good[:-3] + good, ["escape", "ping"]),
    "cobs": lambda good: (good[:-3] + good, ["dispatch"]),
}


def stream_of(encoding: str) -> tuple[bytes, list[str]]:
    """Garbage, good frames and damaged ones, with the events a decoder must give."""
    good = hx(PING_WIRE[encoding])
    bad_escape = hx(BAD_ESCAPES[encoding][0][0])
    delimiter = good[-1:]
    parts = [(b"\x01\x02\x03" + delimiter, ["dispatch"]),  # COBS: 00 03, no such frame either
             (good, ["ping"]),
             (bad_escape, ["escape"]),
             (good, ["ping"]),
             (delimiter + delimiter, []),  # empty stretches between delimiters are not frames
             CUT_SHORT[encoding](good),
             (good, ["ping"])]
    return b"".join(p for p, _ in parts), [e for _, events in parts for e in events]


def events(mod, items) -> list[str]:
    return [x.rule if isinstance(x, mod.DecodeError) else type(x).NAME for x in items]


@pytest.mark.parametrize("encoding", ["slip", "hdlc", "cobs"])
def test_stream_decoder_resynchronises_on_delimiters_however_fed(tmp_path, encoding):
    mod = build(tmp_path, encoding)
    stream, expected = stream_of(encoding)
    whole = mod.StreamDecoder()
    assert events(mod, whole.feed(stream)) == expected
    rng = random.Random(7)
    for _ in range(20):
        split = mod.StreamDecoder()
        got, at = [], 0
        while at < len(stream):
            step = rng.randint(1, 6)
            got += split.feed(stream[at:at + step])
            at += step
        assert events(mod, got) == expected
        assert split.skipped == whole.skipped


def test_long_garbage_without_a_delimiter_is_one_error(tmp_path):
    mod = build(tmp_path, "slip")
    decoder = mod.StreamDecoder()
    got = []
    for _ in range(100):  # 5000 bytes with no END: memory stays bounded
        got += decoder.feed(b"\x11" * 50)
    got += decoder.feed(b"\xc0" + hx(PING_WIRE["slip"]))
    assert events(mod, got) == ["length", "ping"]
    assert decoder.skipped == 5000
    assert len(decoder._buffer) == 0


C_DRIVER = r"""
#include <stdio.h>
#include "%(px)s.h"
static void show(const uint8_t *b, int n)
{
    int i;
    for (i = 0; i < n; i++) {
        printf("%%02X%%s", b[i], i + 1 < n ? " " : "");
    }
    printf("\n");
}
int main(void) {
    static uint8_t wire[%(PX)s_WIRE_MAX];
    static uint8_t frame[%(PX)s_FRAME_MAX];
    %(px)s_message_t any;
    %(px)s_ping_t ping = {0xDBC0u, 0x7Eu};
    %(px)s_parser_t parser;
    int n;
    size_t i;
%(examples)s
    n = %(px)s_ping_encode(&ping, wire, sizeof wire);
    show(wire, n);
    memset(&any, 0, sizeof any);
    n = %(px)s_decode(wire, (size_t)n, %(PX)s_DIR_ANY, &any);
    printf("%%d %%d %%X %%X\n", n, any.kind == %(PX)s_MSG_PING, any.as.ping.a, any.as.ping.b);
    n = %(px)s_ping_encode(&ping, wire, 5u);
    printf("small %%d\n", n);
%(bad)s
    %(px)s_parser_init(&parser, %(PX)s_DIR_ANY);
    for (i = 0; i < sizeof stream; i++) {
        if (%(px)s_parser_feed(&parser, stream[i]) != CW_OK) {
            printf("feed\n");
        }
        while ((n = %(px)s_parser_next(&parser, &any)) != 0) {
            printf("%%s\n", n == 1 ? (any.kind == %(PX)s_MSG_PING ? "ping" : "blob") : cw_error_name(n));
        }
    }
    printf("skipped %%lu\n", (unsigned long)parser.scan.skipped);
    (void)frame;
    return 0;
}
"""


def carray(data: bytes) -> str:
    return "{" + ", ".join(f"0x{b:02x}" for b in data) + "}"


@pytest.mark.parametrize("encoding", ["slip", "hdlc", "cobs"])
def test_c_stuffs_and_parses_as_the_published_frames_say(tmp_path, encoding):
    mod = build(tmp_path, encoding)
    px = f"stuff_{encoding}"
    examples, expected = [], []
    for i, (frame, wire) in enumerate(EXAMPLES[encoding]):
        examples.append(f"    {{ static const uint8_t f{i}[] = {carray(hx(frame))};\n"
                        f"      static const uint8_t w{i}[] = {carray(hx(wire))};\n"
                        f"      n = {px}_stuff(f{i}, sizeof f{i}, wire, sizeof wire); show(wire, n);\n"
                        f"      n = {px}_unstuff(w{i}, sizeof w{i}, frame, sizeof frame); show(frame, n); }}")
        expected += [" ".join(f"{b:02X}" for b in hx(wire)), " ".join(f"{b:02X}" for b in hx(frame))]
    bad = []
    for i, (wire, _) in enumerate(BAD_ESCAPES[encoding]):
        bad.append(f"    {{ static const uint8_t b{i}[] = {carray(hx(wire))};\n"
                   f"      printf(\"%s\\n\", cw_error_name({px}_decode(b{i}, sizeof b{i}, 0, &any))); }}")
        expected.append("?")  # filled below: CW_ERR_ESCAPE has no name in the shared runtime
    stream, stream_events = stream_of(encoding)
    source = C_DRIVER % {"px": px, "PX": px.upper(), "examples": "\n".join(examples),
                         "bad": "\n".join(bad) + f"\n    static const uint8_t stream[] = {carray(stream)};"}
    lines = run_c(tmp_path, source)
    ping = " ".join(f"{b:02X}" for b in hx(PING_WIRE[encoding]))
    count = len(EXAMPLES[encoding]) * 2
    assert lines[:count] == expected[:count]
    assert lines[count:count + 3] == [ping, "0 1 DBC0 7E", "small -1"]
    codes = lines[count + 3:count + 3 + len(BAD_ESCAPES[encoding])]
    assert len(set(codes)) == 1  # every bad escape is the one error code CW_ERR_ESCAPE
    rest = lines[count + 3 + len(BAD_ESCAPES[encoding]):]
    names = {codes[0]: "escape"}
    assert [names.get(x, x) for x in rest[:-1]] == stream_events
    decoder = mod.StreamDecoder()
    decoder.feed(stream)
    assert rest[-1] == f"skipped {decoder.skipped}"


def compiled(tmp_path, encoding):
    from codeword.build import compile_schema
    folder = tmp_path / (encoding or "plain")
    folder.mkdir()
    text = SCHEMA.format(name="stuffed", encoding=encoding or "slip")
    if encoding is None:
        text = text.replace("  encoding: slip\n", "")
    path = folder / "stuffed.yaml"
    path.write_text(text, encoding="utf-8")
    return compile_schema(path)


def test_adding_or_changing_the_encoding_breaks_and_changes_the_fingerprint(tmp_path):
    from codeword.diff import BREAKING, compare
    from codeword.fingerprint import fingerprint
    plain, slip, cobs = compiled(tmp_path, None), compiled(tmp_path, "slip"), compiled(tmp_path, "cobs")
    assert len({fingerprint(plain), fingerprint(slip), fingerprint(cobs)}) == 3
    assert {c.what for c in compare(plain, slip).of_kind(BREAKING)} == {"encoding changed from None to 'slip'"}
    assert {c.what for c in compare(slip, cobs).of_kind(BREAKING)} == {"encoding changed from 'slip' to 'cobs'"}
    assert compare(slip, compiled(tmp_path, "hdlc")).breaking


def test_check_reads_an_encoded_capture(tmp_path, capsys):
    import json

    from codeword.cli import main
    folder = tmp_path / "schema"
    folder.mkdir()
    schema = folder / "stuffed.yaml"
    schema.write_text(SCHEMA.format(name="stuffed", encoding="hdlc"), encoding="utf-8")
    good = hx(PING_WIRE["hdlc"])
    # a good frame @0-9 (flags at 0 and 9), 01 7D @10-11 ending in the escape, then the frame again,
    # its leading flag shared: the escape at 11 is the one finding
    capture = tmp_path / "capture.bin"
    capture.write_bytes(good + hx("7E 01 7D 7E")[1:] + good[1:])
    status = main(["check", "--format", "json", str(schema), str(capture)])
    doc = json.loads(capsys.readouterr().out)
    assert status == 1
    assert [(f["offset"], f["rule"]) for f in doc["findings"]][:1] == [(11, "escape")]
    assert doc["summary"]["valid"] == 2 and doc["summary"]["invalid"] == 1


SMALL = """codeword: 1
protocol: avr_{encoding}
title: t
source: s
framing:
  kind: bytes
  encoding: {encoding}
  layout:
    - {{name: kind, type: u8, dispatch: true}}
    - {{name: len, type: u8, length_of: {{from: payload, to: payload}}}}
    - {{payload: true}}
    - {{name: check, type: u8, checksum: {{algorithm: sum, modulo: 256, covers: {{from: kind, to: payload}}}}}}
messages:
  ping:
    id: 0xC0
    fields:
      - {{name: a, type: u16}}
      - {{name: b, type: u8, const: 0x7E}}
  pong:
    id: 0x00
    fields:
      - {{name: a, type: u8}}
"""


@pytest.mark.parametrize("encoding", ["slip", "hdlc", "cobs"])
def test_conformance_vectors_on_atmega32_under_simavr(tmp_path, encoding):
    """The conformance driver of tests/cdriver.py (valid, invalid and stream vectors, the
    damaged escapes among them) built with avr-gcc, where int is 16 bits, and run."""
    import json
    import re
    import shutil
    import subprocess

    from cdriver import Driver
    from codeword.build import build as build_all, compile_schema
    name = f"avr_{encoding}"
    path = tmp_path / f"{name}.yaml"
    path.write_text(SMALL.format(encoding=encoding), encoding="utf-8")
    out = tmp_path / "out"
    assert not build_all([path], out, root=tmp_path).errors
    vectors = json.loads((out / "vectors" / f"{name}.json").read_text(encoding="utf-8"))
    assert any(c["error"] == "escape" for c in vectors["invalid"])
    src = tmp_path / f"{name}.c"
    src.write_text(Driver(compile_schema(path)).source(vectors), encoding="utf-8")
    gcc, simavr = shutil.which("avr-gcc"), shutil.which("simavr")
    assert gcc and simavr, "avr-gcc and simavr are not installed (.ci/run installs them)"
    elf = tmp_path / f"{name}.elf"
    made = subprocess.run([gcc, "-std=gnu99", "-Os", "-mmcu=atmega32", "-Wall", "-Wextra", "-Wconversion",
                           "-Werror", "-ffunction-sections", "-fdata-sections", "-Wl,--gc-sections",
                           "-I", str(out / "c"), str(src), "-o", str(elf)], capture_output=True, text=True)
    assert made.returncode == 0, made.stderr[-3000:]
    ran = subprocess.run([simavr, "-m", "atmega32", "-f", "16000000", str(elf)], capture_output=True,
                         text=True, timeout=600, errors="replace")
    clean = re.sub(r"\x1b\[[0-9;]*m", "", ran.stdout + ran.stderr)
    assert re.search(rf"CONFORMANCE {name} PASS \d+ checks 0 failures", clean), clean[-3000:]
