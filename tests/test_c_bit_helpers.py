"""The C runtime's bit-field helpers (codeword.h: cw_put_bits, cw_get_bits and their
_wide and _lsb forms), which read and write a byte at a time: every width from 1 to 32
(and 33 to 64 for the wide ones) at every offset in two bytes, with random values and
the all-ones value, against the bits worked out here one by one, written among bits
already set (the field's own clear, as the encoders leave them), which must stay as
they are, and read back from among them; C with the sanitizers."""
from __future__ import annotations

import random
import shutil
import subprocess

from codeword.targets.c import render
from codeword.build import compile_schema
from conftest import SCHEMAS


def placed(size: int, off: int, n: int, value: int, lsb: bool, fill: int) -> bytes:
    """`size` bytes of `fill` with `value`'s n bits written at bit `off`, one at a time."""
    bits = [(fill >> (7 - b if not lsb else b)) & 1 for _ in range(size) for b in range(8)]
    for i in range(n):
        bits[off + i] = (value >> (i if lsb else n - 1 - i)) & 1
    out = bytearray(size)
    for k, bit in enumerate(bits):
        if bit:
            out[k // 8] |= (1 << (k % 8)) if lsb else (0x80 >> (k % 8))
    return bytes(out)


def test_bit_helpers_match_the_bits_one_by_one(tmp_path):
    (tmp_path / "codeword.h").write_text(render(compile_schema(SCHEMAS / "mtv4.yaml"))["c/codeword.h"],
                                         encoding="utf-8")
    rng = random.Random("bit helpers")
    cases = []
    for lsb in (False, True):
        for wide in (False, True):
            widths = range(33, 65) if wide else range(1, 33)
            for n in widths:
                for off in range(16):
                    for value in ((1 << n) - 1, rng.getrandbits(n), rng.getrandbits(n)):
                        size = (off + n + 7) // 8
                        cases.append((lsb, wide, n, off, value, size))
    lines = []
    for k, (lsb, wide, n, off, value, size) in enumerate(cases):
        suffix = ("_wide" if wide else "") + ("_lsb" if lsb else "")
        ctype = "uint64_t" if wide else "uint32_t"
        before = placed(size, off, n, 0, lsb, 0xFF)  # every other bit set, the field's clear
        want = placed(size, off, n, value, lsb, 0xFF)
        lines.append(f"    {{ static const uint8_t want[] = {{{', '.join(map(str, want))}}};"
                     f" uint8_t buf[{size}] = {{{', '.join(map(str, before))}}};"
                     f" cw_put_bits{suffix}(buf, {off}u, {n}u, ({ctype}){value}ULL);"
                     f" if (memcmp(buf, want, {size}u) != 0 || cw_get_bits{suffix}(want, {off}u, {n}u) != ({ctype}){value}ULL)"
                     f" {{ printf(\"FAIL {k}\\n\"); failures++; }} }}")
    source = ("#include <stdio.h>\n#include <string.h>\n#include \"codeword.h\"\nint main(void)\n{\n"
              "    int failures = 0;\n" + "\n".join(lines) + "\n    printf(\"%d failures\\n\", failures);\n"
              "    return failures != 0;\n}\n")
    (tmp_path / "bits.c").write_text(source, encoding="utf-8")
    gcc = shutil.which("gcc")
    assert gcc, "gcc is not installed (.ci/run installs it)"
    built = subprocess.run([gcc, "-std=c99", "-O1", "-fsanitize=address,undefined", "-fno-sanitize-recover=all",
                            "-Wall", "-Wextra", "-Wconversion", "-Wsign-conversion", "-Werror", "-I", str(tmp_path),
                            str(tmp_path / "bits.c"), "-o", str(tmp_path / "bits")], capture_output=True, text=True,
                           timeout=600)
    assert built.returncode == 0, built.stderr[-3000:]
    ran = subprocess.run([str(tmp_path / "bits")], capture_output=True, text=True, timeout=120)
    assert ran.returncode == 0 and ran.stdout.strip() == "0 failures", ran.stdout[-2000:]
    assert len(cases) == 2 * 2 * 32 * 16 * 3
