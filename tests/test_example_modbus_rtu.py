"""examples/modbus_rtu.yaml against the Modbus specification's published frames
(Modbus Application Protocol V1.1b3, §6.3, §6.12 and §7): every CRC is checked
here by a bitwise CRC-16/MODBUS written from the Modbus over Serial Line
specification (§6.2.2), not by codeword. Python and C decode each frame and
encode it back byte for byte; the stream decoders find frames whose size the
function code gives and those whose size the byte count gives. Then against
pymodbus, whose RTU framer and PDU classes build and read frames of every message
(0 to 125 registers, exception responses): see the section below."""
from __future__ import annotations

import random
from pathlib import Path

import pytest
from pymodbus.framer import FramerRTU  # a test extra: pip install -e ".[peers]"
from pymodbus.pdu import DecodePDU, ExceptionResponse
from pymodbus.pdu.register_message import (ReadHoldingRegistersRequest, ReadHoldingRegistersResponse,
                                           WriteMultipleRegistersRequest, WriteMultipleRegistersResponse)

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


# --- against pymodbus --------------------------------------------------------------------
# pymodbus, a widely used Modbus stack, builds frames with its RTU framer and PDU classes:
# codeword's Python and C decode them to the values pymodbus reads, write the same bytes
# back, and pymodbus reads what codeword writes. Expected bytes come from pymodbus.

# a server's framer reads requests, a client's responses
FRAMERS = {"to_server": FramerRTU(DecodePDU(is_server=True)), "to_client": FramerRTU(DecodePDU(is_server=False))}
REFUSED = [1, 2, 3, 4, 5, 6, 15, 16]  # the function codes whose exception responses the example has
EXCEPTION_CODES = [1, 2, 3, 4, 5, 6, 8, 10, 11]


def registers(rng: random.Random, n: int) -> list[int]:
    return [rng.getrandbits(16) for _ in range(n)]


def sample_pdus(seed: int) -> list[tuple[str, object]]:
    """pymodbus PDUs of every message of the example, with the fewest and the most
    registers, each with its direction."""
    rng = random.Random(seed)
    out = []
    for n in [0, 1, 125] + [rng.randint(0, 125) for _ in range(4)]:
        dev = rng.randint(1, 247)
        write = max(1, min(n, 123))
        out += [("to_server", ReadHoldingRegistersRequest(address=rng.getrandbits(16), count=max(n, 1), dev_id=dev)),
                ("to_client", ReadHoldingRegistersResponse(registers=registers(rng, n), dev_id=dev)),
                ("to_server", WriteMultipleRegistersRequest(address=rng.getrandbits(16),
                                                            registers=registers(rng, write), dev_id=dev)),
                ("to_client", WriteMultipleRegistersResponse(address=rng.getrandbits(16), count=write, dev_id=dev)),
                ("to_client", ExceptionResponse(rng.choice(REFUSED), rng.choice(EXCEPTION_CODES), device_id=dev))]
    return out


def sample_frames(seed: int) -> list[tuple[str, bytes]]:
    return [(direction, FRAMERS[direction].buildFrame(pdu)) for direction, pdu in sample_pdus(seed)]


def read_by_pymodbus(frame: bytes, direction: str):
    used, pdu = FRAMERS[direction].handleFrame(frame, 0, 0)
    assert used == len(frame) and pdu is not None, frame.hex(" ")
    return pdu


def values_of(pdu) -> tuple:
    """What pymodbus read from a frame, in the order of the example's fields."""
    if isinstance(pdu, ExceptionResponse):
        return "exception_response", pdu.dev_id, pdu.function_code, pdu.exception_code
    if isinstance(pdu, ReadHoldingRegistersRequest):
        return "read_holding_registers", pdu.dev_id, pdu.address, pdu.count
    if isinstance(pdu, ReadHoldingRegistersResponse):
        return ("read_holding_registers_response", pdu.dev_id, *pdu.registers)
    if isinstance(pdu, WriteMultipleRegistersRequest):
        return ("write_multiple_registers", pdu.dev_id, pdu.address, pdu.count, *pdu.registers)
    return "write_multiple_registers_response", pdu.dev_id, pdu.address, pdu.count


def values_of_ours(m) -> tuple:
    name = m.NAME
    if name == "exception_response":
        return name, m.address, m.function, int(m.exception_code)
    if name == "read_holding_registers_response":
        return (name, m.address, *m.registers)
    if name == "write_multiple_registers":
        return (name, m.address, m.start, m.quantity, *m.values)
    return name, m.address, m.start, m.quantity


@pytest.mark.parametrize("frame", TO_SERVER + TO_CLIENT)
def test_pymodbus_reads_the_published_frames(frame):
    direction = "to_server" if frame in TO_SERVER else "to_client"
    pdu = read_by_pymodbus(bytes.fromhex(frame), direction)
    assert FRAMERS[direction].buildFrame(pdu) == bytes.fromhex(frame)


def test_python_reads_what_pymodbus_reads_and_writes_the_same_bytes(built):
    _, mod = built
    for direction, frame in sample_frames(seed=1):
        ours = mod.decode(frame, direction)
        assert values_of_ours(ours) == values_of(read_by_pymodbus(frame, direction)), frame.hex(" ")
        assert mod.encode(ours) == frame


def test_pymodbus_reads_what_codeword_writes(built):
    _, mod = built
    rng = random.Random(2)
    for _ in range(20):
        dev, n = rng.randint(1, 247), rng.randint(1, 123)
        messages = [
            ("to_server", mod.ReadHoldingRegisters(address=dev, start=rng.getrandbits(16), quantity=rng.randint(1, 125))),
            ("to_client", mod.ReadHoldingRegistersResponse(address=dev, registers=registers(rng, rng.randint(0, 125)))),
            ("to_server", mod.WriteMultipleRegisters(address=dev, start=rng.getrandbits(16), quantity=n,
                                                     values=registers(rng, n))),
            ("to_client", mod.WriteMultipleRegistersResponse(address=dev, start=rng.getrandbits(16),
                                                             quantity=rng.getrandbits(16))),
            ("to_client", mod.ExceptionResponse(address=dev, function=0x80 | rng.choice(REFUSED),
                                                exception_code=rng.choice(EXCEPTION_CODES)))]
        for direction, m in messages:
            frame = mod.encode(m)
            pdu = read_by_pymodbus(frame, direction)
            assert values_of(pdu) == values_of_ours(m)
            assert FRAMERS[direction].buildFrame(pdu) == frame


def test_python_stream_finds_pymodbus_frames(built):
    _, mod = built
    for direction in FRAMERS:
        frames = [f for d, f in sample_frames(seed=3) if d == direction]
        stream = b"".join(frames)
        dec = mod.StreamDecoder(direction)
        found = [x for i in range(0, len(stream), 7) for x in dec.feed(stream[i:i + 7])]
        assert [mod.encode(x) for x in found] == frames


PYMODBUS_DRIVER = r"""
#include <stdio.h>
#include "modbus_rtu.h"
struct frame { int direction; size_t len; uint8_t bytes[MODBUS_RTU_MAX_FRAME]; };
static const struct frame frames[] = {
TABLE
};
static void values(const modbus_rtu_message_t *m) {
    int i;
    switch (m->kind) {
    case MODBUS_RTU_MSG_READ_HOLDING_REGISTERS:
        printf("read_holding_registers %u %u %u", m->as.read_holding_registers.address,
               m->as.read_holding_registers.start, m->as.read_holding_registers.quantity);
        break;
    case MODBUS_RTU_MSG_READ_HOLDING_REGISTERS_RESPONSE:
        printf("read_holding_registers_response %u", m->as.read_holding_registers_response.address);
        for (i = 0; i < m->as.read_holding_registers_response.registers_count; i++) {
            printf(" %u", m->as.read_holding_registers_response.registers[i]);
        }
        break;
    case MODBUS_RTU_MSG_WRITE_MULTIPLE_REGISTERS:
        printf("write_multiple_registers %u %u %u", m->as.write_multiple_registers.address,
               m->as.write_multiple_registers.start, m->as.write_multiple_registers.quantity);
        for (i = 0; i < m->as.write_multiple_registers.values_count; i++) {
            printf(" %u", m->as.write_multiple_registers.values[i]);
        }
        break;
    case MODBUS_RTU_MSG_WRITE_MULTIPLE_REGISTERS_RESPONSE:
        printf("write_multiple_registers_response %u %u %u", m->as.write_multiple_registers_response.address,
               m->as.write_multiple_registers_response.start, m->as.write_multiple_registers_response.quantity);
        break;
    default:
        printf("exception_response %u %u %u", m->as.exception_response.address, m->as.exception_response.function,
               m->as.exception_response.exception_code);
    }
}
static void again(const modbus_rtu_message_t *m) {
    uint8_t out[MODBUS_RTU_MAX_FRAME];
    int i, n = modbus_rtu_encode(m, out, sizeof out);
    printf(" |");
    for (i = 0; i < n; i++) printf(" %02x", out[i]);
    printf("\n");
}
int main(void) {
    modbus_rtu_message_t m;
    modbus_rtu_parser_t p;
    size_t i, j;
    int rc, direction;
    for (i = 0; i < sizeof frames / sizeof frames[0]; i++) {
        rc = modbus_rtu_decode(frames[i].bytes, frames[i].len, frames[i].direction, &m);
        if (rc != 0) { printf("error %d\n", rc); continue; }
        values(&m);
        again(&m);
    }
    for (direction = MODBUS_RTU_DIR_TO_SERVER; direction <= MODBUS_RTU_DIR_TO_CLIENT; direction++) {
        modbus_rtu_parser_init(&p, direction);
        for (i = 0; i < sizeof frames / sizeof frames[0]; i++) {
            for (j = 0; frames[i].direction == direction && j < frames[i].len; j++) {
                modbus_rtu_parser_feed(&p, frames[i].bytes[j]);
                while ((rc = modbus_rtu_parser_next(&p, &m)) != 0) {
                    printf("stream");
                    if (rc == 1) again(&m); else printf(" error %d\n", rc);
                }
            }
        }
    }
    return 0;
}
"""


def test_c_reads_what_pymodbus_reads_and_writes_the_same_bytes(built):
    where, _ = built
    pdus = sample_pdus(seed=4)
    frames = [(direction, FRAMERS[direction].buildFrame(pdu)) for direction, pdu in pdus]
    table = "\n".join(f"    {{MODBUS_RTU_DIR_{d.upper()}, {len(f)}u, {{{c_bytes([f.hex()])}}}}}," for d, f in frames)
    lines = run_c(where, PYMODBUS_DRIVER.replace("TABLE", table))
    expected = [" ".join(map(str, values_of(read_by_pymodbus(f, d)))) + " | " + f.hex(" ") for d, f in frames]
    assert lines[:len(frames)] == expected
    in_stream_order = [f for direction in ("to_server", "to_client") for d, f in frames if d == direction]
    assert lines[len(frames):] == ["stream | " + f.hex(" ") for f in in_stream_order]
