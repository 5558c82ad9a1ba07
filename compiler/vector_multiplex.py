"""Values of multiplexed messages for the conformance vectors: each multiplexor takes,
mostly, a value some field it multiplexes is present for, every field its
multiplexors leave out is None, and one case per multiplexor value a schema names
(both ends of a range) makes every such value appear."""
from __future__ import annotations

import random
from typing import Any

from .model import Field, Message


def dependents(m: Message) -> dict[str, list[Field]]:
    """Each multiplexor's name, with the fields it multiplexes directly."""
    out: dict[str, list[Field]] = {}
    for f in m.layout:
        if f.multiplexed_by:
            out.setdefault(f.multiplexed_by.field, []).append(f)
    return out


def choices(m: Message) -> list[dict[str, int]]:
    """Multiplexor values, one set per value a field's `multiplexed_by` names, each with
    the outer multiplexors' values that let that multiplexor be in the frame."""
    out: list[dict[str, int]] = []
    for f in m.layout:
        mux = f.multiplexed_by
        if mux is None:
            continue
        outer = {x.field: x.ranges[0][0] for x in mux.chain[:-1]}
        for value in sorted({v for r in mux.ranges for v in r}):
            choice = {**outer, mux.field: value}
            if choice not in out:
                out.append(choice)
    return out


def present(f: Field, values: dict) -> bool:
    return f.multiplexed_by is None or all(
        values.get(x.field) is not None and x.holds(values[x.field]) for x in f.multiplexed_by.chain)


def settle(m: Message, values: dict, rng: random.Random, forced: dict[str, int], kept: set[str]) -> None:
    """Set the multiplexors (forced ones as given, those not in `kept` mostly to a value
    that selects a field) and leave out, as None, each field they do not select."""
    chosen = dependents(m)
    for f in m.layout:
        if not f.is_member:
            continue
        if f.name in forced:
            values[f.name] = forced[f.name]
        elif f.name in chosen and f.name not in kept and rng.random() < 0.8:
            lo, hi = rng.choice(rng.choice(chosen[f.name]).multiplexed_by.ranges)
            values[f.name] = rng.randint(lo, hi)
        if not present(f, values):
            values[f.name] = None


def choice_name(choice: dict[str, Any]) -> str:
    return ", ".join(f"{k} {v}" for k, v in choice.items())
