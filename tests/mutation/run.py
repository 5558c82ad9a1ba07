"""Mutation run: each mutant of tests/mutation/mutants.py is applied to a fresh copy of
the checkout (never to the working tree), generated/ is rebuilt from the mutated
generator, and the mutant's tests run there. A mutant is caught when they fail.

    python -m tests.mutation                 # every mutant: a table on stdout
    python -m tests.mutation --only NAME ... # some of them
    python -m tests.mutation --record        # and write tests/mutation/RESULTS.md

Slow (one build and test run per mutant): not part of the default test run."""
from __future__ import annotations

import argparse
import os
import shlex
import subprocess
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

from .mutants import MUTANTS, Mutant

ROOT = Path(__file__).resolve().parents[2]
RESULTS = Path(__file__).resolve().parent / "RESULTS.md"


def apply(text: str, find: str, replace: str, where: str) -> str:
    count = text.count(find)
    if count != 1:
        raise ValueError(f"{where}: the text to replace occurs {count} times, not once: {find[:60]!r}")
    return text.replace(find, replace)


Snapshot = dict[str, tuple[bytes, int]]  # path -> (content, mode)


def snapshot() -> Snapshot:
    """The checkout as it stands when the run starts (tracked files and new ones git does
    not ignore): every trial starts from it, whatever is edited meanwhile."""
    listed = subprocess.run(["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                            cwd=ROOT, capture_output=True, check=True).stdout
    names = [name for name in listed.decode().split("\0") if name and (ROOT / name).is_file()]
    return {name: ((ROOT / name).read_bytes(), (ROOT / name).stat().st_mode & 0o777) for name in names}


def copy_checkout(files: Snapshot, dest: Path) -> Path:
    """A copy of the checkout at dest/repo (a git repository of one commit, before any
    mutant) and, in dest/path, a `codeword` that is its
    compiler/ (put first on PYTHONPATH, ahead of the editable install)."""
    repo = dest / "repo"
    for name, (content, mode) in files.items():
        target = repo / name
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(content)
        target.chmod(mode)
    git = ["git", "-c", "user.name=mutation", "-c", "user.email=mutation@localhost", "-c", "commit.gpgsign=false"]
    for args in (["init", "-q"], ["add", "-A"], ["commit", "-q", "-m", "checkout"]):  # tests read git:HEAD:…
        subprocess.run(git + args, cwd=repo, capture_output=True, check=True)
    (dest / "path").mkdir()
    (dest / "path" / "codeword").symlink_to(repo / "compiler", target_is_directory=True)
    return repo


def environment(dest: Path) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "CODEWORD_CACHE")}
    env["PYTHONPATH"] = str(dest / "path")
    env["CODEWORD_PURE_PYTHON"] = "1"  # a compiled accelerator of the working tree is not the mutant's
    env["CODEWORD_CACHE"] = str(dest / "cache")  # nothing built from the unmutated sources is reused
    return env


def run(cmd: list[str], cwd: Path, env: dict[str, str], timeout: int) -> subprocess.CompletedProcess[str]:
    return subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout)


def trial(mutant: Mutant | None, files: Snapshot, tests: tuple[str, ...], timeout: int) -> tuple[str, str]:
    """(verdict, detail) of one mutant (None: the unmutated checkout, the baseline)."""
    with tempfile.TemporaryDirectory(prefix="codeword-mutant-") as tmp:
        dest = Path(tmp)
        repo = copy_checkout(files, dest)
        env = environment(dest)
        for file, find, replace in mutant.patches if mutant else ():
            path = repo / file
            path.write_text(apply(path.read_text(encoding="utf-8"), find, replace, file), encoding="utf-8")
        for folder in (repo, repo / "examples"):  # generated/ as the mutated generator writes it
            build = run([sys.executable, "-m", "codeword", "build"], folder, env, timeout)
            if build.returncode != 0:
                return "caught by the build", (build.stdout + build.stderr).strip().splitlines()[-1:][0][:200]
        started = time.monotonic()
        result = run([sys.executable, "-m", "pytest", "-q", "-x", "-p", "no:cacheprovider", *tests],
                     repo, env, timeout)
        took = f"{time.monotonic() - started:.0f} s"
        last = (result.stdout.strip().splitlines() or [""])[-1][:200]
        if result.returncode == 0:
            return "SURVIVED", f"{last} ({took})"
        if result.returncode == 1:
            failed = next((line for line in result.stdout.splitlines() if line.startswith("FAILED")), last)
            return "caught", f"{failed[:200]} ({took})"
        return f"error (pytest exit {result.returncode})", f"{last} ({took})"


def row(m: Mutant, verdict: str, detail: str, baseline: str, checkout: str) -> str:
    """One line of the results table."""
    def cell(text: str) -> str:
        return text.replace("|", "\\|").replace("\n", " ")
    note = f" Note: {m.note}." if m.note else ""
    return (f"| `{m.name}` | {cell(m.what)}.{cell(note)} | `{cell(' '.join(m.tests))}` | **{verdict}** "
            f"| {cell(detail)} | {cell(baseline)} | {checkout} |")


HEAD = ["| mutant | bug | tests | result | detail | without the mutant | checkout |",
        "|---|---|---|---|---|---|---|"]


def recorded() -> dict[str, str]:
    """The rows of RESULTS.md by mutant name: a run of some mutants keeps the others'."""
    if not RESULTS.is_file():
        return {}
    lines = RESULTS.read_text(encoding="utf-8").splitlines()
    return {line.split("`")[1]: line for line in lines if line.startswith("| `")}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m tests.mutation", description=__doc__.split("\n\n")[0])
    parser.add_argument("--only", nargs="+", metavar="NAME", help="run these mutants only")
    parser.add_argument("--record", action="store_true", help=f"write the table to {RESULTS.relative_to(ROOT)}")
    parser.add_argument("--timeout", type=int, default=1800, help="seconds per build or test run")
    parser.add_argument("--list", action="store_true", help="list the mutants and exit")
    parser.add_argument("--tests", metavar="ARGS",
                        help="pytest arguments in place of each mutant's tests, as one string (\"tests/test_x.py -k y\")")
    args = parser.parse_args(argv)
    mutants = [m for m in MUTANTS if not args.only or m.name in args.only]
    if args.tests:
        mutants = [replace(m, tests=tuple(shlex.split(args.tests))) for m in mutants]
    if args.list or not mutants:
        for m in MUTANTS:
            print(f"{m.name}: {m.what}")
        return 0 if mutants else 2
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True,
                            text=True).stdout.strip()
    if subprocess.run(["git", "status", "--porcelain"], cwd=ROOT, capture_output=True, text=True).stdout.strip():
        commit += " with uncommitted changes"
    files = snapshot()
    baselines: dict[tuple[str, ...], tuple[str, str]] = {}  # the unmutated checkout must pass each mutant's tests
    rows = {}
    for m in mutants:
        if m.tests not in baselines:
            print(f"baseline: {' '.join(m.tests)}", flush=True)
            verdict, detail = trial(None, files, m.tests, args.timeout)
            baselines[m.tests] = ("passed" if verdict == "SURVIVED" else "FAILED: " + verdict, detail)
            print(f"  {baselines[m.tests][0]}: {detail}", flush=True)
        state, summary = baselines[m.tests]
        if state != "passed":
            rows[m.name] = row(m, "not measured", "the tests fail without the mutant", f"{state}: {summary}", commit)
            continue
        print(f"{m.name}: {' '.join(m.tests)}", flush=True)
        verdict, detail = trial(m, files, m.tests, args.timeout)
        print(f"  {verdict}: {detail}", flush=True)
        rows[m.name] = row(m, verdict, detail, summary, commit)
    print()
    print("\n".join(HEAD + list(rows.values())))
    if args.record:
        kept = {**recorded(), **rows}
        lines = [kept[m.name] for m in MUTANTS if m.name in kept]
        RESULTS.write_text(
            "# Mutation results\n\nWritten by `python -m tests.mutation --record` (a run of some mutants, "
            "`--only`, replaces their rows); run it again after changing the mutants or the tests.\n\n"
            "Each mutant is a plausible bug patched into a copy of the checkout (`tests/mutation/mutants.py`); "
            "generated/ is rebuilt from the mutated generator and the named tests run, with `-x`. Caught: "
            "they fail. SURVIVED: they pass with the bug in. The same tests pass without the mutant "
            "(the column before the checkout).\n\n" + "\n".join(HEAD + lines) + "\n", encoding="utf-8")
        print(f"\nwrote {RESULTS.relative_to(ROOT)}")
    return 0
