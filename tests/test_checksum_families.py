"""Fletcher checksums and finished sums (complement, xorout) over bytes, against
published frames and hand calculation, in Python and in C (host with sanitizers
and strict warnings; the conformance driver on an ATmega32 under simavr).

Hand values:
- Fletcher-16 mod 255 of "abcde" 0xC8F0, "abcdef" 0x2057, "abcdefgh" 0x0627
  (Wikipedia, Fletcher's checksum), sent high byte (B) first in a big-endian frame.
- Fletcher-8 of "ab" (61 62), nibbles high first 6, 1, 6, 2: A runs 6, 7, 13, 15 and
  B 6, 13, 26, 41; mod 15 A = 0, B = 11 -> 0xB0; mod 16 A = 15, B = 9 -> 0x9F.
- u-blox UBX (8-bit Fletcher, sums mod 256 over class, id, length, payload; CK_A
  then CK_B): CFG-RATE poll B5 62 06 08 00 00 0E 30, ACK-ACK B5 62 05 01 02 00 06 01 0F 38.
- Modbus LRC: 11 03 00 6B 00 03 sums to 0x82; two's complement in 8 bits 0x7E (the
  Modbus serial line guide's example). One's complement in 16 bits 0xFFFF - 0x82 =
  0xFF7D; 0x82 XOR 0xA5 = 0x27; two's complement in 32 bits 0xFFFFFF7E, sent
  little-endian 7E FF FF FF, in 64 bits 0xFFFFFFFFFFFFFF7E; the bytes' XOR 0x7A,
  XOR 0xFF = 0x85.
- A 4-bit sum in a 3-byte frame 55 12 _9: 0x55 + 0x12 = 103, mod 16 = 7, two's
  complement in 4 bits 9.
"""
from __future__ import annotations

import io
import json
import re
import shutil
import subprocess

import pytest

from cdriver import Driver
from codeword.build import compile_schema
from codeword.vectors import write_vectors
from schema_in_a_test import load, render, run_c, show_calls

STRICT = ("-Wpedantic", "-Wconversion", "-Wsign-conversion", "-Wshadow")

UBX = """codeword: 1
protocol: ubx
title: u-blox UBX frames
source: u-blox 8 / M8 receiver description, UBX protocol, UBX checksum
framing:
  kind: bytes
  byte_order: little
  layout:
    - {name: sync1, type: u8, const: 0xB5}
    - {name: sync2, type: u8, const: 0x62}
    - {name: msg_class, type: u8}
    - {name: id, type: u8, dispatch: true}
    - {name: length, type: u16}
    - {payload: true}
    - {name: ck, type: u16, checksum: {algorithm: fletcher, modulo: 256, covers: {from: msg_class, to: payload}}}
messages:
  cfg_rate_poll:
    id: 0x08
    fields: []
    examples:
      - values: {msg_class: 6, length: 0}
        hex: "b5 62 06 08 00 00 0e 30"
        source: u-blox UBX-CFG-RATE poll
  ack_ack:
    id: 0x01
    fields:
      - {name: cls_id, type: u8}
      - {name: msg_id, type: u8}
    examples:
      - values: {msg_class: 5, length: 2, cls_id: 6, msg_id: 1}
        hex: "b5 62 05 01 02 00 06 01 0f 38"
        source: u-blox UBX-ACK-ACK of CFG-RATE
      - name: CK_B flipped
        hex: "b5 62 05 01 02 00 06 01 0f c7"
        error: {field: ck, rule: checksum}
        source: the frame above, CK_B 0x38 inverted
"""

FLETCHER = """codeword: 1
protocol: fletch
title: Fletcher checksums
source: Wikipedia, Fletcher's checksum
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: sync, type: u8, const: 0x55}
    - {name: kind, type: u8, dispatch: true}
    - {payload: true}
    - {name: f16, type: u16, checksum: {algorithm: fletcher, covers: {from: data, to: payload}}}
messages:
  five: {id: 5, fields: [{name: data, type: bytes, length: 5}]}
  six: {id: 6, fields: [{name: data, type: bytes, length: 6}]}
  eight: {id: 8, fields: [{name: data, type: bytes, length: 8}]}
"""

NIBBLES = """codeword: 1
protocol: nibbles
title: Fletcher-8
source: hand calculation
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: sync, type: u8, const: 0x55}
    - {payload: true}
    - {name: f15, type: u8, checksum: {algorithm: fletcher, covers: {from: data, to: payload}}}
    - {name: f16, type: u8, checksum: {algorithm: fletcher, modulo: 16, covers: {from: data, to: payload}}}
messages:
  pair: {fields: [{name: data, type: bytes, length: 2}]}
"""

SUMS = """codeword: 1
protocol: sums
title: finished sums
source: Modbus over serial line, LRC example; hand calculation
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: sync, type: u8, const: 0x55}
    - {payload: true}
    - {name: lrc, type: u8, checksum: {algorithm: sum, complement: twos, covers: {from: data, to: payload}}}
    - {name: ones, type: u16, checksum: {algorithm: sum, complement: ones, covers: {from: data, to: payload}}}
    - {name: flipped, type: u8, checksum: {algorithm: sum, xorout: 0xA5, covers: {from: data, to: payload}}}
    - name: neg32
      type: u32
      byte_order: little
      checksum: {algorithm: sum, complement: twos, covers: {from: data, to: payload}}
    - {name: inverted_xor, type: u8, checksum: {algorithm: xor, xorout: 0xFF, covers: {from: data, to: payload}}}
    - {name: neg64, type: u64, checksum: {algorithm: sum, complement: twos, covers: {from: data, to: payload}}}
messages:
  modbus: {fields: [{name: data, type: bytes, length: 6}]}
"""

WORD = """codeword: 1
protocol: nibsum
title: a complemented sum packed with other bits
source: hand calculation
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: sync, type: u8, const: 0x55}
    - {payload: true}
    - {name: pad, type: u4, reserved: true}
    - {name: cs, type: u4, checksum: {algorithm: sum, complement: twos, covers: {from: sync, to: payload}}}
messages:
  one: {fields: [{name: x, type: u8}]}
"""

MODBUS = "11 03 00 6b 00 03"
SUMS_FRAME = f"55 {MODBUS} 7e ff 7d 27 7e ff ff ff 85 ff ff ff ff ff ff ff 7e"


def driver(proto: str, frames: list[str]) -> str:
    """Decode each frame; print its error, or the frame the C encoder writes back."""
    return f"""
#include <stdio.h>
#include "{proto}.h"
static void show(const char *hex, const uint8_t *frame, size_t len)
{{
    {proto}_message_t m;
    uint8_t buf[{proto.upper()}_MAX_FRAME];
    int rc = {proto}_decode(frame, len, 0, &m);
    int i;
    if (rc != CW_OK) {{
        printf("%s error %s\\n", hex, cw_error_name(rc));
        return;
    }}
    rc = {proto}_encode(&m, buf, sizeof buf);
    printf("%s encoded", hex);
    for (i = 0; i < rc; i++) {{
        printf(" %02x", (unsigned)buf[i]);
    }}
    printf("\\n");
}}
int main(void)
{{
{show_calls(frames)}
    return 0;
}}
"""


def c_round_trips(tmp_path, proto: str, good: list[str], bad: list[str]) -> None:
    """C decodes each good frame and writes it back unchanged; each bad one is a checksum error."""
    lines = run_c(tmp_path, driver(proto, good + bad), STRICT)
    assert lines == [f"{h} encoded {h}" for h in good] + [f"{h} error checksum" for h in bad]


def flip(frame: str, index: int) -> str:
    data = bytearray.fromhex(frame)
    data[index] ^= 0xFF
    return data.hex(" ")


def rejected(mod, frame: str, field: str, byte: int) -> None:
    with pytest.raises(mod.DecodeError) as err:
        mod.decode(bytes.fromhex(frame))
    assert err.value.rule == "checksum" and err.value.field == field, str(err.value)
    assert f"at byte {byte} " in str(err.value)


def test_ubx_frames_carry_ck_a_then_ck_b(tmp_path):
    render(tmp_path, "ubx", UBX)
    mod = load(tmp_path / "ubx.py")
    poll, ack = "b5 62 06 08 00 00 0e 30", "b5 62 05 01 02 00 06 01 0f 38"
    assert mod.encode(mod.CfgRatePoll(msg_class=6, length=0)) == bytes.fromhex(poll)
    assert mod.encode(mod.AckAck(msg_class=5, length=2, cls_id=6, msg_id=1)) == bytes.fromhex(ack)
    assert mod.decode(bytes.fromhex(ack)) == mod.AckAck(msg_class=5, length=2, cls_id=6, msg_id=1)
    rejected(mod, flip(ack, 8), "ck", 8)
    rejected(mod, flip(poll, 7), "ck", 6)
    c_round_trips(tmp_path, "ubx", [poll, ack], [flip(ack, 8), flip(poll, 7)])


def test_fletcher16_matches_the_published_values(tmp_path):
    render(tmp_path, "fletch", FLETCHER)
    mod = load(tmp_path / "fletch.py")
    frames = {"five": "55 05 " + b"abcde".hex(" ") + " c8 f0",
              "six": "55 06 " + b"abcdef".hex(" ") + " 20 57",
              "eight": "55 08 " + b"abcdefgh".hex(" ") + " 06 27"}
    for name, frame in frames.items():
        cls = getattr(mod, name.capitalize())
        data = bytes.fromhex(frame)[2:-2]
        assert mod.encode(cls(data=data)) == bytes.fromhex(frame)
        assert mod.decode(bytes.fromhex(frame)) == cls(data=data)
    rejected(mod, flip(frames["six"], 9), "f16", 8)
    c_round_trips(tmp_path, "fletch", list(frames.values()), [flip(frames["six"], 9)])


def test_fletcher8_sums_nibbles(tmp_path):
    render(tmp_path, "nibbles", NIBBLES)
    mod = load(tmp_path / "nibbles.py")
    frame = "55 61 62 b0 9f"
    assert mod.encode(mod.Pair(data=b"ab")) == bytes.fromhex(frame)
    rejected(mod, flip(frame, 3), "f15", 3)
    rejected(mod, flip(frame, 4), "f16", 4)
    c_round_trips(tmp_path, "nibbles", [frame], [flip(frame, 3), flip(frame, 4)])


def test_finished_sums_and_the_modbus_lrc(tmp_path):
    render(tmp_path, "sums", SUMS)
    mod = load(tmp_path / "sums.py")
    assert mod.encode(mod.Modbus(data=bytes.fromhex(MODBUS))) == bytes.fromhex(SUMS_FRAME)
    for index, field, byte in [(7, "lrc", 7), (9, "ones", 8), (10, "flipped", 10), (13, "neg32", 11),
                               (15, "inverted_xor", 15), (20, "neg64", 16)]:
        rejected(mod, flip(SUMS_FRAME, index), field, byte)
    c_round_trips(tmp_path, "sums", [SUMS_FRAME], [flip(SUMS_FRAME, i) for i in (7, 9, 10, 13, 15, 20)])


def test_a_complemented_sum_in_a_packed_word(tmp_path):
    render(tmp_path, "nibsum", WORD)
    mod = load(tmp_path / "nibsum.py")
    assert mod.encode(mod.One(x=0x12)) == bytes.fromhex("55 12 09")
    rejected(mod, "55 12 08", "cs", 2)
    c_round_trips(tmp_path, "nibsum", ["55 12 09"], ["55 12 08"])


SCHEMAS = {"ubx": UBX, "fletch": FLETCHER, "nibbles": NIBBLES, "sums": SUMS, "nibsum": WORD}


def vectors_of(tmp_path, name: str):
    render(tmp_path, name, SCHEMAS[name])
    protocol = compile_schema(tmp_path / f"{name}.yaml")
    out = io.StringIO()
    write_vectors(protocol, load(tmp_path / f"{name}.py"), out)
    return protocol, json.loads(out.getvalue())


@pytest.mark.parametrize("name", sorted(SCHEMAS))
def test_the_damaged_vectors_include_checksum_errors(tmp_path, name):
    """The vectors damage frames generically (a bit flipped, the last byte changed): some
    of them must break a checksum, and the codec must name a checksum field."""
    protocol, vectors = vectors_of(tmp_path, name)
    mod = load(tmp_path / f"{name}.py")
    sums = {leaf.field.name for m in protocol.messages for leaf in m.wire.leaves if leaf.field.checksum}
    named = set()
    for case in vectors["invalid"]:
        if case["error"] == "checksum":
            with pytest.raises(mod.DecodeError) as err:
                mod.decode(bytes.fromhex(case["hex"]))
            named.add(err.value.field)
    assert named and named <= sums, (named, sums)


@pytest.mark.parametrize("name", sorted(SCHEMAS))
def test_conformance_on_atmega32_under_simavr(tmp_path, name):
    """16-bit int and 32-bit double: the sums' arithmetic must not depend on int's width."""
    avr_gcc, simavr = shutil.which("avr-gcc"), shutil.which("simavr")
    assert avr_gcc and simavr, "avr-gcc and simavr are not installed (.ci/run installs them)"
    protocol, vectors = vectors_of(tmp_path, name)
    src, elf = tmp_path / "conformance.c", tmp_path / "conformance.elf"
    src.write_text(Driver(protocol).source(vectors), encoding="utf-8")
    build = subprocess.run([avr_gcc, "-std=gnu99", "-Os", "-mmcu=atmega32", "-Wall", "-Wextra", "-Wconversion",
                            "-Werror", "-ffunction-sections", "-fdata-sections", "-Wl,--gc-sections",
                            "-I", str(tmp_path), str(src), "-o", str(elf)], capture_output=True, text=True, timeout=300)
    assert build.returncode == 0, build.stderr[-3000:]
    run = subprocess.run([simavr, "-m", "atmega32", "-f", "16000000", str(elf)], capture_output=True,
                         text=True, timeout=600, errors="replace")
    output = re.sub(r"\x1b\[[0-9;]*m", "", run.stdout + run.stderr)
    assert re.search(rf"CONFORMANCE {name} PASS \d+ checks 0 failures", output), output[-3000:]


def test_codeword_check_names_the_fletcher_field(tmp_path, capsys):
    from codeword.cli import main
    (tmp_path / "ubx.yaml").write_text(UBX, encoding="utf-8")
    capture = tmp_path / "capture.bin"
    poll, ack = bytes.fromhex("b5 62 06 08 00 00 0e 30"), bytes.fromhex("b5 62 05 01 02 00 06 01 0f 38")
    capture.write_bytes(poll + ack[:-1] + b"\xc7" + poll)  # CK_B 0x38 inverted in the second frame
    assert main(["check", "--format", "json", str(tmp_path / "ubx.yaml"), str(capture)]) == 1
    doc = json.loads(capsys.readouterr().out)
    # the frame at 8 has its checksum at 8 + 8; the stream decoder then skips to the next sync byte
    assert [(f["offset"], f["field"], f["rule"]) for f in doc["findings"]] == [(16, "ck", "checksum"),
                                                                              (None, None, "sync")]
    assert doc["summary"]["valid"] == 2
