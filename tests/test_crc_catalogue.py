"""Every entry of the RevEng CRC catalogue reproduces its check value, both in
the reference implementation and in the code the Python target generates."""
from __future__ import annotations

import pytest

from compiler import crc
from compiler.model import Checksum
from compiler.pyload import load_module
from compiler.targets.pyview import _checksum_code, _checksum_name

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
    module = load_module(f"_crc_{_checksum_name(cs)}", _checksum_code(cs), "<crc>")
    fn = getattr(module, f"_checksum_{_checksum_name(cs)}")
    assert fn(b"123456789") == params.check
    assert fn(b"") == crc.compute(params, b"")
    sample = bytes(range(256)) * 2
    assert fn(sample) == crc.compute(params, sample)


def test_lookup_by_alias_is_case_insensitive():
    assert crc.lookup("crc-16/cms").check == 0xAEE7
    assert crc.lookup("XFER").name == "CRC-32/XFER"
    assert crc.lookup("CRC-16/NOPE") is None
