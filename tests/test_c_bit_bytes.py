"""The C a bit field is moved with (codeword.targets.c.bitbytes: a constant shift per byte
the field touches, in either bit order): every width from 1 to 64 at every offset in two
bytes, with random values and the all-ones value, against the bits worked out here one
by one, written among bits already set (the field's own clear, as the encoders leave
them), which must stay as they are, and read back from among them; C with the sanitizers
and the strict warnings."""
from __future__ import annotations

import random
import shutil
import subprocess

from codeword.targets.c.bitbytes import get_expression, put_statements, value_type


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


def test_bit_fields_match_the_bits_one_by_one(tmp_path):
    rng = random.Random("bit bytes")
    cases = [(lsb, n, off, value) for lsb in (False, True) for n in range(1, 65) for off in range(16)
             for value in ((1 << n) - 1, rng.getrandbits(n), rng.getrandbits(n))]
    lines = []
    for k, (lsb, n, off, value) in enumerate(cases):
        order, vt, size = "little" if lsb else "big", value_type(n), (off + n + 7) // 8
        before = placed(size, off, n, 0, lsb, 0xFF)  # every other bit set, the field's clear
        want = placed(size, off, n, value, lsb, 0xFF)
        puts = " ".join(put_statements("buf", off, n, order, "v", vt))
        lines.append(f"    {{ static const uint8_t want[] = {{{', '.join(map(str, want))}}};"
                     f" uint8_t buf[{size}] = {{{', '.join(map(str, before))}}};"
                     f" {vt} v = ({vt}){value}ULL; {puts}"
                     f" if (memcmp(buf, want, {size}u) != 0 || {get_expression('want', off, n, order)} != v)"
                     f" {{ printf(\"FAIL {k}\\n\"); failures++; }} }}")
    source = ("#include <stdint.h>\n#include <stdio.h>\n#include <string.h>\nint main(void)\n{\n"
              "    int failures = 0;\n" + "\n".join(lines) + "\n    printf(\"%d failures\\n\", failures);\n"
              "    return failures != 0;\n}\n")
    (tmp_path / "bits.c").write_text(source, encoding="utf-8")
    gcc = shutil.which("gcc")
    assert gcc, "gcc is not installed (.ci/run installs it)"
    built = subprocess.run([gcc, "-std=c99", "-O1", "-fsanitize=address,undefined", "-fno-sanitize-recover=all",
                            "-Wall", "-Wextra", "-Wconversion", "-Wsign-conversion", "-Werror",
                            str(tmp_path / "bits.c"), "-o", str(tmp_path / "bits")], capture_output=True, text=True,
                           timeout=900)
    assert built.returncode == 0, built.stderr[-3000:]
    ran = subprocess.run([str(tmp_path / "bits")], capture_output=True, text=True, timeout=120)
    assert ran.returncode == 0 and ran.stdout.strip() == "0 failures", ran.stdout[-2000:]
    assert len(cases) == 2 * 64 * 16 * 3
