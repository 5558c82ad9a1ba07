"""python3 -m fuzz.schema: check generated schemas; see fuzz/schema/__init__.py."""
from __future__ import annotations

import argparse
import os
import platform
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

from . import features as feature_table
from .check import C_MATRIX, check_seed
from .generate import generate
from .mutate import check_mutant
from .typecheck import mypy_problems

RESULTS = Path(__file__).resolve().parents[1] / "RESULTS.md"
MARK = "## Schema fuzzing"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python3 -m fuzz.schema", description=__doc__)
    parser.add_argument("--count", type=int, default=300, help="schemas to check (default 300)")
    parser.add_argument("--seed", type=int, default=0, help="first seed (default 0)")
    parser.add_argument("--features", help="'all', or +name/-name changes to the default set")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="processes (default: every core)")
    parser.add_argument("--mutants", type=int, default=None,
                        help="mutated schemas to check after them (default: as many as --count)")
    parser.add_argument("--c-matrix", choices=C_MATRIX, default="rotate",
                        help="compile each schema's C at one more (compiler, level) chosen by its seed (rotate, "
                             "the default), or at all seven (full); see fuzz/schema/check.py")
    parser.add_argument("--show", action="store_true", help="print the schema of --seed and stop")
    parser.add_argument("--mypy", action="store_true", help="also run mypy --strict on every generated module")
    parser.add_argument("--record", action="store_true", help="write the run's count and result into fuzz/RESULTS.md")
    args = parser.parse_args(argv)
    chosen = feature_table.parse(args.features)
    if args.show:
        sys.stdout.write(generate(args.seed, chosen))
        return 0
    seeds = range(args.seed, args.seed + args.count)
    start = time.monotonic()
    failed = []
    mutants = range(args.seed, args.seed + (args.count if args.mutants is None else args.mutants))
    problems = []
    with ProcessPoolExecutor(max_workers=args.jobs) as pool:
        for outcome in pool.map(check_seed, seeds, [chosen] * len(seeds), [None] * len(seeds),
                                [args.c_matrix] * len(seeds), chunksize=8):
            if not outcome.ok:
                failed.append(outcome)
                print(outcome.line(), flush=True)
        for problem in pool.map(check_mutant, mutants, [chosen] * len(mutants), chunksize=16):
            if problem:
                problems.append(problem)
                print(problem, flush=True)
    if args.mypy:
        for problem in mypy_problems(seeds, chosen):
            problems.append(problem)
            print(problem, flush=True)
    seconds = time.monotonic() - start
    summary = (f"{args.count} schemas (seeds {seeds.start}..{seeds.stop - 1}), {len(failed)} failures; "
               f"{len(mutants)} mutated schemas, {len(problems)} not refused at a line nor built; "
               f"{seconds:.0f} s on {args.jobs} processes")
    print(summary)
    if args.record:
        record(args, chosen, summary, [o.line() for o in failed] + problems)
    return 1 if failed or problems else 0


def record(args, chosen: frozenset[str], summary: str, failed) -> None:
    off = sorted(feature_table.FULL - chosen)
    lines = [MARK, "", f"`python3 -m fuzz.schema --count {args.count} --seed {args.seed}"
             + (f" --features {args.features}" if args.features else "")
             + (f" --c-matrix {args.c_matrix}" if args.c_matrix != "rotate" else "") + "`", "",
             f"- Result: {summary}.", f"- Machine: {platform.machine()}, Python {platform.python_version()}, "
             f"{os.cpu_count()} cores.", f"- Features off: {', '.join(off) or 'none'}."]
    lines += [f"  - `{name}`: {feature_table.KNOWN_OPEN.get(name, 'switched off for this run')}" for name in off]
    lines += [f"- `{line}`" for line in failed[:20]]
    text = RESULTS.read_text(encoding="utf-8") if RESULTS.exists() else ""
    head, _, rest = text.partition(MARK)
    end = rest.find("\n## ") if "\n## " in rest else len(rest)
    earlier, tail = rest[:end].strip("\n"), rest[end:]  # the runs recorded before stay, after this one
    RESULTS.write_text(head.rstrip() + "\n\n" + "\n".join(lines) + "\n" + ("\n" + earlier + "\n" if earlier else "")
                       + tail, encoding="utf-8")


if __name__ == "__main__":
    sys.exit(main())
