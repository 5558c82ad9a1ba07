"""What the generated Markdown says a decoder refuses, and with which error, is what
it does: every statement of the framing section is held against the error kind the
Python codec raised for each invalid vector (the C codec is held to the same kinds
by the conformance tests), for every seed and example protocol and for generated
schemas. The frames each statement speaks of are picked out here from the raw
frame, independently of the code that wrote the statement."""
from __future__ import annotations

import json
import re
import sys
from pathlib import Path

import pytest

from codeword.build import build, compile_schema
from codeword.targets.markdown.errors import error_claims

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
from fuzz.schema.features import DEFAULT  # noqa: E402
from fuzz.schema.generate import generate  # noqa: E402

SCHEMAS = sorted((ROOT / "schemas").glob("*.yaml")) + sorted((ROOT / "examples").glob("*.yaml"))
FUZZ_SEEDS = range(7000, 7016)


def line_checksum(body: str, algorithm: str) -> int:
    data = body.encode("ascii", "replace")
    if algorithm == "xor":
        value = 0
        for byte in data:
            value ^= byte
        return value
    return sum(data) % 256


def concerned(claim: dict, vector: dict) -> bool:
    """Whether the claim speaks of this invalid frame."""
    args = claim["args"]
    if claim["when"] == "shorter_than":
        return len(bytes.fromhex(vector["hex"])) < args["bytes"]
    if claim["when"] == "size_not_in":
        frame = bytes.fromhex(vector["hex"])
        size = len(frame)
        trailer = args.get("trailer")
        if trailer and size > trailer["byte"] and frame[trailer["byte"]] & trailer["mask"]:
            size -= trailer["size"]  # the flag puts the trailer in: the size is the rest's
        return size >= args["least"] and size not in args["sizes"]
    if claim["when"] == "no_terminator":
        return not vector["text"].endswith(args["terminator"])
    if claim["when"] == "line_checksum_differs":
        text, start, suffix, end = vector["text"], args["start"], args["suffix"], args["terminator"]
        shape = re.fullmatch(re.escape(start) + "(.*)" + re.escape(suffix) + "([0-9A-F]{2})" + re.escape(end),
                             text, re.S)
        return bool(shape) and int(shape.group(2), 16) != line_checksum(shape.group(1), args["algorithm"])
    raise AssertionError(f"a claim this test does not know: {claim['when']}")


def check_protocol(path: Path, out: Path) -> int:
    """Checks every claim of the protocol against its vectors; the number of frames checked."""
    result = build([path], out, root=path.parent)
    assert not result.errors, result.errors
    protocol = compile_schema(path)
    name = protocol.name
    vectors = json.loads((out / "vectors" / f"{name}.json").read_text(encoding="utf-8"))
    page = (out / "docs" / f"{name}.md").read_text(encoding="utf-8")
    claims = error_claims(protocol)
    stated = set(re.findall(r"[^.]*\bwith error `\w+`[^.]*", page))
    for sentence in stated:  # the page states no error but the claims'
        assert any(sentence.strip() in c["text"] for c in claims), f"{name}: unchecked statement: {sentence}"
    checked = 0
    for claim in claims:
        assert claim["text"] in page, f"{name}: the page leaves out: {claim['text']}"
        for vector in vectors["invalid"]:
            if concerned(claim, vector):
                checked += 1
                assert vector["error"] == claim["kind"], (
                    f"{name}: the docs say {claim['text']!r} but {vector['name']!r} "
                    f"({vector.get('hex') or vector.get('text')!r}) gives {vector['error']!r}")
    return checked


@pytest.mark.parametrize("path", SCHEMAS, ids=[p.stem for p in SCHEMAS])
def test_every_error_statement_of_a_protocol_page_holds_on_its_vectors(path, tmp_path):
    check_protocol(path, tmp_path / "out")


def test_every_error_statement_holds_on_generated_schemas(tmp_path):
    checked = 0
    for seed in FUZZ_SEEDS:
        path = tmp_path / f"s{seed}" / f"fz{seed}.yaml"
        path.parent.mkdir()
        path.write_text(generate(seed, DEFAULT), encoding="utf-8")
        checked += check_protocol(path, path.parent / "out")
    assert checked > 100  # the statements speak of many of the damaged frames
