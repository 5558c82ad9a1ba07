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


def check_mutant(seed: int, features: frozenset[str] = DEFAULT) -> str:
    """'' when the mutant is refused at a location or builds; else what went wrong."""
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
