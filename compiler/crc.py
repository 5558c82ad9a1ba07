"""CRC parameters: the RevEng catalogue shipped with the package, and a
reference bitwise Rocksoft-model implementation used to check parameters."""
from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import yaml

from .model import CrcParams

CATALOGUE = Path(__file__).parent / "data" / "crc_catalogue.yaml"


@lru_cache(maxsize=1)
def catalogue() -> dict[str, CrcParams]:
    """Catalogue entries by upper-case name and alias."""
    # libyaml when PyYAML has it: the same data, several times faster
    loader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
    data = yaml.load(CATALOGUE.read_text(encoding="utf-8"), Loader=loader)
    entries: dict[str, CrcParams] = {}
    for entry in data["entries"]:
        params = CrcParams(
            name=entry["name"], width=int(entry["width"]), poly=int(entry["poly"], 16),
            init=int(entry["init"], 16), refin=bool(entry["refin"]), refout=bool(entry["refout"]),
            xorout=int(entry["xorout"], 16), check=int(entry["check"], 16))
        for name in [entry["name"], *entry.get("aliases", [])]:
            entries[name.upper()] = params
    return entries


# Names the catalogue gives one entry but that documents in the field use for
# several, so taking the catalogue's reading would silently disagree with half of
# the peers: the CCITT names (RevEng lists them for KERMIT, many datasheets mean
# IBM-3740, XMODEM or AUG-CCITT) and names that give only the width.
AMBIGUOUS: dict[str, tuple[str, ...]] = {
    "CRC-16/CCITT": ("CRC-16/KERMIT", "CRC-16/IBM-3740", "CRC-16/XMODEM", "CRC-16/SPI-FUJITSU"),
    "CRC-CCITT": ("CRC-16/KERMIT", "CRC-16/IBM-3740", "CRC-16/XMODEM", "CRC-16/SPI-FUJITSU"),
    "CRC-16": ("CRC-16/ARC", "CRC-16/MODBUS", "CRC-16/UMTS", "CRC-16/IBM-3740"),
    "CRC-8": ("CRC-8/SMBUS", "CRC-8/MAXIM-DOW", "CRC-8/AUTOSAR", "CRC-8/I-432-1"),
}


def lookup(name: str) -> CrcParams | None:
    """The entry a catalogue name or alias names; None for an unknown or ambiguous name."""
    if name.upper() in AMBIGUOUS:
        return None
    return catalogue().get(name.upper())


def candidates(name: str) -> tuple[CrcParams, ...]:
    """The entries an ambiguous name may mean (none for an unambiguous or unknown name)."""
    return tuple(catalogue()[c] for c in AMBIGUOUS.get(name.upper(), ()))


def near_names(name: str, count: int = 3) -> list[str]:
    """Catalogue names and aliases spelt most like `name`, closest first."""
    import difflib
    names = [n for n in catalogue() if n not in AMBIGUOUS]
    return difflib.get_close_matches(name.upper(), names, n=count, cutoff=0.75)


def describe(params: CrcParams) -> str:
    """The Rocksoft parameters of an entry, and its check value, in one line."""
    digits = (params.width + 3) // 4
    return (f"{params.name} (width {params.width}, poly 0x{params.poly:0{digits}x}, "
            f"init 0x{params.init:0{digits}x}, refin {str(params.refin).lower()}, "
            f"refout {str(params.refout).lower()}, xorout 0x{params.xorout:0{digits}x}; "
            f"CRC of ASCII 123456789 = 0x{params.check:0{digits}x})")


def reflect(value: int, width: int) -> int:
    result = 0
    for _ in range(width):
        result = (result << 1) | (value & 1)
        value >>= 1
    return result


def compute(params: CrcParams, data: bytes) -> int:
    """Bit-at-a-time CRC straight from the Rocksoft model definition."""
    top = 1 << (params.width - 1)
    mask = (1 << params.width) - 1
    reg = params.init
    for byte in data:
        if params.refin:
            byte = reflect(byte, 8)
        for i in range(7, -1, -1):
            bit = (byte >> i) & 1
            feedback = ((reg & top) != 0) ^ bit
            reg = (reg << 1) & mask
            if feedback:
                reg ^= params.poly
    if params.refout:
        reg = reflect(reg, params.width)
    return reg ^ params.xorout
