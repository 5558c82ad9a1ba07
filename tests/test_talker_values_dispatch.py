"""Two text messages whose prefixes have one shape: `romeo` is a talker of three letters
then I, `delta` a talker of one letter then UEI, so OUEI could be either by its shape.
Romeo's talker is one of HLJ and NWA, which tells them apart (the resolver accepts the
schema for that reason): OUEI is delta's, HLJI romeo's, and XYZI neither's. Python and C
dispatch the lines alike."""
from __future__ import annotations

import pytest

from schema_in_a_test import load, render, run_c

SCHEMA = """codeword: 1
protocol: talk
title: talkers of two lengths
source: hand-written
framing:
  kind: text
  prefix_separator: '='
  separator: ','
  terminator: '*'
messages:
  romeo:
    id: I
    fields:
      - {name: talker, type: str, length: 3, prefix: true, values: [HLJ, NWA]}
      - {name: a, type: u8}
  delta:
    id: UEI
    fields:
      - {name: talker, type: str, length: 1, prefix: true}
      - {name: b, type: u8}
"""

LINES = {"OUEI=7*": ("delta", "O", 7), "HLJI=5*": ("romeo", "HLJ", 5), "NWAI=6*": ("romeo", "NWA", 6)}


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    where = tmp_path_factory.mktemp("talk")
    render(where, "talk", SCHEMA)
    return where, load(where / "talk.py")


def test_python_tells_the_messages_apart_by_the_talkers_values(built):
    mod = built[1]
    for line, (name, talker, value) in LINES.items():
        m = mod.decode(line)
        assert (type(m).NAME, m.talker, getattr(m, "a" if name == "romeo" else "b")) == (name, talker, value)
    with pytest.raises(mod.DecodeError) as e:
        mod.decode("XYZI=1*")
    assert e.value.rule == "dispatch"


def test_c_tells_the_messages_apart_by_the_talkers_values(built):
    calls = "\n".join(f'    show("{line}");' for line in [*LINES, "XYZI=1*"])
    driver = f"""#include <stdio.h>
#include <string.h>
#include "talk.h"
static void show(const char *line) {{
    talk_message_t m;
    int rc = talk_decode(line, strlen(line), TALK_DIR_ANY, &m);
    if (rc < 0) printf("%s\\n", cw_error_name(rc));
    else if (m.kind == TALK_MSG_ROMEO) printf("romeo %s %u\\n", m.as.romeo.talker, (unsigned)m.as.romeo.a);
    else printf("delta %s %u\\n", m.as.delta.talker, (unsigned)m.as.delta.b);
}}
int main(void) {{
{calls}
    return 0;
}}
"""
    assert run_c(built[0], driver) == ["delta O 7", "romeo HLJ 5", "romeo NWA 6", "dispatch"]
