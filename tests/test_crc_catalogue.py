"""Every entry of the RevEng CRC catalogue reproduces its check value, in the
reference implementation and in the code the Python and C targets generate."""
from __future__ import annotations

import re
import shutil
import subprocess

import pytest

from codeword import crc
from codeword.model import Checksum, CrcParams
from codeword.targets.c.crc import METHODS as C_METHODS
from codeword.pyload import load_module
from codeword.targets.python.view import _checksum_code, _checksum_name, _fixed_span_crc_code, _positional_crc_code
from conftest import ROOT

HEAD = "from __future__ import annotations\n"  # as in a generated module: annotations are not evaluated
ENTRIES = sorted({p.name: p for p in crc.catalogue().values()}.values(), key=lambda p: p.name)


def test_catalogue_is_complete():
    # the catalogue file states 20 CRC-8, 31 CRC-16 and 12 CRC-32 entries
    widths = [p.width for p in ENTRIES]
    assert (widths.count(8), widths.count(16), widths.count(32), len(ENTRIES)) == (20, 31, 12, 63)


@pytest.mark.parametrize("params", ENTRIES, ids=lambda p: p.name)
def test_reference_reproduces_check(params):
    assert crc.compute(params, b"123456789") == params.check


@pytest.mark.parametrize("params", ENTRIES, ids=lambda p: p.name)
def test_generated_table_code_reproduces_check(params):
    cs = Checksum("crc", "bytes", ("a", "b"), crc=params)
    module = load_module(f"_crc_{_checksum_name(cs)}", HEAD + _checksum_code(cs), "<crc>")
    fn = getattr(module, f"_checksum_{_checksum_name(cs)}")
    assert fn(b"123456789") == params.check
    assert fn(b"") == crc.compute(params, b"")
    sample = bytes(range(256)) * 2
    assert fn(sample) == crc.compute(params, sample)


def test_crcs_the_standard_library_computes_are_delegated_to_it():
    # binascii.crc_hqx and zlib.crc32 run in C: eleven CRC-16 entries (poly 0x1021, reflected ones
    # through bit-reversed bytes) and two CRC-32 entries are theirs
    delegated = sorted(p.name for p in ENTRIES if "import" in _checksum_code(Checksum("crc", "bytes", ("a", "b"), crc=p)))
    assert delegated == ["CRC-16/GENIBUS", "CRC-16/GSM", "CRC-16/IBM-3740", "CRC-16/IBM-SDLC",
                         "CRC-16/ISO-IEC-14443-3-A", "CRC-16/KERMIT", "CRC-16/MCRF4XX", "CRC-16/RIELLO",
                         "CRC-16/SPI-FUJITSU", "CRC-16/TMS37157", "CRC-16/XMODEM", "CRC-32/ISO-HDLC", "CRC-32/JAMCRC"]


@pytest.mark.parametrize("params", ENTRIES, ids=lambda p: p.name)
def test_generated_fixed_length_code_reproduces_check(params):
    # the loop-free CRC over a fixed number of bytes that decoders of fixed frames call
    cs = Checksum("crc", "bytes", ("a", "b"), crc=params)
    name = _checksum_name(cs)
    codes = [_positional_crc_code(name, [1, 9, 40])]
    if "import" not in _checksum_code(cs):  # the standard library's CRCs need no fixed-span code
        codes.append(_fixed_span_crc_code(cs, name, [1, 9, 40]))
    for code in codes:
        source = HEAD + "import struct\n" + _checksum_code(cs) + "\n" + code
        module = load_module(f"_crc_fixed_{name}", source, "<crc>")
        assert getattr(module, f"_checksum_{name}_9")(b"123456789", 0) == params.check
        assert getattr(module, f"_checksum_{name}_9")(b"\xaa\xbb123456789", 2) == params.check
        sample = bytes(range(7, 47))
        assert getattr(module, f"_checksum_{name}_40")(sample, 0) == crc.compute(params, sample)
        for byte in (0x00, 0x5A, 0xFF):
            assert getattr(module, f"_checksum_{name}_1")(bytes((byte,)), 0) == crc.compute(params, bytes((byte,)))


def test_lookup_by_alias_is_case_insensitive():
    assert crc.lookup("crc-16/cms").check == 0xAEE7
    assert crc.lookup("XFER").name == "CRC-32/XFER"
    assert crc.lookup("CRC-16/NOPE") is None


def other_widths() -> list[CrcParams]:
    """The catalogue's entries of the other widths the language takes (3 to 64 bits, reflected
    and not, one whose refout differs from its refin), from tests/data/crc_other_widths.txt."""
    entries = []
    for line in (ROOT / "tests" / "data" / "crc_other_widths.txt").read_text(encoding="utf-8").splitlines():
        if line and not line.startswith("#"):
            f = dict(item.split("=", 1) for item in line.split())
            mask = (1 << int(f["w"])) - 1

            def value(key: str) -> int:
                return int(f.get(key, "0"), 0) & mask  # negative: two's complement in the width
            entries.append(CrcParams(f["n"], int(f["w"]), value("p"), value("i"), f["r"] == "t",
                                     f.get("refo", f["r"]) == "t", value("x"), value("c")))
    return entries


OTHER_WIDTHS = other_widths()


def test_the_other_widths_cover_each_kind_of_register():
    kinds = {(p.width < 8, p.width in (8, 16, 32, 64), p.refin) for p in OTHER_WIDTHS}
    assert kinds == {(a, b, r) for a in (True, False) for b in (False, True) for r in (False, True) if not (a and b)}
    assert {p.width for p in OTHER_WIDTHS} >= {3, 4, 5, 6, 7, 10, 11, 12, 13, 14, 15, 17, 21, 24, 30, 31, 40, 64}
    assert any(p.refin != p.refout for p in OTHER_WIDTHS)


@pytest.mark.parametrize("params", OTHER_WIDTHS, ids=lambda p: p.name)
def test_reference_reproduces_the_other_widths_checks(params):
    assert crc.compute(params, b"123456789") == params.check


def c_crc_driver(entries: list[CrcParams], guard: str) -> str:
    """A C program printing each entry's CRC of "123456789", of "" and of 1000 bytes (every
    method's tails: lengths that are not a multiple of its slice)."""
    from codeword.targets.c.view import checksum_code
    functions = [checksum_code(f"crc_{i}", Checksum("crc", "bytes", ("a", "b"), crc=p), guard)
                 for i, p in enumerate(entries)]
    calls = "\n".join(f'    printf("%llu %llu %llu\\n", (unsigned long long)crc_{i}(check, 9), '
                      f'(unsigned long long)crc_{i}(check, 0), (unsigned long long)crc_{i}(long_data + 3, 997));'
                      for i in range(len(entries)))
    return ("#include <stdio.h>\n#include \"codeword.h\"\n" + "\n".join(functions) +
            "\nint main(void)\n{\n    static const uint8_t check[] = \"123456789\";\n"
            "    static uint8_t long_data[1000];\n    unsigned k;\n"
            "    for (k = 0; k < 1000u; k++) {\n        long_data[k] = (uint8_t)(k * 7u + 1u);\n    }\n"
            + calls + "\n    return 0;\n}\n")


LONG_DATA = bytes((k * 7 + 1) & 0xFF for k in range(1000))[3:]


@pytest.mark.parametrize("method", [m.guard for m in C_METHODS])
def test_generated_c_reproduces_every_check(tmp_path, method):
    """The C a header holds for each CRC of the catalogue, every width the language takes, by
    each method (<GUARD>_CRC_<METHOD>: bitwise, a nibble or a byte at a time from tables,
    sliced by four or eight bytes), gives the catalogue's check value for "123456789", and
    the reference's CRC of no bytes and of 997 (the slices' tails)."""
    from schema_in_a_test import run_c
    entries = ENTRIES + OTHER_WIDTHS
    shutil.copy(ROOT / "generated" / "c" / "codeword.h", tmp_path / "codeword.h")
    lines = run_c(tmp_path, c_crc_driver(entries, "CAT"), (f"-DCAT_CRC_{method}",))
    got = {p.name: tuple(int(x) for x in line.split()) for p, line in zip(entries, lines)}
    assert got == {p.name: (p.check, crc.compute(p, b""), crc.compute(p, LONG_DATA)) for p in entries}


def test_the_default_method_needs_no_macro(tmp_path):
    from schema_in_a_test import run_c
    shutil.copy(ROOT / "generated" / "c" / "codeword.h", tmp_path / "codeword.h")
    lines = run_c(tmp_path, c_crc_driver(ENTRIES, "CAT"))
    assert [int(line.split()[0]) for line in lines] == [p.check for p in ENTRIES]


AVR_PROGRAM = """\
#include <avr/interrupt.h>
#include <avr/io.h>
#include <avr/sleep.h>
#include <stdio.h>
#include "codeword.h"
{functions}
static int uart_putchar(char c, FILE *f)
{{
    (void)f;
    while (!(UCSRA & (1 << UDRE))) {{
    }}
    UDR = (uint8_t)c;
    return 0;
}}
static FILE uart_out = FDEV_SETUP_STREAM(uart_putchar, NULL, _FDEV_SETUP_WRITE);

int main(void)
{{
    static const uint8_t check[] = "123456789";
    unsigned failures = 0;
    stdout = &uart_out;
{calls}
    printf_P(PSTR("CRC CHECKS %u failures\\n"), failures);
    cli();
    sleep_cpu();
    return 0;
}}
"""


@pytest.mark.parametrize("method", [None, "BITWISE"], ids=["default", "bitwise"])
def test_generated_c_reproduces_every_check_on_an_atmega32(tmp_path, method):
    """The same on an 8-bit AVR under simavr (16-bit int, tables read from flash), by the
    default method and bitwise."""
    from codeword.targets.c.view import checksum_code
    avr_gcc, simavr = shutil.which("avr-gcc"), shutil.which("simavr")
    assert avr_gcc and simavr, "avr-gcc and simavr are not installed (.ci/run installs them)"
    entries = ENTRIES + OTHER_WIDTHS
    functions = "\n".join(checksum_code(f"crc_{i}", Checksum("crc", "bytes", ("a", "b"), crc=p), "CAT")
                          for i, p in enumerate(entries))
    calls = "\n".join(f'    if (crc_{i}(check, 9) != {p.check:#x}ULL) {{  /* {p.name} */\n'
                      f'        failures++;\n        printf_P(PSTR("FAIL %u\\n"), {i}u);\n    }}'
                      for i, p in enumerate(entries))
    src, elf = tmp_path / "crcs.c", tmp_path / "crcs.elf"
    src.write_text(AVR_PROGRAM.format(functions=functions, calls=calls), encoding="utf-8")
    shutil.copy(ROOT / "generated" / "c" / "codeword.h", tmp_path / "codeword.h")
    build = subprocess.run([avr_gcc, "-std=gnu99", "-Os", "-mmcu=atmega32", "-Wall", "-Wextra", "-Wconversion",
                            "-Werror", *([f"-DCAT_CRC_{method}"] if method else []), "-I", str(tmp_path), str(src),
                            "-o", str(elf)], capture_output=True, text=True, timeout=300)
    assert build.returncode == 0, build.stderr[-3000:]
    run = subprocess.run([simavr, "-m", "atmega32", "-f", "16000000", str(elf)], capture_output=True, text=True,
                         timeout=600, errors="replace")
    output = re.sub(r"\x1b\[[0-9;]*m", "", run.stdout + run.stderr)
    assert "CRC CHECKS 0 failures" in output, output[-3000:]
