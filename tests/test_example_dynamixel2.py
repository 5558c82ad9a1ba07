"""examples/dynamixel2.yaml against the ROBOTIS e-Manual's published Protocol 2.0
packets (Ping, Read, Write and their status packets), whose CRCs are checked here
by a bitwise CRC-16/UMTS written from its parameters (poly 0x8005, init 0, not
reflected) and by the Dynamixel SDK's own CRC table. Then against the Dynamixel
SDK (`dynamixel-sdk`, the peers extra): its addStuffing and updateCRC write the
packets of random instructions whose parameters hold FF FF FD, codeword's Python
and C write the same bytes and read them back to the same values, and its
removeStuffing reads what codeword writes. Expected bytes never come from
codeword."""
from __future__ import annotations

import random
from pathlib import Path

import pytest
from dynamixel_sdk.protocol2_packet_handler import Protocol2PacketHandler  # pip install -e ".[peers]"

from schema_in_a_test import c_bytes, load, render, run_c

SCHEMA = (Path(__file__).resolve().parents[1] / "examples" / "dynamixel2.yaml").read_text(encoding="utf-8")
SDK = Protocol2PacketHandler()
HEADER = bytes.fromhex("FF FF FD 00")
PING, READ, WRITE, STATUS = 0x01, 0x02, 0x03, 0x55

# e-Manual, Protocol 2.0: Ping examples 1 and 2, Read example, Write example, and their status packets
PUBLISHED = [
    ("FF FF FD 00 01 03 00 01 19 4E", "ping", {"id": 1}),
    ("FF FF FD 00 FE 03 00 01 31 42", "ping", {"id": 0xFE}),
    ("FF FF FD 00 01 07 00 55 00 06 04 26 65 5D", "status", {"id": 1, "error": 0, "params": "060426"}),
    ("FF FF FD 00 02 07 00 55 00 06 04 26 6F 6D", "status", {"id": 2, "error": 0, "params": "060426"}),
    ("FF FF FD 00 01 07 00 02 84 00 04 00 1D 15", "read", {"id": 1, "address": 132, "data_length": 4}),
    ("FF FF FD 00 01 08 00 55 00 A6 00 00 00 8C C0", "status", {"id": 1, "error": 0, "params": "a6000000"}),
    ("FF FF FD 00 01 09 00 03 74 00 00 02 00 00 CA 89", "write", {"id": 1, "address": 116, "data": "00020000"}),
]


def crc16_umts(data: bytes) -> int:
    """Bitwise CRC-16/UMTS: poly 0x8005, init 0, no reflection, no final XOR."""
    crc = 0
    for byte in data:
        crc ^= byte << 8
        for _ in range(8):
            crc = ((crc << 1) ^ 0x8005) & 0xFFFF if crc & 0x8000 else (crc << 1) & 0xFFFF
    return crc


def sdk_packet(pid: int, instruction: int, params: bytes) -> bytes:
    """The packet as the SDK's txPacket sends it: addStuffing, then updateCRC over the stuffed bytes."""
    length = len(params) + 3
    packet = list(HEADER) + [pid, length & 0xFF, length >> 8, instruction] + list(params) + [0, 0]
    packet = SDK.addStuffing(packet)
    length = packet[5] | packet[6] << 8
    crc = SDK.updateCRC(0, packet, length + 5)
    packet[length + 5], packet[length + 6] = crc & 0xFF, crc >> 8
    return bytes(packet)


def sdk_params(packet: bytes) -> bytes:
    """The parameters the SDK's removeStuffing reads from a packet as sent."""
    unstuffed = SDK.removeStuffing(list(packet))
    length = unstuffed[5] | unstuffed[6] << 8
    return bytes(unstuffed[8:length + 5])


def test_the_published_crcs_are_crc16_umts():
    for frame, _, _ in PUBLISHED:
        data = bytes.fromhex(frame)
        assert crc16_umts(data[:-2]) == int.from_bytes(data[-2:], "little") == SDK.updateCRC(0, list(data), len(data) - 2)
    assert crc16_umts(b"123456789") == 0xFEE8  # the catalogue's check value


def test_the_sdk_writes_the_published_packets():
    pings = [sdk_packet(1, PING, b""), sdk_packet(1, READ, bytes.fromhex("84 00 04 00")),
             sdk_packet(1, WRITE, bytes.fromhex("74 00 00 02 00 00"))]
    assert [p.hex(" ").upper() for p in pings] == [PUBLISHED[0][0], PUBLISHED[4][0], PUBLISHED[6][0]]


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    where = tmp_path_factory.mktemp("dynamixel2")
    render(where, "dynamixel2", SCHEMA)
    return where, load(where / "dynamixel2.py")


def test_python_decodes_the_published_packets_and_encodes_them_back(built):
    _, mod = built
    for frame, name, values in PUBLISHED:
        data = bytes.fromhex(frame)
        m = mod.decode(data)
        assert type(m).NAME == name and m.to_dict() == values
        assert mod.encode(m) == data


# --- against the Dynamixel SDK ---------------------------------------------------------------
# Random instructions and status packets whose parameters often hold FF FF FD (so
# the SDK stuffs them), written by the SDK; codeword reads the values and writes the
# SDK's bytes back.

PIECES = [bytes.fromhex("FF FF FD"), bytes.fromhex("FF FF FD FD"), b"\xff", b"\xfd", b"\x00"]


def random_params(rng: random.Random, most: int) -> bytes:
    out = b""
    while len(out) < most and rng.random() < 0.85:
        out += rng.choice(PIECES) if rng.random() < 0.7 else bytes([rng.randrange(256)])
    return out[:most]


def sample(seed: int) -> list[tuple[bytes, str, dict]]:
    """(packet the SDK writes, message name, the values it holds)."""
    rng = random.Random(seed)
    out = []
    for _ in range(300):
        pid = rng.choice([1, 2, 0x7F, 0xFC, 0xFE])
        kind = rng.choice(["read", "write", "status", "ping"])
        if kind == "ping":
            out.append((sdk_packet(pid, PING, b""), kind, {"id": pid}))
        elif kind == "read":
            address, size = rng.choice([0xFDFF, 0xFFFF, 132, rng.randrange(65536)]), rng.randrange(65536)
            params = address.to_bytes(2, "little") + size.to_bytes(2, "little")
            out.append((sdk_packet(pid, READ, params), kind, {"id": pid, "address": address, "data_length": size}))
        elif kind == "write":
            address, data = rng.choice([0xFFFF, 116, rng.randrange(65536)]), random_params(rng, 64)
            out.append((sdk_packet(pid, WRITE, address.to_bytes(2, "little") + data), kind,
                        {"id": pid, "address": address, "data": data.hex()}))
        else:
            error, data = rng.choice([0, 0x80, 0xFF]), random_params(rng, 64)
            out.append((sdk_packet(pid, STATUS, bytes([error]) + data), kind, {"id": pid, "error": error, "params": data.hex()}))
    return out


def test_the_sample_stuffs_often():
    stuffed = [p for p, _, _ in sample(1) if b"\xff\xff\xfd\xfd" in p[7:]]
    assert len(stuffed) > 60


def test_python_reads_what_the_sdk_writes_and_writes_the_same_bytes(built):
    _, mod = built
    for packet, name, values in sample(1):
        m = mod.decode(packet)
        assert (type(m).NAME, m.to_dict()) == (name, values), packet.hex(" ")
        assert mod.encode(m) == packet


def test_the_sdk_reads_what_codeword_writes(built):
    _, mod = built
    for packet, name, values in sample(2):
        written = mod.encode(mod.from_dict(name, values))
        assert written == packet
        params = sdk_params(written)
        expected = {"ping": lambda: b"", "read": lambda: packet[8:12],
                    "write": lambda: values["address"].to_bytes(2, "little") + bytes.fromhex(values["data"]),
                    "status": lambda: bytes([values["error"]]) + bytes.fromhex(values["params"])}[name]()
        assert params == expected, written.hex(" ")


def test_python_stream_finds_stuffed_packets_among_noise(built):
    _, mod = built
    packets = [p for p, _, _ in sample(3)[:60]]
    stream = b"".join(b"\xff\xff\x00" + p for p in packets)  # noise that starts like a header
    got = mod.StreamDecoder().feed(stream)
    assert [mod.encode(x) for x in got if not isinstance(x, mod.DecodeError)] == packets


def test_a_packet_without_its_stuffed_byte_is_an_escape_error(built):
    _, mod = built
    # the SDK's packet with FD FD cut to FD, its length and CRC made to agree by hand
    packet = bytearray(sdk_packet(1, WRITE, bytes.fromhex("74 00 FF FF FD 00")))
    assert packet[10:14] == bytes.fromhex("FF FF FD FD")
    del packet[13]
    packet[5] -= 1
    packet[-2:] = crc16_umts(bytes(packet[:-2])).to_bytes(2, "little")
    with pytest.raises(mod.DecodeError) as caught:
        mod.decode(bytes(packet))
    assert (caught.value.rule, caught.value.offset) == ("escape", 13 * 8)
    damaged = bytearray(sdk_packet(1, WRITE, bytes.fromhex("74 00 FF FF FD 00")))
    damaged[-1] ^= 1
    with pytest.raises(mod.DecodeError) as caught:
        mod.decode(bytes(damaged))
    assert caught.value.rule == "checksum"


DRIVER = r"""
#include <stdio.h>
#include "dynamixel2.h"
static const uint8_t stream_bytes[] = {STREAM};
static void show(const uint8_t *b, size_t n) {
    dynamixel2_message_t m;
    uint8_t out[DYNAMIXEL2_WIRE_MAX];
    int k = 0;
    size_t i;
    int rc = dynamixel2_decode(b, n, DYNAMIXEL2_DIR_ANY, &m);
    if (rc == 0) {
        k = dynamixel2_encode(&m, out, sizeof out);
    }
    printf("%d", rc);
    for (i = 0; k > 0 && i < (size_t)k; i++) {
        printf(" %02x", out[i]);
    }
    printf("\n");
}
int main(void) {
    dynamixel2_parser_t p;
    dynamixel2_message_t m;
    uint8_t out[DYNAMIXEL2_WIRE_MAX];
    size_t i;
    int rc, k, j;
    CALLS
    dynamixel2_parser_init(&p, DYNAMIXEL2_DIR_ANY);
    for (i = 0; i < sizeof stream_bytes; i++) {
        dynamixel2_parser_feed(&p, stream_bytes[i]);
        while ((rc = dynamixel2_parser_next(&p, &m)) != 0) {
            if (rc != 1) {
                continue;
            }
            k = dynamixel2_encode(&m, out, sizeof out);
            printf("frame");
            for (j = 0; j < k; j++) {
                printf(" %02x", out[j]);
            }
            printf("\n");
        }
    }
    return 0;
}
"""


def test_c_reads_what_the_sdk_writes_writes_the_same_bytes_and_finds_it_in_a_stream(built):
    where, _ = built
    packets = [bytes.fromhex(f) for f, _, _ in PUBLISHED] + [p for p, _, _ in sample(4)[:80]]
    escape = bytearray(sdk_packet(1, WRITE, bytes.fromhex("74 00 FF FF FD 00")))
    del escape[13]
    escape[5] -= 1
    escape[-2:] = crc16_umts(bytes(escape[:-2])).to_bytes(2, "little")
    calls = [f"{{ static const uint8_t f[] = {{{c_bytes(p)}}}; show(f, sizeof f); }}" for p in packets + [bytes(escape)]]
    stream = b"".join(b"\xff\xff\x00" + p for p in packets)
    lines = run_c(where, DRIVER.replace("STREAM}", c_bytes(stream) + "}").replace("CALLS", "\n    ".join(calls)))
    assert lines[:len(packets)] == ["0 " + p.hex(" ") for p in packets]
    assert lines[len(packets)] == "-27"  # CW_ERR_ESCAPE: FF FF FD without the FD stuffed after it
    assert lines[len(packets) + 1:] == ["frame " + p.hex(" ") for p in packets]
