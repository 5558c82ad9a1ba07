"""A CRC's C function, with every method of computing it: the header's user picks one
when compiling (`<PX>_CRC_<METHOD>`), trading flash for speed; each method's tables are
`const`, in flash on AVR, and every method gives the same CRC."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

from ...crc import reflect
from ...model import Checksum, CrcParams
from ..code import Code
from .scalars import unsigned_type


@dataclass(frozen=True)
class Method:
    guard: str  # the macro is <PX>_CRC_<guard>
    entries: int  # table entries: a 16-bit CRC's take twice as many bytes, a 32-bit one's four times
    what: str


METHODS = (
    Method("BITWISE", 0, "bit by bit, no table"),
    Method("NIBBLE", 16, "a nibble at a time from 16 entries"),
    Method("SPLIT", 32, "a byte at a time from two 16-entry tables, one for each nibble"),
    Method("TABLE", 256, "a byte at a time from 256 entries"),
    Method("SLICE4", 1024, "four bytes at a time from four 256-entry tables"),
    Method("SLICE8", 2048, "eight bytes at a time from eight 256-entry tables"),
)
# The smallest method that makes the in-place scan at least twice as fast as MAVLink's
# parser on a host, for a few dozen bytes of flash (docs/c-size.md, "CRC methods").
DEFAULT = "SPLIT"
DEFAULT_METHOD = next(m for m in METHODS if m.guard == DEFAULT)
SLICES = {"SLICE4": 4, "SLICE8": 8}
READS = {"uint8_t": "CW_READ_U8", "uint16_t": "CW_READ_U16", "uint32_t": "CW_READ_U32"}


def methods_check(guard: str) -> str:
    """Preprocessor lines refusing more than one method: a header uses one for all its CRCs."""
    names = [f"{guard}_CRC_{m.guard}" for m in METHODS]
    return "\n".join([f"#if {' + '.join(f'defined({n})' for n in names)} > 1",
                      f'#error "define at most one of {", ".join(names)}"', "#endif"])


def crc_table(p: CrcParams, bits: int = 8) -> list[int]:
    """The lookup table of the algorithm the C code runs `bits` bits at a time (8: 256
    entries; 4: 16 entries, for the nibble-wise one)."""
    table = []
    if p.refin:
        rpoly = reflect(p.poly, p.width)
        for value in range(1 << bits):
            reg = value
            for _ in range(bits):
                reg = (reg >> 1) ^ rpoly if reg & 1 else reg >> 1
            table.append(reg)
    elif p.width >= 8:
        mask, top = (1 << p.width) - 1, 1 << (p.width - 1)
        for value in range(1 << bits):
            reg = value << (p.width - bits)
            for _ in range(bits):
                reg = ((reg << 1) ^ p.poly) & mask if reg & top else (reg << 1) & mask
            table.append(reg)
    else:  # widths under 8 run on a register left-aligned in a byte
        poly = p.poly << (8 - p.width)
        for value in range(1 << bits):
            reg = value << (8 - bits)
            for _ in range(bits):
                reg = ((reg << 1) ^ poly) & 0xFF if reg & 0x80 else (reg << 1) & 0xFF
            table.append(reg)
    return table


def slice_tables(p: CrcParams, count: int) -> list[list[int]]:
    """Table j holds each byte's contribution when j zero bytes follow it: slicing by
    `count` looks up each of `count` bytes in its own table and XORs the results."""
    tables = [crc_table(p)]
    for _ in range(count - 1):
        tables.append([zero_byte(p, tables[0], reg) for reg in tables[-1]])
    return tables


def zero_byte(p: CrcParams, table: list[int], reg: int) -> int:
    """The register after one zero byte, a byte at a time from the 256-entry table."""
    if p.refin:
        return (reg >> 8) ^ table[reg & 0xFF]
    if p.width <= 8:  # the register is (left-aligned in) one byte: all of it leaves
        return table[reg]
    return ((reg << 8) & ((1 << p.width) - 1)) ^ table[reg >> (p.width - 8)]


def clit_hex(value: int, digits: int, ctype: str) -> str:
    suffix = {"uint8_t": "u", "uint16_t": "u", "uint32_t": "UL", "uint64_t": "ULL"}[ctype]
    return f"0x{value:0{digits}X}{suffix}"


def byte_loop(c: Code, extra: Optional[str], start: str = "i = 0") -> None:
    """Opens the loop over the data; with an extra byte, one more turn reads it as `byte`."""
    if not extra:
        c(f"for ({start}; i < len; i++) {{")
        return
    c(f"for ({start}; i <= len; i++) {{  /* the data, then the message's extra byte */")
    c("    const uint8_t byte = i < len ? data[i] : extra;")


class CrcCode:
    """The C of one CRC (its Rocksoft parameters `p`) as the function `name`."""

    def __init__(self, name: str, cs: Checksum, guard: str) -> None:
        p = self.p = cs.crc
        self.name, self.extra, self.guard = name, cs.extra, guard
        self.t = unsigned_type(p.width)
        self.widen = "(unsigned)" if p.width <= 16 else ""  # shifts never hit a signed int
        self.left = not p.refin and p.width < 8  # the register runs left-aligned in a byte
        self.keep = "" if p.width in (8, 16, 32, 64) else f" & {clit_hex((1 << p.width) - 1, 1, self.t)}"
        self.read = READS.get(self.t)  # None for 64 bits: those run bitwise only
        self.byte = "byte" if cs.extra else "data[i]"
        self.digits = 2 if self.left else (p.width + 3) // 4

    def code(self) -> str:
        p, t, c = self.p, self.t, Code()
        c(f"/* {p.name}: width {p.width}, poly {p.poly:#x}, init {p.init:#x}, refin {str(p.refin).lower()}, "
          f"refout {str(p.refout).lower()}, xorout {p.xorout:#x} */")
        chosen = self.chosen()
        if self.read:
            tabled = [m for _, m in chosen if m.entries]
            for n, method in enumerate(tabled):
                test = f"defined({self.guard}_CRC_{method.guard})"
                if method.guard == DEFAULT:  # selected by its macro or by none
                    test = f"!defined({self.guard}_CRC_BITWISE)"
                c(("#if " if n == 0 else "#elif ") + test)
                self.tables(c, method)
            c("#endif")
        init = (p.init << (8 - p.width)) if self.left else (reflect(p.init, p.width) if p.refin else p.init)
        c(f"static inline {t} {self.name}(const uint8_t *data, size_t len{', uint8_t extra' if self.extra else ''})")
        c("{")
        c.indent()
        c(f"{t} reg = {clit_hex(init, 1, t)};")
        c("size_t i;")
        if self.read:
            for test, method in chosen:
                c(test)
                self.loop(c, method)
            c("#endif")
        else:
            self.bitwise(c)
        if self.left:
            c(f"reg = (uint8_t)({self.widen}reg >> {8 - p.width});")
        if p.refin != p.refout:
            self.reflect_out(c)
        c(f"return ({t})(reg ^ {clit_hex(p.xorout, 1, t)});")
        c.dedent()
        c("}")
        return c.text()

    def chosen(self) -> list[tuple[str, Method]]:
        """(preprocessor test, method) in turn: every other method when its macro is
        defined, then the default, which is also what its own macro selects."""
        others = [m for m in METHODS if m.guard != DEFAULT]
        tests = [("#if" if n == 0 else "#elif") + f" defined({self.guard}_CRC_{m.guard})" for n, m in enumerate(others)]
        return list(zip(tests, others)) + [("#else", next(m for m in METHODS if m.guard == DEFAULT))]

    def tables(self, c: Code, method: Method) -> None:
        if method.guard in SLICES:
            rows = slice_tables(self.p, SLICES[method.guard])
            shape, name = f"[{len(rows)}][256]", "slices"
        elif method.guard == "SPLIT":
            table = crc_table(self.p)
            rows, shape, name = [table[:16], table[::16]], "[2][16]", "split"  # low nibble, high nibble
        else:
            rows = [crc_table(self.p, 8 if method.guard == "TABLE" else 4)]
            shape, name = f"[{method.entries}]", "table" if method.guard == "TABLE" else "nibbles"
        c(f"static const {self.t} {self.name}_{name}{shape} CW_FLASH = {{")
        per = 8 if self.p.width > 16 else 12
        for row in rows:
            if len(rows) > 1:
                c("    {")
            for i in range(0, len(row), per):
                pad = "        " if len(rows) > 1 else "    "
                c(pad + ", ".join(clit_hex(v, self.digits, self.t) for v in row[i:i + per]) + ",")
            if len(rows) > 1:
                c("    },")
        c("};")

    def loop(self, c: Code, method: Method) -> None:
        if method.guard == "BITWISE":
            self.bitwise(c)
        elif method.guard == "NIBBLE":
            self.nibble(c)
        elif method.guard == "SPLIT":
            byte_loop(c, self.extra)
            self.split_step(c)
            c("}")
        elif method.guard == "TABLE":
            byte_loop(c, self.extra)
            c("    " + self.table_step(f"{self.name}_table"))
            c("}")
        else:
            self.slices(c, SLICES[method.guard])

    def table_step(self, table: str) -> str:
        """One byte through a 256-entry table."""
        p, t, w, look = self.p, self.t, self.widen, f"{self.read}(&{table}"
        if p.refin:
            shift = f"({t})({w}reg >> 8)" if p.width > 8 else "0u"
            return f"reg = ({t})({look}[({w}reg ^ {self.byte}) & 0xFFu]) ^ {shift});"
        if self.left or p.width == 8:
            return f"reg = {look}[({w}reg ^ {self.byte}) & 0xFFu]);"
        return f"reg = ({t})((({w}reg << 8) ^ {look}[(({w}reg >> {p.width - 8}) ^ {self.byte}) & 0xFFu])){self.keep});"

    def split_step(self, c: Code) -> None:
        """One byte through two 16-entry tables: its table entry is the XOR of its low
        nibble's and its high nibble's (a CRC is linear), two lookups that do not wait
        on each other."""
        p, t, w = self.p, self.t, self.widen
        into = f"({w}reg >> {p.width - 8})" if not p.refin and not self.left and p.width > 8 else f"{w}reg"
        c(f"    const uint8_t x = (uint8_t)({into} ^ {self.byte});")
        both = f"{self.read}(&{self.name}_split[0][x & 0xFu]) ^ {self.read}(&{self.name}_split[1][x >> 4])"
        if p.refin:
            shift = f" ^ ({w}reg >> 8)" if p.width > 8 else ""
            c(f"    reg = ({t})({both}{shift});")
        elif self.left or p.width == 8:
            c(f"    reg = (uint8_t)({both});")
        else:
            c(f"    reg = ({t})((({w}reg << 8) ^ {both}){self.keep});")

    def nibble(self, c: Code) -> None:
        p, t, w = self.p, self.t, self.widen
        byte_loop(c, self.extra)
        nibble = f"{self.read}(&{self.name}_nibbles"
        if p.refin:
            c(f"    reg = ({t})(reg ^ {self.byte});")
            for _ in range(2):
                c(f"    reg = ({t})(({w}reg >> 4) ^ {nibble}[{w}reg & 0xFu]));")
        elif self.left or p.width == 8:
            c(f"    reg = (uint8_t)(reg ^ {self.byte});")
            for _ in range(2):
                c(f"    reg = (uint8_t)((({w}reg << 4) & 0xFFu) ^ {nibble}[{w}reg >> 4]));")
        else:
            c(f"    reg = ({t})(reg ^ {self.aligned_byte()});")
            for _ in range(2):
                c(f"    reg = ({t})((({w}reg << 4) ^ {nibble}[({w}reg >> {p.width - 4}) & 0xFu])){self.keep});")
        c("}")

    def slices(self, c: Code, count: int) -> None:
        """`count` bytes a turn, each looked up in its own table, then the rest a byte at a
        time from the first table. The register meets the first bytes of a turn (all of
        it: count * 8 >= the width), the others enter as they are."""
        p, t, w = self.p, self.t, self.widen
        width = 8 if self.left else p.width
        c(f"for (i = 0; len - i >= {count}u; i += {count}u) {{")
        terms = []
        for k in range(count):
            at = f"data[i + {k}u]" if k else "data[i]"
            shift = 8 * k if p.refin else width - 8 - 8 * k
            if (8 * k >= width) if p.refin else shift <= -8:
                index = at
            elif shift == 0:
                index = f"({w}reg ^ {at}) & 0xFFu"
            else:
                moved = f"{w}reg >> {shift}" if shift > 0 else f"{w}reg << {-shift}"
                index = f"(({moved}) ^ {at}) & 0xFFu"
            terms.append(f"{self.read}(&{self.name}_slices[{count - 1 - k}][{index}])")
        lines = [f"    reg = ({t})({terms[0]}"] + [f"        ^ {term}" for term in terms[1:]]
        lines[-1] += ");"
        for line in lines:
            c(line)
        c("}")
        byte_loop(c, self.extra, start="")
        c("    " + self.table_step(f"{self.name}_slices[0]"))
        c("}")

    def aligned_byte(self) -> str:
        """The byte at the top of a register of 8 bits or more, MSB first."""
        p, w = self.p, self.widen
        if p.width == 8:
            return self.byte
        return f"({w}{self.byte} << {p.width - 8})" if p.width <= 16 else f"(({self.t}){self.byte} << {p.width - 8})"

    def bitwise(self, c: Code) -> None:
        p, t, w = self.p, self.t, self.widen
        byte_loop(c, self.extra)
        c.indent()
        c("uint8_t bit;")
        if p.refin:
            c(f"reg = ({t})(reg ^ {self.byte});")
            c("for (bit = 0; bit < 8u; bit++) {")
            rpoly = clit_hex(reflect(p.poly, p.width), 1, t)
            c(f"    reg = (reg & 1u) ? ({t})(({w}reg >> 1) ^ {rpoly}) : ({t})({w}reg >> 1);")
        elif self.left:
            poly = (p.poly << (8 - p.width)) & 0xFF
            c(f"reg = (uint8_t)(reg ^ {self.byte});")
            c("for (bit = 0; bit < 8u; bit++) {")
            c(f"    reg = (reg & 0x80u) ? (uint8_t)(({w}reg << 1) ^ {poly:#x}u) : (uint8_t)({w}reg << 1);")
        else:
            top, poly = clit_hex(1 << (p.width - 1), 1, t), clit_hex(p.poly, 1, t)
            c(f"reg = ({t})(reg ^ {self.aligned_byte()});")
            c("for (bit = 0; bit < 8u; bit++) {")
            c(f"    reg = (reg & {top}) ? ({t})((({w}reg << 1) ^ {poly}){self.keep}) : ({t})(({w}reg << 1){self.keep});")
        c("}")
        c.dedent()
        c("}")

    def reflect_out(self, c: Code) -> None:
        p, t, w = self.p, self.t, self.widen
        c("{")
        c(f"    {t} out = 0;")
        c("    uint8_t n;")
        c(f"    for (n = 0; n < {p.width}u; n++) {{")
        c(f"        out = ({t})(({w}out << 1) | ({w}reg & 1u));")
        c(f"        reg = ({t})({w}reg >> 1);")
        c("    }")
        c("    reg = out;")
        c("}")


def crc_code(name: str, cs: Checksum, guard: str) -> str:
    return CrcCode(name, cs, guard).code()
