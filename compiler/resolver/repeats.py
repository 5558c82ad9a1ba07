"""Which arrays of a binary message generated code loops over (model.Repeat), so that
code grows with the schema and not with the wire: an array of whole-byte elements from a
byte boundary, none of whose values anything outside the array reads (a rule, a
condition, a count, a checksum over fields). Shorter arrays stay written out, where a loop
would cost more than it saves."""
from __future__ import annotations

from dataclasses import replace

from ..model import EACH, Field, Leaf, Repeat, Rule, Run

# An array of fewer leaves than this, over all its elements, is written out one by one.
LOOP_LEAVES = 8


def looped_arrays(layout: tuple[Field, ...], rules: tuple[Rule, ...]) -> frozenset[str]:
    """The names of the message's arrays that nothing outside them reads element by element."""
    if any(f.checksum and f.checksum.over != "bytes" for f in layout):
        return frozenset()  # a checksum over fields sums every element's raw value
    read = {c.path for r in rules for c in r.when + r.require}
    read |= {f.present_if.field for f in layout if f.present_if}
    read |= {f.counted_by for f in layout if f.counted_by}
    read |= {f.multiplexed_by.field for f in layout if f.multiplexed_by}
    arrays = set()
    for f in layout:
        if f.count is None or f.start_bit is not None:
            continue
        if any(name == f.name or name.startswith(f.name + ".") for name in read):
            continue
        if any(read_inside(x) for x in fields_in(f)):
            continue
        arrays.add(f.name)
    return frozenset(arrays)


def fields_in(f: Field) -> list[Field]:
    """Every field an element of `f` holds, groups walked into."""
    out = []
    for x in f.fields:
        out.append(x)
        out.extend(fields_in(x))
    return out


def read_inside(f: Field) -> bool:
    """A field an element holds that its element's neighbours or the frame read: a dispatch or
    length field, a checksum, a count, a conditional one or a multiplexed one."""
    return bool(f.dispatch or f.length_of or f.checksum or f.counts or f.counted_by or f.present_if
                or f.multiplexed_by or f.start_bit is not None or f.signature)


def repeats_of(layout: tuple[Field, ...], leaves: list[Leaf], runs: tuple[Run, ...],
               looped: frozenset[str]) -> tuple[Repeat, ...]:
    """A Repeat for each array named in `looped` whose elements are whole bytes from a byte
    boundary and which holds at least LOOP_LEAVES leaves."""
    out = []
    for f in layout:
        if f.name not in looped or f.count is None or f.count < 2 or f.bit_offset is None:
            continue
        element_bits = f.element.bits
        if not element_bits or element_bits % 8 or f.bit_offset % 8:
            continue
        first = [x for x in leaves if x.path[:2] == (f.name, 0)]
        if len(first) * f.count < LOOP_LEAVES or not any(x.bits for x in first):
            continue
        start = f.bit_offset // 8
        each = {id(x): replace(x, path=(f.name, EACH) + x.path[2:], pos=x.pos - 8 * start) for x in first}
        element_runs = tuple(replace(run, start=run.start - start, leaves=tuple(each[id(x)] for x in run.leaves))
                             for run in runs if id(run.leaves[0]) in each)
        out.append(Repeat(f, start, element_bits // 8, f.count, tuple(each.values()), element_runs))
    return tuple(out)
