"""A stretch of garbage gives one error, not one per byte, in the Python
StreamDecoder, the C parser and `codeword check`; bytes skipped are counted.

tr24 frames start with 0x02 (the seed's start byte): a run of 0x02 makes every
byte a candidate frame that fails, the worst case for resynchronisation."""
from __future__ import annotations

import shutil
import subprocess

from codeword.cli import main
from conftest import ROOT, load_generated

FRAME = bytes.fromhex("02 00 01 03 2c 00 00 00 00 00 00 03")  # schemas/tr24.yaml, first example
GARBAGE = b"\x02" * 50_000


def test_python_gives_one_error_per_stretch():
    tr24 = load_generated("tr24")
    d = tr24.StreamDecoder()
    items = d.feed(GARBAGE + FRAME + GARBAGE) + d.finish()
    kinds = ["error" if isinstance(x, tr24.DecodeError) else "frame" for x in items]
    # a stretch, the frame and the second stretch, whose unfinished tail at the end is part
    # of it: finish() reads the tail again byte by byte and finds no frame, and says nothing more
    assert kinds == ["error", "frame", "error"]
    assert d.skipped == 2 * len(GARBAGE)
    stop = 11 * 8  # bit offset of the stop byte, where a run of 0x02 first fails
    assert items[0].offset == stop and items[2].offset == (len(GARBAGE) + len(FRAME)) * 8 + stop


def test_python_stretch_continues_across_feeds():
    tr24 = load_generated("tr24")
    d = tr24.StreamDecoder()
    errors = [x for chunk in range(0, len(GARBAGE), 997) for x in d.feed(GARBAGE[chunk:chunk + 997])]
    assert len(errors) == 1
    # the stretch's last bytes wait in the buffer: they fail silently, then the frame decodes
    assert [isinstance(x, tr24.DecodeError) for x in d.feed(FRAME)] == [False]
    assert len([x for x in d.feed(GARBAGE) if isinstance(x, tr24.DecodeError)]) == 1  # a new stretch


def test_c_parser_gives_one_error_per_stretch(tmp_path):
    gcc = shutil.which("gcc")
    assert gcc, "gcc is not installed (.ci/run installs it)"
    src, exe = tmp_path / "resync.c", tmp_path / "resync"
    frame = ", ".join(f"0x{b:02x}" for b in FRAME)
    src.write_text(f"""#include <stdio.h>
#include "tr24.h"
static tr24_parser_t p;
static void feed(uint8_t byte, int *errors, int *frames) {{
    tr24_message_t m;
    int rc;
    tr24_parser_feed(&p, byte);
    while ((rc = tr24_parser_next(&p, &m)) != 0) {{
        if (rc < 0) {{
            (*errors)++;
        }} else {{
            (*frames)++;
        }}
    }}
}}
int main(void) {{
    static const uint8_t frame[] = {{{frame}}};
    int errors = 0, frames = 0;
    long i;
    size_t k;
    tr24_parser_init(&p, TR24_DIR_ANY);
    for (i = 0; i < {len(GARBAGE)}; i++) feed(0x02, &errors, &frames);
    for (k = 0; k < sizeof frame; k++) feed(frame[k], &errors, &frames);
    printf("%d %d\\n", errors, frames);
    for (i = 0; i < {len(GARBAGE)}; i++) feed(0x02, &errors, &frames);
    printf("%d %d %lu\\n", errors, frames, (unsigned long)(p.scan.skipped + p.len));
    return 0;
}}
""")
    build = subprocess.run([gcc, "-std=c99", "-O1", "-Wall", "-Wextra", "-Werror", "-fsanitize=address,undefined",
                            "-I", str(ROOT / "generated" / "c"), str(src), "-o", str(exe)],
                           capture_output=True, text=True, timeout=300)
    assert build.returncode == 0, build.stderr
    run = subprocess.run([str(exe)], capture_output=True, text=True, timeout=60)
    assert run.stdout.split("\n")[:2] == ["1 1", f"2 1 {2 * len(GARBAGE)}"]


def test_c_scan_decodes_in_place_with_one_error_per_stretch(tmp_path):
    """tr24_scan over one buffer: the same events as the parser, each call saying how many
    bytes it consumed; what is left at the end is the second stretch's unfinished tail,
    shorter than a frame, for the caller to keep."""
    gcc = shutil.which("gcc")
    assert gcc, "gcc is not installed (.ci/run installs it)"
    src, exe = tmp_path / "scan.c", tmp_path / "scan"
    frame = ", ".join(f"0x{b:02x}" for b in FRAME)
    src.write_text(f"""#include <stdio.h>
#include <stdlib.h>
#include "tr24.h"
int main(void) {{
    static const uint8_t frame[] = {{{frame}}};
    size_t n = 2u * {len(GARBAGE)}u + sizeof frame, at = 0, used;
    uint8_t *buf = malloc(n);
    tr24_scan_state_t s;
    tr24_message_t m;
    int rc;
    memset(buf, 0x02, n);
    memcpy(buf + {len(GARBAGE)}, frame, sizeof frame);
    tr24_scan_start(&s, TR24_DIR_ANY);
    while ((rc = tr24_scan(&s, buf + at, n - at, &used, &m)) != 0) {{
        at += used;
        printf("%s %lu\\n", rc == 1 ? "frame" : cw_error_name(rc), (unsigned long)at);
    }}
    at += used;
    printf("left %lu skipped %lu\\n", (unsigned long)(n - at), (unsigned long)s.skipped);
    free(buf);
    return 0;
}}
""")
    build = subprocess.run([gcc, "-std=c99", "-O1", "-Wall", "-Wextra", "-Werror", "-fsanitize=address,undefined",
                            "-I", str(ROOT / "generated" / "c"), str(src), "-o", str(exe)],
                           capture_output=True, text=True, timeout=300)
    assert build.returncode == 0, build.stderr
    run = subprocess.run([str(exe)], capture_output=True, text=True, timeout=60)
    g, f = len(GARBAGE), len(FRAME)
    # The run of 0x02 fails at its first byte (consumed: 1). The first 12 bytes that hold a
    # frame are the run's last 8 and FRAME's first 4 (02 00 01 03: its 0x03 is where the stop
    # byte goes; tr24 has no checksum), so the frame found ends at g + 4. FRAME's other 8 bytes
    # hold no 0x02: skipped silently; the second run fails at its first byte (g + 12, consumed:
    # up to g + 13); its last 11 bytes wait for more. Skipped: all but those 12 and the 11.
    assert run.stdout.splitlines() == ["const 1", f"frame {g + 4}", f"const {g + f + 1}",
                                       f"left {f - 1} skipped {2 * g - (f - 1)}"]


def test_check_reports_a_stretch_once(tmp_path, capsys):
    capture = tmp_path / "garbage.bin"
    capture.write_bytes(GARBAGE + FRAME)
    assert main(["check", "tr24", str(capture)]) == 1
    out = capsys.readouterr().out
    errors = [line for line in out.splitlines() if ": error: " in line]
    assert len(errors) == 2, out  # the stretch, and the total of bytes skipped
    assert f"1 valid, 1 invalid, {len(GARBAGE)} byte(s) skipped" in out


def test_check_names_a_folder_and_reads_devices(tmp_path, capsys):
    assert main(["check", "mtv4", str(tmp_path)]) == 2
    assert "is a folder" in capsys.readouterr().err
    assert main(["check", "mtv4", "/dev/null"]) == 0
    assert "nothing read" in capsys.readouterr().out
    assert main(["check", "mtv4", str(tmp_path / "none.bin")]) == 2
    assert "no such file" in capsys.readouterr().err


def test_check_counts_words_after_a_program_as_invalid(tmp_path, capsys):
    """An empty car program (one header word of zeros, CAR-D3) followed by junk words:
    the junk is outside the program, so only the header is valid."""
    capture = tmp_path / "junk.bin"
    capture.write_bytes(bytes(4) + bytes(range(256)) * 4)
    assert main(["check", "car", str(capture)]) == 1
    assert "257 word(s) read (raw), 1 valid, 256 invalid" in capsys.readouterr().out
