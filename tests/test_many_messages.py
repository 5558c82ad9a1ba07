"""A protocol of more than 255 messages (MAVLink's all.xml has 300, ardupilotmega.xml 282):
C's `<px>_message_t.kind` holds every `<PX>_MSG_*` (1 … 300 here), so the dispatching
decoder and encoder tell message 300 from message 44 (300 − 256). Found comparing the
imported all.xml with pymavlink: the kind was a `uint8_t`. Expected frames are worked by
hand: sync 0xA5, a 16-bit big-endian id, one byte of value."""
from schema_in_a_test import load, render, run_c

COUNT = 300


def schema() -> str:
    lines = ["codeword: 1", "protocol: many", "title: three hundred messages", "source: tests/test_many_messages.py",
             "framing:", "  kind: bytes", "  byte_order: big", "  layout:",
             "    - {name: sync, type: u8, const: 0xA5}", "    - {name: id, type: u16, dispatch: true}",
             "    - {payload: true}", "messages:"]
    for i in range(1, COUNT + 1):
        lines += [f"  m{i}:", f"    id: {1000 + i}", "    fields:", "      - {name: value, type: u8}"]
    return "\n".join(lines) + "\n"


def test_the_kind_of_a_message_past_the_255th_is_its_own(tmp_path):
    render(tmp_path, "many", schema())
    mod = load(tmp_path / "many.py")
    frames = {i: bytes([0xA5, (1000 + i) >> 8, (1000 + i) & 0xFF, i % 256]) for i in (1, 44, 256, 300)}
    for i, frame in frames.items():  # 1300 is 0x0514, 1044 is 0x0414
        assert type(mod.decode(frame)).NAME == f"m{i}" and mod.decode(frame).value == i % 256
    checks = "\n".join(
        f"    {{ static const uint8_t f[] = {{{', '.join(f'0x{b:02x}' for b in frame)}}}; uint8_t out[4];"
        f" int rc = many_decode(f, sizeof f, MANY_DIR_ANY, &m);"
        f" printf(\"%d %d %d %d\\n\", rc, m.kind == MANY_MSG_M{i}, (int)m.as.m{i}.value,"
        f" many_encode(&m, out, sizeof out) == 4 && memcmp(out, f, 4) == 0); }}"
        for i, frame in frames.items())
    driver = f"""
#include <stdio.h>
#include <string.h>
#include "many.h"
int main(void)
{{
    many_message_t m;
{checks}
    printf("%d\\n", MANY_MSG_M300);
    return 0;
}}
"""
    assert run_c(tmp_path, driver) == [f"0 1 {i % 256} 1" for i in frames] + ["300"]
