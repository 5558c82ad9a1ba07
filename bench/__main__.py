"""python3 -m bench: install the benchmark extras, run every benchmark, write bench/RESULTS.md.

    python3 -m bench                  # full run (about 10-15 minutes on 2 cores)
    python3 -m bench --smoke          # one repetition of everything, small inputs, no file written
    python3 -m bench --no-install     # skip `pip install -e .[bench]`
    python3 -m bench --profile        # cProfile of codeword's encode and decode calls, printed
    python3 -m bench --only compiler  # section 5 alone, spliced into the existing RESULTS.md
    python3 -m bench --only imports   # section 9 alone: importing a module of MAVLink's size
    python3 -m bench --only c         # sections 3 and 4 (C on the host and on AVR) alone, likewise
    python3 -m bench --only examples --smoke  # sections 7 and 8 (the examples against their peers), printed
"""

import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def install():
    subprocess.run([sys.executable, "-m", "pip", "install", "--quiet", "--disable-pip-version-check",
                    "-e", f"{ROOT}[bench]"], check=True)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m bench", description=__doc__.splitlines()[0])
    parser.add_argument("--smoke", action="store_true", help="one repetition, small inputs, print only")
    parser.add_argument("--no-install", action="store_true", help="do not pip install the bench extra")
    parser.add_argument("--profile", action="store_true", help="profile codeword's per-message calls, print")
    parser.add_argument("--only", choices=["compiler", "accelerator", "c", "examples", "imports"],
                        help="measure one section again, keep the others")
    parser.add_argument("--out", default=str(ROOT / "bench" / "RESULTS.md"))
    parser.add_argument("--stream-mb", type=float, default=50.0, help="size of the mtv4 capture")
    # every size the scaling target names; 5,000 messages take about 2 CPU minutes and under 0.5 GB
    parser.add_argument("--scaling-sizes", default="10,100,1000,5000")
    args = parser.parse_args(argv)
    if not args.no_install:
        install()
    if args.profile:
        from bench import profile
        print(profile.profile())
        return 0
    from bench import imports, runner, timing  # runner imports the peers, so only after installing them
    sizes = tuple(int(x) for x in args.scaling_sizes.split(","))
    if args.only == "compiler":
        with tempfile.TemporaryDirectory(prefix="codeword-bench-") as tmp:
            results = runner.run_compiler(Path(tmp), (10,) if args.smoke else sizes, 1 if args.smoke else 3)
        return _splice(args, 5, runner.compiler_section(results, []))
    if args.only == "imports":
        with tempfile.TemporaryDirectory(prefix="codeword-bench-") as tmp:
            results = runner.run_imports(Path(tmp), 1 if args.smoke else 7, 20 if args.smoke else imports.MESSAGES)
        return _splice(args, 9, imports.section(results, [], runner._met))
    if args.only == "c":
        with tempfile.TemporaryDirectory(prefix="codeword-bench-") as tmp:
            results = runner.run_c(Path(tmp), 1 if args.smoke else 7, 200_000 if args.smoke else int(args.stream_mb * 1e6))
        return _splice(args, (3, 4), runner.c_sections(results, []))
    if args.only == "accelerator":
        results = runner.run_accelerator(1 if args.smoke else 7, 200_000 if args.smoke else int(args.stream_mb * 1e6),
                                         0.002 if args.smoke else timing.TARGET_SECONDS, 1 if args.smoke else 3)
        return _splice(args, 6, runner.accelerator_section(results, []))
    if args.only == "examples":
        verdicts: list[bool] = []
        results = runner.run_examples(1 if args.smoke else 7, 0.002 if args.smoke else timing.TARGET_SECONDS)
        lines = runner.examples_sections(results, verdicts)
        if args.smoke:  # the two sections alone
            print("\n".join(lines))
            return 0
        seven = lines[:lines.index("## 8. The examples against their peer libraries")]
        _splice(args, 7, seven)
        return _splice(args, 8, lines[len(seven):])
    with tempfile.TemporaryDirectory(prefix="codeword-bench-") as tmp:
        if args.smoke:
            results = runner.run(Path(tmp), repeats=1, stream_bytes=200_000, c_rounds=1,
                                 scaling_sizes=(10,), timing_target=0.002, import_messages=20)
        else:
            results = runner.run(Path(tmp), repeats=7, stream_bytes=int(args.stream_mb * 1e6),
                                 c_rounds=7, scaling_sizes=sizes, stream_repeats=3,
                                 scaling_repeats=1)
    text = runner.report(results)
    if args.smoke:
        print(text)
    else:
        Path(args.out).write_text(text)
        print(f"wrote {args.out}")
    return 0


def _splice(args, number, lines: list[str]) -> int:
    """RESULTS.md with section `number` (or a tuple of adjacent ones) measured again (printed only,
    for --smoke)."""
    from bench import runner
    out = Path(args.out)
    text = runner.splice(out.read_text(encoding="utf-8"), number, lines, f"python3 -m bench --only {args.only}")
    if args.smoke:
        print(text)
    else:
        out.write_text(text, encoding="utf-8")
        print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
