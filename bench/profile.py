"""cProfile of codeword's per-message calls: where the time of each encode and
decode goes, function by function (`python3 -m bench --profile`)."""

import cProfile
import io
import pstats

from bench import messages

CALLS = 20_000


def profile(top: int = 8, calls: int = CALLS) -> str:
    out = io.StringIO()
    for case in messages.cases():
        cw = case.contenders["codeword"]
        for op, fn in (("encode", cw.encode), ("decode", cw.decode)):
            prof = cProfile.Profile()
            prof.enable()
            for _ in range(calls):
                fn()
            prof.disable()
            out.write(f"\n== {case.key} {op}, {calls:,} calls ==\n")
            stats = pstats.Stats(prof, stream=out)
            stats.sort_stats("tottime").print_stats(top)
    return out.getvalue()
