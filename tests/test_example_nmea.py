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


# Published sentences of receivers that write numbers their own way (padded heights, 3 to 8
# decimals, `8` or `08`): kept as received (NMEA-D4), so each is written back byte for byte.
KEPT_SENTENCES = [
    # u-blox 8 / M8 Receiver Description, NMEA GGA example
    "$GPGGA,092725.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*5B",
    # Quectel L80 GPS Protocol Specification 2.3, GPGGA example
    "$GPGGA,015540.000,3150.68378,N,11711.93139,E,1,17,0.6,0051.6,M,0.0,M,,*58",
    # Haicom HI-505SD user manual, GGA example
    "$GPGGA,104549.04,2447.2038,N,12100.4990,E,1,06,01.7,00078.8,M,0016.3,M,,*5C",
    # a Hemisphere VS100 on R/V Sally Ride, NOAA PSL PISTON 2019 raw GPS log (gps01925920_raw.txt)
    "$GPGGA,195959.00,1813.38282955,N,12606.12767097,E,2,07,1.4,17.2,M,36.5,M,4.0,0129*78",
    # the same receiver on R/V Ronald H. Brown, NOAA PSL ATOMIC 2020 (gps02003906_raw.txt): a negative geoid
    "$GPGGA,060000.00,1353.25162451,N,05445.30213512,W,2,06,1.2,2.9,M,-40.8,M,5.0,0138*76",
    *RECEIVER_SENTENCES,
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


def body_leaves(message):
    """The values after the sentence id, in line order (pynmea2's `data`): all but the talker."""
    return [leaf for leaf in message.wire.leaves if not leaf.field.prefix]


def as_number(text: str):
    return float(text) if text else None


@pytest.mark.parametrize("sentence", SENTENCES)
def test_values_agree_with_pynmea2(built, sentence):
    mod = load(built / "python" / "nmea0183.py")
    ours = mod.decode(sentence + "\r\n")
    theirs = pynmea2.parse(sentence)
    message = next(m for m in compile_schema(SCHEMA).messages if m.name == type(ours).NAME)
    names = [leaf.field.name for leaf in body_leaves(message)]  # in line order
    assert message.text_places.least <= len(theirs.data) <= len(names)
    assert all(getattr(ours, name) is None for name in names[len(theirs.data):])  # fields the sentence predates
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
    for leaf, text in zip(body_leaves(message), theirs.data):
        f, value = leaf.field, getattr(ours, leaf.field.name)
        if f.kind in ("int", "uint") and f.enum is None:
            want = at_step(text, f.decimals or 0) if text else None
            assert value == want, (f.name, value, text)
            raws.append(0 if value is None else round(value * 10 ** (f.decimals or 0)))
        else:
            assert wire(value) == text, (f.name, value, text)
    # the C decoder reads the same raw values
    names = [leaf.field.name for leaf in body_leaves(message) if leaf.field.kind in ("int", "uint")
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


def test_the_line_checksum_of_every_length_is_pynmea2s(built):
    """The line's checksum, folded over the line as one integer, is the XOR pynmea2 computes
    character by character, for lines of every length up to past the longest."""
    import random
    mod = load(built / "python" / "nmea0183.py")
    rng = random.Random(183)
    for n in range(0, 320):
        body = "".join(chr(rng.randrange(0x20, 0x7F)) for _ in range(n))
        assert mod._line_checksum(body) == pynmea2.NMEASentence.checksum(body), n


# a C driver's round_trip(line): decode, encode, print the decode's code and whether the bytes came back
ROUND_TRIP_C = r"""
#include <stdio.h>
#include <string.h>
#include "nmea0183.h"
static void round_trip(const char *line) {
    nmea0183_message_t m;
    char buf[120];
    int rc, n;
    memset(&m, 0, sizeof m);
    rc = nmea0183_decode(line, strlen(line), NMEA0183_DIR_ANY, &m);
    n = nmea0183_encode(&m, buf, sizeof buf);
    printf("%d %d\n", rc, n > 0 && (size_t)n == strlen(line) && memcmp(buf, line, (size_t)n) == 0);
}
"""


def test_c_writes_each_sentence_back_and_refuses_a_bad_checksum(built):
    calls = "\n".join(f'    round_trip("{s}\\r\\n");' for s in SENTENCES)
    driver = ROUND_TRIP_C + r"""
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


AVR_PARTS = 40  # the vectors (text lines, and structs with 25-byte kept spellings) and streams in parts that fit 32 KB of flash


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


@pytest.mark.parametrize("sentence", KEPT_SENTENCES)
def test_python_writes_receiver_sentences_back_byte_for_byte(built, sentence):
    """Each number is read as pynmea2 reads it (at the field's step) and written back as the
    receiver spelt it; the checksum pynmea2 verifies is the one written."""
    mod = load(built / "python" / "nmea0183.py")
    theirs = pynmea2.parse(sentence, check=True)
    ours = mod.decode(sentence + "\r\n")
    message = next(m for m in compile_schema(SCHEMA).messages if m.name == type(ours).NAME)
    for leaf, text in zip(body_leaves(message), theirs.data):
        f, value = leaf.field, getattr(ours, leaf.field.name)
        if f.kind in ("int", "uint") and f.enum is None:
            assert value == (at_step(text, f.decimals or 0) if text else None), (f.name, value, text)
    assert mod.encode(ours) == sentence + "\r\n"
    assert ours == mod.Gga.from_dict(ours.to_dict())  # the spellings are not part of the value


def test_a_changed_value_is_written_in_the_schemas_spelling(built):
    """Quectel's padded altitude `0051.6` is kept until the altitude changes; then it is
    written as NMEA-D2 spells it, and the rest of the line as received. The checksum of the
    expected line is pynmea2's."""
    mod = load(built / "python" / "nmea0183.py")
    ours = mod.decode(KEPT_SENTENCES[1] + "\r\n")
    ours.altitude = 51.7
    ours.num_sats = 17  # the same value: its spelling stays
    body = "GPGGA,015540.000,3150.68378,N,11711.93139,E,1,17,0.6,51.7,M,0.0,M,,"
    assert mod.encode(ours) == f"${body}*{pynmea2.NMEASentence.checksum(body):02X}\r\n"
    fresh = mod.Gga.from_dict(mod.decode(KEPT_SENTENCES[1] + "\r\n").to_dict())  # values only
    body = "GPGGA,015540,3150.68378,N,11711.93139,E,1,17,0.6,51.6,M,0.0,M,,"
    assert mod.encode(fresh) == f"${body}*{pynmea2.NMEASentence.checksum(body):02X}\r\n"


def test_a_value_left_as_decoded_keeps_its_text_and_any_other_is_checked(built):
    """Encode writes a number's received text at once while the field still holds the very
    value decoded; an equal value of another object keeps the text too (compared as raw
    values), and any other value is checked as a new one would be."""
    mod = load(built / "python" / "nmea0183.py")
    ours = mod.decode(KEPT_SENTENCES[1] + "\r\n")
    ours.altitude = float("51.6")  # equal, not the object decoded
    assert mod.encode(ours) == KEPT_SENTENCES[1] + "\r\n"
    ours.altitude = 1e9
    with pytest.raises(mod.EncodeError) as err:
        mod.encode(ours)
    assert (err.value.field, err.value.rule) == ("altitude", "range")
    ours.altitude = "51.6"
    with pytest.raises(mod.EncodeError) as err:
        mod.encode(ours)
    assert (err.value.field, err.value.rule) == ("altitude", "type")


def test_a_spelling_past_its_bound_is_refused_not_cut(built):
    """A kept number holds at most 24 characters (SPELLING_MAX): a longer one is a `length`
    error naming the field at its offset, in Python; CW_ERR_LENGTH in C."""
    mod = load(built / "python" / "nmea0183.py")
    body = "GPGGA,123519,0000000000000004807.03800,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,"
    line = f"${body}*{pynmea2.NMEASentence.checksum(body):02X}\r\n"
    assert len("0000000000000004807.03800") == 25
    with pytest.raises(mod.DecodeError) as err:
        mod.decode(line)
    assert (err.value.field, err.value.rule, err.value.offset) == ("lat", "length", 14)
    driver = r"""
#include <stdio.h>
#include <string.h>
#include "nmea0183.h"
int main(void) {
    static const char line[] = "LINE";
    nmea0183_gga_t m;
    printf("%d\n", nmea0183_gga_decode(line, sizeof line - 1, &m) == CW_ERR_LENGTH);
    return 0;
}
""".replace("LINE", line.replace("\r\n", "\\r\\n"))
    assert run_c(built / "c", driver) == ["1"]


def test_c_writes_receiver_sentences_back_and_a_changed_value_in_its_own_spelling(built):
    calls = "\n".join(f'    round_trip("{s}\\r\\n");' for s in KEPT_SENTENCES)
    driver = ROUND_TRIP_C + r"""
int main(void) {
    static const char quectel[] = "QUECTEL\r\n";
    nmea0183_gga_t m;
    char buf[100];
    int n;
CALLS
    memset(&m, 0, sizeof m);
    printf("%d\n", nmea0183_gga_decode(quectel, sizeof quectel - 1, &m));
    m.altitude = 517;  /* tenths: 51.7 */
    n = nmea0183_gga_encode(&m, buf, sizeof buf);
    printf("%.*s\n", n > 2 ? n - 2 : 0, buf);
    return 0;
}
""".replace("CALLS", calls).replace("QUECTEL", KEPT_SENTENCES[1])
    body = "GPGGA,015540.000,3150.68378,N,11711.93139,E,1,17,0.6,51.7,M,0.0,M,,"
    assert run_c(built / "c", driver) == ["0 1"] * len(KEPT_SENTENCES) + [
        "0", f"${body}*{pynmea2.NMEASentence.checksum(body):02X}"]


# Sentences from talkers other than GP (NMEA-D1): one message each, the talker a field.
TALKER_SENTENCES = [
    # C-Nav3050 on R/V Kilo Moana, Rolling Deck to Repository format notes (C-Nav3050.txt)
    "$GNGGA,000001.00,2304.167961,N,16553.836924,W,2,11,1.0,44.542,M,0.000,M,2.0,0103*43",
    # the published GGA (gpsd) from GLONASS, Galileo and BeiDou receivers; checksums by pynmea2
    "$GLGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*5B",
    "$GAGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*56",
    "$BDGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*56",
]


@pytest.mark.parametrize("sentence", TALKER_SENTENCES)
def test_any_talker_reads_as_pynmea2_reads_it_and_is_written_back(built, sentence):
    """The talker is the message's `talker` (pynmea2's `talker`); the values are pynmea2's at
    the field's step; the sentence is written back byte for byte, its checksum pynmea2's."""
    mod = load(built / "python" / "nmea0183.py")
    theirs = pynmea2.parse(sentence, check=True)
    ours = mod.decode(sentence + "\r\n")
    assert type(ours) is mod.Gga and ours.talker == theirs.talker
    message = next(m for m in compile_schema(SCHEMA).messages if m.name == "gga")
    for leaf, text in zip(body_leaves(message), theirs.data):
        f, value = leaf.field, getattr(ours, leaf.field.name)
        if f.kind in ("int", "uint") and f.enum is None:
            assert value == (at_step(text, f.decimals or 0) if text else None), (f.name, value, text)
        else:
            assert wire(value) == text, (f.name, value, text)
    assert mod.encode(ours) == sentence + "\r\n"


def test_the_talker_given_is_the_talker_written(built):
    """A message encoded with another talker: the line pynmea2 reads with that talker."""
    mod = load(built / "python" / "nmea0183.py")
    ours = mod.Gga.from_dict(mod.decode(SENTENCES[0] + "\r\n").to_dict())
    ours.talker = "GN"
    line = mod.encode(ours)
    theirs = pynmea2.parse(line.strip(), check=True)
    assert line.startswith("$GNGGA,") and theirs.talker == "GN" and theirs.sentence_type == "GGA"
    for bad, rule in (("gn", "text"), ("G", "length"), ("GNS", "length"), ("G1", "text")):
        ours.talker = bad
        with pytest.raises(mod.EncodeError) as err:
            mod.encode(ours)
        assert (err.value.field, err.value.rule) == ("talker", rule)


def test_c_reads_and_writes_the_talker(built):
    """C: each talker's sentence decodes to GGA with its talker and is written back byte for
    byte; a lowercase talker is CW_ERR_TEXT, an unknown sentence CW_ERR_DISPATCH, and
    encoding with talker GL writes the line pynmea2 checks."""
    calls = "\n".join(f'    round_trip("{s}\\r\\n");' for s in TALKER_SENTENCES)
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
    printf("%d %d %s %d\n", rc, m.kind == NMEA0183_MSG_GGA, m.as.gga.talker,
           n > 0 && (size_t)n == strlen(line) && memcmp(buf, line, (size_t)n) == 0);
}
int main(void) {
    static const char lower[] = "$gpGGA,123519,4807.03800,N,01131.00000,E,1,08,0.9,545.4,M,46.9,M,,*47\r\n";
    static const char other[] = "$GPGGB,1*48\r\n";
    nmea0183_message_t m;
    char buf[100];
    int n;
CALLS
    printf("%d\n", nmea0183_decode(lower, sizeof lower - 1, NMEA0183_DIR_ANY, &m) == CW_ERR_TEXT);
    printf("%d\n", nmea0183_decode(other, sizeof other - 1, NMEA0183_DIR_ANY, &m) == CW_ERR_DISPATCH);
    memset(&m, 0, sizeof m);
    static const char gp[] = "$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47\r\n";
    nmea0183_decode(gp, sizeof gp - 1, NMEA0183_DIR_ANY, &m);
    memcpy(m.as.gga.talker, "GL", 3u);
    n = nmea0183_encode(&m, buf, sizeof buf);
    printf("%.*s\n", n > 2 ? n - 2 : 0, buf);
    memcpy(m.as.gga.talker, "gl", 3u);
    printf("%d\n", nmea0183_encode(&m, buf, sizeof buf) == CW_ERR_TEXT);
    return 0;
}
""".replace("CALLS", calls)
    talkers = [pynmea2.parse(s).talker for s in TALKER_SENTENCES]
    assert run_c(built / "c", driver) == [f"0 1 {t} 1" for t in talkers] + [
        "1", "1", TALKER_SENTENCES[1], "1"]  # pynmea2's checksum for GL


def xor_line(body: str) -> str:
    """The sentence of `body` with its checksum worked out here, character by character."""
    acc = 0
    for ch in body:
        acc ^= ord(ch)
    return f"${body}*{acc:02X}\r\n"


# RMC and VTG as receivers of each NMEA 0183 version send them (NMEA-D3): 11 RMC fields before
# 2.3, 12 from 2.3 (the mode), 13 from 4.1 (the navigational status); VTG 8, then 9.
VERSIONED_SENTENCES = [
    # gpsd's "NMEA 0183 revealed": 2.0
    "$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A",
    "$GPVTG,054.7,T,034.4,M,005.5,N,010.2,K*48",
    # u-blox 8 / M8 Receiver Description, NMEA RMC and VTG examples: 2.3, mode A
    "$GPRMC,083559.00,A,4717.11437,N,00833.91522,E,0.004,77.52,091202,,,A*57",
    "$GPVTG,77.52,T,,M,0.004,N,0.008,K,A*06",
    # the published RMC as a 2.3 receiver without a mode writes it, and as a 4.1 one
    xor_line("GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W,").strip(),
    xor_line("GNRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W,D,S").strip(),
    xor_line("GPVTG,054.7,T,034.4,M,005.5,N,010.2,K,").strip(),
]
PYNMEA2_NAMES = {"mode_indicator": "mode", "faa_mode": "faa_mode", "nav_status": "nav_status"}


@pytest.mark.parametrize("sentence", VERSIONED_SENTENCES)
def test_each_versions_sentence_reads_as_pynmea2_reads_it_and_is_written_back(built, sentence):
    """The fields a sentence has are pynmea2's (the mode and status by pynmea2's names); the
    ones it predates are absent; the sentence is written back with as many fields, byte for
    byte, its checksum the one pynmea2 verifies."""
    mod = load(built / "python" / "nmea0183.py")
    theirs = pynmea2.parse(sentence, check=True)
    ours = mod.decode(sentence + "\r\n")
    message = next(m for m in compile_schema(SCHEMA).messages if m.name == type(ours).NAME)
    leaves = body_leaves(message)
    for leaf, text in zip(leaves, theirs.data):
        f, value = leaf.field, getattr(ours, leaf.field.name)
        if f.kind in ("int", "uint") and f.enum is None:
            assert value == (at_step(text, f.decimals or 0) if text else None), (f.name, value, text)
        else:
            assert wire(value) == text, (f.name, value, text)
    for name, ours_name in PYNMEA2_NAMES.items():  # by name too: pynmea2 knows these fields
        if hasattr(theirs, name) and ours_name in {leaf.field.name for leaf in leaves}:
            assert wire(getattr(ours, ours_name)) == (getattr(theirs, name) or "")
    assert all(getattr(ours, leaf.field.name) is None for leaf in leaves[len(theirs.data):])
    assert mod.encode(ours) == sentence + "\r\n"


def test_new_values_are_written_as_a_2_3_receiver_writes_them(built):
    """Values given afresh: the mode keeps its empty place (a 2.3 receiver always writes it);
    the navigational status is written only when there is one (keep_empty: false)."""
    mod = load(built / "python" / "nmea0183.py")
    old = mod.decode(VERSIONED_SENTENCES[0] + "\r\n")
    fresh = mod.Rmc.from_dict(old.to_dict())  # values only: no kept spellings, no kept field count
    body = "GPRMC,123519,A,4807.03800,N,01131.00000,E,022.4,084.4,230394,003.1,W,"
    assert mod.encode(fresh) == xor_line(body)
    fresh.mode = mod.FaaMode.differential
    assert mod.encode(fresh) == xor_line(body + "D")
    fresh.nav_status = mod.NavStatus.safe
    assert mod.encode(fresh) == xor_line(body + "D,S")
    fresh.mode = None  # the status is present, so the mode's place is written, empty
    assert mod.encode(fresh) == xor_line(body + ",S")
    assert pynmea2.parse(mod.encode(fresh).strip(), check=True).nav_status == "S"


def test_a_decoded_sentence_keeps_its_field_count_while_its_values_fit(built):
    """11 fields decoded, 11 written back; a mode given afterwards needs the 12th place."""
    mod = load(built / "python" / "nmea0183.py")
    ours = mod.decode(VERSIONED_SENTENCES[0] + "\r\n")
    assert mod.encode(ours) == VERSIONED_SENTENCES[0] + "\r\n"
    ours.mode = mod.FaaMode.autonomous
    assert mod.encode(ours) == xor_line("GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W,A")
    thirteen = mod.decode(VERSIONED_SENTENCES[5] + "\r\n")
    thirteen.nav_status = None  # the kept 13th place is written empty
    assert mod.encode(thirteen) == xor_line("GNRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W,D,")


def test_lines_of_other_lengths_are_refused(built):
    """Fewer fields than a 2.0 RMC, or more than a 4.1 one: a count error in Python and C."""
    mod = load(built / "python" / "nmea0183.py")
    short = xor_line("GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1")
    long = xor_line("GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W,A,S,X")
    for line in (short, long):
        with pytest.raises(mod.DecodeError) as err:
            mod.decode(line)
        assert err.value.rule == "count"
    driver = r"""
#include <stdio.h>
#include <string.h>
#include "nmea0183.h"
int main(void) {
    static const char s[] = "SHORT", l[] = "LONG";
    nmea0183_message_t m;
    printf("%d %d\n", nmea0183_decode(s, sizeof s - 1, NMEA0183_DIR_ANY, &m) == CW_ERR_COUNT,
           nmea0183_decode(l, sizeof l - 1, NMEA0183_DIR_ANY, &m) == CW_ERR_COUNT);
    return 0;
}
""".replace("SHORT", short.replace("\r\n", "\\r\\n")).replace("LONG", long.replace("\r\n", "\\r\\n"))
    assert run_c(built / "c", driver) == ["1 1"]


def test_c_writes_each_versions_sentence_back_and_new_values_as_2_3(built):
    """C: each sentence decoded and written back with as many fields; a struct filled afresh
    (line_values 0) writes the mode's empty place and no status."""
    calls = "\n".join(f'    round_trip("{s}\\r\\n");' for s in VERSIONED_SENTENCES)
    driver = ROUND_TRIP_C + r"""
int main(void) {
    static const char old[] = "OLD\r\n";
    nmea0183_rmc_t m;
    char buf[120];
    int n;
CALLS
    memset(&m, 0, sizeof m);
    nmea0183_rmc_decode(old, sizeof old - 1, &m);
    printf("%u\n", (unsigned)m.line_values);
    m.has_mode = true;
    m.mode = NMEA0183_FAA_MODE_AUTONOMOUS;
    n = nmea0183_rmc_encode(&m, buf, sizeof buf);
    printf("%.*s\n", n > 2 ? n - 2 : 0, buf);
    m.has_mode = false;
    m.line_values = 0u;  /* as a struct filled afresh */
    memset(m.lat_spelling, 0, sizeof m.lat_spelling);
    n = nmea0183_rmc_encode(&m, buf, sizeof buf);
    printf("%.*s\n", n > 2 ? n - 2 : 0, buf);
    return 0;
}
""".replace("CALLS", calls).replace("OLD", VERSIONED_SENTENCES[0])
    assert run_c(built / "c", driver) == ["0 1"] * len(VERSIONED_SENTENCES) + [
        "11",
        xor_line("GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W,A").strip(),
        xor_line("GPRMC,123519,A,4807.03800,N,01131.000,E,022.4,084.4,230394,003.1,W,").strip()]
