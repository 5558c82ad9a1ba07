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


# The same id after a two-letter talker in both directions: the talker's values tell the
# messages apart, except KA, which both take. A decode without a direction finds GP..FIX and
# BD..FIX, and must be told the direction for KA..FIX.
DIRECTED = """codeword: 1
protocol: talkdir
title: talkers across directions
source: hand-written
roles:
  host: {doc: host}
  device: {doc: device}
directions:
  up: {from: device, to: host}
  down: {from: host, to: device}
framing:
  kind: text
  prefix_separator: ':'
  separator: ','
  terminator: ';'
messages:
  report:
    id: FIX
    direction: up
    fields:
      - {name: talker, type: str, length: 2, prefix: true, values: [GP, KA]}
      - {name: a, type: u8}
  order:
    id: FIX
    direction: down
    fields:
      - {name: talker, type: str, length: 2, prefix: true, values: [BD, KA]}
      - {name: b, type: u8}
"""


@pytest.fixture(scope="module")
def directed(tmp_path_factory):
    where = tmp_path_factory.mktemp("talkdir")
    render(where, "talkdir", DIRECTED)
    return where, load(where / "talkdir.py")


def test_python_needs_a_direction_only_for_a_talker_both_take(directed):
    mod = directed[1]
    assert (type(mod.decode("GPFIX:1;")).NAME, type(mod.decode("BDFIX:2;")).NAME) == ("report", "order")
    with pytest.raises(mod.DecodeError) as e:
        mod.decode("KAFIX:3;")
    assert e.value.rule == "dispatch"
    assert type(mod.decode("KAFIX:3;", "down")).NAME == "order"


def test_c_needs_a_direction_only_for_a_talker_both_take(directed):
    driver = r"""#include <stdio.h>
#include <string.h>
#include "talkdir.h"
static void show(const char *line, int direction) {
    talkdir_message_t m;
    int rc = talkdir_decode(line, strlen(line), direction, &m);
    if (rc < 0) printf("%s\n", cw_error_name(rc));
    else if (m.kind == TALKDIR_MSG_REPORT) printf("report %s %u\n", m.as.report.talker, (unsigned)m.as.report.a);
    else printf("order %s %u\n", m.as.order.talker, (unsigned)m.as.order.b);
}
int main(void) {
    show("GPFIX:1;", TALKDIR_DIR_ANY);
    show("BDFIX:2;", TALKDIR_DIR_ANY);
    show("KAFIX:3;", TALKDIR_DIR_ANY);
    show("KAFIX:3;", TALKDIR_DIR_DOWN);
    return 0;
}
"""
    assert run_c(directed[0], driver) == ["report GP 1", "order BD 2", "dispatch", "order KA 3"]
