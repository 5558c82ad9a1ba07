"""Frames with neither a sync byte nor a length field (Modbus RTU): a stream decoder
finds them by the size each function code gives and by the CRC. Frames are the
Modbus specification's published examples: read holding registers 40108..40110
of device 17 (`11 03 00 6B 00 03 76 87`) and write 3 to register 40002
(`11 06 00 01 00 03 9A 9B`), CRC-16/MODBUS sent low byte first."""
from __future__ import annotations

from schema_in_a_test import load, render, run_c

SCHEMA = """codeword: 1
protocol: rtu
title: t
source: s
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: address, type: u8}
    - {name: function, type: u8, dispatch: true}
    - {payload: true}
    - {name: crc, type: u16, byte_order: little, checksum: {algorithm: CRC-16/MODBUS, covers: {from: address, to: payload}}}
messages:
  read_holding_registers:
    id: 0x03
    fields:
      - {name: start, type: u16}
      - {name: count, type: u16}
    examples:
      - {hex: "11 03 00 6b 00 03 76 87", values: {address: 17, start: 107, count: 3}}
  write_single_register:
    id: 0x06
    fields:
      - {name: reg, type: u16}
      - {name: value, type: u16}
    examples:
      - {hex: "11 06 00 01 00 03 9a 9b", values: {address: 17, reg: 1, value: 3}}
"""

READ = "11 03 00 6b 00 03 76 87"
WRITE = "11 06 00 01 00 03 9a 9b"
# line noise, a frame, a frame with a damaged CRC, a frame
STREAM = "00 ff " + READ + " 11 06 00 01 00 03 9a 9c " + WRITE


def test_python_finds_frames_by_size_and_crc(tmp_path):
    render(tmp_path, "rtu", SCHEMA)
    mod = load(tmp_path / "rtu.py")
    dec = mod.StreamDecoder()
    out = dec.feed(bytes.fromhex(STREAM))
    messages = [x for x in out if not isinstance(x, Exception)]
    assert [type(x).__name__ for x in messages] == ["ReadHoldingRegisters", "WriteSingleRegister"]
    assert (messages[0].start, messages[0].count, messages[1].value) == (107, 3, 3)
    assert any(isinstance(x, mod.DecodeError) and x.rule == "checksum" for x in out)


def test_c_finds_frames_by_size_and_crc(tmp_path):
    render(tmp_path, "rtu", SCHEMA)
    data = ", ".join(f"0x{b:02x}" for b in bytes.fromhex(STREAM))
    driver = r"""
#include <stdio.h>
#include "rtu.h"
static const uint8_t stream[] = {DATA};
int main(void) {
    rtu_message_t m;
    rtu_parser_t p;
    size_t i;
    int rc, crc_errors = 0;
    rtu_parser_init(&p, RTU_DIR_ANY);
    for (i = 0; i < sizeof stream; i++) {
        rtu_parser_feed(&p, stream[i]);
        while ((rc = rtu_parser_next(&p, &m)) != 0) {
            if (rc == 1 && m.kind == RTU_MSG_READ_HOLDING_REGISTERS) {
                printf("read %u %u\n", (unsigned)m.as.read_holding_registers.start,
                       (unsigned)m.as.read_holding_registers.count);
            } else if (rc == 1) {
                printf("write %u\n", (unsigned)m.as.write_single_register.value);
            } else if (rc == CW_ERR_CHECKSUM) {
                crc_errors++;
            }
        }
    }
    printf("crc errors %d\n", crc_errors > 0);
    return 0;
}
""".replace("DATA", data)
    assert run_c(tmp_path, driver) == ["read 107 3", "write 3", "crc errors 1"]
