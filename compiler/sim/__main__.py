"""Command line: run the tr24 machines over a lossy channel and print the counts.

    python -m codeword.sim --seed 7 --loss 0.3 --slaves 4 --commands 1000
    python -m codeword.sim --efficiency --commands 4000 --seed 1
"""
from __future__ import annotations

import argparse
import sys

from . import Link, Simulation, efficiency_table


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m codeword.sim", description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=1, help="random seed of the channel and the application")
    ap.add_argument("--loss", type=float, default=0.1, help="loss rate in both directions, 0..0.5")
    ap.add_argument("--loss-fwd", type=float, help="loss rate of commands (overrides --loss)")
    ap.add_argument("--loss-ack", type=float, help="loss rate of replies (overrides --loss)")
    ap.add_argument("--duplicate", type=float, default=0.0, help="probability a packet arrives twice")
    ap.add_argument("--corrupt", type=float, default=0.0, help="probability of a flipped bit (dropped by CRC)")
    ap.add_argument("--delay", type=int, nargs=2, default=(1, 5), metavar=("MIN", "MAX"), help="delay in ticks")
    ap.add_argument("--slaves", type=int, default=1, help="number of slaves, 1..4")
    ap.add_argument("--commands", type=int, default=1000, help="commands to send")
    ap.add_argument("--timeout", type=int, default=20, help="master timeout in ticks")
    ap.add_argument("--retry-limit", type=int, default=0, help="resends before failure; 0 = unlimited")
    ap.add_argument("--data-length", type=int, default=7, help="data bytes per packet, 1..59")
    ap.add_argument("--trace", action="store_true", help="print every machine input and its outputs")
    ap.add_argument("--efficiency", action="store_true", help="print transmissions per command against theory")
    args = ap.parse_args(argv)
    if args.efficiency:
        print("| p | measured | theory 1/(1-p)^2 | error |")
        print("|---|---|---|---|")
        for row in efficiency_table(commands=args.commands if args.commands != 1000 else 20000, seed=args.seed):
            print(f"| {row['p']:.1f} | {row['measured']:.3f} | {row['theory']:.3f} | {100 * row['error']:.2f}% |")
        return 0
    try:
        link = Link(p_fwd=args.loss if args.loss_fwd is None else args.loss_fwd,
                    p_ack=args.loss if args.loss_ack is None else args.loss_ack,
                    duplicate=args.duplicate, corrupt=args.corrupt, delay=tuple(args.delay))
        sim = Simulation(args.seed, link, slaves=args.slaves, data_length=args.data_length,
                         timeout=args.timeout, retry_limit=args.retry_limit, trace=args.trace)
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
