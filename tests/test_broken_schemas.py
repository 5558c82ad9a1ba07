"""Every schema in tests/broken/ has exactly one defect and must be rejected.

Each file starts with one or more lines

    # expect: <line>: <substring of the error message>

and the compiler (load → resolve → render → verify examples) must raise a
SchemaError that contains, for every expectation, a diagnostic on that line
whose message contains the substring. Every diagnostic must name the schema's
own file and carry a hint.
"""
from __future__ import annotations

import re
import subprocess
import sys
import time
from pathlib import Path

import pytest

from codeword.build import compile_schema, render_protocol, verify
from codeword.diagnostics import SchemaError

ROOT = Path(__file__).resolve().parent.parent
BROKEN = Path(__file__).resolve().parent / "broken"
EXPECT = re.compile(r"^# expect: (\d+): (.+?)\s*$")

# Genuine compiler bugs these files show. Strict xfail: the day the compiler is
# fixed the test passes unexpectedly and fails, so whoever fixes it removes the
# entry here. Location/message bugs and missing hints are tracked separately so
# that a file with a missing hint still has its line checked.
WRONG_ERROR: dict[str, str] = {}
MISSING_HINT: dict[str, str] = {}


def expectations(path: Path) -> list[tuple[int, str]]:
    out = []
    for line in path.read_text(encoding="utf-8").splitlines():
        m = EXPECT.match(line)
        if m:
            out.append((int(m.group(1)), m.group(2)))
        elif out:
            break  # the expect lines are the first lines of the file
    return out


def cases(known: dict[str, str]):
    for path in sorted(BROKEN.glob("*.yaml")):
        marks = []
        if path.name in known:
            marks.append(pytest.mark.xfail(strict=True, reason=known[path.name]))
        yield pytest.param(path, id=path.stem, marks=marks)


def diagnostics_of(path: Path):
    """Run the whole pipeline in-process; return the diagnostics it raised."""
    try:
        p = compile_schema(path)
        verify(p, render_protocol(p))
    except SchemaError as exc:
        return exc.diagnostics
    pytest.fail(f"{path.name}: the broken schema was accepted")


def test_every_broken_schema_states_its_expectation():
    files = sorted(BROKEN.glob("*.yaml"))
    assert len(files) >= 24
    for path in files:
        first = path.read_text(encoding="utf-8").splitlines()[0]
        assert EXPECT.match(first), f"{path.name}: first line must be '# expect: <line>: <text>'"
    names = {p.name for p in files}
    assert set(WRONG_ERROR) <= names and set(MISSING_HINT) <= names


@pytest.mark.parametrize("path", list(cases(WRONG_ERROR)))
def test_broken_schema_is_rejected_at_the_right_line(path: Path):
    expected = expectations(path)
    assert expected, f"{path.name} has no '# expect:' line"
    started = time.monotonic()
    found = diagnostics_of(path)
    elapsed = time.monotonic() - started
    assert elapsed < 10, f"{path.name}: took {elapsed:.1f} s to reject"
    assert found, f"{path.name}: SchemaError without diagnostics"
    shown = "\n".join(str(d) for d in found)
    for line, text in expected:
        assert any(d.loc.line == line and text in d.message for d in found), (
            f"{path.name}: expected an error on line {line} containing {text!r}; got:\n{shown}")
    for d in found:
        assert d.loc.file == str(path), f"{path.name}: diagnostic names file {d.loc.file!r}:\n{d}"
        assert d.loc.line >= 1 and d.loc.col >= 1, f"{path.name}: bad position:\n{d}"


@pytest.mark.parametrize("path", list(cases(MISSING_HINT)))
def test_broken_schema_diagnostics_have_hints(path: Path):
    for d in diagnostics_of(path):
        assert d.hint.strip(), f"{path.name}: diagnostic without a hint:\n{d}"


def test_alias_bomb_is_rejected_fast():
    path = BROKEN / "yaml_alias_bomb.yaml"
    # A hang guard, not a speed check: an unbounded expansion of this file runs
    # for hours and exhausts memory; the bounded loader stops within a second
    # on an idle machine, so even a heavily loaded one stays far inside 30 s.
    started = time.monotonic()
    found = diagnostics_of(path)
    assert time.monotonic() - started < 30.0
    assert any("expan" in d.message for d in found)


def test_python_tag_is_not_executed(tmp_path: Path):
    """The tag is refused at load time, so nothing is constructed or run."""
    marker = tmp_path / "pwned"
    text = (BROKEN / "yaml_python_tag.yaml").read_text(encoding="utf-8")
    text = text.replace("echo pwned", f"touch {marker}")
    schema = tmp_path / "tagged.yaml"
    schema.write_text(text, encoding="utf-8")
    found = diagnostics_of(schema)
    assert any("YAML tag" in d.message for d in found)
    assert not marker.exists()


def test_lint_cli_reports_car_33_bits():
    path = BROKEN / "car_33_bits.yaml"
    line = expectations(path)[0][0]
    proc = subprocess.run([sys.executable, "-m", "codeword", "lint", str(path)], cwd=ROOT,
                          capture_output=True, text=True, timeout=60)
    output = proc.stdout + proc.stderr
    assert proc.returncode == 1, output
    assert f"car_33_bits.yaml:{line}:" in proc.stderr
    assert "33 bits" in proc.stderr and "32" in proc.stderr
    assert "  hint: " in proc.stderr
    assert "Traceback" not in output


YAML11_NAMES = """\
codeword: 1
protocol: yaml_names
title: fields named like YAML 1.1 booleans
source: hand-written
framing: {kind: bits, max_bits: 30, byte_order: big}
messages:
  answers:
    bits: 8
    fields:
      - {name: kind, type: u4, const: 1, dispatch: true}
      - {name: no, type: bool}
      - {name: yes, type: bool}
      - {name: on, type: bool}
      - {name: off, type: bool}
    examples:
      - name: all true
        values: {no: true, yes: true, on: true, off: true}
        hex: "1f"
"""


def test_yaml11_boolean_words_are_plain_names(tmp_path: Path):
    """Positive control: `no`, `yes`, `on`, `off` are strings (YAML 1.2 core), not booleans."""
    path = tmp_path / "yaml_names.yaml"
    path.write_text(YAML11_NAMES, encoding="utf-8")
    p = compile_schema(path)
    verify(p, render_protocol(p))
    (message,) = p.messages
    assert [f.name for f in message.fields] == ["kind", "no", "yes", "on", "off"]
