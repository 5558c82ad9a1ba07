"""Markdown target, delivery: what a stop-and-wait pair of machines guarantees,
its limits, and its cost measured over a lossy link.

Only protocols whose schema declares a `delivery` section get the section: the
lossy-link simulator (codeword.sim) runs the sender and receiver machines it
names from the codec the docs build has just rendered, and the section cites
the notes it names. The table is measured at build time with a fixed seed, so
the page is the same on every build, and the measurement is kept (cache.py)
for the next build of the same schema and codec; the guarantee and its limits are those the
simulator and SPIN check (tests/test_sim.py, tests/test_spin.py).
"""
from __future__ import annotations

import types
from pathlib import Path
from typing import Optional

from ... import cache, sim
from ...diagnostics import Diagnostic, SchemaError
from ...model import Protocol
from ...sim import Undelivered, efficiency_table
from .. import promela
from .text import DecisionLinker

RATES = (0.0, 0.1, 0.3, 0.5)
SEED = 1
# Enough for every row to be within 3% of theory (at p = 0.5 the count of
# attempts per command has a standard deviation of 3.5, so the mean's is about
# 1.4% of 4); the four runs take well under a second.
COMMANDS = 4000


def efficiency_rows(p: Protocol, codec: types.ModuleType) -> list[dict]:
    rows = []
    for row in measured(p, codec):
        rows.append({"p": f"{row['p']:.1f}", "measured": f"{row['measured']:.3f}",
                     "theory": f"{row['theory']:.3f}", "error": f"{100 * row['error']:.1f}%"})
    return rows


def measured(p: Protocol, codec: types.ModuleType) -> list[dict]:
    """The efficiency table's rows, measured or, for a schema and codec measured
    before with the same simulator, as measured then (the run is seeded)."""
    def measure() -> list[dict]:
        return efficiency_table(p, codec, RATES, COMMANDS, SEED)
    codec_hash = getattr(codec, "__source_sha256__", None)
    if codec_hash is None:  # a codec not loaded by the build: nothing to key it on
        return measure()
    simulator = cache.source_hash(*sorted(Path(sim.__file__).parent.glob("*.py")))
    return cache.remembered(cache.slot("efficiency", p.name),
                            cache.key("efficiency", p.sha256, codec_hash, simulator, RATES, COMMANDS, SEED), measure)


def measured_rows(p: Protocol, codec: types.ModuleType) -> list[dict]:
    """The efficiency rows; machines that do not deliver are an error of the schema's."""
    try:
        return efficiency_rows(p, codec)
    except Undelivered as exc:
        sender = p.machine(p.delivery.sender)
        raise SchemaError([Diagnostic(sender.loc, f"delivery: {exc}",
                                      f"follow a command through {p.delivery.sender!r} and "
                                      f"{p.delivery.receiver!r}: every command must end delivered or failed")]) from None


def delivery_view(p: Protocol, codec: types.ModuleType, linker: DecisionLinker) -> Optional[dict]:
    d = p.delivery
    if d is None:
        return None
    return {"guarantee": linker.ref(d.notes.guarantee), "retry_limit": linker.ref(d.notes.retry_limit),
            "restart": linker.ref(d.notes.restart),
            "sender": d.sender, "receiver": d.receiver, "retry_parameter": d.retry_limit,
            "model": f"generated/promela/{p.name}.pml",
            "restart_macro": promela.restart_macro(p.machine(d.sender)),
            "retry_macro": promela.macro(d.retry_limit),
            "rows": measured_rows(p, codec), "commands": f"{COMMANDS:,}", "seed": SEED,
            "command": f"python -m codeword.sim --schema {p.name} --efficiency --commands {COMMANDS} --seed {SEED}"}
