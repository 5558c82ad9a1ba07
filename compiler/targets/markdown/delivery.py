"""Markdown target, delivery: what a stop-and-wait pair of machines guarantees,
its limits, and its cost measured over a lossy link.

Only protocols the lossy-link simulator (codeword.sim) drives get the section:
it runs their master and slave machines from the codec the docs build has just
rendered. The table is measured at build time with a fixed seed, so the page is
the same on every build; the guarantee and its limits are those the simulator
and SPIN check (tests/test_sim.py, tests/test_spin.py).
"""
from __future__ import annotations

import types
from dataclasses import dataclass
from typing import Optional

from ...model import Protocol
from ...sim import efficiency_table
from .. import promela
from .text import DecisionLinker

RATES = (0.0, 0.1, 0.3, 0.5)
SEED = 1
# Enough for every row to be within 3% of theory (at p = 0.5 the count of
# attempts per command has a standard deviation of 3.5, so the mean's is about
# 1.4% of 4); the four runs take well under a second.
COMMANDS = 4000


@dataclass(frozen=True)
class Decisions:
    """The notes that state the guarantee and each of its limits."""

    guarantee: str
    retry_limit: str
    restart: str


SIMULATED = {"tr24": Decisions(guarantee="TR24-D5", retry_limit="TR24-D4", restart="TR24-D5")}


def efficiency_rows(codec: types.ModuleType) -> list[dict]:
    rows = []
    for row in efficiency_table(RATES, COMMANDS, SEED, module=codec):
        rows.append({"p": f"{row['p']:.1f}", "measured": f"{row['measured']:.3f}",
                     "theory": f"{row['theory']:.3f}", "error": f"{100 * row['error']:.1f}%"})
    return rows


def delivery_view(p: Protocol, codec: types.ModuleType, linker: DecisionLinker) -> Optional[dict]:
    decisions = SIMULATED.get(p.name)
    if decisions is None or not p.machines:
        return None
    master = next(m for m in p.machines if m.role == "master")
    return {"guarantee": linker.ref(decisions.guarantee), "retry_limit": linker.ref(decisions.retry_limit),
            "restart": linker.ref(decisions.restart),
            "model": f"generated/promela/{p.name}.pml",
            "restart_macro": f"{promela.macro(master.name)}_RESTART",
            "retry_macro": promela.macro("retry_limit"),
            "rows": efficiency_rows(codec), "commands": f"{COMMANDS:,}", "seed": SEED}
