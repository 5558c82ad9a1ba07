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


def lookup(name: str) -> CrcParams | None:
    return catalogue().get(name.upper())


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
