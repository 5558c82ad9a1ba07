"""A text message's id constant in C is its prefix as a string literal, also when the
prefix has several characters (a `'GPGGA'` character constant has an
implementation-defined value and warns under -Wmultichar) or characters C must
escape in a string (`"`, `\\`, a trigraph `??=`). The decoders compare the line's
prefix with that constant."""
from __future__ import annotations

import shutil
import subprocess

import pytest

from schema_in_a_test import render, run_c

SCHEMA = r"""codeword: 1
protocol: ids
title: t
source: s
framing: {kind: text, prefix_separator: ":", separator: ",", terminator: ";"}
messages:
  gga:
    id: GPGGA
    fields:
      - {name: n, type: u8}
  one:
    id: $
    fields:
      - {name: n, type: u8}
  odd:
    id: 'Q"\??='
    fields:
      - {name: n, type: u8}
"""

STRICT = ["-std=c99", "-Wall", "-Wextra", "-Wpedantic", "-Wconversion", "-Wsign-conversion", "-Wshadow",
          "-Wmultichar", "-Werror"]

DRIVER = r"""#include <stdio.h>
#include <string.h>
#include "ids.h"
int main(void) {
    ids_message_t msg;
    printf("%s %u\n", IDS_GGA_ID, (unsigned)strlen(IDS_GGA_ID));
    printf("%s %u\n", IDS_ONE_ID, (unsigned)strlen(IDS_ONE_ID));
    printf("%s %u\n", IDS_ODD_ID, (unsigned)strlen(IDS_ODD_ID));
    printf("%d\n", ids_decode("GPGGA:7;", 8u, IDS_DIR_ANY, &msg) == CW_OK && msg.kind == IDS_MSG_GGA);
    printf("%d\n", ids_decode("Q\"\\?\?=:7;", 9u, IDS_DIR_ANY, &msg) == CW_OK && msg.kind == IDS_MSG_ODD);
    return 0;
}
"""


def test_ids_are_string_constants_with_their_characters(tmp_path):
    render(tmp_path, "ids", SCHEMA)
    header = (tmp_path / "ids.h").read_text(encoding="utf-8")
    assert '#define IDS_GGA_ID "GPGGA"' in header
    assert '#define IDS_ONE_ID "$"' in header
    assert run_c(tmp_path, DRIVER, ("-Wmultichar", "-Wno-trigraphs")) == [
        "GPGGA 5", "$ 1", 'Q"\\??= 6', "1", "1"]


@pytest.mark.parametrize("compiler", ["gcc", "clang"])
def test_using_the_id_constants_compiles_warning_free(tmp_path, compiler):
    cc = shutil.which(compiler)
    assert cc, f"{compiler} is not installed"
    render(tmp_path, "ids", SCHEMA)
    src = tmp_path / "use.c"
    src.write_text('#include <string.h>\n#include "ids.h"\n'
                   "int main(void) { return (int)strlen(IDS_GGA_ID) + (int)strlen(IDS_ODD_ID); }\n",
                   encoding="utf-8")
    built = subprocess.run([cc, *STRICT, "-I", str(tmp_path), str(src), "-o", str(tmp_path / "use")],
                           capture_output=True, text=True, timeout=120)
    assert built.returncode == 0, built.stderr
