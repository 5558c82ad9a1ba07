"""The suite tests what it claims to: this checkout's codeword, and, in CI, every check
whose tool a developer's machine may lack (a missing tool skips locally, fails in CI)."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import ROOT, needs


def pytest_run(tmp_path: Path, args: list[str], hidden: dict[str, str], ci: bool,
               path: str | None = None) -> subprocess.CompletedProcess[str]:
    """pytest in a subprocess with the packages named in `hidden` shadowed by stand-ins
    (name -> their __init__.py text) and CI set or not."""
    shadow = tmp_path / "shadow"
    for name, text in hidden.items():
        (shadow / name).mkdir(parents=True)
        (shadow / name / "__init__.py").write_text(text, encoding="utf-8")
    env = {k: v for k, v in os.environ.items() if k != "CI"}
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(shadow), env.get("PYTHONPATH")]))
    if ci:
        env["CI"] = "1"
    if path is not None:
        env["PATH"] = path
    return subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", *args],
                          cwd=ROOT, env=env, capture_output=True, text=True, timeout=600)


MISSING = "raise ImportError('not installed here')\n"


def test_needs_skips_locally_and_fails_in_ci(monkeypatch):
    monkeypatch.delenv("CI", raising=False)
    with pytest.raises(pytest.skip.Exception, match="tool is not installed"):
        needs("tool", "install it")
    monkeypatch.setenv("CI", "1")
    with pytest.raises(pytest.fail.Exception, match="tool is missing; install it"):
        needs("tool", "install it")


@pytest.mark.parametrize("test, hidden", [
    ("tests/test_byte_stuffing.py::test_cobs_agrees_with_the_cobs_package", "cobs"),
    ("tests/test_typing.py::test_mypy_strict_accepts_every_generated_module", "mypy"),
])
def test_a_missing_python_tool_fails_the_test_in_ci(tmp_path, test, hidden):
    local = pytest_run(tmp_path / "local", [test, "-rs"], {hidden: MISSING}, ci=False)
    assert local.returncode == 0 and "1 skipped" in local.stdout, local.stdout[-2000:]
    ci = pytest_run(tmp_path / "ci", [test], {hidden: MISSING}, ci=True)
    assert ci.returncode == 1 and "1 failed" in ci.stdout and "is missing" in ci.stdout, ci.stdout[-2000:]


def test_a_missing_pyright_fails_the_test_in_ci(tmp_path):
    test = "tests/test_typing.py::test_pyright_strict_accepts_every_generated_module"
    bare = "/usr/bin:/bin"  # the interpreter is named by its full path; pyright is not on it
    assert not any((Path(folder) / "pyright").exists() for folder in bare.split(":"))
    local = pytest_run(tmp_path / "local", [test], {}, ci=False, path=bare)
    assert local.returncode == 0 and "1 skipped" in local.stdout, local.stdout[-2000:]
    ci = pytest_run(tmp_path / "ci", [test], {}, ci=True, path=bare)
    assert ci.returncode == 1 and "pyright is missing" in ci.stdout, ci.stdout[-2000:]


def test_ci_runs_the_tests_with_ci_set():
    """.ci/run sets CI before the tests, wherever it runs: a missing tool then fails."""
    run = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert "export CI=" in run and run.index("export CI=") < run.index("./scripts/test"), run


def test_the_suite_refuses_to_test_another_codeword(tmp_path):
    """An editable install of another clone would be imported and tested in this one's place."""
    result = pytest_run(tmp_path, ["tests/test_fingerprint.py"], {"codeword": ""}, ci=False)
    assert result.returncode == 4, result.stdout[-2000:] + result.stderr[-2000:]
    out = result.stdout + result.stderr
    assert f"`import codeword` finds {tmp_path / 'shadow' / 'codeword'}" in out and "pip install -e ." in out, out
