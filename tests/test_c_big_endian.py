"""The conformance vectors through the generated C on a big-endian target: s390x,
cross-compiled and run under qemu-user. codeword.h takes its byte-by-byte path there
(the compiler says __BYTE_ORDER__ is big-endian), so every multi-byte field, CRC and
length is read and written as on a big-endian MCU, and must agree with Python.

A missing cross compiler or qemu is a failure, not a skip: `.ci/run` installs them.
"""
from __future__ import annotations

import json
import subprocess
from pathlib import Path

import pytest

from codeword.build import compile_schema

from cdriver import Driver
from conftest import PROTOCOLS, ROOT
from test_c import passed, tool

EXAMPLES = ("dynamixel2", "mavlink1", "mavlink2", "modbus_rtu", "nmea0183", "ubx")


def where(name: str) -> tuple[Path, Path, Path]:
    """The schema, the vectors and the C folder of a seed protocol or an example."""
    if name in PROTOCOLS:
        return ROOT / "schemas" / f"{name}.yaml", ROOT / "generated" / "vectors" / f"{name}.json", \
            ROOT / "generated" / "c"
    return ROOT / "examples" / f"{name}.yaml", ROOT / "generated" / "examples" / "vectors" / f"{name}.json", \
        ROOT / "generated" / "examples" / "c"


def test_the_target_is_big_endian(tmp_path):
    src = tmp_path / "order.c"
    src.write_text("#include <stdio.h>\n#include <stdint.h>\n"
                   "int main(void) { uint16_t x = 0x0102; unsigned char b[2];\n"
                   "  b[0] = ((unsigned char *)&x)[0]; b[1] = ((unsigned char *)&x)[1];\n"
                   "  printf(\"%d %d %d\\n\", b[0], b[1], __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__); return 0; }\n")
    exe = tmp_path / "order"
    subprocess.run([tool("s390x-linux-gnu-gcc"), "-static", str(src), "-o", str(exe)], check=True)
    out = subprocess.run([tool("qemu-s390x"), str(exe)], capture_output=True, text=True, check=True).stdout
    assert out.split() == ["1", "2", "1"]


@pytest.mark.parametrize("crc", ["default", "BITWISE", "SLICE8"])
@pytest.mark.parametrize("name", PROTOCOLS + EXAMPLES)
def test_conformance_on_a_big_endian_target(tmp_path, name, crc):
    schema, vectors, include = where(name)
    define = [f"-D{name.upper()}_CRC_{crc}"] if crc != "default" else []
    src = tmp_path / f"{name}.c"
    src.write_text(Driver(compile_schema(schema)).source(json.loads(vectors.read_text(encoding="utf-8"))))
    exe = tmp_path / name
    build = subprocess.run([tool("s390x-linux-gnu-gcc"), "-std=c99", "-O1", "-static", "-Wall", "-Wextra",
                            "-Werror", *define, "-I", str(include), str(src), "-o", str(exe)],
                           capture_output=True, text=True, timeout=300)
    assert build.returncode == 0, build.stderr
    result = subprocess.run([tool("qemu-s390x"), str(exe)], capture_output=True, text=True, timeout=600,
                            errors="replace")
    assert result.returncode == 0 and passed(result.stdout, name), (result.stdout + result.stderr)[-3000:]
    assert int(passed(result.stdout, name).group(1)) > 100
