"""Identifier rules shared by every target: a schema name must be usable as-is
in Python, C and C++ and must not collide with names the generated code uses."""
from __future__ import annotations

import keyword
import re
import sys

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
GENERATED = frozenset({"encode", "decode", "validate", "self", "cls", "MESSAGE", "NAME", "to_dict", "from_dict"})

# C99 guarantees 63 significant characters in an identifier; generated names
# add a prefix, so schema names stay well below that.
MAX_NAME_LENGTH = 40

# Class names every generated Python module defines or imports: a message, enum
# or flag set whose class name is one of these would replace it.
GENERATED_CLASSES = frozenset({
    "CodecError", "EncodeError", "DecodeError", "SequenceError", "StreamDecoder",
    "ClassVar", "Optional", "Union", "Fraction", "Decimal",
    "Any", "Callable", "Iterator", "Literal", "TypeVar", "AnyMessage",
})

# A protocol name becomes generated/python/<name>.py and generated/c/<name>.h: it
# must not shadow a standard module for code that puts generated/python on
# sys.path, nor replace the shared C runtime header codeword.h (prefix cw_).
RESERVED_PROTOCOLS = frozenset(sys.stdlib_module_names) | {"codeword", "cw"}
# Nor may <name>.h stand for a system header under `-I generated/c` (`#include
# <stdint.h>` would find the protocol's): the C89..C23 standard headers, common
# POSIX ones, and those the generated C includes (Python.h and structmember.h in
# the accelerators); a header in a folder (<sys/types.h>) cannot be met. Compared
# without case, as file systems on macOS and Windows do.
C_STANDARD_HEADERS = frozenset("""
assert complex ctype errno fenv float inttypes iso646 limits locale math setjmp signal
stdalign stdarg stdatomic stdbit stdbool stdckdint stddef stdint stdio stdlib stdnoreturn
string tgmath threads time uchar wchar wctype
""".split())
POSIX_HEADERS = frozenset("""
aio cpio dirent dlfcn fcntl fmtmsg fnmatch ftw glob grp iconv langinfo libgen
monetary mqueue ndbm netdb nl_types poll pthread pwd regex sched search
semaphore spawn strings stropts syslog tar termios trace ulimit unistd utime utmpx
wordexp alloca endian err getopt malloc memory features
""".split())
GENERATED_C_INCLUDES = frozenset({"python", "structmember"})
RESERVED_HEADERS = C_STANDARD_HEADERS | POSIX_HEADERS | GENERATED_C_INCLUDES
_RESERVED_MODULES = frozenset(n.lower() for n in RESERVED_PROTOCOLS)
# It is also generated/docs/<name>.md: `index` would overwrite the list of protocols.
RESERVED_PAGES = frozenset({"index"})


def name_problem(name: str) -> str | None:
    """Why `name` cannot be used as a schema name, or None if it can."""
    if not isinstance(name, str) or not IDENTIFIER.match(name):
        return f"{name!r} is not an identifier (letters, digits and _, not starting with a digit)"
    if not name.isascii():
        return f"{name!r} must be ASCII"
    if len(name) > MAX_NAME_LENGTH:
        return f"{name[:20]!r}… is {len(name)} characters long (at most {MAX_NAME_LENGTH})"
    if name in PYTHON_KEYWORDS:
        return f"{name!r} is a Python keyword"
    if name in C_KEYWORDS:
        return f"{name!r} is a C/C++ keyword or reserved name"
    if name.startswith("_") or "__" in name:
        return f"{name!r}: names starting with '_' or containing '__' are reserved for generated code"
    if name in GENERATED:
        return f"{name!r} is used by the generated code"
    return None


def protocol_name_problem(name: str) -> str | None:
    """Why `name` cannot name a protocol (a module and a header), or None."""
    problem = name_problem(name)
    if problem is None and name.lower() in _RESERVED_MODULES:
        problem = f"{name!r} is a Python standard module or codeword's own runtime"
    if problem is None and name.lower() in RESERVED_HEADERS:
        problem = (f"{name!r} is a C standard or system header: with -I generated/c, "
                   f"#include <{name.lower()}.h> would find the protocol's {name}.h")
    if problem is None and name in RESERVED_PAGES:
        problem = f"{name!r} would replace the docs page {name}.md"
    return problem


def camel(name: str) -> str:
    """snake_case → CamelCase for class names."""
    return "".join(part[:1].upper() + part[1:] for part in name.split("_") if part)
