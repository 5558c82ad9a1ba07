"""A multiplexed payload in the docs (CAN DBC multiplexing): for each multiplexor,
each set of its values that selects the same fields, the fields a frame then
carries and their bits, drawn as the payload grid."""
from __future__ import annotations

from typing import Optional

from ...model import Field, Message
from .placement import payload_grid


def value_sets(m: Message, mux: str) -> list[tuple[tuple[tuple[int, int], ...], tuple[str, ...]]]:
    """The multiplexor's values that select fields, grouped by the fields they select:
    (ranges, field names), in the order of their first value."""
    direct = [f for f in m.layout if f.multiplexed_by and f.multiplexed_by.field == mux]
    edges = sorted({lo for f in direct for lo, _ in f.multiplexed_by.ranges}
                   | {hi + 1 for f in direct for _, hi in f.multiplexed_by.ranges})
    groups: dict[tuple[str, ...], list[tuple[int, int]]] = {}
    for lo, end in zip(edges, edges[1:]):
        names = tuple(f.name for f in direct if f.multiplexed_by.holds(lo))
        if names:
            held = groups.setdefault(names, [])
            if held and held[-1][1] == lo - 1:
                held[-1] = (held[-1][0], end - 1)
            else:
                held.append((lo, end - 1))
    return sorted(((tuple(r), names) for names, r in groups.items()), key=lambda x: x[0][0][0])


def ranges_text(ranges: tuple[tuple[int, int], ...]) -> str:
    return ", ".join(str(lo) if lo == hi else f"{lo}..{hi}" for lo, hi in ranges)


def carried(m: Message, chosen: dict[str, int]) -> list[Field]:
    """The fields a frame carries when the multiplexors in `chosen` hold those values
    (the fields of multiplexors not chosen left aside)."""
    def present(f: Field) -> bool:
        return f.multiplexed_by is None or all(x.field in chosen and x.holds(chosen[x.field])
                                               for x in f.multiplexed_by.chain)
    return [f for f in m.layout if f.start_bit is not None and present(f)]


def multiplexed_views(m: Message) -> Optional[list[dict]]:
    """One view per multiplexor value set: its condition in words, the fields it selects,
    and the grid of every field a frame then carries. None when nothing is multiplexed."""
    placed = [f for f in m.layout if f.start_bit is not None]
    muxes = [f for f in placed if any(g.multiplexed_by and g.multiplexed_by.field == f.name for g in placed)]
    if not muxes:
        return None
    out = []
    for mux in muxes:
        outer = {x.field: x.ranges[0][0] for x in mux.multiplexed_by.chain} if mux.multiplexed_by else {}
        said = [f"`{x.field}` is {ranges_text(x.ranges)}" for x in mux.multiplexed_by.chain] if mux.multiplexed_by else []
        for ranges, names in value_sets(m, mux.name):
            chosen = {**outer, mux.name: ranges[0][0]}
            fields = carried(m, chosen)
            out.append({"when": " and ".join(said + [f"`{mux.name}` is {ranges_text(ranges)}"]),
                        "selects": ", ".join(f"`{n}`" for n in names),
                        "carries": ", ".join(f"`{f.name}`" for f in fields),
                        "grid": payload_grid(m, {f.name for f in fields})})
    return out
