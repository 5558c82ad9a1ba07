"""Conformance vectors for whole sequences: the `sequences` section of
generated/vectors/<protocol>.json (format in docs/vectors.md).

Candidates are built from the model: the schema's sequence examples, then
random instances of the item grammar (messages taken from the valid message
vectors, counts set to what follows, the rules mostly made to hold), then
unit-level mutations of the valid ones (a unit dropped, doubled, swapped,
replaced, cut short, appended). Each candidate's bytes are the units encoded
one by one, so the sequence checks run only in the codec's decode_<sequence>,
whose verdict is recorded: the messages, or the first error's kind and unit.
"""
from __future__ import annotations

import random
from typing import Any, Callable

from .model import Protocol, Sequence, SequenceItem
from .names import camel

RANDOM_PER_SEQUENCE = 24
MUTATED_SEQUENCES = 12
MOST_REPEATS = 3


def _slots(obj: Any, parts: list[str]) -> list[tuple[Any, str]]:
    """(owner, attribute) pairs a dotted path names, through lists."""
    if isinstance(obj, list):
        return [pair for x in obj for pair in _slots(x, parts)]
    if len(parts) == 1:
        return [(obj, parts[0])]
    return _slots(getattr(obj, parts[0]), parts[1:])


def _get(values: dict, parts: list[str]) -> Any:
    for part in parts:
        values = values.get(part) if isinstance(values, dict) else None
    return values


def _owners(obj: Any, parts: list[str]) -> list[Any]:
    if isinstance(obj, list):
        return [o for x in obj for o in _owners(x, parts)]
    if not parts:
        return [obj]
    return _owners(getattr(obj, parts[0]), parts[1:])


class SequenceVectors:
    def __init__(self, p: Protocol, module: Any, rng: random.Random, valid: list[dict]):
        self.p, self.mod, self.rng = p, module, rng
        self.pool: dict[str, list[dict]] = {}
        for case in valid:
            if "canonical" not in case:
                self.pool.setdefault(case["message"], []).append(case["values"])

    # -- building instances of the grammar ---------------------------------------------------
    def message(self, name: str) -> Any:
        return self.mod.from_dict(name, self.rng.choice(self.pool[name]))

    def build(self, items: tuple[SequenceItem, ...], cls: Any) -> Any:
        values: dict[str, Any] = {}
        for item in items:
            if item.count:
                n = len(values[item.name])
            elif item.repeat:
                values[item.name] = [self.one(item, cls) for _ in range(self.rng.randint(0, MOST_REPEATS))]
                continue
            else:
                values[item.name] = self.one(item, cls)
                counts = {c.name: c.count.partition(".")[2] for c in items
                          if c.count and c.count.partition(".")[0] == item.name}
                if counts:
                    for _attempt in range(100):
                        wanted = {name: self.rng.randint(0, MOST_REPEATS) for name in counts}
                        try:
                            values[item.name] = self.counting(values[item.name],
                                                              {counts[k]: n for k, n in wanted.items()})
                            break
                        except self.mod.EncodeError:
                            continue
                    else:
                        raise ValueError(f"no {item.message} encodes with small counts")
                    for name, n in wanted.items():
                        message = next(c.message for c in items if c.name == name)
                        values[name] = [self.message(message) for _ in range(n)]
        return cls(**values)

    def counting(self, head: Any, fields: dict[str, int]) -> Any:
        """A message of head's kind with the count fields set: one of the valid
        vectors that has them, else head with the fields set, if that encodes
        (other fields may depend on a count)."""
        name = type(head).NAME
        having = [v for v in self.pool[name]
                  if all(_get(v, dotted.split(".")) == n for dotted, n in fields.items())]
        if having:
            return self.mod.from_dict(name, self.rng.choice(having))
        for dotted, n in fields.items():
            owner, attr = _slots(head, dotted.split("."))[0]
            setattr(owner, attr, n)
        self.mod.encode(head)
        return head

    def one(self, item: SequenceItem, owner: Any) -> Any:
        if item.message:
            return self.message(item.message)
        group_cls = getattr(self.mod, owner.__name__ + camel(item.name))
        return self.build(item.items, group_cls)

    def repair(self, s: Sequence, seq: Any) -> None:
        """Make the consecutive, equal and member rules hold (unique is left to chance)."""
        for r in s.rules:
            path = r.path.split(".")
            if r.kind == "consecutive":
                for k, (owner, attr) in enumerate(_slots(seq, path)):
                    setattr(owner, attr, r.start + k)
            elif r.kind in ("equal", "member"):
                other = (r.to if r.kind == "equal" else r.of).split(".")
                common = 0
                while path[common] == other[common]:
                    common += 1
                for owner in _owners(seq, path[:common]):
                    found = [getattr(o, a) for o, a in _slots(owner, other[common:])]
                    if found:
                        for o, a in _slots(owner, path[common:]):
                            setattr(o, a, found[0] if r.kind == "equal" else self.rng.choice(found))

    def flatten(self, items: tuple[SequenceItem, ...], obj: Any) -> list[Any]:
        out = []
        for item in items:
            value = getattr(obj, item.name)
            for x in value if item.repeat or item.count else [value]:
                out.extend(self.flatten(item.items, x) if item.items else [x])
        return out

    # -- verdicts ------------------------------------------------------------------------------
    def case(self, s: Sequence, name: str, units: list[Any], plain: Callable) -> dict:
        data = b"".join(self.mod.encode(u) for u in units)
        return self.verdict(s, name, data, plain)

    def verdict(self, s: Sequence, name: str, data: bytes, plain: Callable) -> dict:
        case = {"name": name, "sequence": s.name, "hex": data.hex()}
        try:
            seq = getattr(self.mod, f"decode_{s.name}")(data)
        except self.mod.SequenceError as exc:
            first = exc.errors[0]
            case.update(error=first.rule, index=getattr(first, "index", None))
            return case
        case["messages"] = [{"message": type(u).NAME, "values": plain(u)}
                            for u in self.flatten(s.items, seq)]
        return case

    def mutations(self, units: list[Any]) -> list[tuple[str, list[Any] | bytes]]:
        rng, out = self.rng, []
        if units:
            k = rng.randrange(len(units))
            out.append((f"unit {k} dropped", units[:k] + units[k + 1:]))
            out.append((f"unit {k} doubled", units[:k + 1] + units[k:]))
            other = rng.choice(sorted(self.pool))
            out.append((f"unit {k} replaced by a {other}", units[:k] + [self.message(other)] + units[k + 1:]))
            same = type(units[k]).NAME
            out.append((f"unit {k} replaced by another {same}",
                        units[:k] + [self.message(same)] + units[k + 1:]))
            data = b"".join(self.mod.encode(u) for u in units)
            out.append(("last byte cut", data[:-1]))
        if len(units) > 1:
            k = rng.randrange(len(units) - 1)
            out.append((f"units {k} and {k + 1} swapped", units[:k] + [units[k + 1], units[k]] + units[k + 2:]))
        out.append(("a unit appended", units + [self.message(rng.choice(sorted(self.pool)))]))
        return out

    def vectors(self, plain: Callable) -> list[dict]:
        out: list[dict] = []
        for s in self.p.sequences:
            valid_units: list[list[Any]] = []
            for ex in s.examples:
                if ex.hex is not None:
                    case = self.verdict(s, ex.name, ex.hex, plain)
                    out.append(case)
            cls = getattr(self.mod, camel(s.name))
            for i in range(RANDOM_PER_SEQUENCE):
                seq = self.build(s.items, cls)
                if self.rng.random() < 0.8:
                    self.repair(s, seq)
                units = self.flatten(s.items, seq)
                case = self.case(s, f"{s.name} random {i}", units, plain)
                out.append(case)
                if "messages" in case:
                    valid_units.append(units)
            for i, units in enumerate(valid_units[:MUTATED_SEQUENCES]):
                for label, bad in self.mutations(units):
                    name = f"{s.name} valid {i}: {label}"
                    if isinstance(bad, bytes):
                        out.append(self.verdict(s, name, bad, plain))
                    else:
                        out.append(self.case(s, name, bad, plain))
        return out


def sequence_vectors(p: Protocol, module: Any, rng: random.Random, valid: list[dict],
                     plain: Callable) -> list[dict]:
    return SequenceVectors(p, module, rng, valid).vectors(plain)
