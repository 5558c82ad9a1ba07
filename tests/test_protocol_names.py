"""A protocol's name is a file name: generated/python/<name>.py and
generated/c/<name>.h. None may stand for a standard Python module or a C system
header (with -I generated/c, `#include <stdint.h>` would find the protocol's
header), whatever the case of its letters. The lists here are written out from the
C standards (C99, C11, C23), POSIX and the generated C's own includes."""
from __future__ import annotations

import sys

import pytest

from codeword.names import protocol_name_problem

C_HEADERS = ["assert", "complex", "ctype", "errno", "fenv", "float", "inttypes", "iso646", "limits", "locale",
             "math", "setjmp", "signal", "stdalign", "stdarg", "stdatomic", "stdbool", "stddef", "stdint", "stdio",
             "stdlib", "stdnoreturn", "string", "tgmath", "threads", "time", "uchar", "wchar", "wctype",
             "stdbit", "stdckdint"]
POSIX = ["unistd", "fcntl", "pthread", "dirent", "dlfcn", "termios", "poll", "sched", "semaphore", "strings",
         "syslog", "pwd", "grp", "regex", "glob", "fnmatch", "libgen", "netdb", "spawn", "utime", "endian"]
GENERATED_INCLUDES = ["stdint", "stdbool", "stddef", "string", "float", "Python", "structmember"]


@pytest.mark.parametrize("name", C_HEADERS + POSIX + GENERATED_INCLUDES)
def test_a_system_header_name_is_refused_in_any_case(name):
    for spelling in (name, name.upper(), name.capitalize()):
        assert protocol_name_problem(spelling), spelling


def test_every_python_standard_module_is_refused():
    accepted = [n for n in sorted(sys.stdlib_module_names) if not protocol_name_problem(n)]
    assert accepted == []
    assert protocol_name_problem("Struct") and protocol_name_problem("JSON")


@pytest.mark.parametrize("name", ["rover", "mtv4", "stdint_link", "my_stdio", "limits2"])
def test_other_names_are_accepted(name):
    assert protocol_name_problem(name) is None
