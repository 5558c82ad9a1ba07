"""A bit field moved between its value and the bytes it touches with constant shifts: what
cw_put_bits and cw_get_bits (and their _lsb forms) do in a loop, written out by the
generator, which knows the field's place and width. One statement or term per byte, so a
codec grows with its fields, not with their widths; the compiler folds each shift.

Bit positions count from the frame's first byte. In the big-endian order (`cw_put_bits`)
bit 0 is the first byte's most significant bit and a field's most significant bit comes
first; in the little-endian order (`_lsb`) bit 0 is the first byte's least significant
bit and a field's least significant bit comes first (a DBC's Intel signal)."""
from __future__ import annotations

from .scalars import clit


def value_type(bits: int) -> str:
    """The unsigned type a value of `bits` bits is shifted in: never one that promotes to a
    signed int, and no wider than it needs (`unsigned` has 16 bits on an 8-bit MCU, where
    every wider shift takes several instructions)."""
    return "unsigned" if bits <= 16 else "uint32_t" if bits <= 32 else "uint64_t"


def _byte_shifts(pos: int, bits: int, order: str) -> list[tuple[int, int]]:
    """(byte, shift) for each byte the field touches: the value shifted right by `shift`
    (left by -shift) has, in its low 8 bits, the byte's bits of the field in place."""
    first, last = pos // 8, (pos + bits - 1) // 8
    if order == "little":
        return [(b, 8 * b - pos) for b in range(first, last + 1)]
    low = 7 - (pos + bits - 1) % 8  # where the value's least significant bit sits in the last byte
    return [(b, 8 * (last - b) - low) for b in range(first, last + 1)]


def _shifted(expr: str, shift: int) -> str:
    return f"({expr} >> {shift})" if shift > 0 else f"({expr} << {-shift})" if shift < 0 else expr


def put_statements(buf: str, pos: int, bits: int, order: str, value: str, ctype: str,
                   cut: bool = False) -> list[str]:
    """Statements that OR `value` (a variable of C type `ctype`, below 2**bits) into the
    zeroed bytes of `buf` its field takes; `cut`: `cut` bytes before them were left out."""
    shifted = value if ctype == value_type(bits) else f"({value_type(bits)}){value}"
    out = []
    for b, s in _byte_shifts(pos, bits, order):
        at = f"{b}u - cut" if cut else b
        out.append(f"{buf}[{at}] = (uint8_t)({buf}[{at}] | (uint8_t){_shifted(shifted, s) if s else value});")
    return out


def get_expression(buf: str, pos: int, bits: int, order: str) -> str:
    """The field's value read from `buf`, of value_type(bits)."""
    wide = value_type(bits)
    terms = [_shifted(f"({wide}){buf}[{b}]", -s) for b, s in _byte_shifts(pos, bits, order)]
    value = " | ".join(terms)
    exact = pos % 8 == 0 and (pos + bits) % 8 == 0  # whole bytes: no other field's bits
    if exact:
        return value if len(terms) == 1 else f"({value})"
    return f"({value} & {clit((1 << bits) - 1, True)})" if len(terms) == 1 else f"(({value}) & {clit((1 << bits) - 1, True)})"
