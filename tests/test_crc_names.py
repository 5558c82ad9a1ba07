"""CRC names: a catalogue name or an alias with one meaning selects that CRC; a
name that different documents use for different CRCs is refused with every
candidate and its parameters; a misspelt name gets the nearest catalogue names."""
from __future__ import annotations

import binascii
from pathlib import Path

import pytest

from codeword.build import compile_schema, render_protocol, verify
from codeword.diagnostics import SchemaError

SCHEMA = """\
codeword: 1
protocol: crcname
title: a CRC given by name
source: hand-written
roles:
  host: {doc: the host}
  device: {doc: the device}
directions:
  host_to_device: {from: host, to: device}
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: start, type: u8, const: 0x02}
    - {name: code, type: u8, dispatch: true}
    - {payload: true}
    - name: crc
      type: u16
      checksum:
        algorithm: NAME
        covers: {from: code, to: payload}
messages:
  ping:
    id: 1
    direction: host_to_device
    fields:
      - {name: value, type: u8}
"""
ALGORITHM_LINE = 20


def compile_with(tmp_path: Path, name: str, extra: str = ""):
    path = tmp_path / "crcname.yaml"
    path.write_text(SCHEMA.replace("NAME", name) + extra, encoding="utf-8")
    protocol = compile_schema(path)
    verify(protocol, render_protocol(protocol))
    return protocol


def refusal(tmp_path: Path, name: str):
    with pytest.raises(SchemaError) as info:
        compile_with(tmp_path, name)
    return info.value.diagnostics


# Parameters as the RevEng catalogue lists them, written out by hand.
CCITT_CANDIDATES = [
    "CRC-16/KERMIT (width 16, poly 0x1021, init 0x0000, refin true, refout true, xorout 0x0000",
    "CRC-16/IBM-3740 (width 16, poly 0x1021, init 0xffff, refin false, refout false, xorout 0x0000",
    "CRC-16/XMODEM (width 16, poly 0x1021, init 0x0000, refin false, refout false, xorout 0x0000",
    "CRC-16/SPI-FUJITSU (width 16, poly 0x1021, init 0x1d0f, refin false, refout false, xorout 0x0000",
]


@pytest.mark.parametrize("name", ["CRC-16/CCITT", "crc-ccitt"])
def test_an_ambiguous_ccitt_name_is_refused_with_every_candidate(tmp_path, name):
    found = refusal(tmp_path, name)
    assert len(found) == 1, found
    d = found[0]
    assert d.loc.line == ALGORITHM_LINE and "ambiguous" in d.message and name in d.message
    for candidate in CCITT_CANDIDATES:
        assert candidate in d.hint, d.hint


def test_a_bare_width_name_is_refused(tmp_path):
    d, = refusal(tmp_path, "CRC-16")
    assert d.loc.line == ALGORITHM_LINE and "ambiguous" in d.message
    assert "CRC-16/ARC (width 16, poly 0x8005, init 0x0000, refin true, refout true, xorout 0x0000" in d.hint
    assert "CRC-16/MODBUS (width 16, poly 0x8005, init 0xffff, refin true, refout true, xorout 0x0000" in d.hint


def test_an_unambiguous_alias_selects_its_entry(tmp_path):
    # CRC-16/CCITT-FALSE is CRC-16/IBM-3740: binascii.crc_hqx with preset 0xFFFF computes it
    value = binascii.crc_hqx(bytes([0x01, 0x2A]), 0xFFFF)
    example = f"""    examples:
      - name: forty-two
        values: {{value: 42}}
        hex: 02 01 2a {value:04x}
"""
    protocol = compile_with(tmp_path, "CRC-16/CCITT-FALSE", example)
    crc = next(f for f in protocol.framing.envelope if f.name == "crc").checksum.crc
    assert crc.name == "CRC-16/IBM-3740"


def test_a_misspelt_name_gets_the_nearest_catalogue_names(tmp_path):
    d, = refusal(tmp_path, "CRC-16/MODBSU")
    assert d.loc.line == ALGORITHM_LINE and "unknown checksum algorithm" in d.message
    assert "did you mean CRC-16/MODBUS" in d.hint, d.hint


def test_every_ambiguous_name_offers_the_catalogues_own_reading():
    # refusing a name never hides the entry the catalogue gives it
    from codeword import crc
    for name, meanings in crc.AMBIGUOUS.items():
        assert crc.catalogue()[name].name in meanings, name
        assert len(set(meanings)) == len(meanings) > 1
        assert all(crc.catalogue()[m].name == m for m in meanings)
