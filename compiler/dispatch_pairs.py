"""Which pairs of messages could share a dispatch key, found without comparing
every pair: a protocol of thousands of messages would take millions of checks.

The pairs returned are a superset of the ambiguous ones, in the order a loop
over all pairs (i < j) visits them, so the exact check and its error order stay
with the caller.
"""
from __future__ import annotations

from collections import defaultdict
from typing import Any, Iterator, Sequence

from .model import Message


def candidate_pairs(keyed: Sequence[Message], framing: str) -> Iterator[tuple[int, int]]:
    try:
        if framing == "bits":
            later = _bits_candidates(keyed)
        elif framing == "text":
            later = _text_candidates(keyed)
        else:
            later = _id_candidates(keyed)
    except TypeError:  # an unhashable key value: fall back to every pair
        later = [range(i + 1, len(keyed)) for i in range(len(keyed))]
    for i, js in enumerate(later):
        for j in js:
            yield i, j


def _id_candidates(keyed: Sequence[Message]) -> list[list[int]]:
    """Bytes and text: two messages overlap only if they share a value of the
    first message's first key field (each key field holds a set of values)."""
    index: dict[tuple[str, Any], list[int]] = defaultdict(list)
    for j, m in enumerate(keyed):
        for name, values in m.dispatch_key:
            for v in set(values):
                index[(name, v)].append(j)
    out = []
    for i, m in enumerate(keyed):
        name, values = m.dispatch_key[0]
        out.append(sorted({j for v in set(values) for j in index.get((name, v), ()) if j > i}))
    return out


def _text_candidates(keyed: Sequence[Message]) -> list[list[int]]:
    """Text: a prefix field's value comes before the id, so two messages overlap only if
    one's id ends with the other's (equal ids included)."""
    index: dict[str, list[int]] = defaultdict(list)
    for j, m in enumerate(keyed):
        index[m.ids[0]].append(j)
    pairs: dict[int, set[int]] = defaultdict(set)
    for i, m in enumerate(keyed):
        ident = m.ids[0]
        for k in range(len(ident)):
            for j in index.get(ident[k:], ()):
                if j != i:
                    pairs[min(i, j)].add(max(i, j))
    return [sorted(pairs[i]) for i in range(len(keyed))]


def _bits_candidates(keyed: Sequence[Message]) -> list[list[int]]:
    """Bits: two messages are told apart only by a key field both have with
    different values. Messages are grouped by their set of key fields; within a
    group pairing, only equal values of the shared fields can collide."""
    groups: dict[frozenset, list[int]] = defaultdict(list)
    for j, m in enumerate(keyed):
        groups[frozenset(name for name, _ in m.dispatch_key)].append(j)
    indexes: dict[tuple[frozenset, tuple], dict[tuple, list[int]]] = {}
    out = []
    for i, m in enumerate(keyed):
        key = dict(m.dispatch_key)
        found: set[int] = set()
        for names, members in groups.items():
            common = tuple(sorted(names & key.keys()))
            if not common:
                found.update(members)
                continue
            index = indexes.get((names, common))
            if index is None:
                index = indexes[(names, common)] = defaultdict(list)
                for j in members:
                    other = dict(keyed[j].dispatch_key)
                    index[tuple(other[k] for k in common)].append(j)
            found.update(index.get(tuple(key[k] for k in common), ()))
        out.append(sorted(j for j in found if j > i))
    return out
