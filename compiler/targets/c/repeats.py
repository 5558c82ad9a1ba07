"""The arrays the model makes Repeats, in loops: one function checks and writes an
element (`<msg>_<array>_put`), one reads and checks it (`<msg>_<array>_get`), and the
message's encoder and decoder call them for each element the frame holds. Their code is
the element's, once, whatever the count."""
from __future__ import annotations

from typing import TYPE_CHECKING

from ...model import Message, Repeat, count_member
from ..code import Code
from .pack import spans
from .scalars import unsigned_type

if TYPE_CHECKING:
    from .view import CView


def put_name(v: "CView", m: Message, r: Repeat) -> str:
    return f"{v.px}_{m.name}_{r.field.name}_put"


def get_name(v: "CView", m: Message, r: Repeat) -> str:
    return f"{v.px}_{m.name}_{r.field.name}_get"


def element_raws(r: Repeat) -> tuple[dict[str, str], str]:
    """The r[] slot of each integer leaf of an element, and the narrowest type that holds them."""
    slots = [leaf for leaf in r.leaves if leaf.bits and leaf.field.kind != "bytes"]
    widest = max([leaf.bits for leaf in slots] + [1])
    return {leaf.var: f"r[{k}]" for k, leaf in enumerate(slots)}, unsigned_type(widest)


def uses_message(r: Repeat) -> bool:
    return any(leaf.field.is_member for leaf in r.leaves)


def functions(v: "CView", m: Message) -> list[str]:
    """The element functions of each Repeat of `m`."""
    return [f(v, m, r) for r in m.wire.repeats for f in (put_function, get_function)]


def opened(r: Repeat, raws: dict[str, str], rt: str, comment: str, signature: str) -> Code:
    """An element function's code up to its body: its comment, signature and raw values."""
    c = Code()
    c(comment)
    c(signature)
    c("{")
    c.indent()
    if not uses_message(r):
        c("(void)m;")
        c("(void)i;")
    if raws:
        c(f"{rt} r[{len(raws)}];")
    return c


def put_function(v: "CView", m: Message, r: Repeat) -> str:
    raws, rt = element_raws(r)
    c = opened(r, raws, rt, f"/* Element i of {m.name}.{r.field.name}: checked, and written to its {r.stride} bytes at buf. */",
               f"static inline int {put_name(v, m, r)}(const {v.tname(m)} *m, size_t i, uint8_t *buf)")
    for leaf in r.leaves:
        if leaf.var in raws:
            v.encode_leaf(c, leaf, raws[leaf.var], rt)
    for span in spans(r.runs):
        v.put_span(c, span, raws, rt)
    c("return CW_OK;")
    c.dedent()
    c("}")
    return c.text()


def get_function(v: "CView", m: Message, r: Repeat) -> str:
    raws, rt = element_raws(r)
    c = opened(r, raws, rt, f"/* Element i of {m.name}.{r.field.name}: read from its {r.stride} bytes at buf, checked and stored. */",
               f"static inline int {get_name(v, m, r)}(const uint8_t *buf, size_t i, {v.tname(m)} *m)")
    for span in spans(r.runs):
        v.get_span(c, span, raws, rt)
    for leaf in r.leaves:
        if leaf.field.kind == "bytes":
            c(f"memcpy({v.member(leaf)}, buf + {leaf.pos // 8}, {leaf.field.length});")
        elif leaf.var in raws:
            v.decode_leaf(c, leaf, raws[leaf.var], m, rt)
    c("return CW_OK;")
    c.dedent()
    c("}")
    return c.text()


def gap_of_repeat(m: Message, r: Repeat):
    gaps = m.shortening.gaps if m.shortening else ()
    return next((g for g in gaps if g.field == r.field.name), None)


def encode_loops(v: "CView", c: Code, m: Message) -> None:
    """Write each Repeat's elements (in a frame that holds the whole array: elements past a
    count, or an absent array, are zeros, which the encoder then leaves out)."""
    for r in m.wire.repeats:
        element_loop(v, c, m, r, f"rc = {put_name(v, m, r)}(m, i, buf + {r.start}u + i * {r.stride}u);",
                     lambda first: f"memset(buf + {r.start}u + {first} * {r.stride}u, 0, "
                                   f"({r.count}u - {first}) * {r.stride}u);")


def decode_loop(v: "CView", c: Code, m: Message, r: Repeat) -> None:
    """Read, check and store each element of Repeat `r` the frame holds, in the field's place
    among the checks; elements past a count, or an absent array, are zeros."""
    member = f"m->{r.field.name}"
    element_loop(v, c, m, r, f"int rc = {get_name(v, m, r)}(buf + {r.start}u + i * {r.stride}u, i, m);",
                 lambda first: f"memset(&{member}[{first}], 0, ({r.count}u - {first}) * sizeof {member}[0]);")


def element_loop(v: "CView", c: Code, m: Message, r: Repeat, call: str, zeros) -> None:
    """`call` (which sets rc) for each element the frame holds, returning its error; `zeros(first)`
    clears the elements from `first` on: past a count, or all of an absent array."""
    gap = gap_of_repeat(m, r)
    count = f"{r.count}u"
    if gap is not None and gap.presence:
        c(f"if ({v.presence_test(m, gap)}) {{")
        c.indent()
    elif gap is not None and gap.counter:
        count = f"(size_t)m->{count_member(r.field.name)}"
    c(f"for (size_t i = 0u; i < {count}; i++) {{")
    c(f"    {call}")
    c("    if (rc != CW_OK) {")
    c("        return rc;")
    c("    }")
    c("}")
    if gap is not None and gap.presence:
        c.dedent()
        c("} else {")
        c(f"    {zeros('0u')}")
        c("}")
    elif gap is not None and gap.counter:
        c(zeros(count))
