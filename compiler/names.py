"""Identifier rules shared by every target: a schema name must be usable as-is
in Python, C and C++ and must not collide with names the generated code uses."""
from __future__ import annotations

import keyword
import re

IDENTIFIER = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*\Z")

C_KEYWORDS = frozenset("""
auto break case char const continue default do double else enum extern float for goto if
inline int long register restrict return short signed sizeof static struct switch typedef
union unsigned void volatile while _Alignas _Alignof _Atomic _Bool _Complex _Generic
_Imaginary _Noreturn _Static_assert _Thread_local alignas alignof and and_eq asm bitand
bitor bool catch char16_t char32_t class compl constexpr const_cast decltype delete
dynamic_cast explicit export false friend mutable namespace new noexcept not not_eq nullptr
operator or or_eq private protected public reinterpret_cast static_assert static_cast
template this thread_local throw true try typeid typename using virtual wchar_t xor xor_eq
NULL main errno assert offsetof
""".split())

PYTHON_KEYWORDS = frozenset(keyword.kwlist) | frozenset(keyword.softkwlist)

# Names the generated code defines on every message class or module.
GENERATED = frozenset({"encode", "decode", "validate", "self", "cls", "MESSAGE", "NAME"})


def name_problem(name: str) -> str | None:
    """Why `name` cannot be used as a schema name, or None if it can."""
    if not isinstance(name, str) or not IDENTIFIER.match(name):
        return f"{name!r} is not an identifier (letters, digits and _, not starting with a digit)"
    if not name.isascii():
        return f"{name!r} must be ASCII"
    if name in PYTHON_KEYWORDS:
        return f"{name!r} is a Python keyword"
    if name in C_KEYWORDS:
        return f"{name!r} is a C/C++ keyword or reserved name"
    if name.startswith("_") or "__" in name:
        return f"{name!r}: names starting with '_' or containing '__' are reserved for generated code"
    if name in GENERATED:
        return f"{name!r} is used by the generated code"
    return None


def camel(name: str) -> str:
    """snake_case → CamelCase for class names."""
    return "".join(part[:1].upper() + part[1:] for part in name.split("_") if part)
