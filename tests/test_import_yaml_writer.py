"""The importer's YAML writer: whatever text a dialect holds (quotes, colons, hashes, YAML's
own words, backslashes, tabs, non-ASCII), the schema it writes reads back as that text, on
one line or folded over several."""
from __future__ import annotations

import random

import yaml

from codeword.importers.yaml_writer import Writer, scalar

ALPHABET = "aZ09 _-./%()':\"#&*!|>{}[],?@`\\\t~éü°±"
WORDS = ["yes", "no", "on", "off", "true", "false", "null", "~", "- item", "key: value", "# note", "0x1F", "1e3",
         ".inf", "NaN", "%TAG", "---", "..."]


def texts(n: int):
    rng = random.Random(31)
    for _ in range(n):
        parts = [rng.choice(WORDS) if rng.random() < 0.3 else "".join(rng.choice(ALPHABET)
                                                                      for _ in range(rng.randint(0, 12)))
                 for _ in range(rng.randint(1, 30))]
        yield " ".join(parts) if rng.random() < 0.7 else "".join(parts)


def test_every_scalar_reads_back_as_its_text():
    for text in texts(3000):
        assert yaml.safe_load(f"k: {scalar(text)}") == {"k": text}, text
        assert yaml.safe_load(f"k: [{scalar(text)}]") == {"k": [text]}, text


def test_prose_folded_or_not_reads_back_as_its_text():
    for text in texts(1000):
        w = Writer()
        w.key("m", 0)
        w.prose("doc", text, 2, first=True)
        assert yaml.safe_load(w.text()) == {"m": [{"doc": text}]}, w.text()
