"""Every YAML example of the language reference (docs/schema-language.md) is
valid language: each block is checked against the JSON Schema the compiler
validates schemas with, key by key (a block is a fragment of a schema: a
framing, some fields, a checksum, a machine), so the reference cannot show a
key or a shape the compiler refuses."""
from __future__ import annotations

import json
import re
import textwrap

import jsonschema
import pytest

from codeword.build import compile_schema, render_protocol, verify
from codeword.loader import load_text

from conftest import ROOT

REFERENCE = (ROOT / "docs" / "schema-language.md").read_text(encoding="utf-8")
SCHEMA = json.loads((ROOT / "compiler" / "schema" / "codeword.schema.json").read_text(encoding="utf-8"))
MESSAGE = SCHEMA["properties"]["messages"]["additionalProperties"]
FIELD = SCHEMA["$defs"]["fields"]["items"]
BLOCKS = [textwrap.dedent(b) for b in re.findall(r"```yaml\n(.*?)```", REFERENCE, re.S)]


def subschema(key: str) -> dict:
    """The part of the JSON Schema a top-level key of a fragment is checked against."""
    if key in SCHEMA["properties"]:
        return SCHEMA["properties"][key]
    if key in MESSAGE["properties"]:  # rules, examples: keys of a message
        return MESSAGE["properties"][key]
    if key in FIELD["properties"]:  # checksum: a key of a field
        return FIELD["properties"][key]
    raise AssertionError(f"the reference shows a key the language does not have: {key!r}")


def check(instance, schema: dict) -> None:
    """Validates against a part of the JSON Schema, its $refs resolved in the whole."""
    jsonschema.Draft202012Validator({**schema, "$defs": SCHEMA["$defs"]}).validate(instance)


def fragments(block: str):
    """The block as data, read as the compiler reads schemas (YAML 1.2: `on` is a
    word); one line per checksum when a block lists alternatives."""
    text = block.replace("[...]", "[]")
    if not any(line.strip() and not line.lstrip().startswith("#") for line in text.splitlines()):
        return []  # a comment only (the editor's schema line)
    if all(line.startswith("checksum:") or not line.strip() for line in text.splitlines()):
        return [load_text(line, "reference").data for line in text.splitlines() if line.strip()]
    return [load_text(text, "reference").data]


def test_the_reference_shows_every_new_key_in_an_example():
    shown = "\n".join(BLOCKS)
    for key in ("by_direction:", "crc_extra:", "extra: message", "extra: mavlink", "mavlink_name:", "encoding:", "bit_order:", "fletcher",
                "complement:", "keep_empty:", "start:", "digits:", "decimals:", "width:", "delivery:",
                "id: {msg_class", "length_of: {from: payload, to: payload}",
                "count: {from: byte_count, unit: bytes}", "max_count:", "present_if: {field: parts, has: gps}",
                "present_if: {field: mode, equals: [2, 3]}", "count: {from: points}",
                "length_of: {from: len, to: end, adjust: -1}", "to_end: true, max_count: 8",
                "count: {from: registers, unit: 2}"):
        assert key in shown, key


@pytest.mark.parametrize("block", [b for b in BLOCKS if b.startswith("codeword: 1")])
def test_whole_schemas_of_the_reference_build(block, tmp_path):
    """A block that is a whole schema builds, its examples checked both ways."""
    path = tmp_path / "reference.yaml"
    path.write_text(block, encoding="utf-8")
    protocol = compile_schema(path)
    verify(protocol, render_protocol(protocol))


@pytest.mark.parametrize("block", BLOCKS, ids=[f"block{i}" for i in range(len(BLOCKS))])
def test_every_yaml_block_is_valid_language(block):
    for data in fragments(block):
        if isinstance(data, list):  # fields
            for item in data:
                check(item, FIELD)
            continue
        for key, value in data.items():
            check(value, subschema(key))
