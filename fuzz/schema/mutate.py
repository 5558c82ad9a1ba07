"""Random damage to a valid schema: each result must be refused with a located
diagnostic or build for every target; an internal error is a failure."""
from __future__ import annotations

import random
import re
import tempfile
import traceback
from pathlib import Path
from typing import Any

import yaml

from codeword.build import build

from .features import DEFAULT
from .generate import Generator
from .machines import check_machine_collision

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


# Names of C standard, POSIX and Python standard headers and modules: a protocol called
# so would stand for them (`-I generated/c` finds its stdint.h for <stdint.h>).
SYSTEM_NAMES = ["stdint", "stdio", "stdlib", "string", "limits", "stddef", "stdbool", "inttypes", "ctype", "errno",
                "math", "time", "signal", "setjmp", "wchar", "threads", "stdatomic", "unistd", "fcntl", "pthread",
                "termios", "dirent", "struct", "json", "socket", "random", "array", "types", "select", "codeword"]


def _referenced(text: str, name: str) -> bool:
    """Whether `name` appears in the schema text other than as one field's name."""
    return len(re.findall(rf"(?<![A-Za-z0-9_]){re.escape(name)}(?![A-Za-z0-9_])", text)) > 1


def _fields_lists(node: Any) -> list[list]:
    """Every list of fields in the messages (groups included)."""
    out = []
    if isinstance(node, dict):
        if isinstance(node.get("fields"), list):
            out.append(node["fields"])
        for value in node.values():
            out += _fields_lists(value)
    elif isinstance(node, list):
        for value in node:
            out += _fields_lists(value)
    return out


def _member_owner(f: dict) -> str | None:
    """The C member a field brings beside its own: has_<f> (optional, one-hot) or <f>_count
    (an array or bytes whose count varies); None if it brings none."""
    if not isinstance(f, dict) or not isinstance(f.get("name"), str) or "const" in f:
        return None  # a constant is no member, so it brings none beside it
    if f.get("optional") or f.get("one_hot"):
        return f"has_{f['name']}"
    if isinstance(f.get("count"), dict) or isinstance(f.get("length"), dict) or f.get("to_end"):
        return f"{f['name']}_count"
    return None


def collide(doc: dict, rng: random.Random) -> tuple[str, str] | None:
    """A name that meets one the generated code needs: the protocol named like a system
    header or module, or a field renamed to the C member a sibling brings. Returns what
    was done and the text of the line that must be refused; None if the schema offers none."""
    text = yaml.safe_dump(doc, sort_keys=False, allow_unicode=True)
    choices = []
    for fields in _fields_lists(doc.get("messages", {})):
        for owner in fields:
            member = _member_owner(owner)
            if member is None:
                continue
            for other in fields:
                plain = isinstance(other, dict) and isinstance(other.get("name"), str) and other is not owner \
                    and not {"const", "reserved", "dispatch", "checksum", "length_of"} & set(other)
                if plain and not _referenced(text, other["name"]):
                    choices.append((other, member))
    if choices and rng.random() < 0.9:
        other, member = rng.choice(choices)
        was, other["name"] = other["name"], member
        return f"field {was} renamed {member}", f"name: {member}"
    name = rng.choice(SYSTEM_NAMES)
    doc["protocol"] = name
    return f"protocol named {name}", f"protocol: {name}"


def _build(text: str, seed: int, what: str):
    """The build result of a schema text, or the line saying it raised an internal error."""
    with tempfile.TemporaryDirectory(prefix=f"mut{seed}-") as tmp:
        path = Path(tmp) / f"fz{seed}.yaml"
        path.write_text(text, encoding="utf-8")
        try:
            return build([path], Path(tmp) / "out", root=Path(tmp)), ""
        except Exception:
            return None, f"{what}: internal error: {traceback.format_exc(limit=-1).strip().splitlines()[-1]}"


def check_collision(seed: int, features: frozenset[str] = DEFAULT) -> str:
    """'' when a schema with a colliding name is refused at that name's line."""
    doc = Generator(seed, features).schema()
    what, line_text = collide(doc, random.Random(f"collide {seed}"))
    text = yaml.safe_dump(doc, sort_keys=False, allow_unicode=True)
    lines = [i for i, line in enumerate(text.splitlines(), 1) if line.strip().lstrip("- ") == line_text]
    result, crashed = _build(text, seed, f"collision {seed} ({what})")
    if crashed:
        return crashed
    if not result.errors:
        return f"collision {seed} ({what}): built, not refused at line {lines}"
    if not any(d.loc.line in lines and d.hint.strip() for d in result.errors):
        return f"collision {seed} ({what}): refused elsewhere: {str(result.errors[0]).splitlines()[0]}"
    return ""


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
    result, crashed = _build(text, seed, f"mutant {seed} (CRC named {name})")
    if crashed:
        return crashed
    if not any(d.loc.line == line and "ambiguous" in d.message and "poly 0x" in d.hint for d in result.errors):
        got = str(result.errors[0]).splitlines()[0] if result.errors else "built"
        return f"mutant {seed} (CRC named {name}): not refused as ambiguous at line {line}: {got}"
    return ""


def check_mutant(seed: int, features: frozenset[str] = DEFAULT) -> str:
    """'' when the mutant is refused at a location or builds, a CRC named ambiguously is
    refused at its name, (with `collisions`) a schema with a colliding name is refused
    at its line and (with `machines`) a machine name that meets a generated one is refused
    at its line or builds to machines that work; else what went wrong."""
    problem = check_ambiguous_crc(seed, features) or _check_mutant(seed, features)
    if not problem and "collisions" in features:
        problem = check_collision(seed, features)
    if not problem and "machines" in features:
        problem = check_machine_collision(seed, Generator(seed, features).schema(), _build)
    return problem


def _check_mutant(seed: int, features: frozenset[str] = DEFAULT) -> str:
    rng = random.Random(seed)
    doc = Generator(seed, features).schema()
    what = mutate(doc, rng)
    text = yaml.safe_dump(doc, sort_keys=False, allow_unicode=True)
    result, crashed = _build(text, seed, f"mutant {seed} ({what})")
    if crashed:
        return crashed
    for diagnostic in result.errors:
        if diagnostic.loc.line < 1 or "codeword bug" in str(diagnostic):
            return f"mutant {seed} ({what}): {str(diagnostic).splitlines()[0]}"
    return ""
