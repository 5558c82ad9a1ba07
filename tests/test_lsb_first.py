"""Bit fields packed least significant bit first (`bit_order: lsb_first`): the
frame is a little-endian bit stream, as SBUS and CAN "Intel" signals pack it.
The expected bytes are worked out by hand below (and, for the mixed frame,
checked against bitstruct's LSB-first fields); Python and C both write them
and read them back, one frame at a time and, for the framed protocol, in a
stream with garbage around it."""
from __future__ import annotations


import bitstruct
import pytest

from codeword.build import compile_schema
from codeword.diff import BREAKING, compare
from codeword.fingerprint import fingerprint
from codeword.targets.markdown.layout import position, slots

from schema_in_a_test import conformance_on_host_and_avr, load, render, run_c

CHANNELS = "\n".join(f"      - {{name: ch{i}, type: u11}}" for i in range(1, 17))
SBUS = f"""codeword: 1
protocol: sbus
title: SBUS-like receiver frame
source: hand-written
framing:
  kind: bytes
  bit_order: lsb_first
  layout:
    - {{name: header, type: u8, const: 0x0F}}
    - {{payload: true}}
    - {{name: footer, type: u8, const: 0x00}}
messages:
  channels:
    fields:
{CHANNELS}
      - {{name: ch17, type: bool}}
      - {{name: ch18, type: bool}}
      - {{name: frame_lost, type: bool}}
      - {{name: failsafe, type: bool}}
      - {{name: spare, type: u4, reserved: true}}
"""

# Every channel at 1024 = 0x400: of its 11 bits only bit 10 is set. Channel k
# (from 0) takes stream bits 11k..11k+10 of the channel bytes, stream bit n being
# bit n % 8 (0 = LSB) of channel byte n // 8. So the ones are at stream bits
#   k=0: 10 -> byte 1 bit 2 = 0x04    k=4: 54 -> byte 6 bit 6 = 0x40
#   k=1: 21 -> byte 2 bit 5 = 0x20    k=5: 65 -> byte 8 bit 1 = 0x02
#   k=2: 32 -> byte 4 bit 0 = 0x01    k=6: 76 -> byte 9 bit 4 = 0x10
#   k=3: 43 -> byte 5 bit 3 = 0x08    k=7: 87 -> byte 10 bit 7 = 0x80
# bytes 0, 3 and 7 hold none: 00 04 20 00 01 08 40 00 02 10 80. Channels 8..15
# start at stream bit 88 = byte 11 bit 0 and repeat the pattern.
CENTRED = "0f" + "00 04 20 00 01 08 40 00 02 10 80" * 2 + "00 00"
# Channel 1 at 0x7FF, others 0: stream bits 0..10 set = byte 0 all, byte 1 bits 0-2:
# FF 07 00 ...; flags ch17 (bit 0) and failsafe (bit 3) = 0x09.
FIRST_FULL = "0f ff 07" + " 00" * 20 + " 09 00"


def sbus_values(mod, channels, **flags):
    values = {f"ch{i + 1}": v for i, v in enumerate(channels)}
    values.update(ch17=False, ch18=False, frame_lost=False, failsafe=False)
    values.update(flags)
    return mod.Channels(**values)


def test_the_model_reads_the_channels_as_little_endian_runs(tmp_path):
    path = tmp_path / "sbus.yaml"
    path.write_text(SBUS, encoding="utf-8")
    m = compile_schema(path).messages[0]
    runs = [(r.kind, r.start, r.size, r.order) for r in m.wire.runs]
    # eight channels end on a byte boundary (88 bits): a run of 11 bytes each
    assert runs == [("number", 0, 1, "big"), ("packed", 1, 11, "little"), ("packed", 12, 11, "little"),
                    ("packed", 23, 1, "little"), ("number", 24, 1, "big")]
    first, second, flags = m.wire.runs[1:4]
    # a leaf's shift is its bit position from the run's first byte's least significant bit
    assert [first.shift(leaf) for leaf in first.leaves] == [11 * k for k in range(8)]
    assert [second.shift(leaf) for leaf in second.leaves] == [11 * k for k in range(8)]
    assert [flags.shift(leaf) for leaf in flags.leaves] == [0, 1, 2, 3, 4]
    assert m.padding() == (8, 0)  # no padding: 200 bits


def test_python_writes_and_reads_the_sbus_frames(tmp_path):
    render(tmp_path, "sbus", SBUS)
    sbus = load(tmp_path / "sbus.py")
    centred = sbus_values(sbus, [1024] * 16)
    assert sbus.encode(centred) == bytes.fromhex(CENTRED)
    assert sbus.decode(bytes.fromhex(CENTRED)) == centred
    first = sbus_values(sbus, [0x7FF] + [0] * 15, ch17=True, failsafe=True)
    assert sbus.encode(first) == bytes.fromhex(FIRST_FULL)
    assert sbus.decode(bytes.fromhex(FIRST_FULL)) == first
    spare = bytearray.fromhex(FIRST_FULL)
    spare[23] |= 0x10  # the spare bits are the high nibble of the flags byte
    with pytest.raises(sbus.DecodeError):
        sbus.decode(bytes(spare))


SBUS_DRIVER = r"""
#include <stdio.h>
#include <string.h>
#include "sbus.h"
static void show(const sbus_channels_t *m)
{
    uint8_t out[25];
    sbus_channels_t back;
    int n = sbus_channels_encode(m, out, sizeof out), i;
    printf("%d", n);
    for (i = 0; i < n; i++) printf(" %02x", out[i]);
    printf("\n");
    n = sbus_channels_decode(out, sizeof out, &back);
    printf("%d %u %u %u %d %d\n", n, (unsigned)back.ch1, (unsigned)back.ch2, (unsigned)back.ch16,
           (int)back.ch17, (int)back.failsafe);
}
int main(void)
{
    sbus_channels_t m;
    memset(&m, 0, sizeof m);
    m.ch1 = m.ch2 = m.ch3 = m.ch4 = m.ch5 = m.ch6 = m.ch7 = m.ch8 = 1024;
    m.ch9 = m.ch10 = m.ch11 = m.ch12 = m.ch13 = m.ch14 = m.ch15 = m.ch16 = 1024;
    show(&m);
    memset(&m, 0, sizeof m);
    m.ch1 = 0x7ff; m.ch17 = true; m.failsafe = true;
    show(&m);
    return 0;
}
"""


def test_c_writes_and_reads_the_sbus_frames(tmp_path):
    render(tmp_path, "sbus", SBUS)
    assert run_c(tmp_path, SBUS_DRIVER) == [
        "25 " + " ".join(CENTRED.replace(" ", "")[i:i + 2] for i in range(0, 50, 2)),
        "0 1024 1024 1024 0 0",
        "25 " + " ".join(FIRST_FULL.replace(" ", "")[i:i + 2] for i in range(0, 50, 2)),
        "0 2047 0 0 1 1"]


FRAMED = """codeword: 1
protocol: lsbf
title: least significant bit first, with an id, a length and a sum
source: hand-written
framing:
  kind: bytes
  bit_order: lsb_first
  layout:
    - {name: sync, type: u8, const: 0xA5}
    - {name: kind, type: u5, dispatch: true}
    - {name: len, type: u11, length_of: {from: sync, to: payload}}
    - {payload: true}
    - {name: check, type: u8, checksum: {algorithm: sum, covers: {from: sync, to: payload}}}
messages:
  mixed:
    id: 3
    fields:
      - {name: a, type: u3}
      - {name: b, type: u11}
      - {name: c, type: u7}
      - {name: d, type: u3}
    examples:
      - {name: worked by hand below, values: {a: 5, b: 0x5A3, c: 0x55, d: 6}, hex: "a5 c3 00 1d 6d d5 c7"}
  brief:
    id: 17
    fields:
      - {name: e, type: u8}
    examples:
      - {name: worked by hand below, values: {e: 0x42}, hex: "a5 91 00 42 78"}
"""

# mixed a=5 b=0x5A3 c=0x55 d=6, 24 bits from the payload's byte 0 bit 0:
#   byte 0: a 101 in bits 0-2, b bits 0-4 (00011) in bits 3-7   -> 00011 101 = 0x1D
#   byte 1: b bits 5-10 (101101) in bits 0-5, c bits 0-1 (01)   -> 01 101101 = 0x6D
#   byte 2: c bits 2-6 (10101) in bits 0-4, d 110 in bits 5-7   -> 110 10101 = 0xD5
# (the payload read as a little-endian integer: 5 | 0x5A3 << 3 | 0x55 << 14 | 6 << 21 = 0xD56D1D)
# header: kind (5 bits) then len (11 bits) in bytes 1-2, read little-endian:
#   kind 3 | len 6 << 5 = 0x00C3 -> C3 00 (len: sync .. payload = 1 + 2 + 3 bytes)
# sum mod 256 of A5 C3 00 1D 6D D5 = 0x2C7 -> C7
MIXED = "a5 c3 00 1d 6d d5 c7"
MIXED_VALUES = dict(a=5, b=0x5A3, c=0x55, d=6)
# brief e=0x42: kind 17 | len 4 << 5 = 0x91 -> 91 00; sum A5 + 91 + 00 + 42 = 0x178 -> 78
BRIEF = "a5 91 00 42 78"
GARBAGE = bytes.fromhex("00 a5 ff 13")


def test_bitstruct_lsb_first_fields_agree_with_the_hand_worked_payload():
    # bitstruct's `<` bit order puts a field's low bit first into an MSB-first stream;
    # mirroring each byte's bits turns that into the little-endian bit stream
    packed = bitstruct.pack("<u3<u11<u7<u3", 5, 0x5A3, 0x55, 6)
    mirrored = bytes(int(f"{b:08b}"[::-1], 2) for b in packed)
    assert mirrored == bytes.fromhex(MIXED)[3:6]


def test_python_writes_reads_and_finds_the_framed_messages(tmp_path):
    render(tmp_path, "lsbf", FRAMED)
    lsbf = load(tmp_path / "lsbf.py")
    mixed, brief = lsbf.Mixed(**MIXED_VALUES), lsbf.Brief(e=0x42)
    assert lsbf.encode(mixed) == bytes.fromhex(MIXED)
    assert lsbf.encode(brief) == bytes.fromhex(BRIEF)
    assert lsbf.decode(bytes.fromhex(MIXED)) == mixed
    assert lsbf.decode(bytes.fromhex(BRIEF)) == brief
    decoder = lsbf.StreamDecoder()
    data = GARBAGE + bytes.fromhex(MIXED) + bytes.fromhex(BRIEF) + GARBAGE[:2] + bytes.fromhex(MIXED)
    events = [e for k in range(0, len(data), 3) for e in decoder.feed(data[k:k + 3])]
    assert [e for e in events if not isinstance(e, lsbf.CodecError)] == [mixed, brief, mixed]


FRAMED_DRIVER = r"""
#include <stdio.h>
#include <string.h>
#include "lsbf.h"
static const uint8_t stream[] = {STREAM};
int main(void)
{
    lsbf_mixed_t m;
    lsbf_brief_t s;
    lsbf_parser_t p;
    lsbf_message_t any;
    uint8_t out[8];
    size_t i;
    int n, k, rc;
    m.a = 5; m.b = 0x5a3; m.c = 0x55; m.d = 6;
    s.e = 0x42;
    n = lsbf_mixed_encode(&m, out, sizeof out);
    for (k = 0; k < n; k++) printf("%02x ", out[k]);
    n = lsbf_brief_encode(&s, out, sizeof out);
    for (k = 0; k < n; k++) printf("%02x ", out[k]);
    printf("\n");
    lsbf_parser_init(&p, 0);
    for (i = 0; i < sizeof stream; i++) {
        if (lsbf_parser_feed(&p, stream[i]) != CW_OK) {
            return 1;
        }
        while ((rc = lsbf_parser_next(&p, &any)) != 0) {
            if (rc < 0) {
                continue;
            }
            if (any.kind == LSBF_MSG_MIXED) {
                printf("mixed %u %x %x %u\n", (unsigned)any.as.mixed.a, (unsigned)any.as.mixed.b,
                       (unsigned)any.as.mixed.c, (unsigned)any.as.mixed.d);
            } else {
                printf("brief %x\n", (unsigned)any.as.brief.e);
            }
        }
    }
    return 0;
}
"""


def test_c_writes_and_finds_the_framed_messages(tmp_path):
    render(tmp_path, "lsbf", FRAMED)
    data = GARBAGE + bytes.fromhex(MIXED) + bytes.fromhex(BRIEF) + GARBAGE[:2] + bytes.fromhex(MIXED)
    driver = FRAMED_DRIVER.replace("{STREAM}", "{" + ", ".join(f"0x{b:02x}" for b in data) + "}")
    assert run_c(tmp_path, driver) == [MIXED + " " + BRIEF + " ", "mixed 5 5a3 55 6", "brief 42",
                                       "mixed 5 5a3 55 6"]


def test_the_docs_number_the_bits_from_the_least_significant(tmp_path):
    path = tmp_path / "lsbf.yaml"
    path.write_text(FRAMED, encoding="utf-8")
    p = compile_schema(path)
    where = {s.path: position(p, s) for s in slots(p.message("mixed"))}
    # kind: frame bits 8-12 = B1 bits 0-4; len: bits 13-23 = B1 bit 5 up to B2 bit 7
    assert where["kind"] == "B1 bits 0–4"
    assert where["len"] == "B1 bit 5 – B2 bit 7"
    # a: payload bits 0-2; b: B3 bit 3 up to B4 bit 5; d: B5 bits 5-7
    assert (where["a"], where["b"], where["d"]) == ("B3 bits 0–2", "B3 bit 3 – B4 bit 5", "B5 bits 5–7")


def compiled(where, name, text):
    where.mkdir(exist_ok=True)
    path = where / f"{name}.yaml"
    path.write_text(text, encoding="utf-8")
    return compile_schema(path)


def test_changing_the_bit_order_breaks_the_wire_and_the_fingerprint(tmp_path):
    lsb = compiled(tmp_path / "lsb", "lsbf", FRAMED)
    msb = compiled(tmp_path / "msb", "lsbf", FRAMED.replace("  bit_order: lsb_first\n", "  bit_order: msb_first\n"))
    default = compiled(tmp_path / "default", "lsbf", FRAMED.replace("  bit_order: lsb_first\n", ""))
    d = compare(lsb, msb)
    assert ("framing", "bit_order changed from 'lsb_first' to 'msb_first'") in \
        {(c.subject, c.what) for c in d.of_kind(BREAKING)}
    assert fingerprint(lsb) != fingerprint(msb)
    # msb_first is the default: saying so changes nothing, and schemas without it keep their fingerprint
    assert fingerprint(msb) == fingerprint(default)
    assert not compare(msb, default).breaking


WORD = """codeword: 1
protocol: lsbw
title: a frame that fits one word, least significant bit first
source: hand-written
framing:
  kind: bytes
  bit_order: lsb_first
  layout: [{payload: true}]
messages:
  tiny:
    fields:
      - {name: x, type: u5}
      - {name: y, type: u7}
      - {name: z, type: u4}
      - {name: w, type: u5}
      - {name: pad, type: u3, reserved: true}
"""
# x=0x15 (10101), y=0x4B (1001011), z=9 (1001), w=0x11 (10001), 3 reserved bits:
#   byte 0: x in bits 0-4, y bits 0-2 (011) in bits 5-7     -> 011 10101 = 0x75
#   byte 1: y bits 3-6 (1001) in bits 0-3, z in bits 4-7    -> 1001 1001 = 0x99
#   byte 2: w in bits 0-4, pad in bits 5-7                  -> 000 10001 = 0x11
TINY = "75 99 11"
TINY_DRIVER = r"""
#include <stdio.h>
#include "lsbw.h"
int main(void)
{
    lsbw_tiny_t m = {0x15, 0x4b, 9, 0x11}, back;
    uint8_t out[3];
    static const uint8_t padded[3] = {0x75, 0x99, 0x31};
    int n = lsbw_tiny_encode(&m, out, sizeof out);
    printf("%d %02x %02x %02x\n", n, out[0], out[1], out[2]);
    n = lsbw_tiny_decode(out, sizeof out, &back);
    printf("%d %x %x %x %x\n", n, (unsigned)back.x, (unsigned)back.y, (unsigned)back.z, (unsigned)back.w);
    printf("%d\n", lsbw_tiny_decode(padded, sizeof padded, &back) == CW_ERR_RESERVED);
    return 0;
}
"""


def test_a_frame_of_one_word_is_one_little_endian_integer(tmp_path):
    render(tmp_path, "lsbw", WORD)
    lsbw = load(tmp_path / "lsbw.py")
    tiny = lsbw.Tiny(x=0x15, y=0x4B, z=9, w=0x11)
    assert lsbw.encode(tiny) == bytes.fromhex(TINY)
    assert lsbw.decode(bytes.fromhex(TINY)) == tiny
    with pytest.raises(lsbw.DecodeError):  # a reserved bit set: byte 2 bit 5
        lsbw.decode(bytes.fromhex("75 99 31"))
    header = (tmp_path / "lsbw.h").read_text(encoding="utf-8")
    assert "word = cw_get_le(buf + 0, 3u);" in header  # the one-word codec, read little-endian
    assert run_c(tmp_path, TINY_DRIVER) == ["3 75 99 11", "0 15 4b 9 11", "1"]


SUM_IN_A_WORD = """codeword: 1
protocol: lsbs
title: a sum over bytes sharing its byte, in one word
source: hand-written
framing:
  kind: bytes
  bit_order: lsb_first
  layout: [{payload: true}]
messages:
  m:
    fields:
      - {name: a, type: u8}
      - {name: b, type: u8}
      - {name: x, type: u4, checksum: {algorithm: sum, modulo: 16, covers: {from: a, to: b}}}
      - {name: p, type: u1}
      - {name: pad, type: u3, reserved: true}
    examples:
      # (0x12 + 0x34) mod 16 = 6 in bits 0-3 of byte 2, p in bit 4: 0x16
      - {values: {a: 0x12, b: 0x34, p: 1}, hex: "12 34 16"}
"""


@pytest.mark.parametrize("name,schema", [("sbus", SBUS), ("lsbf", FRAMED), ("lsbw", WORD), ("lsbs", SUM_IN_A_WORD)])
def test_conformance_vectors_on_the_host_and_on_atmega32_under_simavr(tmp_path, name, schema):
    """Python's vectors (valid frames, damaged ones, streams) through the C codec,
    on the host with the sanitizers and on an 8-bit AVR, whose `int` is 16 bits."""
    host, avr = conformance_on_host_and_avr(tmp_path, name, schema)
    assert host > 100 and avr > 100
