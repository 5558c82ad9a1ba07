"""A range on an f32 field: integer bounds (`range: [0, 100]`) must make C that
compiles under the strict flags, and the C checks must agree with Python, which
compares the decoded binary32 value with the bound itself. Frames are hand-made:
kind 01, then the big-endian binary32 bits (100.0 is 42c80000, the next float up
42c80001; 0.1 rounds up to 3dcccccd = 0.10000000149…, the float below is 3dcccccc)."""
from __future__ import annotations

import subprocess
import shutil

import pytest

from schema_in_a_test import load, render, run_c, show_calls

STRICT = ["-std=c99", "-Wall", "-Wextra", "-Wpedantic", "-Wconversion", "-Wsign-conversion", "-Wshadow", "-Werror"]

SCHEMA = """codeword: 1
protocol: {name}
title: t
source: s
framing:
  kind: bytes
  byte_order: big
  layout:
    - {{name: kind, type: u8, dispatch: true}}
    - {{payload: true}}
messages:
  a:
    id: 1
    fields:
      - {{name: x, type: f32, range: {range}}}
"""

SHOW = """#include <stdio.h>
#include "{name}.h"
static void show(const char *hex, const uint8_t *frame, size_t len) {{
    {name}_a_t m;
    int rc = {name}_a_decode(frame, len, &m);
    (void)hex;
    printf("%s\\n", rc == CW_OK ? "ok" : cw_error_name(rc));
}}
int main(void) {{
{calls}
    return 0;
}}
"""


def python_verdicts(mod, frames: list[str]) -> list[str]:
    out = []
    for frame in frames:
        try:
            mod.decode(bytes.fromhex(frame))
            out.append("ok")
        except mod.DecodeError as err:
            out.append(err.rule)
    return out


@pytest.mark.parametrize("compiler", ["gcc", "clang"])
@pytest.mark.parametrize("opt", ["-O0", "-O2", "-Os"])
def test_integer_bounds_compile_warning_free(tmp_path, compiler, opt):
    cc = shutil.which(compiler)
    assert cc, f"{compiler} is not installed"
    render(tmp_path, "fint", SCHEMA.format(name="fint", range="[0, 100]"))
    src = tmp_path / "use.c"
    src.write_text('#include "fint.h"\nint main(void) { return 0; }\n', encoding="utf-8")
    built = subprocess.run([cc, *STRICT, opt, "-I", str(tmp_path), "-c", str(src), "-o", str(tmp_path / "use.o")],
                           capture_output=True, text=True, timeout=120)
    assert built.returncode == 0, built.stderr


@pytest.mark.parametrize("name, bounds, frames, expected", [
    ("fint", "[0, 100]", ["01 42c80000", "01 42c80001", "01 00000000", "01 80000000", "01 80000001"],
     ["ok", "range", "ok", "ok", "range"]),
    ("fdec", "[-0.1, 0.1]", ["01 3dcccccc", "01 3dcccccd", "01 bdcccccc", "01 bdcccccd"],
     ["ok", "range", "ok", "range"]),
    # 16777217 lies between the floats 16777216 (4b800000) and 16777218 (4b800001)
    ("fbig", "[16777217, 1e39]", ["01 4b800000", "01 4b800001", "01 7f7fffff"], ["range", "ok", "ok"]),
])
def test_c_decides_each_bound_as_python_does(tmp_path, name, bounds, frames, expected):
    render(tmp_path, name, SCHEMA.format(name=name, range=bounds))
    assert python_verdicts(load(tmp_path / f"{name}.py"), frames) == expected
    assert run_c(tmp_path, SHOW.format(name=name, calls=show_calls(frames))) == expected


def test_c_encoder_refuses_the_float_just_past_a_bound(tmp_path):
    render(tmp_path, "fenc", SCHEMA.format(name="fenc", range="[0, 100]"))
    driver = """#include <stdio.h>
#include <string.h>
#include "fenc.h"
int main(void) {
    fenc_a_t m;
    uint8_t buf[8];
    uint32_t past = 0x42c80001UL;
    memcpy(&m.x, &past, sizeof past);
    printf("%s\\n", cw_error_name(fenc_a_encode(&m, buf, sizeof buf)));
    m.x = 100.0f;
    printf("%d\\n", fenc_a_encode(&m, buf, sizeof buf));
    return 0;
}
"""
    assert run_c(tmp_path, driver) == ["range", "5"]
