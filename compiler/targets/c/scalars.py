"""C integer types and literals: the narrowest type for a range, literals that keep
their value where int has 16 bits, and the codeword.h helpers chosen by width."""
from __future__ import annotations


from .errors import CTargetError

INT_TYPES = [(8, "int8_t", "uint8_t"), (16, "int16_t", "uint16_t"), (32, "int32_t", "uint32_t"),
             (64, "int64_t", "uint64_t")]


def int_ctype(lo: int, hi: int) -> str:
    for bits, signed, unsigned in INT_TYPES:
        if lo >= 0 and hi < (1 << bits):
            return unsigned
        if lo < 0 and lo >= -(1 << (bits - 1)) and hi < (1 << (bits - 1)):
            return signed
    raise CTargetError(f"no C integer type holds {lo}..{hi}")


def type_limits(ctype: str) -> tuple[int, int]:
    for bits, signed, unsigned in INT_TYPES:
        if ctype == unsigned:
            return 0, (1 << bits) - 1
        if ctype == signed:
            return -(1 << (bits - 1)), (1 << (bits - 1)) - 1
    if ctype == "char":
        return 0, 127
    raise KeyError(ctype)


def unsigned_type(bits: int) -> str:
    """The narrowest unsigned C type of at least `bits` bits (at most 64)."""
    return "uint8_t" if bits <= 8 else "uint16_t" if bits <= 16 else "uint32_t" if bits <= 32 else "uint64_t"


def sign_extend(bits: int) -> str:
    """The codeword.h function that sign-extends a raw value of `bits` bits."""
    return "cw_sign_extend_wide" if bits > 32 else "cw_sign_extend"


def clit(value: int, unsigned: bool = False) -> str:
    """An integer literal that has the intended value on 16-bit-int targets."""
    if value < 0:
        return f"(-{-value - 1} - 1)" if value <= -32768 else str(value)
    suffix = "u" if unsigned or value > 32767 else ""
    if value > 0xFFFF:
        suffix = "UL"
    if value > 0xFFFFFFFF:
        suffix = "ULL"
    return f"{value:#x}{suffix}" if value > 255 else f"{value}{suffix}"


def clit_signed(value: int) -> str:
    """A literal compared with a signed value: signed itself, long where int may be 16 bits."""
    if value < 0 or value <= 32767:
        return clit(value)
    return f"{value:#x}L" if value <= 0x7FFFFFFF else f"{value:#x}LL"


def final_step(cs, value: str, wide: str) -> str:
    """A sum's or xor's `value` (unsigned, reduced by the modulo) finished by the
    checksum's complement and xorout, in `wide` (`unsigned` or `uint32_t`, never a type
    that promotes to int) so that the two's complement wraps in the field's width."""
    if cs.complement == "ones":
        value = f"({value} ^ {clit((1 << cs.width) - 1, True)})"
    elif cs.complement == "twos":
        value = f"(({wide})(({wide})0u - {value}) & {clit((1 << cs.width) - 1, True)})"
    if cs.xorout is not None:
        value = f"({value} ^ {clit(cs.xorout, True)})"
    return value


# A message without values has one placeholder member; decoders set it, so a caller's
# struct handed on after a decode is never read unset (gcc -Wmaybe-uninitialized).
SET_UNUSED = "m->unused = 0u;  /* the placeholder of a message without values */"
