"""examples/nmea0183.yaml against published NMEA 0183 sentences and an independent
parser (pynmea2): the values it reads are the values pynmea2 reads, Python and C
write each sentence back byte for byte, and a corrupted checksum is refused. The
C decoder also passes the schema's conformance vectors, on the host with
sanitizers and under simavr on an ATmega32 (16-bit int, 32-bit double)."""
from __future__ import annotations

import json
from decimal import ROUND_HALF_UP, Decimal
import os
import re
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

import pynmea2  # the test extra (scripts/setup installs it)
import pytest

from cdriver import Driver
from codeword.build import compile_schema
from conftest import ROOT
from schema_in_a_test import C_FLAGS, load, run_c


SCHEMA = ROOT / "examples" / "nmea0183.yaml"
SENTENCES = [  # gpsd's "NMEA 0183 revealed"
    "$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47",
    "$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A",
    "$GPVTG,054.7,T,034.4,M,005.5,N,010.2,K*48",
]


# Receivers' own spellings: more decimals, `8` for `08`, `.00` on the time. Each is read
# at the schema's decimals (NMEA-D2): pynmea2's number rounded to the field's step.
RECEIVER_SENTENCES = [
    # SiRF's GGA example (NMEA Reference Manual), as quoted in "NMEA 0183 standard" pages
    "$GPGGA,092750.000,5321.6802,N,00630.3372,W,1,8,1.03,61.7,M,55.2,M,,*76",
    # a Hemisphere VS110 on R/V Sette, NOAA PSL raw GPS log WHOTS 2022 (gps02220604_raw.txt)
    "$GPGGA,040001.00,2246.08014690,N,15755.97486679,W,2,07,1.1,15.8,M,0.4,M,7.0,0133*50",
    # Deltares Markermeer survey log 2007 (loc11GPS.txt)
    "$GPGGA,132421.00,5231.91448,N,00516.97727,E,1,04,4.6,6.6,M,46.6,M,,*62",
]


def at_step(text: str, decimals: int) -> float:
    """pynmea2's number text rounded to `decimals`, halves away from zero, by decimal arithmetic."""
    value = Decimal(text).quantize(Decimal(1).scaleb(-decimals), rounding=ROUND_HALF_UP)
    return float(value)


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    out = tmp_path_factory.mktemp("nmea")
    run = subprocess.run([sys.executable, "-m", "codeword", "build", str(SCHEMA), "--out", str(out)],
                         capture_output=True, text=True, timeout=300, cwd=ROOT)
    assert run.returncode == 0, run.stdout + run.stderr
    return out


def wire(value) -> str:
    """A decoded value as the text NMEA would hold for it, to compare with pynmea2's fields."""
    if value is None:
        return ""
    if hasattr(value, "_value_"):
        return value._value_
    return repr(float(value)) if isinstance(value, float) else str(value)


def as_number(text: str):
    return float(text) if text else None


@pytest.mark.parametrize("sentence", SENTENCES)
def test_values_agree_with_pynmea2(built, sentence):
    mod = load(built / "python" / "nmea0183.py")
    ours = mod.decode(sentence + "\r\n")
    theirs = pynmea2.parse(sentence)
    message = next(m for m in compile_schema(SCHEMA).messages if m.name == type(ours).NAME)
    names = [leaf.field.name for leaf in message.wire.leaves]  # in line order
    assert len(names) <= len(theirs.data)
    for name, text in zip(names, theirs.data):
        value = getattr(ours, name)
        if value is None or isinstance(value, (int, float)) and not hasattr(value, "_value_"):
            assert value == as_number(text), (name, value, text)  # 4807.038 == float("4807.038")
        else:
            assert wire(value) == text, (name, value, text)


@pytest.mark.parametrize("sentence", RECEIVER_SENTENCES)
def test_receiver_spellings_read_as_pynmea2_reads_them(built, sentence):
    mod = load(built / "python" / "nmea0183.py")
    ours = mod.decode(sentence + "\r\n")
    theirs = pynmea2.parse(sentence, check=True)
    message = next(m for m in compile_schema(SCHEMA).messages if m.name == type(ours).NAME)
    raws = []
    for leaf, text in zip(message.wire.leaves, theirs.data):
        f, value = leaf.field, getattr(ours, leaf.field.name)
        if f.kind in ("int", "uint") and f.enum is None:
            want = at_step(text, f.decimals or 0) if text else None
            assert value == want, (f.name, value, text)
            raws.append(0 if value is None else round(value * 10 ** (f.decimals or 0)))
        else:
            assert wire(value) == text, (f.name, value, text)
    # the C decoder reads the same raw values
    names = [leaf.field.name for leaf in message.wire.leaves if leaf.field.kind in ("int", "uint")
             and leaf.field.enum is None]
    driver = r"""
#include <stdio.h>
#include <string.h>
#include "nmea0183.h"
int main(void) {
    static const char line[] = "LINE\r\n";
    nmea0183_gga_t m;
    memset(&m, 0, sizeof m);
    printf("%d\n", nmea0183_gga_decode(line, sizeof line - 1, &m));
PRINTS
    return 0;
}
""".replace("LINE", sentence).replace("PRINTS", "\n".join(f'    printf("%ld\\n", (long)m.{n});' for n in names))
    assert run_c(built / "c", driver) == ["0"] + [str(r) for r in raws]


@pytest.mark.parametrize("sentence", SENTENCES)
def test_python_writes_each_sentence_back(built, sentence):
    mod = load(built / "python" / "nmea0183.py")
    assert mod.encode(mod.decode(sentence + "\r\n")) == sentence + "\r\n"


def test_a_corrupted_checksum_is_refused(built):
    mod = load(built / "python" / "nmea0183.py")
    for sentence in SENTENCES:
        bad = sentence[:-1] + ("0" if sentence[-1] != "0" else "1") + "\r\n"
        with pytest.raises(mod.DecodeError) as err:
            mod.decode(bad)
        assert err.value.rule == "checksum" and err.value.offset == sentence.index("*")
        assert pynmea2.parse(sentence)  # the untouched one is good for pynmea2 too
        with pytest.raises(pynmea2.ChecksumError):
            pynmea2.parse(bad.strip(), check=True)


def test_c_writes_each_sentence_back_and_refuses_a_bad_checksum(built):
    calls = "\n".join(f'    round_trip("{s}\\r\\n");' for s in SENTENCES)
    driver = r"""
#include <stdio.h>
#include <string.h>
#include "nmea0183.h"
static void round_trip(const char *line) {
    nmea0183_message_t m;
    char buf[100];
    int rc, n;
    memset(&m, 0, sizeof m);
    rc = nmea0183_decode(line, strlen(line), NMEA0183_DIR_ANY, &m);
    n = nmea0183_encode(&m, buf, sizeof buf);
    printf("%d %d\n", rc, n > 0 && (size_t)n == strlen(line) && memcmp(buf, line, (size_t)n) == 0);
}
int main(void) {
    nmea0183_message_t m;
    static const char bad[] = "$GPVTG,054.7,T,034.4,M,005.5,N,010.2,K*49\r\n";
CALLS
    printf("%d\n", nmea0183_decode(bad, sizeof bad - 1, NMEA0183_DIR_ANY, &m) == CW_ERR_CHECKSUM);
    return 0;
}
""".replace("CALLS", calls)
    assert run_c(built / "c", driver) == ["0 1"] * len(SENTENCES) + ["1"]


def conformance_driver(built, part: int = 0, parts: int = 1) -> str:
    vectors = json.loads((built / "vectors" / "nmea0183.json").read_text())
    return Driver(compile_schema(SCHEMA)).source(vectors, part, parts)


def test_c_conformance_on_the_host(built, tmp_path):
    src, exe = tmp_path / "conf.c", tmp_path / "conf"
    src.write_text(conformance_driver(built))
    build = subprocess.run(["gcc", *C_FLAGS, "-Wconversion", "-Wsign-conversion", "-Wshadow", "-Wpedantic",
                            "-I", str(built / "c"), str(src), "-o", str(exe)],
                           capture_output=True, text=True, timeout=300)
    assert build.returncode == 0, build.stderr
    run = subprocess.run([str(exe)], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0 and re.search(r"CONFORMANCE nmea0183 PASS \d+ checks 0 failures", run.stdout), \
        run.stdout[-3000:] + run.stderr


AVR_PARTS = 8  # the vectors' text lines take about 100 KB: in parts that fit 32 KB of flash


def test_c_conformance_on_atmega32_under_simavr(built, tmp_path):
    if not (shutil.which("avr-gcc") and shutil.which("simavr")):
        pytest.fail("avr-gcc and simavr are needed (.ci/run installs them)")

    def build_and_run(part: int) -> str:
        src, elf = tmp_path / f"conf{part}.c", tmp_path / f"conf{part}.elf"
        src.write_text(conformance_driver(built, part, AVR_PARTS))
        build = subprocess.run(["avr-gcc", "-std=gnu99", "-Os", "-mmcu=atmega32", "-Wall", "-Wextra", "-Werror",
                                "-ffunction-sections", "-fdata-sections", "-Wl,--gc-sections",
                                "-I", str(built / "c"), str(src), "-o", str(elf)],
                               capture_output=True, text=True, timeout=300)
        if build.returncode != 0:
            return f"part {part}: build failed\n{build.stderr[-3000:]}"
        run = subprocess.run(["simavr", "-m", "atmega32", "-f", "16000000", str(elf)],
                             capture_output=True, text=True, timeout=600, errors="replace")
        return f"part {part}: " + run.stdout + run.stderr

    with ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        for output in pool.map(build_and_run, range(AVR_PARTS)):
            assert re.search(r"CONFORMANCE nmea0183 PASS \d+ checks 0 failures",
                             re.sub(r"\x1b\[[0-9;]*m", "", output)), output[-3000:]
