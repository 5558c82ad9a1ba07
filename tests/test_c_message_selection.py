"""A firmware that handles a few messages selects them (`<PX>_SELECTED_MESSAGES` and
`<PX>_SELECT_<MESSAGE>` before the header): the dispatching encoder and decoder, and the
streams over them, then hold only those messages' code, and any other message is
CW_ERR_DISPATCH. Checked on the committed headers' conformance frames, for warnings in
every kind of dispatch, and for what it saves in flash."""
import json
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from cdriver import selection_flags
from schema_in_a_test import STRICT_WARNINGS, run_c

ROOT = Path(__file__).resolve().parent.parent
C = ROOT / "generated" / "c"
EXAMPLES_C = ROOT / "generated" / "examples" / "c"
SELECTED = ("set_led", "ack")  # of mtv4's six messages, one in each direction


def frames(protocol: str) -> list[dict]:
    vectors = json.loads((ROOT / "generated" / "vectors" / f"{protocol}.json").read_text(encoding="utf-8"))
    return [c for c in vectors["valid"] if "hex" in c and "canonical" not in c]


def c_bytes(hex_text: str) -> str:
    return "{" + ", ".join(f"0x{b:02x}" for b in bytes.fromhex(hex_text)) + "}"


def test_only_the_selected_messages_are_decoded_and_encoded(tmp_path):
    """Each mtv4 conformance frame through the dispatching decoder, by its direction: a
    selected message's frame decodes as that message and encodes back to the same bytes,
    any other is CW_ERR_DISPATCH, as is encoding it; the byte parser over all the frames
    in a row finds the selected messages' frames, in order."""
    cases = frames("mtv4")
    assert {c["message"] for c in cases} >= {"set_led", "ack", "set_wheels_velocities", "odometry_reply"}
    for name in ("mtv4.h", "codeword.h"):
        shutil.copy(C / name, tmp_path / name)
    table = ",\n".join(f"    {{{c_bytes(c['hex'])}, {len(bytes.fromhex(c['hex']))}u, "
                       f"MTV4_DIR_{c['direction'].upper()}}}" for c in cases)
    stream = b"".join(bytes.fromhex(c["hex"]) for c in cases)
    driver = f"""
#include <stdio.h>
#include <string.h>
#include "mtv4.h"
static const struct {{ uint8_t bytes[64]; size_t len; int direction; }} cases[] = {{
{table}
}};
static const uint8_t stream[] = {c_bytes(stream.hex())};
int main(void)
{{
    size_t i;
    static mtv4_parser_t p;
    mtv4_message_t m;
    uint8_t again[64];
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {{
        int rc = mtv4_decode(cases[i].bytes, cases[i].len, cases[i].direction, &m);
        int back = rc < 0 ? rc : mtv4_encode(&m, again, sizeof again);
        printf("%d %d %d\\n", rc, rc < 0 ? -1 : (int)m.kind,
               back == (int)cases[i].len && memcmp(again, cases[i].bytes, cases[i].len) == 0);
    }}
    memset(&m, 0, sizeof m);
    m.kind = MTV4_MSG_SET_WHEELS_VELOCITIES;
    printf("encode %d\\n", mtv4_encode(&m, again, sizeof again));
    mtv4_parser_init(&p, MTV4_DIR_ANY);
    for (i = 0; i < sizeof stream; i++) {{
        int rc;
        mtv4_parser_feed(&p, stream[i]);
        while ((rc = mtv4_parser_next(&p, &m)) != 0) {{
            if (rc == 1) {{
                printf("stream %d\\n", (int)m.kind);
            }}
        }}
    }}
    return 0;
}}
"""
    kinds = {"set_wheels_velocities": 1, "set_led": 2, "set_wheels_velocities_with_odometry": 3,
             "ack": 4, "odometry_reply": 5}  # MTV4_MSG_*, in the schema's order of messages
    header = (C / "mtv4.h").read_text(encoding="utf-8")
    for name, kind in kinds.items():
        assert re.search(rf"MTV4_MSG_{name.upper()} = {kind},?$", header, re.M), name
    lines = run_c(tmp_path, driver, selection_flags("MTV4", SELECTED))
    expected = [f"0 {kinds[c['message']]} 1" if c["message"] in SELECTED else "-12 -1 0" for c in cases]
    assert lines[:len(cases)] == expected
    assert lines[len(cases)] == "encode -12"
    assert lines[len(cases) + 1:] == [f"stream {kinds[c['message']]}" for c in cases if c["message"] in SELECTED]
    err = re.search(r"CW_ERR_DISPATCH = (-\d+)", (C / "codeword.h").read_text(encoding="utf-8"))
    assert err and err.group(1) == "-12"


# One header of each kind of dispatch: bytes by id and size, bit-packed words, text by
# prefix, text with a talker before the id.
DISPATCHES = [(C / "mtv4.h", "MTV4"), (C / "route.h", "ROUTE"), (C / "tank.h", "TANK"),
              (EXAMPLES_C / "nmea0183.h", "NMEA0183")]


@pytest.mark.parametrize("compiler", ["gcc", "clang"])
@pytest.mark.parametrize("level", ["-O0", "-O2", "-Os"])
def test_every_selection_compiles_without_warnings(tmp_path, compiler, level):
    """All messages, one, and none selected: each header's dispatchers compile under the
    strict warnings (a decoder that tests no message's id must not leave it unused)."""
    path = shutil.which(compiler)
    assert path, f"{compiler} is not installed (.ci/run installs it)"
    for header, px in DISPATCHES:
        text = header.read_text(encoding="utf-8")
        names = re.findall(rf"#define {px}_HANDLES_(\w+) 1", text)
        assert names, header.name
        shutil.copy(header, tmp_path / header.name)
        shutil.copy(header.parent / "codeword.h", tmp_path / "codeword.h")
        px_lower = px.lower()
        src = tmp_path / f"{px_lower}_firmware.c"
        text_framing = f"static inline int {px_lower}_decode(const char *" in text
        directed = re.search(rf"static inline int {px_lower}_decode\([^)]*int direction", text) is not None
        src.write_text(f"""#include "{header.name}"
int decode_any(const {'char' if text_framing else 'uint8_t'} *buf, size_t len, {px_lower}_message_t *m);
int encode_any(const {px_lower}_message_t *m, {'char' if text_framing else 'uint8_t'} *buf, size_t cap);
int decode_any(const {'char' if text_framing else 'uint8_t'} *buf, size_t len, {px_lower}_message_t *m)
{{
    return {px_lower}_decode(buf, len, {f'{px}_DIR_ANY, ' if directed else ''}m);
}}
int encode_any(const {px_lower}_message_t *m, {'char' if text_framing else 'uint8_t'} *buf, size_t cap)
{{
    return {px_lower}_encode(m, buf, cap);
}}
""", encoding="utf-8")
        for selection in ((), selection_flags(px, names[:1]), selection_flags(px, ())):
            build = subprocess.run([path, *STRICT_WARNINGS, level, *selection, "-c", str(src), "-o",
                                    str(src.with_suffix(".o"))], capture_output=True, text=True, timeout=300)
            assert build.returncode == 0 and not build.stderr, (header.name, selection, build.stderr)


def test_a_selection_leaves_the_other_messages_out_of_flash(tmp_path):
    """A firmware of MAVLink 2's HEARTBEAT alone, through the byte parser: selected, it
    takes less flash on AVR than with all six messages of examples/mavlink2.yaml in the
    dispatching decoder, and no other message's decoder is in it."""
    avr_gcc, avr_nm = shutil.which("avr-gcc"), shutil.which("avr-nm")
    assert avr_gcc and avr_nm, "gcc-avr is not installed (.ci/run installs it)"
    for name in ("mavlink2.h", "codeword.h"):
        shutil.copy(EXAMPLES_C / name, tmp_path / name)
    src = tmp_path / "fw.c"
    src.write_text("""#include "mavlink2.h"
volatile uint8_t rx;
int main(void)
{
    static mavlink2_parser_t p;
    static mavlink2_message_t m;
    mavlink2_parser_init(&p, MAVLINK2_DIR_ANY);
    for (;;) {
        mavlink2_parser_feed(&p, rx);
        while (mavlink2_parser_next(&p, &m) != 0) {
            rx = m.kind;
        }
    }
}
""", encoding="utf-8")
    sizes, symbols = {}, {}
    for label, flags in (("all", ()), ("heartbeat", selection_flags("MAVLINK2", ["heartbeat"]))):
        elf = tmp_path / f"{label}.elf"
        subprocess.run([avr_gcc, "-std=c99", "-Os", "-mmcu=atmega2560", "-fno-inline", "-ffunction-sections",
                        "-fdata-sections", "-Wl,--gc-sections", *flags, str(src), "-o", str(elf)],
                       check=True, capture_output=True, text=True, timeout=300)
        out = subprocess.run([avr_nm, "-S", "--size-sort", str(elf)], check=True, capture_output=True,
                             text=True).stdout
        symbols[label] = set(re.findall(r"\b(mavlink2_\w+_decode)\b", out))
        sizes[label] = sum(int(size, 16) for size, kind in re.findall(r"^\w+ (\w+) ([tTdDrR]) ", out, re.M))
    assert symbols["all"] >= {"mavlink2_heartbeat_decode", "mavlink2_attitude_decode", "mavlink2_sys_status_decode"}
    assert symbols["heartbeat"] == {"mavlink2_heartbeat_decode"}
    assert sizes["heartbeat"] < sizes["all"], sizes
