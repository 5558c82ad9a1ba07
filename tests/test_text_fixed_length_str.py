"""A text `str` of a fixed `length` (a two-letter code): every target builds it, and
Python and C agree on every vector, the strings that run over the length included."""
from __future__ import annotations

from fuzz.schema.check import Outcome, check_text, matrix_points

SCHEMA = """
codeword: 1
protocol: coded
title: a text protocol with a fixed-length code
source: hand-written
framing: {kind: text, prefix_separator: ",", separator: ",", terminator: "\\n"}
messages:
  reading:
    id: RD
    fields:
      - {name: code, type: str, length: 2}
      - {name: n, type: u8}
    examples:
      - {name: a code and a number, text: "RD,xy,5\\n", values: {code: xy, n: 5}}
"""


def test_builds_and_python_and_c_agree(tmp_path):
    outcome = Outcome(0)
    check_text(SCHEMA, "coded", tmp_path, outcome, matrix_points(0, "rotate"))
    assert outcome.ok, outcome.line()
    assert outcome.checks > 0
