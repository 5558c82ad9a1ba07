"""The generated C headers, compiled and run: the warning matrix, the
conformance vectors on the host under ASan/UBSan, on an ATmega32 under simavr
and on a Cortex-M3 under qemu. Python and C must agree on every vector.

A missing compiler is a failure, not a skip: `.ci/run` installs them all.
"""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

from codeword.build import compile_schema
from codeword.targets.c.crc import DEFAULT, METHODS

from cdriver import Driver, firmware_source, load_vectors
from conftest import PROTOCOLS, ROOT, load_model

INCLUDE = ROOT / "generated" / "c"
EXAMPLES = ROOT / "generated" / "examples" / "c"
LEVELS = ["-O0", "-O2", "-Os"]  # what -O2/-Os inline and analyse warns of more
WARNINGS = ["-Wall", "-Wextra", "-Wpedantic", "-Wconversion", "-Wsign-conversion", "-Wshadow", "-Werror"]
MATRIX = [
    ("gcc", ["-std=c99"]), ("gcc", ["-std=c11"]), ("clang", ["-std=c99"]), ("clang", ["-std=c11"]),
    ("g++", ["-std=c++11", "-x", "c++"]), ("clang++", ["-std=c++11", "-x", "c++"]),
]
CORTEX_M = Path(__file__).resolve().parent / "cortex_m"


def tool(name: str) -> str:
    path = shutil.which(name)
    assert path, f"{name} is not installed (.ci/run installs it)"
    return path


# The default CRC method (no macro), then each other one by its macro.
CRC_METHODS = ["default"] + [m.guard for m in METHODS if m.guard != DEFAULT]


def run(cmd: list[str], timeout: int = 300) -> subprocess.CompletedProcess:
    return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, errors="replace")


def all_headers(tmp_path: Path, folder: Path = INCLUDE) -> Path:
    """Every header of `folder` in one translation unit, each protocol's codec used as
    firmware uses it (cdriver.firmware_source): an unused inline function is never
    compiled, and -O2/-Os warn of what only their inlining and flow analysis see."""
    names = sorted(path.stem for path in folder.glob("*.h") if path.stem != "codeword")
    src = tmp_path / "all.c"
    src.write_text("".join(f'#include "{name}.h"\n' for name in names) + "\n"
                   + "".join(firmware_source(compile_schema(schema_of(folder, name)), include=False)
                             for name in names)
                   + "int main(void) { return 0; }\n")
    return src


def schema_of(folder: Path, name: str) -> Path:
    return (ROOT / "examples" if folder == EXAMPLES else ROOT / "schemas") / f"{name}.yaml"


@pytest.mark.parametrize("level", LEVELS)
@pytest.mark.parametrize("compiler,flags", MATRIX, ids=[f"{c}{' '.join(f[:1])}" for c, f in MATRIX])
@pytest.mark.parametrize("crc", CRC_METHODS)
def test_headers_compile_together_without_warnings(tmp_path, compiler, flags, crc, level):
    """All five headers in one translation unit: no clashing names, no warnings."""
    defines = [f"-D{p.upper()}_CRC_{crc}" for p in PROTOCOLS] if crc != "default" else []
    result = run([tool(compiler), *flags, level, *WARNINGS, *defines, "-I", str(INCLUDE), "-c",
                  str(all_headers(tmp_path)), "-o", str(tmp_path / "all.o")])
    assert result.returncode == 0, result.stderr


@pytest.mark.parametrize("level", LEVELS)
@pytest.mark.parametrize("compiler", ["gcc", "clang"])
@pytest.mark.parametrize("crc", CRC_METHODS)
def test_example_headers_compile_together_without_warnings(tmp_path, compiler, crc, level):
    """The third-party examples (generated/examples/c) as the project's own headers."""
    names = sorted(path.stem for path in EXAMPLES.glob("*.h") if path.stem != "codeword")
    assert len(names) >= 5, names
    defines = [f"-D{name.upper()}_CRC_{crc}" for name in names] if crc != "default" else []
    result = run([tool(compiler), "-std=c99", level, *WARNINGS, *defines, "-I", str(EXAMPLES), "-c",
                  str(all_headers(tmp_path, EXAMPLES)), "-o", str(tmp_path / "all.o")])
    assert result.returncode == 0, result.stderr


def driver(tmp_path: Path, name: str, part: int = 0, parts: int = 1) -> Path:
    src = tmp_path / f"{name}_{part}.c"
    src.write_text(Driver(load_model(name)).source(load_vectors(name), part, parts))
    return src


def passed(output: str, name: str) -> re.Match:
    clean = re.sub(r"\x1b\[[0-9;]*m", "", output)
    return re.search(rf"CONFORMANCE {name} PASS (\d+) checks 0 failures", clean)


@pytest.mark.parametrize("name", PROTOCOLS)
@pytest.mark.parametrize("crc", CRC_METHODS)
def test_conformance_on_host_with_sanitizers(tmp_path, name, crc):
    define = [f"-D{name.upper()}_CRC_{crc}"] if crc != "default" else []
    exe = tmp_path / name
    build = run([tool("gcc"), "-std=c99", "-g", "-O1", "-fsanitize=address,undefined",
                 "-fno-sanitize-recover=all", "-Wall", "-Wextra", "-Werror", *define, "-I", str(INCLUDE),
                 str(driver(tmp_path, name)), "-o", str(exe)])
    assert build.returncode == 0, build.stderr
    result = run([str(exe)])
    assert result.returncode == 0 and passed(result.stdout, name), result.stdout + result.stderr
    assert int(passed(result.stdout, name).group(1)) > 500


@pytest.mark.parametrize("name", PROTOCOLS)
def test_conformance_on_host_through_the_portable_byte_access(tmp_path, name):
    """codeword.h reads and writes little-endian integers with memcpy where the compiler
    says the target is little-endian (__BYTE_ORDER__), and byte by byte elsewhere: on
    big-endian targets and compilers without the macro. Undefined, the host runs the
    byte-by-byte path, which no other host build compiles."""
    exe = tmp_path / name
    build = run([tool("gcc"), "-std=c99", "-g", "-O1", "-U__BYTE_ORDER__", "-fsanitize=address,undefined",
                 "-fno-sanitize-recover=all", *WARNINGS, "-I", str(INCLUDE),
                 str(driver(tmp_path, name)), "-o", str(exe)])
    assert build.returncode == 0, build.stderr
    result = run([str(exe)])
    assert result.returncode == 0 and passed(result.stdout, name), result.stdout + result.stderr
    assert int(passed(result.stdout, name).group(1)) > 500


def test_mtv4_codec_meets_the_avr_size_target(tmp_path):
    """scripts/size-report --check: encoding and decoding one SetWheelsVelocities
    frame with its CRC takes at most 400 B flash and 64 B static RAM on an
    ATmega32 (avr-gcc -Os, gc-sections), measured above an empty program; and no
    static RAM at all, as the README says (measured: 0 B)."""
    for name in ("avr-gcc", "avr-size", "avr-nm", "avr-objdump"):
        tool(name)
    result = run([sys.executable, str(ROOT / "scripts" / "size-report"), "--check",
                  "--output", str(tmp_path / "c-size.md")])
    assert result.returncode == 0, (result.stdout + result.stderr)[-3000:]
    measured = re.search(r"target for mtv4 .*: met, (\d+) B flash and (\d+) B static RAM", result.stdout)
    assert measured, result.stdout[-3000:]
    assert int(measured.group(2)) == 0, measured.group(0)
    assert "and no static RAM)" in (ROOT / "README.md").read_text(encoding="utf-8")


# ATmega32: 32 KiB flash, 2 KiB RAM; vectors go to flash in parts that fit
# (tank: its ~1600 vectors hold ~130 KB of text, and a text stream with its events takes a part a few KB).
AVR_PARTS = {"route": 5, "car": 4, "tank": 36, "mtv4": 8, "tr24": 3}


@pytest.mark.parametrize("name", PROTOCOLS)
def test_conformance_on_atmega32_under_simavr(tmp_path, name):
    parts = AVR_PARTS[name]
    sources = [driver(tmp_path, name, part, parts) for part in range(parts)]

    def build_and_run(src: Path) -> str:
        elf = src.with_suffix(".elf")
        build = run([tool("avr-gcc"), "-std=gnu99", "-Os", "-mmcu=atmega32", "-Wall", "-Wextra", "-Werror",
                     "-ffunction-sections", "-fdata-sections", "-Wl,--gc-sections",
                     "-I", str(INCLUDE), str(src), "-o", str(elf)])
        if build.returncode != 0:
            return f"{src.name}: build failed\n{build.stderr[-3000:]}"
        result = run([tool("simavr"), "-m", "atmega32", "-f", "16000000", str(elf)], timeout=600)
        return f"{src.name}: " + result.stdout + result.stderr

    with ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        outputs = list(pool.map(build_and_run, sources))
    total = 0
    for output in outputs:
        found = passed(output, name)
        assert found, output[-3000:]
        total += int(found.group(1))
    assert total > 500


# lm3s6965: 256 KiB flash; tank's vectors (long text lines) need several parts.
QEMU_PARTS = {"tank": 6}


@pytest.mark.parametrize("name", PROTOCOLS)
def test_conformance_on_cortex_m3_under_qemu(tmp_path, name):
    total = 0
    for part in range(QEMU_PARTS.get(name, 1)):
        elf = tmp_path / f"{name}_{part}.elf"
        build = run([tool("arm-none-eabi-gcc"), "-mcpu=cortex-m3", "-mthumb", "-std=gnu99", "-Os",
                     "-Wall", "-Wextra", "-Werror", "-ffunction-sections", "-fdata-sections",
                     "-Wl,--gc-sections", "--specs=rdimon.specs",
                     "-T", str(CORTEX_M / "lm3s6965.ld"), str(CORTEX_M / "startup.c"), "-I", str(INCLUDE),
                     str(driver(tmp_path, name, part, QEMU_PARTS.get(name, 1))), "-o", str(elf)])
        assert build.returncode == 0, build.stderr[-3000:]
        result = run([tool("qemu-system-arm"), "-M", "lm3s6965evb", "-nographic", "-semihosting-config",
                      "enable=on,target=native", "-kernel", str(elf)], timeout=600)
        found = passed(result.stdout + result.stderr, name)
        assert result.returncode == 0 and found, (result.stdout + result.stderr)[-3000:]
        total += int(found.group(1))
    assert total > 500


def test_a_header_refuses_two_crc_methods(tmp_path):
    """One method for all of a header's CRCs: two macros at once are an error, not a silent choice."""
    src = tmp_path / "two.c"
    src.write_text('#include "mtv4.h"\nint main(void) { return 0; }\n')
    result = run([tool("gcc"), "-std=c99", "-DMTV4_CRC_TABLE", "-DMTV4_CRC_SLICE4", "-I", str(INCLUDE), "-c",
                  str(src), "-o", str(tmp_path / "two.o")])
    assert result.returncode != 0 and "define at most one of MTV4_CRC_BITWISE" in result.stderr, result.stderr
