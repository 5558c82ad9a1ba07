"""f64 fields in binary framings: IEEE 754 binary64 in the field's byte order,
NaN and infinities refused as in f32 fields, ranges checked exactly. The frames
are worked out by hand (1.0 = 3FF0 0000 0000 0000, -2.5 = C004 0000 0000 0000,
pi = 4009 21FB 5444 2D18); Python and C (on the host, and on an ATmega32 under
simavr, where double has 32 bits and the member holds the bits) must agree."""
from __future__ import annotations

import json
import math
import re
import shutil
import struct
import subprocess
from pathlib import Path

import pytest

from cdriver import Driver
from codeword.build import build, compile_schema
from schema_in_a_test import load, render, run_c

SCHEMA = """codeword: 1
protocol: wide_float
title: t
source: s
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: kind, type: u8, dispatch: true}
    - {payload: true}
messages:
  sample:
    id: 1
    fields:
      - {name: a, type: f64}
      - {name: b, type: f64, byte_order: little}
      - {name: c, type: f64, range: [-10, 10.5]}
    examples:
      - name: one, minus two and a half, pi
        values: {a: 1.0, b: -2.5, c: 3.141592653589793}
        hex: "01 3ff0000000000000 00000000000004c0 400921fb54442d18"
        source: hand-computed binary64 bits; b little-endian
      - name: signed zero, smallest subnormal, low end of the range
        values: {a: -0.0, b: 5.0e-324, c: -10}
        hex: "01 8000000000000000 0100000000000000 c024000000000000"
        source: hand-computed
      - name: largest finite values, high end of the range
        values: {a: 1.7976931348623157e308, b: -1.7976931348623157e308, c: 10.5}
        hex: "01 7fefffffffffffff ffffffffffffefff 4025000000000000"
        source: hand-computed
      - name: infinity
        hex: "01 7ff0000000000000 0000000000000000 0000000000000000"
        error: {field: a, rule: finite}
      - name: NaN, little-endian
        hex: "01 0000000000000000 000000000000f87f 0000000000000000"
        error: {field: b, rule: finite}
      - name: just above the range
        hex: "01 0000000000000000 0000000000000000 4025000000000001"
        error: {field: c, rule: range}
      - name: just below the range
        hex: "01 0000000000000000 0000000000000000 c024000000000001"
        error: {field: c, rule: range}
  gate:
    id: 2
    fields:
      - {name: on, type: bool}
      - {name: pad, type: u7, reserved: true}
      - {name: d, type: f64, range: [0, 9007199254740993]}
    rules:
      - {when: {on: true}, require: {d: {range: [1, 2]}}}
      - {when: {d: 0.5}, require: {on: false}}
    examples:
      - name: on at one
        values: {on: true, d: 1.0}
        hex: "02 80 3ff0000000000000"
        source: hand-computed
      - name: minus zero is within 0 and up
        values: {on: false, d: -0.0}
        hex: "02 00 8000000000000000"
        source: hand-computed
      - name: on past two
        hex: "02 80 4000000000000001"
        error: {field: d, rule: rule}
      - name: the smallest negative subnormal is below 0
        hex: "02 00 8000000000000001"
        error: {field: d, rule: range}
"""

BITS = """codeword: 1
protocol: wide_word
title: t
source: s
framing:
  kind: bits
  word_bits: 64
  byte_order: big
messages:
  reading:
    bits: 64
    fields:
      - {name: v, type: f64, range: [-1, 1]}
    examples:
      - name: minus one
        values: {v: -1}
        hex: "bff0000000000000"
        source: hand-computed
"""

STRICT = ["-Wall", "-Wextra", "-Wpedantic", "-Wconversion", "-Wsign-conversion", "-Wshadow",
          "-Wdouble-promotion", "-Wfloat-equal", "-Wcast-qual", "-Wundef", "-Werror"]


def bits(x: float) -> str:
    return struct.pack(">d", x).hex()


def test_python_writes_and_reads_the_hand_worked_frames(tmp_path):
    mod = load(render(tmp_path, "wide_float", SCHEMA) / "wide_float.py")
    frames = [("01 3ff0000000000000 00000000000004c0 400921fb54442d18", (1.0, -2.5, math.pi)),
              ("01 8000000000000000 0100000000000000 c024000000000000", (-0.0, 5e-324, -10.0)),
              ("01 7fefffffffffffff ffffffffffffefff 4025000000000000",
               (1.7976931348623157e308, -1.7976931348623157e308, 10.5))]
    for frame, (a, b, c) in frames:
        data = bytes.fromhex(frame.replace(" ", ""))
        assert mod.encode(mod.Sample(a=a, b=b, c=c)) == data
        back = mod.decode(data)
        assert (bits(back.a), bits(back.b), bits(back.c)) == (bits(a), bits(b), bits(c))  # -0.0 kept


@pytest.mark.parametrize("values,rule", [
    (dict(a=math.nan, b=0.0, c=0.0), "finite"), (dict(a=0.0, b=math.inf, c=0.0), "finite"),
    (dict(a=0.0, b=-math.inf, c=0.0), "finite"), (dict(a=0.0, b=0.0, c=10.500000000000002), "range"),
    (dict(a=0.0, b=0.0, c=-10.000000000000002), "range"), (dict(a=10**400, b=0.0, c=0.0), "finite"),
])
def test_python_refuses_what_f32_refuses(tmp_path, values, rule):
    mod = load(render(tmp_path, "wide_float", SCHEMA) / "wide_float.py")
    with pytest.raises(mod.EncodeError) as err:
        mod.encode(mod.Sample(**values))
    assert err.value.rule == rule


def test_c_writes_and_reads_the_hand_worked_frames(tmp_path):
    render(tmp_path, "wide_float", SCHEMA)
    driver = r"""
#include <stdio.h>
#include "wide_float.h"
static void show(const uint8_t *f, size_t n)
{
    wide_float_sample_t m;
    uint8_t out[25];
    size_t i;
    int rc = wide_float_sample_decode(f, n, &m);
    printf("%s", cw_error_name(rc > 0 ? 0 : rc));
    if (rc == CW_OK) {
        rc = wide_float_sample_encode(&m, out, sizeof out);
        printf(" %d ", rc);
        for (i = 0; i < 25u; i++) printf("%02x", out[i]);
        printf(" %016llx", (unsigned long long)cw_f64_to_bits(m.c));
    }
    printf("\n");
}
int main(void)
{
    static const uint8_t f1[] = {1, 0x3f, 0xf0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0x04, 0xc0,
                                 0x40, 0x09, 0x21, 0xfb, 0x54, 0x44, 0x2d, 0x18};
    static const uint8_t f2[] = {1, 0x80, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0,
                                 0xc0, 0x24, 0, 0, 0, 0, 0, 0};
    static const uint8_t inf[] = {1, 0x7f, 0xf0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
                                  0, 0, 0, 0, 0, 0, 0, 0};
    static const uint8_t above[] = {1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
                                    0x40, 0x25, 0, 0, 0, 0, 0, 1};
    wide_float_sample_t m = {CW_F64_CONST(0x3ff0000000000000ULL, 1.0),
                             CW_F64_CONST(0xc004000000000000ULL, -2.5),
                             CW_F64_CONST(0x400921fb54442d18ULL, 3.141592653589793)};
    uint8_t out[25];
    size_t i;
    int n = wide_float_sample_encode(&m, out, sizeof out);
    printf("%d ", n);
    for (i = 0; i < 25u; i++) printf("%02x", out[i]);
    printf("\n");
    m.c = cw_f64_from_bits(0x7ff8000000000000ULL);
    printf("%s\n", cw_error_name(wide_float_sample_encode(&m, out, sizeof out)));
    m.c = cw_f64_from_bits(0xc024000000000001ULL);
    printf("%s\n", cw_error_name(wide_float_sample_encode(&m, out, sizeof out)));
    show(f1, sizeof f1);
    show(f2, sizeof f2);
    show(inf, sizeof inf);
    show(above, sizeof above);
    return 0;
}
"""
    assert run_c(tmp_path, driver, tuple(STRICT)) == [
        "25 013ff000000000000000000000000004c0400921fb54442d18",
        "finite",
        "range",
        "ok 25 013ff000000000000000000000000004c0400921fb54442d18 400921fb54442d18",
        "ok 25 01" "8000000000000000" "0100000000000000" "c024000000000000 c024000000000000",
        "finite",
        "range",
    ]


def tool(name: str) -> str:
    path = shutil.which(name)
    assert path, f"{name} is not installed (.ci/run installs it)"
    return path


def run(cmd: list, timeout: int = 300) -> subprocess.CompletedProcess:
    return subprocess.run([str(x) for x in cmd], capture_output=True, text=True, timeout=timeout, errors="replace")


def conformance_sources(tmp_path: Path, name: str, schema: str, parts: int = 1) -> tuple[Path, list[Path]]:
    """The schema built (vectors included) and its conformance driver, in `parts` parts."""
    path = tmp_path / f"{name}.yaml"
    path.write_text(schema, encoding="utf-8")
    result = build([path], tmp_path / "out", root=tmp_path)
    assert not result.errors, result.errors
    vectors = json.loads((tmp_path / "out" / "vectors" / f"{name}.json").read_text(encoding="utf-8"))
    driver = Driver(compile_schema(path))
    sources = []
    for part in range(parts):
        src = tmp_path / f"{name}_{part}.c"
        src.write_text(driver.source(vectors, part, parts), encoding="utf-8")
        sources.append(src)
    return tmp_path / "out" / "c", sources


@pytest.mark.parametrize("name,schema", [("wide_float", SCHEMA), ("wide_word", BITS)])
def test_conformance_on_the_host_with_strict_warnings(tmp_path, name, schema):
    include, (src,) = conformance_sources(tmp_path, name, schema)
    exe = tmp_path / name
    built = run([tool("gcc"), "-std=c99", "-O1", "-fsanitize=address,undefined", "-fno-sanitize-recover=all",
                 *STRICT, "-I", include, src, "-o", exe])
    assert built.returncode == 0, built.stderr[-3000:]
    result = run([exe])
    assert result.returncode == 0 and f"CONFORMANCE {name} PASS" in result.stdout, result.stdout[-3000:]
    for compiler, flags in (("clang", ["-std=c99"]), ("g++", ["-std=c++11", "-x", "c++"]),
                            ("arm-none-eabi-gcc", ["-std=c99", "-mcpu=cortex-m3", "-mthumb", "-Os"])):
        header = tmp_path / "only_header.c"
        header.write_text(f'#include "{name}.h"\nint f64_unused;\n', encoding="utf-8")
        compiled = run([tool(compiler), *flags, *STRICT, "-I", include, "-c", header, "-o", tmp_path / "h.o"])
        assert compiled.returncode == 0, (compiler, compiled.stderr[-3000:])


def test_conformance_on_avr_where_double_has_32_bits(tmp_path):
    """avr-gcc's double is binary32: the member holds the binary64 bits, and every
    vector still decodes and encodes to the same bytes (ATmega32 under simavr)."""
    include, sources = conformance_sources(tmp_path, "wide_float", SCHEMA, parts=3)
    header = tmp_path / "only_header.c"
    header.write_text('#include "wide_float.h"\nint f64_unused;\n', encoding="utf-8")
    compiled = run([tool("avr-gcc"), "-std=c99", "-Os", "-mmcu=atmega328p", *STRICT, "-I", include, "-c", header,
                    "-o", tmp_path / "h.o"])
    assert compiled.returncode == 0, compiled.stderr[-3000:]
    for src in sources:
        elf = src.with_suffix(".elf")
        built = run([tool("avr-gcc"), "-std=gnu99", "-Os", "-mmcu=atmega32", *STRICT, "-Wno-pedantic",
                     "-ffunction-sections", "-fdata-sections", "-Wl,--gc-sections", "-I", include, src, "-o", elf])
        assert built.returncode == 0, built.stderr[-3000:]
        result = run([tool("simavr"), "-m", "atmega32", "-f", "16000000", elf], timeout=600)
        assert "CONFORMANCE wide_float PASS" in result.stdout + result.stderr, (result.stdout + result.stderr)[-3000:]


# -- the helpers for firmware whose double has 32 bits ----------------------------------------

FLOATS = [0x00000000, 0x80000000, 0x00000001, 0x80000001, 0x007FFFFF, 0x00800000, 0x00400001, 0x7F7FFFFF,
          0xFF7FFFFF, 0x3F800000, 0xC0200000, 0x40490FDB, 0x7F800000, 0xFF800000, 0x7FC00000, 0x3DCCCCCD]
DOUBLES = [0.1, 1e-46, 2.0 ** -150, 3 * 2.0 ** -149, 2.0 ** -130 + 2.0 ** -149, 2.0 ** -130 + 2.0 ** -150,
           2.0 ** 128, -2.0 ** 128, math.nextafter(3.4028234663852886e38, math.inf), 2.0 ** 128 - 2.0 ** 75,
           5e-324, 1 + 2.0 ** -23, 1 + 2.0 ** -24, -0.0, math.nan, -math.inf, math.pi, 1e300, -2.5]


def widened(f32: int) -> int:
    """Python's own float32 -> double (exact), as bits."""
    return struct.unpack(">Q", struct.pack(">d", struct.unpack(">f", f32.to_bytes(4, "big"))[0]))[0]


def narrowed(x: float) -> str:
    """What cw_f64_to_float must answer: the float's bits, or the error of a value no float holds."""
    if math.isnan(x):
        return "finite"
    if abs(x) >= 2.0 ** 128 and not math.isinf(x):
        return "range"
    try:
        packed = struct.pack(">f", x)
    except OverflowError:  # rounds up past the largest float
        return "precision"
    return f"ok {packed.hex()}" if struct.unpack(">f", packed)[0] == x or math.isinf(x) else "precision"


HELPERS = r"""
#include <stdio.h>
#include "codeword.h"
#if defined(__AVR__)
#include <avr/interrupt.h>
#include <avr/io.h>
#include <avr/sleep.h>
static int uart_putchar(char c, FILE *stream)
{
    (void)stream;
    while (!(UCSRA & (1 << UDRE))) {
    }
    UDR = (uint8_t)c;
    return 0;
}
static FILE uart_out = FDEV_SETUP_STREAM(uart_putchar, NULL, _FDEV_SETUP_WRITE);
#endif
static const uint32_t floats[] = {@FLOATS@};
static const uint64_t doubles[] = {@DOUBLES@};
static const char *name(int rc)
{
    return rc == CW_OK ? "ok" : rc == CW_ERR_RANGE ? "range" : rc == CW_ERR_PRECISION ? "precision"
         : rc == CW_ERR_FINITE ? "finite" : "?";
}
int main(void)
{
    size_t i;
#if defined(__AVR__)
    UCSRB = (1 << TXEN);
    stdout = &uart_out;
#endif
    for (i = 0; i < sizeof floats / sizeof floats[0]; i++) {
        uint64_t b = cw_f64_to_bits(cw_f64_from_float(cw_f32_from_bits(floats[i])));
        float back = 0.0f;
        int rc = cw_f64_to_float(cw_f64_from_bits(b), &back);
        printf("w %08lx%08lx %s %08lx\n", (unsigned long)(b >> 32), (unsigned long)(b & 0xFFFFFFFFUL), name(rc),
               (unsigned long)cw_f32_to_bits(back));
    }
    for (i = 0; i < sizeof doubles / sizeof doubles[0]; i++) {
        float f = 0.0f;
        int rc = cw_f64_to_float(cw_f64_from_bits(doubles[i]), &f);
        if (rc == CW_OK) {
            printf("n ok %08lx\n", (unsigned long)cw_f32_to_bits(f));
        } else {
            printf("n %s\n", name(rc));
        }
    }
    printf("end\n");
#if defined(__AVR__)
    cli();
    sleep_cpu();
#endif
    return 0;
}
"""


def helper_expectations() -> list[str]:
    lines = []
    for f32 in FLOATS:
        wide = widened(f32) if f32 != 0x7FC00000 else 0x7FF8000000000000  # the quiet NaN, payload moved
        back = "finite 00000000" if f32 == 0x7FC00000 else f"ok {f32:08x}"
        lines.append(f"w {wide:016x} {back}")
    return lines + [f"n {narrowed(x)}" for x in DOUBLES] + ["end"]


def helper_source() -> str:
    doubles = (struct.unpack(">Q", struct.pack(">d", x))[0] for x in DOUBLES)
    return (HELPERS.replace("@FLOATS@", ", ".join(f"{x:#010x}UL" for x in FLOATS))
            .replace("@DOUBLES@", ", ".join(f"{x:#018x}ULL" for x in doubles)))


def test_float_helpers_widen_exactly_and_narrow_only_exact_values(tmp_path):
    render(tmp_path, "wide_float", SCHEMA)
    assert run_c(tmp_path, helper_source(), tuple(STRICT)) == helper_expectations()


def test_float_helpers_on_avr(tmp_path):
    render(tmp_path, "wide_float", SCHEMA)
    src, elf = tmp_path / "helpers.c", tmp_path / "helpers.elf"
    src.write_text(helper_source(), encoding="utf-8")
    built = run([tool("avr-gcc"), "-std=gnu99", "-Os", "-mmcu=atmega32", *STRICT, "-Wno-pedantic",
                 "-I", tmp_path, src, "-o", elf])
    assert built.returncode == 0, built.stderr[-3000:]
    result = run([tool("simavr"), "-m", "atmega32", "-f", "16000000", elf], timeout=300)
    output = re.sub(r"\x1b\[[0-9;]*m", "", result.stdout + result.stderr)
    lines = [line.rstrip(".").strip() for line in output.splitlines()]
    start = lines.index(helper_expectations()[0])
    assert lines[start:start + len(helper_expectations())] == helper_expectations()
