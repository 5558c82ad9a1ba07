"""The arrays the model makes Repeats (model.Repeat), read and written in loops, so that a
generated module grows with the schema and not with the count. The encoder packs an array's
bytes with one function (`_put_<msg>_<array>`): a loop checks each element and packs it at
its place; elements past a count, or an absent array, are the zeros the message's own
packing pads the region with. The decoder reads the elements in a loop in the array's place
among the checks, so the first value that is wrong is the one reported, named by its element
(`sv[3].cno`) at its bit offset in the frame."""
from __future__ import annotations

import struct
from dataclasses import replace
from typing import TYPE_CHECKING, Optional

from ...model import Each, Leaf, Repeat, dotted, path_name
from ..code import Code
from .chunks import Chunk, access, chunks_of, segments_of

if TYPE_CHECKING:
    from .view import MessageCode


# the struct codes of a number that one item holds: an array of them is one struct of `count` items
NUMBER_CODES = frozenset("BHIQbhiqfd")


def named(path: tuple) -> str:
    """Python for a field's name in an error: a literal, or, inside a looped element, an
    f-string that names the element by the loop's index `i`."""
    if not any(isinstance(p, Each) for p in path):
        return repr(dotted(path))
    text = "".join("[{i}]" if isinstance(p, Each) else f"[{p}]" if isinstance(p, int) else f".{p}" if k else p
                   for k, p in enumerate(path))
    return "f" + repr(text)


def suffix(r: Repeat) -> str:
    """The array's part of the names of its functions and structs (`2sv`: as path_name spells it)."""
    return path_name((r.field.name, 0))[:-2]


def blob(r: Repeat) -> str:
    """The encoder's local holding the array's packed bytes."""
    return f"b_{r.field.name}"


def region(r: Repeat) -> str:
    """The decoder's local holding the array's bytes, read with the frame's other fields."""
    return f"a_{r.field.name}"


def elements(r: Repeat) -> str:
    """The decoder's local holding the list of the elements read."""
    return f"l_{r.field.name}"


class RepeatCode:
    """The generated code of one Repeat of a message."""

    def __init__(self, mc: "MessageCode", r: Repeat):
        self.mc, self.r = mc, r
        self.chunks = chunks_of(r.runs, mc.view.p.framing.byte_order)
        self.segments = segments_of(self.chunks)
        self.fn = f"{mc.fn}_{suffix(r)}"
        self.array = mc.group_var((r.field.name,))

    # -- what the message's code sees -----------------------------------------------------
    def chunk(self) -> Chunk:
        """The array's bytes as one item of the message's struct: the blob the encoder packs
        (padded with zeros past the elements given), the bytes the decoder's loop reads."""
        size = self.r.end - self.r.start
        return Chunk(self.r.start, size, [], f"{size}s", None, True, repeat=self.r)

    def structs(self) -> list[tuple[str, str]]:
        """One element's structs (unless the array's are packed at once and read at once),
        and the whole array's where its elements are one number each."""
        out = [] if self.raw_is_value() else [(self.struct(n), seg.fmt) for n, seg in enumerate(self.segments)]
        if self.vector():
            out.append((f"_A_{self.fn}", self.segments[0].fmt[0] + f"{self.r.count}{self.chunks[0].code}"))
        return out

    def struct(self, n: int) -> str:
        return f"_E_{self.fn}_{n}"

    def scalar(self) -> Optional[Leaf]:
        """The element's one leaf, when an element is a number stored as it is."""
        leaf = self.r.leaves[0]
        if len(self.r.leaves) != 1 or len(leaf.path) != 2 or len(self.chunks) != 1:
            return None
        chunk = self.chunks[0]
        return leaf if chunk.lone and chunk.code in NUMBER_CODES else None

    def vector(self) -> bool:
        """The array's numbers are one struct's items: packed and unpacked in one call."""
        return self.scalar() is not None

    def iterated(self) -> bool:
        """One element is one struct of all its bytes: the decoder iterates over them."""
        return len(self.segments) == 1 and struct.calcsize(self.segments[0].fmt) == self.r.stride

    # -- encode --------------------------------------------------------------------------
    def put_call(self, present: Optional[str]) -> str:
        """The encoder's statement packing the array (`present`: the test of an array a
        frame may leave out, whose bytes are then zeros)."""
        call = f"_put_{self.fn}({self.array})"
        return f"{blob(self.r)} = {call} if {present} else b''" if present else f"{blob(self.r)} = {call}"

    def put_function(self) -> str:
        """`_put_<msg>_<array>(elements)`: each element checked in turn, and the bytes of those given."""
        mc, r, c = self.mc, self.r, Code()
        vector = self.raw_is_value()
        c(f"def _put_{self.fn}({self.array}: Any) -> {'bytes' if vector else 'bytearray'}:")
        c.indent()
        c(f'"""The bytes of the {r.field.name} of a {mc.m.name}, each element checked."""')
        if not vector:
            c(f"b = bytearray({r.stride} * len({self.array}))")
        c(f"for i in range(len({self.array})):")
        c.indent()
        self.check_elements(c)
        if not vector:
            for n, seg in enumerate(self.segments):
                at = f"{r.stride} * i" + (f" + {seg.start}" if seg.start else "")
                values = ", ".join(mc.chunk_value(ch) for ch in seg.chunks)
                c(f"{self.struct(n)}.pack_into(b, {at}, {values})")
        c.dedent()
        if vector:  # the values are their raw values: packed at once
            fmt = self.segments[0].fmt
            c(f"return struct.pack(f'{fmt[0]}{{len({self.array})}}{fmt[1:]}', *{self.array})")
            mc.view.calls.use("struct")
        else:
            c("return b")
        return c.text()

    def raw_is_value(self) -> bool:
        """An element is a number whose checked value is what is packed."""
        leaf = self.scalar()
        if leaf is None:
            return False
        f = leaf.field
        return (f.kind in ("uint", "int") and f.enum is None and f.flags is None and not f.one_hot
                and f.scale is None and not f.offset and self.mc.view.fixed_raw(f) is None)

    def check_elements(self, c: Code) -> None:
        """Read element i's groups and values, check each and set its raw value."""
        mc, view = self.mc, self.mc.view
        read: set[tuple] = set()
        for leaf in self.r.leaves:
            for depth in range(2, len(leaf.path)):  # each group and array inside the element, once
                prefix = leaf.path[:depth]
                if prefix in read:
                    continue
                read.add(prefix)
                c(f"{mc.group_var(prefix)} = {access(mc.group_var(prefix[:-1]), prefix[-1])}")
                if isinstance(leaf.path[depth], int):
                    mc.check_list(c, prefix)
                else:
                    mc.check_group(c, prefix)
            if self.packs_var(leaf):
                view.encode_leaf(c, mc.m, leaf, mc.group_var(leaf.path[:-1]))

    def packs_var(self, leaf: Leaf) -> bool:
        """Whether the packing reads the leaf's local: a fixed value is a literal in it, but
        where its chunk holds it as it is (bytes, a float, an odd-sized integer)."""
        if self.mc.view.fixed_raw(leaf.field) is None:
            return True
        chunk = next(ch for ch in self.chunks if any(x is leaf for x, _ in ch.leaves))
        return chunk.lone and (chunk.code in ("s", "f", "d") or chunk.code.endswith("s"))

    # -- decode --------------------------------------------------------------------------
    def read_loop(self, c: Code, count: Optional[str], present: Optional[str]) -> None:
        """Read, check and keep each element the frame holds (`count`: a counted array's
        local; `present`: the test of an array a frame may leave out, then None)."""
        mc, r = self.mc, self.r
        out = elements(r)
        if present:
            c(f"{out}: Any = None")
            c(f"if {present}:")
            c.indent()
        body, values = Code(), {}
        body.depth = c.depth + 1  # the loop's body
        checked = self.element_checks(body, values)
        value = self.element_value(body, values)
        scalar = self.scalar()
        if scalar is not None:
            items = f"_A_{self.fn}.unpack({region(r)})" + (f"[:{count}]" if count else "")
            if not body.lines and value == scalar.var:  # nothing to check or convert
                c(f"{out} = list({items})")
                self.close(c, present)
                return
            target = scalar.var
        elif self.iterated():
            data = region(r) if count is None else f"{region(r)}[:{r.stride} * {count}]"
            items = f"{self.struct(0)}.iter_unpack({data})"
            target = f"({', '.join(v for v, _ in self.unpacked_names())},)"
        else:
            items, target, checked = f"range({count or r.count})", "i", False
        c(f"{out} = []" if present else f"{out}: list[Any] = []")
        c(f"for i, {target} in enumerate({items}):" if checked else f"for {target} in {items}:")
        c.indent()
        if scalar is None and not self.iterated():
            names, at = self.unpacked_names(), 0
            for n, seg in enumerate(self.segments):
                these = names[at:at + len(seg.chunks)]
                at += len(seg.chunks)
                start = f"{r.stride} * i" + (f" + {seg.start}" if seg.start else "")
                c(f"{', '.join(v for v, _ in these)}, = {self.struct(n)}.unpack_from({region(r)}, {start})")
        if scalar is None:
            mc.unpack_chunks(c, self.unpacked_names())
        c.lines.extend(body.lines)
        c(f"{out}.append({value})")
        c.dedent()
        self.close(c, present)

    @staticmethod
    def close(c: Code, present: Optional[str]) -> None:
        if present:
            c.dedent()

    def unpacked_names(self) -> list[tuple[str, Chunk]]:
        """The local each chunk of an element is unpacked into: a value that fills its own
        item goes straight into its leaf's local."""
        out = []
        for seg in self.segments:
            for k, ch in enumerate(seg.chunks):
                out.append((ch.leaves[0][0].var if ch.lone and ch.code != "s" else f"e{seg.start}_{k}", ch))
        return out

    def element_checks(self, c: Code, values: dict) -> bool:
        """Check element i's raw values, each at its bit offset in the frame; `values` gets
        each leaf's value. Whether any check was written (and names the element)."""
        mc, r = self.mc, self.r
        checked = False
        for leaf in r.leaves:
            at = mc.sent_offset(replace(leaf, pos=8 * r.start + leaf.pos)) + f" + {8 * r.stride} * i"
            before = len(c.lines)
            expr = mc.view.decode_leaf(c, mc.m, leaf, at, bounded=True)
            checked = checked or len(c.lines) > before
            if expr is not None:
                values[leaf.path] = expr
        return checked

    def element_value(self, c: Code, values: dict) -> str:
        """The expression of element i: its value, or its group built from the values."""
        mc, r = self.mc, self.r
        path = (r.field.name, self.r.leaves[0].path[1])
        if r.field.kind != "group":
            return values[path]
        var = mc.group_var(path)
        mc.construct(c, r.field.fields, path, values, var)
        return var
