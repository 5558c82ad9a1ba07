"""examples/ipv4.yaml against scapy, a widely used packet library, and the published
IPv4 header of Wikipedia's "Internet checksum" article: the header's checksum and
ICMP's sit inside the bytes they check. Datagrams scapy builds decode to the values
scapy reads from them, codeword writes their bytes back, and scapy finds the checksums
codeword writes right, in Python and in C. Expected bytes come from scapy, the
published header or the RFC 1071 sum written here."""
from __future__ import annotations

import random

import pytest
from scapy.layers.inet import ICMP, IP, UDP  # a test extra: pip install -e ".[peers]"
from scapy.packet import Raw

from schema_in_a_test import build_example, load, run_c
from test_checksum_families import STRICT, driver

PUBLISHED = bytes.fromhex("45 00 00 73 00 00 40 00 40 11 b8 61 c0 a8 00 01 c0 a8 00 c7")


def rfc1071(data: bytes) -> int:
    """RFC 1071 section 4.1: big-endian words, each carry added back in, then inverted."""
    total = 0
    for i in range(0, len(data), 2):
        total += data[i] << 8 | (data[i + 1] if i + 1 < len(data) else 0)
        total = (total & 0xFFFF) + (total >> 16)
    return ~total & 0xFFFF


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    out = build_example("ipv4", tmp_path_factory.mktemp("ipv4"))
    return out, load(out / "ipv4.py")


def published_datagram(mod):
    """The published header's values, with 95 bytes of UDP after it as its total length says."""
    return mod.Udp(dscp=0, ecn=0, identification=0, flags=2, fragment_offset=0, ttl=64, src=0xC0A80001,
                   dst=0xC0A800C7, src_port=1, dst_port=2, length=95, udp_checksum=0, data=bytes(87))


def test_the_published_header_in_place(built):
    _, mod = built
    assert rfc1071(PUBLISHED[:10] + bytes(2) + PUBLISHED[10 + 2:]) == 0xB861 and rfc1071(PUBLISHED) == 0
    assert IP(PUBLISHED).chksum == 0xB861
    frame = mod.encode(published_datagram(mod))
    assert frame[:20] == PUBLISHED and len(frame) == 0x73
    assert mod.decode(frame) == published_datagram(mod)
    bad = frame[:19] + b"\xc8" + frame[20:]  # another destination, the checksum kept
    with pytest.raises(mod.DecodeError) as err:
        mod.decode(bad)
    assert err.value.rule == "checksum" and err.value.field == "header_checksum"
    assert f"expected {hex(rfc1071(bad[:10] + bytes(2) + bad[12:20]))}" in str(err.value)


def scapy_datagrams(count: int) -> list[bytes]:
    rng = random.Random(1071)
    out = []
    for i in range(count):
        ip = IP(src=f"10.{rng.randrange(256)}.{rng.randrange(256)}.{rng.randrange(256)}",
                dst=f"192.168.{rng.randrange(256)}.{rng.randrange(256)}", id=rng.randrange(1 << 16),
                ttl=rng.randrange(1, 256), tos=rng.randrange(256), flags=rng.choice(["", "DF"]))
        data = Raw(rng.randbytes(rng.randrange(0, 65 if i % 2 else 129)))
        if i % 2:
            out.append(bytes(ip / ICMP(type=8, id=rng.randrange(1 << 16), seq=rng.randrange(1 << 16)) / data))
        else:
            out.append(bytes(ip / UDP(sport=rng.randrange(1 << 16), dport=rng.randrange(1 << 16)) / data))
    return out


DATAGRAMS = scapy_datagrams(40)


def test_python_reads_what_scapy_writes_and_writes_the_same_bytes(built):
    _, mod = built
    for raw in DATAGRAMS:
        theirs = IP(raw)
        ours = mod.decode(raw)
        assert (ours.src, ours.dst, ours.ttl, ours.identification) == (
            int.from_bytes(raw[12:16], "big"), int.from_bytes(raw[16:20], "big"), theirs.ttl, theirs.id)
        assert (ours.dscp << 2 | ours.ecn) == theirs.tos and ours.data == bytes(theirs.payload.payload)
        if theirs.proto == 1:
            assert (ours.identifier, ours.sequence) == (theirs[ICMP].id, theirs[ICMP].seq)
        else:
            assert (ours.src_port, ours.dst_port, ours.udp_checksum) == (theirs[UDP].sport, theirs[UDP].dport,
                                                                          theirs[UDP].chksum)
        assert mod.encode(ours) == raw


def test_scapy_finds_the_checksums_codeword_writes(built):
    _, mod = built
    for raw in DATAGRAMS[1::2]:  # ICMP: both checksums are codeword's
        written = mod.encode(mod.decode(raw))
        again = IP(written)
        del again.chksum
        del again[ICMP].chksum
        assert bytes(again) == written  # scapy computes the same two checksums


def test_c_reads_what_scapy_writes_and_writes_the_same_bytes(built):
    where, mod = built
    published = mod.encode(published_datagram(mod))
    frames = [published.hex(" ")] + [d.hex(" ") for d in DATAGRAMS[:8]]
    bad = [(published[:19] + b"\xc8" + published[20:]).hex(" "),  # the header's checksum, then ICMP's
           DATAGRAMS[1][:-1].hex(" ") + f" {DATAGRAMS[1][-1] ^ 1:02x}"]
    lines = run_c(where, driver("ipv4", frames + bad), STRICT)
    assert lines == [f"{h} encoded {h}" for h in frames] + [f"{h} error checksum" for h in bad]
