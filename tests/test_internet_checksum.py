"""The internet checksum (RFC 1071) over bytes, against the RFC's worked example, a
published IPv4 header and a reference sum written here, in Python, in C (host with
sanitizers and strict warnings; the conformance driver on an ATmega32 under simavr)
and in the compiled accelerator.

Published values:
- RFC 1071 section 3: the bytes 00 01 f2 03 f4 f5 f6 f7 sum to ddf2 in big-endian
  words (f2dd in little-endian ones); the checksum is 220d, sent 22 0d either way.
- An IPv4 header (Wikipedia, "Internet checksum"): 45 00 00 73 00 00 40 00 40 11 b8 61
  c0 a8 00 01 c0 a8 00 c7, checksum b861 over the header with its checksum as zero;
  the schema below carries it in place, a checksum that covers itself.
- RFC 1071 section 1: a receiver sums the covered bytes with the checksum; all ones
  (a checksum of the whole of 0) means no error. In one's complement 0000 and ffff
  are both zero: where the sender's checksum is 0000, ffff passes that check too.
"""
from __future__ import annotations

import io
import json
import shutil

import pytest

from codeword import accelerate as accel
from codeword.build import compile_schema, render_protocol
from codeword.vectors import write_vectors
from fuzz.schema.accelerated import difference, load as load_module
from schema_in_a_test import conformance_on_host_and_avr, load, render, run_c
from test_checksum_families import STRICT, c_round_trips, driver, flip, rejected


def rfc1071(data: bytes) -> int:
    """RFC 1071 section 4.1's algorithm: 16-bit big-endian words (an odd last byte
    padded with a zero byte) added with each carry out of 16 bits folded back in, then
    the one's complement."""
    total = 0
    for i in range(0, len(data), 2):
        high = data[i]
        low = data[i + 1] if i + 1 < len(data) else 0
        total += (high << 8) | low
        total = (total & 0xFFFF) + (total >> 16)
    return ~total & 0xFFFF


RFC_DATA = bytes.fromhex("00 01 f2 03 f4 f5 f6 f7")
IPV4_HEADER = bytes.fromhex("45 00 00 73 00 00 40 00 40 11 b8 61 c0 a8 00 01 c0 a8 00 c7")
IPV4_FRAME = IPV4_HEADER

IPV4 = """codeword: 1
protocol: ipv4h
title: an IPv4 header, its checksum in place
source: RFC 791; the header from Wikipedia, Internet checksum
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: ver_ihl, type: u8, const: 0x45}
    - {name: tos, type: u8}
    - {name: total_length, type: u16}
    - {name: ident, type: u16}
    - {name: flags_frag, type: u16}
    - {name: ttl, type: u8}
    - {name: proto, type: u8, dispatch: true}
    - {name: checksum, type: u16, checksum: {algorithm: internet, covers: {from: ver_ihl, to: payload}}}
    - {payload: true}
messages:
  udp:
    id: 17
    fields:
      - {name: src, type: u32}
      - {name: dst, type: u32}
    examples:
      - hex: "45 00 00 73 00 00 40 00 40 11 b8 61 c0 a8 00 01 c0 a8 00 c7"
        values: {tos: 0, total_length: 0x73, ident: 0, flags_frag: 0x4000, ttl: 64,
                 src: 0xc0a80001, dst: 0xc0a800c7}
  zero:
    id: 0
    fields:
      - {name: src, type: u32}
      - {name: dst, type: u32}
    examples:
      - hex: "45 00 00 00 00 00 00 00 00 00 00 00 ba ff 00 00 00 00 00 00"
        values: &zero {tos: 0, total_length: 0, ident: 0, flags_frag: 0, ttl: 0, src: 0xbaff0000, dst: 0}
      - hex: "45 00 00 00 00 00 00 00 00 00 ff ff ba ff 00 00 00 00 00 00"
        values: *zero
        decode_only: true
"""

# ver_ihl 45 and tos 00 make the word 4500; with src ba ff 00 00 and every other
# byte 0, the words sum to 4500 + baff = ffff: the checksum is 0000 (RFC 1071), and
# ffff, one's complement's other zero, passes the receiver's check too.
ZERO_FRAME = bytes.fromhex("45 00 00 00 00 00 00 00 00 00 00 00 ba ff 00 00 00 00 00 00")
ZERO_OTHER = ZERO_FRAME[:10] + b"\xff\xff" + ZERO_FRAME[12:]

# One checksum in each byte order, over the same bytes; an odd count pads a zero byte.
ORDERS = """codeword: 1
protocol: inet
title: internet checksums in both byte orders
source: RFC 1071
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: sync, type: u8, const: 0x55}
    - {name: kind, type: u8, dispatch: true}
    - {payload: true}
    - {name: be, type: u16, checksum: {algorithm: internet, covers: {from: data, to: payload}}}
    - {name: le, type: u16, byte_order: little, checksum: {algorithm: internet, covers: {from: data, to: payload}}}
messages:
  rfc: {id: 1, fields: [{name: data, type: bytes, length: 8}]}
  odd: {id: 2, fields: [{name: data, type: bytes, length: 5}]}
  zeros: {id: 3, fields: [{name: data, type: bytes, length: 4}]}
  ones: {id: 4, fields: [{name: data, type: bytes, length: 2}]}
"""

ODD = bytes.fromhex("01 02 03 04 05")  # words 0102 0304 0500: 0x0906, checksum f6f9


def test_the_reference_gives_the_published_values():
    assert rfc1071(RFC_DATA) == 0x220D
    assert rfc1071(IPV4_HEADER[:10] + b"\0\0" + IPV4_HEADER[12:]) == 0xB861
    assert rfc1071(IPV4_HEADER) == 0  # the receiver's check: the sum with the checksum is all ones
    assert rfc1071(ODD) == 0xF6F9
    assert rfc1071(bytes(4)) == 0xFFFF and rfc1071(b"\xff\xff") == 0x0000


def test_a_checksum_in_place_before_data_of_any_length(tmp_path):
    icmp = bytes.fromhex("08 00 33 9a 00 01 00 02 61 62 63")
    assert rfc1071(icmp[:2] + bytes(2) + icmp[4:]) == 0x339A and rfc1071(icmp) == 0
    frame = (b"\0\x0b" + icmp).hex(" ")
    render(tmp_path, "echo", ECHO)
    mod = load(tmp_path / "echo.py")
    for data in (b"", b"abc", b"abcdef"):
        request = mod.Request(code=0, identifier=1, sequence=2, data=data)
        sent = mod.encode(request)
        assert sent[:2] == (8 + len(data)).to_bytes(2, "big") and rfc1071(sent[2:]) == 0
        assert sent[4:6] == rfc1071(sent[2:4] + bytes(2) + sent[6:]).to_bytes(2, "big")
        assert mod.decode(sent) == request
    rejected(mod, flip(frame, 12), "checksum", 4)
    c_round_trips(tmp_path, "echo", [frame, "00 08 08 00 f7 fc 00 01 00 02"], [flip(frame, 12)])


def orders_frame(kind: int, data: bytes) -> str:
    value = rfc1071(data)
    return f"55 {kind:02x} {data.hex(' ')} {value >> 8:02x} {value & 0xFF:02x} {value >> 8:02x} {value & 0xFF:02x}"


ORDERS_FRAMES = {"rfc": orders_frame(1, RFC_DATA), "odd": orders_frame(2, ODD),
                 "zeros": orders_frame(3, bytes(4)), "ones": orders_frame(4, b"\xff\xff")}


def test_the_ipv4_header_checksum_in_place(tmp_path):
    render(tmp_path, "ipv4h", IPV4)  # the example above is checked both ways by the build
    mod = load(tmp_path / "ipv4h.py")
    header = mod.Udp(tos=0, total_length=0x73, ident=0, flags_frag=0x4000, ttl=64,
                     src=0xC0A80001, dst=0xC0A800C7)
    assert mod.encode(header) == IPV4_FRAME
    assert mod.decode(IPV4_FRAME) == header
    frame = IPV4_FRAME.hex(" ")
    rejected(mod, flip(frame, 19), "checksum", 10)
    rejected(mod, flip(frame, 3), "checksum", 10)
    rejected(mod, flip(frame, 10), "checksum", 10)
    with pytest.raises(mod.DecodeError) as err:  # the value expected is the one an encoder sends
        mod.decode(bytes.fromhex(flip(frame, 19)))
    assert "expected 0x{:x}".format(rfc1071(bytes.fromhex(flip(frame, 19))[:10] + bytes(2) + IPV4_HEADER[12:19]
                                            + bytes.fromhex(flip(frame, 19))[19:])) in str(err.value)
    c_round_trips(tmp_path, "ipv4h", [frame], [flip(frame, 19), flip(frame, 3), flip(frame, 10)])


def test_either_zero_passes_the_receiver_check(tmp_path):
    """The sender computes 0000 (the sum of the rest is ffff); a receiver that sums the
    whole finds all ones with 0000 and with ffff. Decoders accept both and read the same
    values; encoders send 0000, RFC 1071's complement of the sum."""
    assert rfc1071(ZERO_FRAME[:10] + bytes(2) + ZERO_FRAME[12:]) == 0x0000
    assert rfc1071(ZERO_FRAME) == 0 and rfc1071(ZERO_OTHER) == 0
    render(tmp_path, "ipv4h", IPV4)
    mod = load(tmp_path / "ipv4h.py")
    zero = mod.Zero(tos=0, total_length=0, ident=0, flags_frag=0, ttl=0, src=0xBAFF0000, dst=0)
    assert mod.encode(zero) == ZERO_FRAME
    assert mod.decode(ZERO_FRAME) == zero and mod.decode(ZERO_OTHER) == zero
    other = ZERO_OTHER.hex(" ")
    lines = run_c(tmp_path, driver("ipv4h", [ZERO_FRAME.hex(" "), other]), STRICT)
    assert lines == [f"{ZERO_FRAME.hex(' ')} encoded {ZERO_FRAME.hex(' ')}", f"{other} encoded {ZERO_FRAME.hex(' ')}"]
    # all covered bytes zero but the checksum: only ffff makes the sum all ones
    empty = mod.Zero(tos=0, total_length=0, ident=0, flags_frag=0, ttl=0, src=0, dst=0)
    assert rfc1071(bytes.fromhex("45 00") + bytes(18)) == 0xBAFF
    assert mod.encode(empty)[10:12] == bytes.fromhex("ba ff")


def test_both_byte_orders_send_the_rfc_bytes(tmp_path):
    """RFC 1071 2(B): summed in the field's byte order, the checksum's bytes on the wire
    are the same (the little-endian field holds f2dd's complement, 0d22)."""
    assert ORDERS_FRAMES["rfc"] == "55 01 00 01 f2 03 f4 f5 f6 f7 22 0d 22 0d"
    render(tmp_path, "inet", ORDERS)
    mod = load(tmp_path / "inet.py")
    for name, frame in ORDERS_FRAMES.items():
        cls = getattr(mod, name.capitalize())
        data = bytes.fromhex(frame)[2:-4]
        assert mod.encode(cls(data=data)) == bytes.fromhex(frame), name
        assert mod.decode(bytes.fromhex(frame)) == cls(data=data), name
    rfc = ORDERS_FRAMES["rfc"]
    rejected(mod, flip(rfc, 10), "be", 10)
    rejected(mod, flip(rfc, 13), "le", 12)
    c_round_trips(tmp_path, "inet", list(ORDERS_FRAMES.values()), [flip(rfc, 10), flip(rfc, 13), flip(rfc, 4)])


# An ICMP echo's shape after a length (IPv4's total length, here its own): the
# checksum near the start of what it covers, before data of any length; it covers
# the bytes sent. type 08, code 00, identifier 0001, sequence
# 0002, data 61 62 63: words 0800 0000 0001 0002 6162 6300 sum to 0xcc65, sent 339a.
ECHO = """codeword: 1
protocol: echo
title: an echo request with data of any length
source: RFC 792
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: length, type: u16, length_of: {from: type, to: payload}}
    - {name: type, type: u8, dispatch: true}
    - {name: code, type: u8}
    - {name: checksum, type: u16, checksum: {algorithm: internet, covers: {from: type, to: payload}}}
    - {payload: true}
messages:
  request:
    id: 8
    fields:
      - {name: identifier, type: u16}
      - {name: sequence, type: u16}
      - {name: data, type: bytes, max_length: 6, to_end: true}
    examples:
      - hex: "00 0b 08 00 33 9a 00 01 00 02 61 62 63"
        values: {code: 0, identifier: 1, sequence: 2, data: "616263"}
"""

SCHEMAS = {"ipv4h": IPV4, "inet": ORDERS, "echo": ECHO}


def vectors_of(tmp_path, name: str):
    tmp_path.mkdir(exist_ok=True)
    render(tmp_path, name, SCHEMAS[name])
    protocol = compile_schema(tmp_path / f"{name}.yaml")
    out = io.StringIO()
    write_vectors(protocol, load(tmp_path / f"{name}.py"), out)
    return protocol, json.loads(out.getvalue())


@pytest.mark.parametrize("name", sorted(SCHEMAS))
def test_conformance_on_host_and_atmega32(tmp_path, name):
    """Python's vectors through the C driver; on AVR int is 16 bits, and the sum's
    carries must not depend on it."""
    _, vectors = vectors_of(tmp_path / "py", name)
    assert any(case["error"] == "checksum" for case in vectors["invalid"])
    host, avr = conformance_on_host_and_avr(tmp_path, name, SCHEMAS[name])
    assert host > len(vectors["valid"]) and avr == host


STREAMS = {"inet": bytes.fromhex("".join(ORDERS_FRAMES.values())),
           "ipv4h": IPV4_FRAME + ZERO_OTHER + ZERO_FRAME + bytes.fromhex(flip(IPV4_FRAME.hex(" "), 10))}


@pytest.mark.parametrize("name", sorted(STREAMS))
def test_the_accelerator_decodes_as_python(tmp_path, name):
    if shutil.which("gcc") is None or accel.python_headers() is None:
        pytest.fail("gcc and Python's headers are needed (scripts/install-toolchains installs them)")
    _, vectors = vectors_of(tmp_path, name)
    if name == "ipv4h":  # the other zero among the vectors, decoded by both
        assert any(bytes.fromhex(case["hex"]) == ZERO_OTHER for case in vectors["valid"] if "hex" in case)
    folder = tmp_path / "accel"
    assert accel.accelerate([tmp_path / f"{name}.yaml"], folder).built
    fast = load_module(tmp_path / f"{name}.py", f"_{name}_fast", folder)
    pure = load_module(tmp_path / f"{name}.py", f"_{name}_pure", None)
    assert fast.ACCELERATOR is not None
    problem, compared = difference(fast, pure, vectors, [STREAMS[name]])
    assert not problem, problem
    assert compared > len(vectors["valid"])


@pytest.mark.parametrize("compiler", ["gcc", "clang"])
@pytest.mark.parametrize("level", ["-O0", "-O2", "-Os"])
def test_strict_warnings(tmp_path, compiler, level):
    from schema_in_a_test import firmware_warnings
    render(tmp_path, "inet", ORDERS)
    assert firmware_warnings(tmp_path, "inet", compiler, level) == ""


def test_the_spec_works_the_published_header_in_place(tmp_path):
    """The Markdown's worked example: the field counted as 00 00, the RFC's words and sum
    (hand-checked: 4500 + 0073 + 4000 + 4011 + c0a8 + 0001 + c0a8 + 00c7 = 2479c, folded
    479e, inverted b861), and the receiver's sum of all ones."""
    (tmp_path / "ipv4h.yaml").write_text(IPV4, encoding="utf-8")
    files = render_protocol(compile_schema(tmp_path / "ipv4h.yaml"))
    page = next(text for path, text in files.items() if path.endswith("ipv4h.md"))
    assert "`45 00 00 73 00 00 40 00 40 11 00 00 c0 a8 00 01 c0 a8 00 c7`, `checksum` itself (B10–B11) " \
           "counted as `00 00`" in page
    assert "add to `0x2479c`" in page and "`0x479e`" in page and "one's complement: `0xb861`" in page
    assert f"`{IPV4_HEADER.hex(' ')}`, to `0xffff` (all ones: no error)" in page


def test_covering_itself_changes_the_fingerprint_and_breaks(tmp_path):
    """The same fields and coverage names; only whether the checksum lies inside it."""
    from codeword.diff import BREAKING, compare
    from codeword.fingerprint import fingerprint
    last = IPV4.replace("    - {name: checksum, type: u16, checksum: {algorithm: internet, covers: {from: ver_ihl, to: payload}}}\n"
                        "    - {payload: true}\n",
                        "    - {payload: true}\n"
                        "    - {name: checksum, type: u16, checksum: {algorithm: internet, covers: {from: ver_ihl, to: payload}}}\n")
    last = last[:last.index("    examples:")]
    protocols = []
    for name, schema in (("a", IPV4[:IPV4.index("    examples:")]), ("b", last)):
        (tmp_path / name).mkdir()
        (tmp_path / name / "ipv4h.yaml").write_text(schema, encoding="utf-8")
        protocols.append(compile_schema(tmp_path / name / "ipv4h.yaml"))
    inside, after = (next(f for f in p.messages[0].layout if f.name == "checksum") for p in protocols)
    assert inside.checksum.covers_self and not after.checksum.covers_self
    assert fingerprint(protocols[0]) != fingerprint(protocols[1])
    assert any("checksum" in c.subject for c in compare(*protocols).of_kind(BREAKING))


LSB = """codeword: 1
protocol: inetlsb
title: least significant bit first, little-endian by default
source: RFC 1071
framing:
  kind: bytes
  bit_order: lsb_first
  layout:
    - {name: kind, type: u8, dispatch: true}
    - {name: pad, type: u8}
    - {name: check, type: u16, checksum: {algorithm: internet, covers: {from: kind, to: payload}}}
    - {payload: true}
messages:
  a: {id: 1, fields: [{name: x, type: u16}]}
"""


def test_words_follow_the_framings_default_byte_order(tmp_path):
    """lsb_first makes multi-byte fields little-endian unless byte_order says otherwise;
    the checksum's words follow, so the field in place is one word of what it covers and
    the wire carries RFC 1071's bytes: 01 00 00 00 02 01 sum to 0301, sent fc fe."""
    assert rfc1071(bytes.fromhex("01 00 00 00 02 01")) == 0xFCFE
    render(tmp_path, "inetlsb", LSB)
    mod = load(tmp_path / "inetlsb.py")
    assert mod.encode(mod.A(pad=0, x=0x0102)) == bytes.fromhex("01 00 fc fe 02 01")
    assert mod.decode(bytes.fromhex("01 00 fc fe 02 01")) == mod.A(pad=0, x=0x0102)
    c_round_trips(tmp_path, "inetlsb", ["01 00 fc fe 02 01"], ["01 00 fe fc 02 01"])
