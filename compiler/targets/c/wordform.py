"""The word form of a bit-packed protocol in C: `<msg>_to_word` and
`<msg>_from_word` move a message between its bytes and one unsigned word,
left-aligned in the protocol's word_bits (or max_bits), low bits zero.

A word of up to 32 bits is a uint32_t. A wider one, up to 64 bits (a message
of up to 8 bytes), is a uint64_t whose bytes are moved one shift each: the
runtime's byte helpers stop at 32 bits.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

from .scalars import clit
from ..code import Code

if TYPE_CHECKING:
    from ...model import Message
    from .view import CView


def word_type(word_bits: int) -> str:
    return "uint32_t" if word_bits <= 32 else "uint64_t"


def word_functions(v: "CView", m: "Message") -> str:
    w = v.word_bits()
    return narrow(v, m, w) if w <= 32 else wide(v, m, w)


def narrow(v: "CView", m: "Message", w: int) -> str:
    """A uint32_t word; the message has at most 4 bytes (its bits fit the word)."""
    bits = 8 * m.size
    c = Code()
    c(f"static inline int {v.fn(m, 'to_word')}(const {v.tname(m)} *m, uint32_t *word)")
    c("{")
    c(f"    uint8_t b[{m.size}] = {{0}};  /* encode fills it; compilers cannot always tell */")
    c(f"    int rc = {v.fn(m, 'encode')}(m, b, sizeof b);")
    c("    if (rc < 0) {")
    c("        return rc;")
    c("    }")
    shift = f" << {w - bits}" if bits < w else f" >> {bits - w}" if bits > w else ""
    c(f"    *word = cw_get_be(b, {m.size}u){shift};")
    c("    return CW_OK;")
    c("}")
    c("")
    c(f"static inline int {v.fn(m, 'from_word')}(uint32_t word, {v.tname(m)} *m)")
    c("{")
    c(f"    uint8_t b[{m.size}];")
    if w < 32:
        v.fail_if(c.indent(), f"word > {clit((1 << w) - 1, True)}", "range")
        c.dedent()
    if bits < w:
        v.fail_if(c.indent(), f"(word & {clit((1 << (w - bits)) - 1, True)}) != 0u", "reserved")
        c.dedent()
        c(f"    cw_put_be(b, {m.size}u, word >> {w - bits});")
    else:
        c(f"    cw_put_be(b, {m.size}u, word{' << ' + str(bits - w) if bits > w else ''});")
    c(f"    return {v.fn(m, 'decode')}(b, sizeof b, m);")
    c("}")
    return c.text()


def wide(v: "CView", m: "Message", w: int) -> str:
    """A uint64_t word; the message has up to 8 bytes."""
    n, bits = m.size, 8 * m.size
    shifts = [8 * (n - 1 - i) for i in range(n)]
    c = Code()
    c(f"static inline int {v.fn(m, 'to_word')}(const {v.tname(m)} *m, uint64_t *word)")
    c("{")
    c.indent()
    c(f"uint8_t b[{n}] = {{0}};  /* encode fills it; compilers cannot always tell */")
    c(f"int rc = {v.fn(m, 'encode')}(m, b, sizeof b);")
    c("if (rc < 0) {")
    c("    return rc;")
    c("}")
    value = " | ".join(f"((uint64_t)b[{i}] << {s})" if s else f"(uint64_t)b[{i}]"
                       for i, s in enumerate(shifts))
    if bits != w:
        value = f"({value}) {'<<' if bits < w else '>>'} {abs(w - bits)}"
    c(f"*word = {value};")
    c("return CW_OK;")
    c.dedent()
    c("}")
    c("")
    c(f"static inline int {v.fn(m, 'from_word')}(uint64_t word, {v.tname(m)} *m)")
    c("{")
    c.indent()
    c(f"uint8_t b[{n}];")
    if w < 64:
        v.fail_if(c, f"word > {clit((1 << w) - 1, True)}", "range")
    if bits < w:
        v.fail_if(c, f"(word & {clit((1 << (w - bits)) - 1, True)}) != 0u", "reserved")
        c(f"word >>= {w - bits};")
    elif bits > w:
        c(f"word <<= {bits - w};")
    for i, s in enumerate(shifts):
        c(f"b[{i}] = (uint8_t)(word >> {s});" if s else f"b[{i}] = (uint8_t)word;")
    c(f"return {v.fn(m, 'decode')}(b, sizeof b, m);")
    c.dedent()
    c("}")
    return c.text()
