"""Importers: specifications in other formats written out as codeword schemas that a
person can read and keep editing (`codeword import FORMAT FILE --out DIR`)."""
from __future__ import annotations

from pathlib import Path


def write_schema(protocol: str, text: str, out: Path) -> Path:
    """The imported schema written as OUT/<protocol>.yaml; its path."""
    out.mkdir(parents=True, exist_ok=True)
    path = out / f"{protocol}.yaml"
    path.write_text(text, encoding="utf-8")
    return path
