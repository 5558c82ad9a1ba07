"""codeword.h's SHA-256 against hashlib: FIPS 180-4's "abc" example and random inputs
of every length from 0 to 300 bytes (the padding's edges at 55, 56, 63 and 64 among
them), each hashed whole and in two pieces, compiled with the sanitizers and the strict
warnings, on the host and, for the boundary lengths, on an ATmega328P under simavr."""
from __future__ import annotations

import hashlib
import random
import shutil
import subprocess
from pathlib import Path

import pytest

from codeword.targets.render import environment
from schema_in_a_test import c_bytes, run_c

STRICT = ("-Wpedantic", "-Wconversion", "-Wsign-conversion", "-Wshadow")


def runtime(where: Path) -> Path:
    (where / "codeword.h").write_text(environment().get_template("c/codeword.h.j2").render(), encoding="utf-8")
    return where


def inputs(seed: int = 180) -> list[bytes]:
    rng = random.Random(seed)
    out = [b"abc"]
    for n in range(301):
        out.append(bytes(rng.getrandbits(8) for _ in range(n)))
    return out


def driver(cases: list[bytes]) -> str:
    table = "\n".join(f"static const uint8_t in{i}[] = {{{c_bytes(c) or '0'}}};" for i, c in enumerate(cases))
    rows = ",\n".join(f"    {{in{i}, {len(c)}u}}" for i, c in enumerate(cases))
    return """#include <stdio.h>
#include "codeword.h"
TABLE
static const struct { const uint8_t *p; size_t n; } cases[] = {
ROWS
};
static void show(const uint8_t d[32]) {
    unsigned i;
    for (i = 0; i < 32u; i++) printf("%02x", d[i]);
}
int main(void) {
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        cw_sha256_t s;
        uint8_t whole[32], split[32];
        size_t cut = cases[i].n / 3u;
        cw_sha256_init(&s);
        cw_sha256_update(&s, cases[i].p, cases[i].n);
        cw_sha256_final(&s, whole);
        cw_sha256_init(&s);  /* the same bytes in two pieces, the first not a whole block */
        cw_sha256_update(&s, cases[i].p, cut);
        cw_sha256_update(&s, cases[i].p + cut, cases[i].n - cut);
        cw_sha256_final(&s, split);
        show(whole);
        printf(" ");
        show(split);
        printf("\\n");
    }
    return 0;
}
""".replace("TABLE", table).replace("ROWS", rows)


def test_fips_180_4_abc():
    """FIPS 180-4 (and its example document) give SHA-256("abc")."""
    assert hashlib.sha256(b"abc").hexdigest() == \
        "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"


def test_c_sha256_agrees_with_hashlib_on_the_host(tmp_path):
    cases = inputs()
    lines = run_c(runtime(tmp_path), driver(cases), STRICT)
    expected = [f"{hashlib.sha256(c).hexdigest()} {hashlib.sha256(c).hexdigest()}" for c in cases]
    assert lines == expected
    assert lines[0].split()[0] == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"


AVR_MAIN = r"""#include <stdio.h>
#include <avr/io.h>
#include <avr/interrupt.h>
#include <avr/sleep.h>
#include "codeword.h"
static int uart_putchar(char c, FILE *stream)
{
    (void)stream;
    while (!(UCSRA & (1 << UDRE))) {
    }
    UDR = (uint8_t)c;
    return 0;
}
static FILE uart_out = FDEV_SETUP_STREAM(uart_putchar, NULL, _FDEV_SETUP_WRITE);
TABLE
static const struct { const uint8_t *p; size_t n; const uint8_t *want; } cases[] = {
ROWS
};
int main(void)
{
    size_t i;
    unsigned ok = 0;
    UCSRB = (1 << TXEN);
    stdout = &uart_out;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        cw_sha256_t s;
        uint8_t d[32];
        cw_sha256_init(&s);
        cw_sha256_update(&s, cases[i].p, cases[i].n);
        cw_sha256_final(&s, d);
        if (memcmp(d, cases[i].want, 32u) == 0) {
            ok++;
        } else {
            printf("SHA FAIL %u\n", (unsigned)i);
        }
    }
    printf("SHA %u OF %u\n", ok, (unsigned)(sizeof cases / sizeof cases[0]));
    cli();
    sleep_cpu();
    return 0;
}
"""


def test_c_sha256_on_avr_at_the_padding_edges(tmp_path):
    """AVR's int is 16 bits: every shift and sum must still be done in 32."""
    if not (shutil.which("avr-gcc") and shutil.which("simavr")):
        pytest.fail("avr-gcc and simavr are needed (.ci/run installs them)")
    rng = random.Random(5)
    cases = [b"abc"] + [bytes(rng.getrandbits(8) for _ in range(n)) for n in (0, 1, 55, 56, 57, 63, 64, 65, 119, 120, 128)]
    table = "\n".join(f"static const uint8_t in{i}[] = {{{c_bytes(c) or '0'}}};\n"
                      f"static const uint8_t want{i}[] = {{{c_bytes(hashlib.sha256(c).digest())}}};"
                      for i, c in enumerate(cases))
    rows = ",\n".join(f"    {{in{i}, {len(c)}u, want{i}}}" for i, c in enumerate(cases))
    src, elf = tmp_path / "sha.c", tmp_path / "sha.elf"
    runtime(tmp_path)
    src.write_text(AVR_MAIN.replace("TABLE", table).replace("ROWS", rows), encoding="utf-8")
    build = subprocess.run(["avr-gcc", "-std=gnu99", "-Os", "-mmcu=atmega32", "-Wall", "-Wextra", "-Werror",
                            "-I", str(tmp_path), str(src), "-o", str(elf)], capture_output=True, text=True, timeout=300)
    assert build.returncode == 0, build.stderr
    run = subprocess.run(["simavr", "-m", "atmega32", "-f", "16000000", str(elf)],
                         capture_output=True, text=True, timeout=300, errors="replace")
    assert f"SHA {len(cases)} OF {len(cases)}" in run.stdout + run.stderr, run.stdout[-2000:] + run.stderr[-2000:]
