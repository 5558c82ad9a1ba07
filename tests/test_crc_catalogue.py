"""Every entry of the RevEng CRC catalogue reproduces its check value, in the
reference implementation and in the code the Python and C targets generate."""
from __future__ import annotations

import shutil

import pytest

from codeword import crc
from codeword.model import Checksum
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


@pytest.mark.parametrize("method", [None, "CAT_CRC_TABLE", "CAT_CRC_NIBBLE"], ids=["bitwise", "table", "nibble"])
def test_generated_c_reproduces_every_check(tmp_path, method):
    """The C a header holds for each catalogue CRC (bitwise, a byte at a time from a table
    under <GUARD>_CRC_TABLE, a nibble at a time under <GUARD>_CRC_NIBBLE) gives the
    catalogue's check value for "123456789"."""
    from codeword.targets.c.view import checksum_code
    from schema_in_a_test import run_c
    functions = [checksum_code(f"crc_{i}", Checksum("crc", "bytes", ("a", "b"), crc=p), "CAT")
                 for i, p in enumerate(ENTRIES)]
    calls = "\n".join(f'    printf("%llu\\n", (unsigned long long)crc_{i}(check, 9));' for i in range(len(ENTRIES)))
    driver = ("#include <stdio.h>\n#include \"codeword.h\"\n" + "\n".join(functions) +
              "\nint main(void)\n{\n    static const uint8_t check[] = \"123456789\";\n" + calls + "\n    return 0;\n}\n")
    shutil.copy(ROOT / "generated" / "c" / "codeword.h", tmp_path / "codeword.h")
    lines = run_c(tmp_path, driver, (f"-D{method}",) if method else ())
    assert {p.name: int(line) for p, line in zip(ENTRIES, lines)} == {p.name: p.check for p in ENTRIES}
