"""Hostile schemas: code in names, invisible or control characters in text,
numbers that break generated code, YAML tricks, collisions of generated names.

Every file in tests/hostile/ starts with `# expect: <line>: <substring>` and
must be rejected with that diagnostic, a hint, and nothing written. The one
schema in tests/hostile/allowed/ is full of Chinese, Russian and Polish text
and of ASCII that is legal but dangerous if pasted unescaped (comment and
docstring terminators, template braces, preprocessor lines, backslashes,
trigraphs): its generated C must compile with -Werror, its generated Python
must import, and the strings must come back unchanged.
"""
from __future__ import annotations

import importlib.util
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

from codeword.build import build, compile_schema, render_protocol, verify
from codeword.diagnostics import SchemaError
from codeword.loader import MAX_FILE_BYTES
from test_broken_schemas import EXPECT, expectations

ROOT = Path(__file__).resolve().parent.parent
HOSTILE = Path(__file__).resolve().parent / "hostile"
ALLOWED = HOSTILE / "allowed" / "multilingual_text.yaml"
FILES = sorted(HOSTILE.glob("*.yaml"))


def rejection(path: Path):
    try:
        p = compile_schema(path)
        verify(p, render_protocol(p))
    except SchemaError as exc:
        return exc.diagnostics
    pytest.fail(f"{path.name}: the hostile schema was accepted")


def test_corpus_is_large_and_every_file_states_its_expectation():
    assert len(FILES) >= 25
    for path in FILES:
        first = path.read_text(encoding="utf-8").splitlines()[0]
        assert EXPECT.match(first), f"{path.name}: first line must be '# expect: <line>: <text>'"


@pytest.mark.parametrize("path", FILES, ids=[p.stem for p in FILES])
def test_hostile_schema_is_rejected_with_a_clear_error(path: Path):
    started = time.monotonic()
    found = rejection(path)
    assert time.monotonic() - started < 10, f"{path.name}: too slow to reject"
    shown = "\n".join(str(d) for d in found)
    for line, text in expectations(path):
        assert any(d.loc.line == line and text in d.message for d in found), (
            f"{path.name}: expected an error on line {line} containing {text!r}; got:\n{shown}")
    for d in found:
        assert d.loc.file == str(path) and d.loc.line >= 1, shown
        assert d.hint.strip(), f"{path.name}: diagnostic without a hint:\n{d}"


@pytest.mark.parametrize("path", FILES, ids=[p.stem for p in FILES])
def test_hostile_schema_generates_nothing(path: Path, tmp_path: Path):
    out = tmp_path / "generated"
    result = build([path], out)
    assert result.errors and not result.written
    assert not out.exists() or not any(out.rglob("*"))


def test_lint_reports_every_hostile_file_without_a_traceback():
    proc = subprocess.run([sys.executable, "-m", "codeword", "lint", *map(str, FILES)], cwd=ROOT,
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 1
    assert "Traceback" not in proc.stdout + proc.stderr and "internal error" not in proc.stderr
    for path in FILES:
        assert str(path) in proc.stderr, f"{path.name} not reported"
    assert ": ok (" not in proc.stdout


def test_oversized_schema_is_rejected_before_parsing(tmp_path: Path):
    path = tmp_path / "huge.yaml"
    filler = "# " + "x" * 98 + "\n"
    path.write_text("codeword: 1\n" + filler * (MAX_FILE_BYTES // len(filler) + 1), encoding="utf-8")
    started = time.monotonic()
    found = rejection(path)
    assert time.monotonic() - started < 1.0
    assert any("larger than" in d.message for d in found)


def test_schema_that_is_not_utf8_is_rejected(tmp_path: Path):
    path = tmp_path / "latin1.yaml"
    path.write_bytes("codeword: 1\ntitle: Zażółć\n".encode("iso-8859-2"))
    assert any("not UTF-8" in d.message for d in rejection(path))


# ---------------------------------------------------------------- the allowed schema

TITLE = 'Zażółć gęślą jaźń */ """ {{ 7*7 }} #include <stdio.h> C:\\temp\\ ??/'
EXAMPLE = '"\\?:f,42;'  # the schema's example: prefix `"\?`, ':', mode 'f', ',', 42, ';'


@pytest.fixture(scope="module")
def allowed_build(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("polyglot")
    result = build([ALLOWED], out)
    assert not result.errors, "\n".join(str(d) for d in result.errors)
    return out


def test_allowed_schema_python_imports_with_its_strings_intact(allowed_build: Path):
    spec = importlib.util.spec_from_file_location("hostile_polyglot", allowed_build / "python" / "polyglot.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod
    try:
        spec.loader.exec_module(mod)
    finally:
        del sys.modules[spec.name]
    assert mod.__doc__ == f"{TITLE}: codec generated from the polyglot schema."
    assert mod.Command.__doc__ == 'команда "quoted" */'
    assert mod.encode(mod.Command(mode=mod.Mode.fast, speed=42)) == EXAMPLE
    with pytest.raises(mod.EncodeError) as err:
        mod.encode(mod.Command(mode=mod.Mode.slow, speed=101))
    assert "скорость вне диапазона */ \"\"\" \\" in err.value.user_message
    assert "速度超出范围" in err.value.user_message and "prędkość poza zakresem" in err.value.user_message


def test_allowed_schema_c_compiles_cleanly_and_round_trips(allowed_build: Path, tmp_path: Path):
    main = tmp_path / "main.c"
    main.write_text(
        '#include <stdio.h>\n#include <string.h>\n#include "polyglot.h"\n'
        "int main(int argc, char **argv)\n{\n"
        "    polyglot_command_t m;\n    char out[64];\n    int n;\n"
        "    (void)argc;\n"
        "    if (polyglot_command_decode(argv[1], strlen(argv[1]), &m) < 0) return 2;\n"
        "    n = polyglot_command_encode(&m, out, sizeof out);\n"
        "    if (n < 0) return 3;\n"
        "    fwrite(out, 1, (size_t)n, stdout);\n    return 0;\n}\n", encoding="utf-8")
    include = allowed_build / "c"
    for compiler, std in (("gcc", "-std=c99"), ("g++", "-std=c++11")):
        exe = tmp_path / f"rt-{compiler}"
        lang = ["-x", "c++"] if compiler == "g++" else []
        cmd = [shutil.which(compiler) or compiler, std, "-Wall", "-Wextra", "-Wpedantic", "-Werror",
               "-Wtrigraphs", "-Wcomment", "-I", str(include), *lang, str(main), "-o", str(exe)]
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
        assert proc.returncode == 0, proc.stderr
        run = subprocess.run([str(exe), EXAMPLE], capture_output=True, timeout=30)
        assert run.returncode == 0 and run.stdout.decode() == EXAMPLE, run


def test_allowed_schema_c_keeps_schema_text_inside_comments(allowed_build: Path):
    """The preprocessor sees no directive and no string that came from the schema's prose."""
    header = (allowed_build / "c" / "polyglot.h").read_text(encoding="utf-8")
    assert "#include <stdio.h>" not in [line.strip() for line in header.splitlines()]
    proc = subprocess.run(["gcc", "-std=c99", "-fpreprocessed", "-dD", "-E", "-P", "-"], input=header,
                          capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0, proc.stderr
    code = proc.stdout  # comments removed: what the compiler reads
    for prose in ("Zażółć", "7*7", "Съешь", "скорость", "быстро", "int x;"):
        assert prose not in code, f"{prose!r} escaped from a comment"


def test_parameters_without_a_doc_each_keep_their_own_line(tmp_path: Path):
    """A parameter line without a comment once ran into the next: `A = 5B = 3`."""
    text = (HOSTILE / "protocol_name_docs_index.yaml").read_text(encoding="utf-8")
    text = text.replace("protocol: index", "protocol: twoparams").replace(
        "framing:", "parameters:\n  timeout: {default: 5}\n  retries: {default: 3}\n  own_id: {doc: set per device}\nframing:")
    path = tmp_path / "twoparams.yaml"
    path.write_text(text, encoding="utf-8")
    result = build([path], tmp_path / "out")
    assert not result.errors, "\n".join(map(str, result.errors))
    source = (tmp_path / "out" / "python" / "twoparams.py").read_text(encoding="utf-8")
    lines = source.splitlines()
    assert "TIMEOUT = 5" in lines and "RETRY" not in source and "RETRIES = 3" in lines
    assert "OWN_ID = None  # set per device" in lines
