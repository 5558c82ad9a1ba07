"""A multi-byte dispatch field in a byte-framed protocol follows the byte
order the schema declares: the generated Python and C encoders write the
frames written out by hand below, and the Python and C decoders, which find the
message by that field, read each back as the message it holds."""
from __future__ import annotations

import importlib.util
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from compiler.build import compile_schema, render_protocol

SCHEMA = """\
codeword: 1
protocol: ledis
title: a two-byte message id
source: hand-written
framing:
  kind: bytes
  byte_order: {order}
  layout:
    - {{name: sync, type: u8, const: 0x55}}
    - {{name: kind, type: u16, dispatch: true}}
    - {{payload: true}}
messages:
  ping:
    id: 0x0102
    fields:
      - {{name: v, type: u16}}
  pong:
    id: 0x0201
    fields:
      - {{name: w, type: u16}}
"""

# The ids are each other's byte swap, so a frame read in the wrong order
# names the other message. ping v=0x1234, pong w=0xabcd:
#   little: 55 | 02 01 | 34 12    and    55 | 01 02 | cd ab
#   big:    55 | 01 02 | 12 34    and    55 | 02 01 | ab cd
FRAMES = {
    "little": ("55 02 01 34 12", "55 01 02 cd ab"),
    "big": ("55 01 02 12 34", "55 02 01 ab cd"),
}

DRIVER = """\
#include <stdio.h>
#include "ledis.h"

static const uint8_t ping_frame[] = {PING};
static const uint8_t pong_frame[] = {PONG};

static void show_decode(const char *label, const uint8_t *frame, size_t len)
{
    ledis_message_t m;
    int rc = ledis_decode(frame, len, 0, &m);
    if (rc != CW_OK) {
        printf("%s error %s\\n", label, cw_error_name(rc));
    } else if (m.kind == LEDIS_MSG_PING) {
        printf("%s ping %04x\\n", label, (unsigned)m.as.ping.v);
    } else {
        printf("%s pong %04x\\n", label, (unsigned)m.as.pong.w);
    }
}

int main(void)
{
    ledis_message_t m;
    uint8_t buf[LEDIS_MAX_FRAME];
    int n;
    int i;
    show_decode("ping_frame", ping_frame, sizeof ping_frame);
    show_decode("pong_frame", pong_frame, sizeof pong_frame);
    m.kind = LEDIS_MSG_PING;
    m.as.ping.v = 0x1234u;
    n = ledis_encode(&m, buf, sizeof buf);
    printf("encoded");
    for (i = 0; i < n; i++) {
        printf(" %02x", (unsigned)buf[i]);
    }
    printf("\\n");
    return 0;
}
"""


def c_array(spaced_hex: str) -> str:
    return "{" + ", ".join(f"0x{b:02x}" for b in bytes.fromhex(spaced_hex)) + "}"


@pytest.fixture(params=sorted(FRAMES))
def built(request, tmp_path: Path):
    order = request.param
    schema = tmp_path / "ledis.yaml"
    schema.write_text(SCHEMA.format(order=order), encoding="utf-8")
    files = render_protocol(compile_schema(schema))
    for rel in ("python/ledis.py", "c/ledis.h", "c/codeword.h"):
        (tmp_path / Path(rel).name).write_text(files[rel], encoding="utf-8")
    return order, tmp_path


def load(path: Path):
    key = f"ledis_{path.parent.name}"
    spec = importlib.util.spec_from_file_location(key, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[key] = module  # dataclasses look their module up while the class is made
    spec.loader.exec_module(module)
    return module


def test_python_writes_the_id_in_the_declared_order(built):
    order, where = built
    ledis = load(where / "ledis.py")
    ping, pong = (bytes.fromhex(h) for h in FRAMES[order])
    assert ledis.encode(ledis.Ping(v=0x1234)) == ping
    assert ledis.encode(ledis.Pong(w=0xABCD)) == pong
    assert ledis.Ping.decode(ping).v == 0x1234
    assert ledis.Pong.decode(pong).w == 0xABCD


def test_python_dispatch_reads_the_id_in_the_declared_order(built):
    order, where = built
    ledis = load(where / "ledis.py")
    ping, pong = (bytes.fromhex(h) for h in FRAMES[order])
    assert ledis.decode(ping) == ledis.Ping(v=0x1234)
    assert ledis.decode(pong) == ledis.Pong(w=0xABCD)
    stream = ledis.StreamDecoder()
    assert stream.feed(ping + pong) == [ledis.Ping(v=0x1234), ledis.Pong(w=0xABCD)]


def test_c_dispatch_reads_the_id_in_the_declared_order(built):
    order, where = built
    gcc = shutil.which("gcc")
    assert gcc, "gcc is not installed (.ci/run installs it)"
    ping, pong = FRAMES[order]
    src = where / "driver.c"
    src.write_text(DRIVER.replace("{PING}", c_array(ping)).replace("{PONG}", c_array(pong)),
                   encoding="utf-8")
    exe = where / "driver"
    build = subprocess.run([gcc, "-std=c99", "-g", "-O1", "-fsanitize=address,undefined",
                            "-fno-sanitize-recover=all", "-Wall", "-Wextra", "-Werror", "-I", str(where), str(src), "-o", str(exe)],
                           capture_output=True, text=True, timeout=300)
    assert build.returncode == 0, build.stderr
    run = subprocess.run([str(exe)], capture_output=True, text=True, timeout=60)
    assert run.returncode == 0, run.stdout + run.stderr
    assert run.stdout.splitlines() == [
        "ping_frame ping 1234",
        "pong_frame pong abcd",
        f"encoded {ping}",
    ]
