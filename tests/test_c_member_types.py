"""A C struct member has the type of its wire field (with its offset), whatever its
range: widening a range in a later version of a schema must not change the C API.
The expected sizes and signedness are the wire types' own (u16: 2 bytes unsigned,
i16: 2 bytes signed, u8 with offset -100: values -100..155, so int16_t)."""
from __future__ import annotations

from schema_in_a_test import render, run_c

SCHEMA = """codeword: 1
protocol: members
title: t
source: s
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: kind, type: u8, dispatch: true}
    - {payload: true}
messages:
  a:
    id: 1
    fields:
      - {name: quantity, type: u16, range: [1, 125]}
      - {name: level, type: i16, range: [0, 10]}
      - {name: wide, type: u32, range: [0, 200]}
      - {name: moved, type: u8, offset: -100, range: [0, 50]}
      - {name: scaled, type: u16, scale: 0.5, range: [0, 10]}
"""

TEXT = """codeword: 1
protocol: tmembers
title: t
source: s
framing: {kind: text, prefix_separator: ":", separator: ",", terminator: ";"}
messages:
  a:
    id: A
    fields:
      - {name: speed, type: i32, range: [0, 100]}
      - {name: small, type: u16, range: [0, 9]}
"""


def facts(member: str) -> str:
    """A line `<member> <size> <signed>` printed by the driver."""
    return (f"    m.{member} = 0;\n    m.{member}--;  /* wraps to the largest value if unsigned */\n"
            f'    printf("{member} %u %d\\n", (unsigned)sizeof m.{member}, (int)(m.{member} < 0));')


def test_binary_members_follow_the_wire_type(tmp_path):
    render(tmp_path, "members", SCHEMA)
    names = ["quantity", "level", "wide", "moved", "scaled"]
    driver = ('#include <stdio.h>\n#include "members.h"\nint main(void) {\n    members_a_t m;\n'
              + "\n".join(facts(n) for n in names) + "\n    return 0;\n}\n")
    assert run_c(tmp_path, driver, ("-Wno-type-limits",)) == [
        "quantity 2 0", "level 2 1", "wide 4 0", "moved 2 1", "scaled 2 0"]


def test_text_members_follow_the_wire_type(tmp_path):
    render(tmp_path, "tmembers", TEXT)
    driver = ('#include <stdio.h>\n#include "tmembers.h"\nint main(void) {\n    tmembers_a_t m;\n'
              + facts("speed") + "\n" + facts("small") + "\n    return 0;\n}\n")
    assert run_c(tmp_path, driver, ("-Wno-type-limits",)) == ["speed 4 1", "small 2 0"]


def test_a_wide_member_still_refuses_values_outside_the_range(tmp_path):
    """The member can hold 300 now; the encoder refuses it, as Python does."""
    render(tmp_path, "members", SCHEMA)
    driver = """#include <stdio.h>
#include "members.h"
int main(void) {
    members_a_t m = {0};
    uint8_t buf[16];
    m.quantity = 300u;
    m.level = 0;
    printf("%s\\n", cw_error_name(members_a_encode(&m, buf, sizeof buf)));
    m.quantity = 125u;
    printf("%d\\n", members_a_encode(&m, buf, sizeof buf));
    return 0;
}
"""
    assert run_c(tmp_path, driver) == ["range", "12"]
