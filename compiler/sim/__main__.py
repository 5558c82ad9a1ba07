"""Command line: run a protocol's delivery machines over a lossy channel and print the counts.

    python -m codeword.sim --seed 7 --loss 0.3 --receivers 4 --commands 1000
    python -m codeword.sim --efficiency --commands 4000 --seed 1
    python -m codeword.sim --schema path/to/protocol.yaml --param data_length=59

The machines are those of the project's schema that declares `delivery`
(--schema names one when there are several), generated afresh from it.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Optional

from ..check.run import load_codec
from ..diagnostics import SchemaError
from ..loader import load_file
from ..project import ProjectError, load_project
from ..usage import UsageError
from . import Link, Simulation, efficiency_table


def delivery_schema(name: Optional[str]) -> Path:
    """The schema named (a file or a protocol of the project), else the project's
    one schema with a `delivery` section."""
    project = load_project()
    if name is not None:
        path = project.find_schema(name)
        if path is None:
            raise UsageError(f"no schema {name!r} (not a file, nor a protocol in {project.describe_schemas()})")
        return path
    declaring = [path for path in project.schema_files() if "delivery" in load_file(path).data]
    if len(declaring) != 1:
        found = ", ".join(p.stem for p in declaring) or "none"
        raise UsageError(f"{len(declaring)} schemas in {project.describe_schemas()} declare `delivery` "
                         f"({found}): name one with --schema")
    return declaring[0]


def parameter(text: str) -> tuple[str, int]:
    name, sep, value = text.partition("=")
    try:
        if not sep or not name:
            raise ValueError
        return name, int(value, 0)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not NAME=INTEGER") from None


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m codeword.sim", description=__doc__.splitlines()[0])
    ap.add_argument("--schema", metavar="NAME_OR_FILE",
                    help="the protocol to simulate (default: the project's one schema with `delivery`)")
    ap.add_argument("--seed", type=int, default=1, help="random seed of the channel and the application")
    ap.add_argument("--loss", type=float, default=0.1, help="loss rate in both directions, 0..0.5")
    ap.add_argument("--loss-fwd", type=float, help="loss rate of commands (overrides --loss)")
    ap.add_argument("--loss-ack", type=float, help="loss rate of replies (overrides --loss)")
    ap.add_argument("--duplicate", type=float, default=0.0, help="probability a packet arrives twice")
    ap.add_argument("--corrupt", type=float, default=0.0, help="probability of a flipped bit (dropped by CRC)")
    ap.add_argument("--delay", type=int, nargs=2, default=(1, 5), metavar=("MIN", "MAX"), help="delay in ticks")
    ap.add_argument("--receivers", type=int, default=1, help="number of receiver devices, 1..4")
    ap.add_argument("--commands", type=int, default=1000, help="commands to send")
    ap.add_argument("--timeout", type=int, default=20, help="sender timeout in ticks")
    ap.add_argument("--retry-limit", type=int, default=0, help="resends before failure; 0 = unlimited")
    ap.add_argument("--param", type=parameter, action="append", default=[], metavar="NAME=VALUE",
                    help="another machine parameter (default: the schema's), e.g. data_length=59")
    ap.add_argument("--trace", action="store_true", help="print every machine input and its outputs")
    ap.add_argument("--efficiency", action="store_true", help="print transmissions per command against theory")
    args = ap.parse_args(argv)
    try:
        protocol, module = load_codec(delivery_schema(args.schema))
        if protocol.delivery is None:
            raise UsageError(f"{protocol.file}: the schema declares no `delivery` section")
    except (UsageError, ProjectError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    except SchemaError as exc:
        print(exc, file=sys.stderr)
        return 2
    if args.efficiency:
        print("| p | measured | theory 1/(1-p)^2 | error |")
        print("|---|---|---|---|")
        for row in efficiency_table(protocol, module, commands=args.commands if args.commands != 1000 else 20000,
                                    seed=args.seed):
            print(f"| {row['p']:.1f} | {row['measured']:.3f} | {row['theory']:.3f} | {100 * row['error']:.2f}% |")
        return 0
    try:
        link = Link(p_fwd=args.loss if args.loss_fwd is None else args.loss_fwd,
                    p_ack=args.loss if args.loss_ack is None else args.loss_ack,
                    duplicate=args.duplicate, corrupt=args.corrupt, delay=tuple(args.delay))
        sim = Simulation(protocol, module, args.seed, link, receivers=args.receivers, timeout=args.timeout,
                         retry_limit=args.retry_limit, parameters=dict(args.param), trace=args.trace)
    except Exception as exc:  # bad option values: say which, no traceback
        print(f"error: {exc}", file=sys.stderr)
        return 2
    stats = sim.run(args.commands)
    if args.trace:
        print(sim.trace.text(), end="")
    for name, value in vars(stats).items():
        print(f"{name}: {value}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
