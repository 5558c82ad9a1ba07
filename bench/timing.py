"""Interleaved timing: every contender is measured once per round, rounds repeat.

The machines are shared and noisy, so a slow spell hits all contenders of a
round alike; the median over rounds is reported, and ratios are taken between
medians measured in the same process.
"""

import gc
import itertools
import statistics
import time

TARGET_SECONDS = 0.02  # length of one measurement


def calibrate(fn, target=TARGET_SECONDS, clock=time.perf_counter):
    """Calls of `fn` that take about `target` seconds."""
    n = 1
    while True:
        elapsed = run(fn, n, clock)
        if elapsed >= target / 4 or n >= 1 << 24:
            return max(1, int(n * target / max(elapsed, 1e-9)))
        n *= 4


def run(fn, n, clock=time.perf_counter):
    """Seconds for n calls of fn (loop overhead included, the same for every fn), by `clock`:
    wall time, or time.process_time for the CPU time of this process alone."""
    loop = itertools.repeat(None, n)
    gc_was = gc.isenabled()
    gc.disable()
    try:
        start = clock()
        for _ in loop:
            fn()
        return clock() - start
    finally:
        if gc_was:
            gc.enable()


def interleaved(contenders, repeats, target=TARGET_SECONDS, clock=time.perf_counter):
    """{key: fn} → {key: median ns per call}; one round measures every key once."""
    counts = {key: calibrate(fn, target, clock) for key, fn in contenders.items()}
    samples = {key: [] for key in contenders}
    for _ in range(repeats):
        for key, fn in contenders.items():
            samples[key].append(run(fn, counts[key], clock) / counts[key] * 1e9)
    return {key: statistics.median(values) for key, values in samples.items()}


def interleaved_once(jobs, repeats):
    """{key: fn} where each fn does one long job and returns its own figure
    (e.g. seconds); rounds interleave the jobs; returns {key: median figure}."""
    samples = {key: [] for key in jobs}
    for _ in range(repeats):
        for key, fn in jobs.items():
            samples[key].append(fn())
    return {key: statistics.median(values) for key, values in samples.items()}
