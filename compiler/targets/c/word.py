"""How the C target codes a binary message that fits one word of at most 32
bits: the message is built in one unsigned integer with shifts and written
with one store in the frame's bit order (big-endian most significant bit
first, little-endian least significant bit first), and read back with one
load, as hand-written firmware does. A parity bit over fields is then the parity of that word,
not of the fields one by one; a parity, sum or xor over bytes that shares its
bytes with other fields is taken over the word's covered bytes. A message
with a CRC (it runs over bytes in memory) or a checksum in whole bytes of its
own is left to the byte-wise codec.

Inside the word the fields keep cpack's byte-aligned parts: each part is
packed in the narrowest integer that holds it (16 bits where it fits) and
moved into the word by whole bytes, which 8-bit targets do with register
moves instead of 32-bit shift loops; on wider targets the compiler merges
the shifts.

Checks and error kinds are the field-by-field codec's (`<msg>_raw` and
`<msg>_check_raw`, which the text form still uses), in the same order; only
where the raw values live differs: a local per field instead of an array.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Optional

from .scalars import SET_UNUSED, clit, final_step, type_limits
from ..code import Code
from .pack import Span
from ...model import Leaf, shift_in

if TYPE_CHECKING:
    from ...model import Message
    from .view import CView


@dataclass(frozen=True)
class Word:
    size: int  # bytes, 1 to 4
    parts: tuple[Span, ...]  # cpack's byte-aligned spans, first byte first
    order: str = "big"  # byte order of the word: the frame's bit order

    @property
    def ctype(self) -> str:
        return int_type(self.size)

    @property
    def pieces(self) -> list[Leaf]:
        return [p for part in self.parts for p in part.pieces]

    def part_of(self, piece: Leaf) -> Span:
        return next(part for part in self.parts if piece in part.pieces)

    def byte_shift(self, part: Span) -> int:
        """Where `part` sits in the word, from bit 0."""
        return self.shift(8 * part.start, 8 * part.size)

    def shift(self, pos: int, bits: int) -> int:
        """Where the `bits` bits from frame bit `pos` sit in the word, from bit 0."""
        return shift_in(self.order, 0, self.size, pos, bits)


def int_type(size: int) -> str:
    return "unsigned" if size <= 2 else "uint32_t"  # unsigned: at least 16 bits


def leaf_type(leaf: Leaf) -> str:
    bits = leaf.field.bits
    return "uint8_t" if bits <= 8 else "uint16_t" if bits <= 16 else "uint32_t"


def mask(bits: int) -> str:
    return clit((1 << bits) - 1, True)


def container(v: "CView", m: "Message") -> Optional[Word]:
    """The message as one word, or None when it does not fit one: over 4 bytes,
    a `bytes` field, a CRC, Fletcher or internet checksum, a checksum over bytes in whole
    bytes of its own (the byte-wise loop is smaller on AVR) or a multi-byte
    integer in the other byte order than the word's, a frame that may be cut short, or
    one whose fields are read and written only when their multiplexors select them."""
    if v.text or m.size is None or not 1 <= m.size <= 4 or m.shortening:
        return None
    if any(leaf.field.multiplexed_by for leaf in m.wire.leaves):
        return None
    spans = v.spans(m)
    for span in spans:
        leaf = span.pieces[0]
        if any(v.is_byte_checksum(p) and p.field.checksum.algorithm in ("crc", "fletcher", "internet")
               for p in span.pieces):
            return None
        if span.kind == "pack" and span.size > 1 and span.order != m.wire.order:
            return None  # fields placed in the other bit order than the frame's
        if span.kind == "pack":
            continue
        if span.kind != "int" or v.is_byte_checksum(leaf):
            return None
        if span.size > 1 and v.order_of(leaf.field) != m.wire.order:
            return None
    return Word(m.size, tuple(spans), m.wire.order)


def field_sums(word: Word) -> list[Leaf]:
    """Every checksum, in wire order (over fields or over bytes: never both, the resolver
    refuses a checksum over fields beside another checksum)."""
    return [p for p in word.pieces if p.field.checksum]


def over_bytes(leaf: Leaf) -> bool:
    return leaf.field.checksum.over == "bytes"


def bytes_checksum(word: Word, leaf: Leaf) -> str:
    """A parity, sum or xor over the covered bytes of `word`, as the leaf's type (a
    Fletcher checksum, like a CRC, keeps the message out of a word). The
    encoder calls it with the checksums after `leaf` still 0 (none is covered)."""
    cs = leaf.field.checksum
    rt = leaf_type(leaf)
    start, end = cs.byte_span
    if cs.algorithm == "parity":
        covered = ((1 << 8 * (end - start)) - 1) << word.shift(8 * start, 8 * (end - start))
        value = "word" if covered == (1 << 8 * word.size) - 1 else f"word & {clit(covered, True)}"
        flip = " ^ 1u" if cs.parity == "odd" else ""
        return f"({rt})(cw_parity32({value}){flip})"
    shifts = [word.shift(8 * i, 8) for i in range(start, end)]
    data = [f"(uint8_t)(word >> {s})" if s else "(uint8_t)word" for s in shifts]
    data[0] = f"(unsigned){data[0]}"  # at most 4 bytes: the sum fits 16 bits
    op = " + " if cs.algorithm == "sum" else " ^ "
    value = f"({op.join(data)})"
    if cs.modulo:
        value = f"({value} % {clit(cs.modulo, True)})"
    return f"({rt}){final_step(cs, value, 'uint32_t' if rt == 'uint32_t' else 'unsigned')}"


def fills_type(piece: Leaf) -> bool:
    """The piece is as wide as its C type: the type's width masks it."""
    return piece.bits in (8, 16, 32)


def fits_field(v: "CView", leaf: Leaf) -> bool:
    """Whether the value encode_leaf leaves for `leaf` is known to fit its
    bits (checked or masked there), so that packing needs no mask."""
    f = leaf.field
    if f.checksum or f.reserved or f.kind == "bool":
        return True
    if f.const is not None or f.length_of or f.flags is not None or f.one_hot:
        return False
    if f.kind == "int":
        return True  # encode_leaf masks two's complement to the field, enum or not
    if f.enum is not None:  # checked to be a member
        return f.enum.kind == "int" and all(0 <= x.value < (1 << f.bits) for x in f.enum.members)
    if f.kind != "uint":
        return False
    lo, hi = v.int_bounds(f)
    tlo, thi = type_limits(v.rep(f).ctype)
    off = int(f.offset or 0) if f.scale is None else 0
    return 0 <= max(lo, tlo) - off and min(hi, thi) - off < (1 << f.bits)


# -- encode ---------------------------------------------------------------------------------
def place(v: "CView", word: Word, pieces: list[Leaf]) -> str:
    """The word's bits of `pieces` (all of one part, or of several), from their locals."""
    out = []
    for part in word.parts:
        mine = [p for p in pieces if p in part.pieces]
        if not mine:
            continue
        pt = int_type(part.size)
        terms = []
        for piece in mine:
            value = f"({pt}){piece.var}"
            if not (fills_type(piece) or fits_field(v, piece)):
                value = f"({value} & {mask(piece.bits)})"
            shift = part.shift(piece)
            terms.append(f"({value} << {shift})" if shift else value)
        value = " | ".join(terms)
        shift = word.byte_shift(part)
        if terms == [f"({pt}){mine[0].var}"]:  # a lone unshifted value: one cast will do
            value = f"({word.ctype}){mine[0].var}"
        elif shift or pt != word.ctype:
            value = f"({word.ctype})({value})" if len(terms) > 1 else f"({word.ctype}){terms[0]}"
        out.append(f"({value} << {shift})" if shift else value)
    return " | ".join(out) or "0u"


def checksum_value(v: "CView", word: Word, leaf: Leaf) -> str:
    cs = leaf.field.checksum
    rt = leaf_type(leaf)
    if over_bytes(leaf):
        return bytes_checksum(word, leaf)
    if cs.algorithm == "parity":  # the other fields' parity is the word's: the bit is still 0 in it
        flip = " ^ 1u" if cs.parity == "odd" else ""
        return f"({rt})(cw_parity32(word){flip})"
    return v.field_checksum(leaf, [p.var for p in word.pieces if p is not leaf], rt)


def encode_function(v: "CView", m: "Message", word: Word) -> str:
    c = Code()
    c(f"static inline int {v.fn(m, 'encode')}(const {v.tname(m)} *m, uint8_t *buf, size_t cap)")
    c("{")
    c.indent()
    for piece in word.pieces:
        c(f"{leaf_type(piece)} {piece.var};")
    c(f"{word.ctype} word;")
    if not any(p.field.is_member for p in word.pieces):
        c("(void)m;")
    v.rule_checks(c, m, "m")
    for piece in word.pieces:
        v.encode_leaf(c, piece, piece.var, leaf_type(piece))
    c(f"if (cap < {m.size}u) {{")
    c("    return CW_ERR_CAPACITY;")
    c("}")
    # Checksums in wire order, each over the others with the later ones still 0,
    # as <msg>_raw. A sum over fields is taken over the values; a parity, or any
    # checksum over bytes, over the word, so the word is built before the first
    # of those and the sums before it go in.
    sums = field_sums(word)
    done: list[Leaf] = []
    built = False
    for leaf in sums:
        piece = next(p for p in word.pieces if p is leaf)
        if (leaf.field.checksum.algorithm == "parity" or over_bytes(leaf)) and not built:
            ready = [p for p in word.pieces if p not in sums or p in done]
            c(f"word = {place(v, word, ready)};")
            built = True
        c(f"{leaf.var} = {checksum_value(v, word, leaf)};")
        if built:
            c(f"word |= {place(v, word, [piece])};")
        done.append(leaf)
    if not built:
        c(f"word = {place(v, word, word.pieces)};")
    c(v.int_put(0, m.size, word.order, "word"))
    c(f"return {m.size};")
    c.dedent()
    c("}")
    return c.text()


# -- decode ---------------------------------------------------------------------------------
def read(word: Word, piece: Leaf, local: dict) -> str:
    """The statement reading a piece's raw value into its local: from its
    part's local when the part has one, else straight from the word."""
    part = word.part_of(piece)
    shift = part.shift(piece)
    if part.start in local:
        name = local[part.start]
    else:
        name, shift = "word", shift + word.byte_shift(part)
    value = f"({name} >> {shift})" if shift else name
    if not fills_type(piece):
        value = f"({value} & {mask(piece.bits)})"
    return f"{piece.var} = ({leaf_type(piece)}){value};"


def decode_function(v: "CView", m: "Message", word: Word) -> str:
    sums = field_sums(word)
    # a parity bit over fields is checked on the word: its own value is read only
    # for a sum over it; a checksum over bytes is compared with its bits
    parity_only = all(leaf.field.checksum.algorithm == "parity" and not over_bytes(leaf) for leaf in sums)
    pieces = [p for p in word.pieces if not (parity_only and p in sums)]
    # a narrower part read for several pieces gets a local of its width (16-bit shifts on 8-bit targets)
    parts = [part for part in word.parts
             if int_type(part.size) != word.ctype and sum(p in part.pieces for p in pieces) > 1]
    local = {part.start: f"w{word.parts.index(part)}" for part in parts}
    c = Code()
    c(f"static inline int {v.fn(m, 'decode')}(const uint8_t *buf, size_t len, {v.tname(m)} *m)")
    c("{")
    c.indent()
    for piece in pieces:
        c(f"{leaf_type(piece)} {piece.var};")
    c(f"{word.ctype} word;")
    for part in parts:
        c(f"{int_type(part.size)} {local[part.start]};")
    if not m.members:
        c(SET_UNUSED)
    c(f"if (len != {m.size}u) {{")
    c("    return CW_ERR_LENGTH;")
    c("}")
    c(f"word = {v.int_get(0, m.size, word.order)};")
    pad = m.size * 8 - m.bits  # under 8: the padding fills the last byte
    if pad:
        v.fail_if(c, f"(word & {clit(((1 << pad) - 1) << word.shift(m.bits, pad), True)}) != 0u", "reserved")
    for part in parts:
        shift = word.byte_shift(part)
        c(f"{local[part.start]} = ({int_type(part.size)})" + (f"(word >> {shift});" if shift else "word;"))
    for piece in pieces:
        c(read(word, piece, local))
    for leaf in sums:  # before the fields' checks, as the byte-wise decoder
        if over_bytes(leaf):
            v.fail_if(c, f"{leaf.var} != {bytes_checksum(word, leaf)}", "checksum")
    for piece in word.pieces:
        v.decode_leaf(c, piece, piece.var, m)
    for leaf in sums:
        cs = leaf.field.checksum
        if over_bytes(leaf):
            continue
        if cs.algorithm == "parity":  # the padding is 0: the word's parity is that of its fields
            v.fail_if(c, f"cw_parity32(word) != {1 if cs.parity == 'odd' else 0}u", "checksum")
        else:
            others = [p.var for p in word.pieces if p is not leaf]
            v.fail_if(c, f"{leaf.var} != {v.field_checksum(leaf, others, leaf_type(leaf))}", "checksum")
    v.rule_checks(c, m, "m")
    c("return CW_OK;")
    c.dedent()
    c("}")
    return c.text()
