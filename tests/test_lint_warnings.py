"""`codeword lint` warns, without failing, about messages that share an id and are told
apart only by their size, and about messages with no example; each warning names the
message's file:line. The seed schemas lint without a warning."""
from __future__ import annotations

from codeword.cli import main
from conftest import ROOT

SCHEMA = """codeword: 1
protocol: sized
title: t
source: s
framing:
  kind: bytes
  layout:
    - {name: sync, type: u8, const: 0xA5}
    - {name: len, type: u8, length_of: {from: kind, to: payload}}
    - {name: kind, type: u8, dispatch: true}
    - {payload: true}
messages:
  small:
    id: 1
    fields:
      - {name: x, type: u8}
    examples:
      - {hex: "a5 02 01 07", values: {x: 7}}
  large:
    id: 1
    fields:
      - {name: x, type: u16}
"""


def test_lint_warns_about_a_shared_id_and_a_missing_example(tmp_path, capsys):
    path = tmp_path / "sized.yaml"
    path.write_text(SCHEMA, encoding="utf-8")
    assert main(["lint", str(path)]) == 0
    err = capsys.readouterr().err
    warnings = [line for line in err.splitlines() if ": warning: " in line]
    assert warnings == [
        f"{path}:19:3: warning: message 'large' has no example: nothing checks its wire bytes against a frame "
        "worked out by hand",
        f"{path}:19:3: warning: message 'large' has the id of 'small' and is told apart from it only by its size "
        "(5 bytes, 4)"], err


def test_seed_schemas_lint_without_warnings(capsys):
    assert main(["lint", *[str(p) for p in sorted((ROOT / "schemas").glob("*.yaml"))]]) == 0
    assert "warning" not in capsys.readouterr().err
