"""examples/modbus_rtu.yaml against the Modbus specification's published frames
(Modbus Application Protocol V1.1b3, §6.3, §6.12 and §7): every CRC is checked
here by a bitwise CRC-16/MODBUS written from the Modbus over Serial Line
specification (§6.2.2), not by codeword. Python and C decode each frame and
encode it back byte for byte; the stream decoders find frames whose size the
function code gives and those whose size the byte count gives."""
from __future__ import annotations

from pathlib import Path

import pytest

from schema_in_a_test import load, render, run_c

SCHEMA = (Path(__file__).resolve().parents[1] / "examples" / "modbus_rtu.yaml").read_text(encoding="utf-8")

READ_RESPONSE = "11 03 06 AE 41 56 52 43 40 49 AD"  # 3 registers 0xAE41 0x5652 0x4340
READ_REQUEST = "11 03 00 6B 00 03 76 87"
WRITE_REQUEST = "11 10 00 01 00 02 04 00 0A 01 02 C6 F0"
WRITE_RESPONSE = "11 10 00 01 00 02 12 98"
EXCEPTION = "0A 81 02 B0 53"
TO_SERVER = [READ_REQUEST, WRITE_REQUEST]
TO_CLIENT = [READ_RESPONSE, WRITE_RESPONSE, EXCEPTION]


def crc16_modbus(data: bytes) -> int:
    """Bitwise CRC-16/MODBUS: init 0xFFFF, reflected polynomial 0xA001."""
    crc = 0xFFFF
    for byte in data:
        crc ^= byte
        for _ in range(8):
            crc = (crc >> 1) ^ 0xA001 if crc & 1 else crc >> 1
    return crc


@pytest.mark.parametrize("frame", TO_SERVER + TO_CLIENT)
def test_published_crcs(frame):
    data = bytes.fromhex(frame)
    assert crc16_modbus(data[:-2]) == int.from_bytes(data[-2:], "little")


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    where = tmp_path_factory.mktemp("modbus")
    render(where, "modbus_rtu", SCHEMA)
    return where, load(where / "modbus_rtu.py")


def test_python_decodes_and_encodes_back(built):
    _, mod = built
    for frames, direction in ((TO_SERVER, "to_server"), (TO_CLIENT, "to_client")):
        for frame in frames:
            data = bytes.fromhex(frame)
            message = mod.decode(data, direction)
            assert mod.encode(message) == data
    response = mod.decode(bytes.fromhex(READ_RESPONSE), "to_client")
    assert response.registers == [0xAE41, 0x5652, 0x4340]
    write = mod.decode(bytes.fromhex(WRITE_REQUEST), "to_server")
    assert (write.start, write.quantity, write.values) == (1, 2, [0x000A, 0x0102])
    assert mod.decode(bytes.fromhex(EXCEPTION), "to_client").exception_code == 2


def test_python_counted_frames_checked(built):
    _, mod = built
    response = mod.ReadHoldingRegistersResponse(address=17, registers=[])
    empty = bytes.fromhex("11 03 00") + crc16_modbus(bytes.fromhex("11 03 00")).to_bytes(2, "little")
    assert mod.encode(response) == empty
    most = mod.ReadHoldingRegistersResponse(address=17, registers=list(range(125)))
    assert len(mod.encode(most)) == 255
    with pytest.raises(mod.EncodeError) as e:
        mod.encode(mod.ReadHoldingRegistersResponse(address=17, registers=list(range(126))))
    assert e.value.field == "registers"
    body = bytes.fromhex("11 03 FA") + bytes(6)  # claims 250 bytes, holds 6
    with pytest.raises(mod.DecodeError) as e:
        mod.decode(body + crc16_modbus(body).to_bytes(2, "little"), "to_client")
    assert (e.value.field, e.value.rule) == ("registers", "length")
    body = bytes.fromhex("11 03 FC") + bytes(252)  # 126 registers: more than 125
    with pytest.raises(mod.DecodeError):
        mod.decode(body + crc16_modbus(body).to_bytes(2, "little"), "to_client")


def test_python_stream_finds_frames(built):
    _, mod = built
    for frames, direction in ((TO_SERVER, "to_server"), (TO_CLIENT, "to_client")):
        stream = bytes.fromhex(" ".join(frames))
        out = mod.StreamDecoder(direction).feed(stream)
        assert [mod.encode(x).hex(" ").upper() for x in out] == frames


DRIVER = r"""
#include <stdio.h>
#include "modbus_rtu.h"
static const uint8_t to_server[] = {TO_SERVER};
static const uint8_t to_client[] = {TO_CLIENT};
static void show(const uint8_t *b, size_t n, int direction) {
    modbus_rtu_message_t m;
    uint8_t out[300];
    int k = 0;
    size_t i;
    int rc = modbus_rtu_decode(b, n, direction, &m);
    if (rc == 0) {
        k = modbus_rtu_encode(&m, out, sizeof out);
    }
    printf("%d", rc);
    for (i = 0; k > 0 && i < (size_t)k; i++) {
        printf(" %02X", out[i]);
    }
    printf("\n");
}
static void stream(const uint8_t *b, size_t n, int direction) {
    modbus_rtu_parser_t p;
    modbus_rtu_message_t m;
    uint8_t out[300];
    size_t i;
    int rc, k, j;
    modbus_rtu_parser_init(&p, direction);
    for (i = 0; i < n; i++) {
        modbus_rtu_parser_feed(&p, b[i]);
        while ((rc = modbus_rtu_parser_next(&p, &m)) != 0) {
            if (rc != 1) {
                printf("error %d\n", rc);
                continue;
            }
            k = modbus_rtu_encode(&m, out, sizeof out);
            printf("frame");
            for (j = 0; j < k; j++) {
                printf(" %02X", out[j]);
            }
            printf("\n");
        }
    }
}
int main(void) {
    CALLS
    stream(to_server, sizeof to_server, MODBUS_RTU_DIR_TO_SERVER);
    stream(to_client, sizeof to_client, MODBUS_RTU_DIR_TO_CLIENT);
    return 0;
}
"""


def c_bytes(frames: list[str]) -> str:
    return ", ".join(f"0x{b:02x}" for b in bytes.fromhex(" ".join(frames)))


def test_c_decodes_encodes_and_finds_frames(built):
    where, _ = built
    calls = []
    for frames, direction in ((TO_SERVER, "MODBUS_RTU_DIR_TO_SERVER"), (TO_CLIENT, "MODBUS_RTU_DIR_TO_CLIENT")):
        for frame in frames:
            data = c_bytes([frame])
            calls.append(f"{{ static const uint8_t f[] = {{{data}}}; show(f, sizeof f, {direction}); }}")
    bad = bytes.fromhex("11 03 FA") + bytes(6)
    bad += crc16_modbus(bad).to_bytes(2, "little")
    calls.append(f"{{ static const uint8_t f[] = {{{c_bytes([bad.hex()])}}}; show(f, sizeof f, MODBUS_RTU_DIR_TO_CLIENT); }}")
    driver = (DRIVER.replace("TO_SERVER}", c_bytes(TO_SERVER) + "}").replace("TO_CLIENT}", c_bytes(TO_CLIENT) + "}")
              .replace("CALLS", "\n    ".join(calls)))
    lines = run_c(where, driver)
    frames = TO_SERVER + TO_CLIENT
    assert lines[:len(frames)] == ["0 " + f.upper() for f in frames]
    assert lines[len(frames)] == "-2"  # CW_ERR_LENGTH: 250 bytes claimed, 6 sent
    assert lines[len(frames) + 1:] == ["frame " + f.upper() for f in frames]
