"""Random damage to a valid schema: each result must be refused with a located
diagnostic or build for every target; an internal error is a failure."""
from __future__ import annotations

import random
import tempfile
import traceback
from pathlib import Path
from typing import Any

import yaml

from codeword.build import build

from .features import DEFAULT
from .generate import Generator

ODD_VALUES = [None, True, -1, 0, 1, 7, 2 ** 64, -2 ** 63 - 1, 1.5, 1e308, "", "x" * 300, "u0", "u65", "i1",
              "nosuch", [], {}, [1, 2], {"a": 1}, "payload", "kind", "\u202e", "0x10"]


def _paths(node: Any, path: tuple = ()) -> list[tuple]:
    out = [path] if path else []
    if isinstance(node, dict):
        for key, value in node.items():
            out += _paths(value, path + (key,))
    elif isinstance(node, list):
        for i, value in enumerate(node):
            out += _paths(value, path + (i,))
    return out


def _parent(doc: Any, path: tuple) -> Any:
    for key in path[:-1]:
        doc = doc[key]
    return doc


def mutate(doc: dict, rng: random.Random) -> str:
    """One random change: a value replaced, a key dropped, an entry duplicated."""
    path = rng.choice(_paths(doc))
    parent, key = _parent(doc, path), path[-1]
    how = rng.random()
    if how < 0.6:
        parent[key] = rng.choice(ODD_VALUES)
    elif how < 0.8:
        del parent[key]
    elif isinstance(parent, list):
        parent.insert(key, parent[key])
    else:
        parent[f"{key}_copy" if isinstance(key, str) else key] = parent[key]
    return f"{'/'.join(map(str, path))}: {'replaced' if how < 0.6 else 'dropped' if how < 0.8 else 'duplicated'}"


# names that documents use for several CRCs of one width: a schema must say which
AMBIGUOUS_CRC_NAMES = {8: ["CRC-8", "crc-8"], 16: ["CRC-16/CCITT", "CRC-CCITT", "crc-16", "Crc-16/Ccitt"]}


def ambiguous_crc(doc: dict, rng: random.Random) -> str | None:
    """Give the schema's CRC over bytes an ambiguous name; the name, or None without one."""
    for f in doc.get("framing", {}).get("layout", []):
        algorithm = str(f.get("checksum", {}).get("algorithm", "")).lower()
        width = int(f["type"][1:]) if algorithm else 0
        if algorithm not in ("", "sum", "xor", "fletcher", "parity", "crc") and width in AMBIGUOUS_CRC_NAMES:
            f["checksum"]["algorithm"] = rng.choice(AMBIGUOUS_CRC_NAMES[width])
            return f["checksum"]["algorithm"]
    return None


def check_ambiguous_crc(seed: int, features: frozenset[str]) -> str:
    """A CRC named ambiguously must be refused on the name's line, the candidates named."""
    rng = random.Random(~seed)
    doc = Generator(seed, features).schema()
    name = ambiguous_crc(doc, rng) if "crc_alias" in features else None
    if name is None:
        return ""
    text = yaml.safe_dump(doc, sort_keys=False, allow_unicode=True)
    line = next(i for i, x in enumerate(text.splitlines(), 1) if "algorithm:" in x and name in x)
    with tempfile.TemporaryDirectory(prefix=f"amb{seed}-") as tmp:
        path = Path(tmp) / f"fz{seed}.yaml"
        path.write_text(text, encoding="utf-8")
        try:
            result = build([path], Path(tmp) / "out", root=Path(tmp))
        except Exception:
            return f"mutant {seed} (CRC named {name}): internal error: " \
                   f"{traceback.format_exc(limit=-1).strip().splitlines()[-1]}"
    if not any(d.loc.line == line and "ambiguous" in d.message and "poly 0x" in d.hint for d in result.errors):
        got = str(result.errors[0]).splitlines()[0] if result.errors else "built"
        return f"mutant {seed} (CRC named {name}): not refused as ambiguous at line {line}: {got}"
    return ""


def check_mutant(seed: int, features: frozenset[str] = DEFAULT) -> str:
    """'' when the mutant is refused at a location or builds, and a CRC named ambiguously
    is refused at its name; else what went wrong."""
    ambiguous = check_ambiguous_crc(seed, features)
    if ambiguous:
        return ambiguous
    rng = random.Random(seed)
    doc = Generator(seed, features).schema()
    what = mutate(doc, rng)
    text = yaml.safe_dump(doc, sort_keys=False, allow_unicode=True)
    with tempfile.TemporaryDirectory(prefix=f"mut{seed}-") as tmp:
        path = Path(tmp) / f"fz{seed}.yaml"
        path.write_text(text, encoding="utf-8")
        try:
            result = build([path], Path(tmp) / "out", root=Path(tmp))
        except Exception:
            return f"mutant {seed} ({what}): internal error: {traceback.format_exc(limit=-1).strip().splitlines()[-1]}"
        for diagnostic in result.errors:
            if diagnostic.loc.line < 1 or "codeword bug" in str(diagnostic):
                return f"mutant {seed} ({what}): {str(diagnostic).splitlines()[0]}"
    return ""
