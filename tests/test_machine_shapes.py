"""Machines over packets unlike tr24's: data of a fixed length, fields with other names,
a dispatch bit and the sequence bit sharing a byte with a nonzero constant. The C
machines compile under the strict flags with gcc and clang and, like the Python ones,
send the bytes worked out by hand (tests/machines/fixed_link.yaml):

  order, bit 0, from 1 to 3, body 01 02 03:  a5 | 1 0 000000 = 80 | 01 | 03 | 01 02 03
  answer, bit 0, from 3 to 1, body + 3:      a5 | 0 0 000000 = 00 | 03 | 01 | 04 05 06
  order, bit 1 (after the answer):           a5 | 1 1 000000 = c0 | 01 | 03 | 0a 0b 0c
"""
from __future__ import annotations

import importlib.util
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from codeword.build import build

HERE = Path(__file__).resolve().parent
SCHEMA = HERE / "machines" / "fixed_link.yaml"
STRICT = ["-std=c99", "-Wall", "-Wextra", "-Wpedantic", "-Wconversion", "-Wsign-conversion", "-Wshadow", "-Werror"]
ORDER = bytes.fromhex("a5 80 01 03 01 02 03")
ANSWER = bytes.fromhex("a5 00 03 01 04 05 06")
SECOND = bytes.fromhex("a5 c0 01 03 0a 0b 0c")

DRIVER = r"""
#include <stdio.h>
#include "fixed_link.h"

static void add3(void *ctx, const uint8_t *command, uint8_t len, uint8_t *result)
{
    (void)ctx;
    for (uint8_t i = 0u; i < len; i++) result[i] = (uint8_t)(command[i] + 3u);
}

static void put(const uint8_t *b, unsigned n)
{
    for (unsigned i = 0u; i < n; i++) printf("%02x", b[i]);
    printf("\n");
}

int main(void)
{
    fixed_link_boss_t boss;
    fixed_link_worker_t worker;
    fixed_link_machine_out_t o, a;
    static const uint8_t body[] = {1u, 2u, 3u};
    static const uint8_t body2[] = {10u, 11u, 12u};
    if (fixed_link_boss_init(&boss, 10u, 1u) != 0 || fixed_link_worker_init(&worker, 3u, add3, NULL) != 0) return 2;
    if (fixed_link_boss_give(&boss, 0u, 3u, body, 3u, &o) != 0) return 3;
    put(o.sent, o.sent_len);
    if (fixed_link_worker_hear(&worker, 1u, o.sent, o.sent_len, &a) != 0) return 4;
    put(a.executed, a.executed_len);
    put(a.sent, a.sent_len);
    if (fixed_link_boss_hear(&boss, 2u, a.sent, a.sent_len, &o) != 0) return 5;
    put(o.delivered, o.delivered_len);
    if (fixed_link_boss_give(&boss, 3u, 3u, body2, 3u, &o) != 0) return 6;
    put(o.sent, o.sent_len);
    if (fixed_link_boss_tick(&boss, 13u, &o) != 0) return 7;  /* the timer: sent again */
    put(o.sent, o.sent_len);
    fixed_link_boss_reset(&boss);
    fixed_link_worker_reset(&worker);
    return 0;
}
"""


@pytest.fixture(scope="module")
def generated(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("fixed_link")
    result = build([SCHEMA], out, root=HERE)
    assert not result.errors, result.errors
    return out


@pytest.mark.parametrize("compiler", ["gcc", "clang"])
@pytest.mark.parametrize("level", ["-O0", "-O2", "-Os"])
def test_c_machines_of_fixed_length_data(generated, tmp_path, compiler, level):
    cc = shutil.which(compiler)
    assert cc, f"{compiler} is needed for the C machine tests"
    src, exe = tmp_path / "driver.c", tmp_path / "driver"
    src.write_text(DRIVER, encoding="utf-8")
    built = subprocess.run([cc, *STRICT, level, "-I", str(generated / "c"), str(src), "-o", str(exe)],
                           capture_output=True, text=True, timeout=120)
    assert built.returncode == 0, built.stderr
    ran = subprocess.run([str(exe)], capture_output=True, text=True, timeout=30)
    assert ran.returncode == 0, ran.stdout + ran.stderr
    assert ran.stdout.split() == [ORDER.hex(), "010203", ANSWER.hex(), "040506", SECOND.hex(), SECOND.hex()]


def test_python_machines_of_fixed_length_data(generated):
    spec = importlib.util.spec_from_file_location("_fixed_link", generated / "python" / "fixed_link.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    try:
        spec.loader.exec_module(module)
    finally:
        sys.modules.pop(spec.name, None)
    boss = module.BossMachine(wait=10, me=1)
    worker = module.WorkerMachine(me=3, execute=lambda data: bytes((b + 3) & 0xFF for b in data))
    assert boss.give(0, to_id=3, body=b"\x01\x02\x03").sent == [ORDER]
    out = worker.hear(1, ORDER)
    assert (out.executed, out.sent) == ([b"\x01\x02\x03"], [ANSWER])
    assert boss.hear(2, ANSWER).delivered == [b"\x04\x05\x06"]
    assert boss.give(3, to_id=3, body=b"\x0a\x0b\x0c").sent == [SECOND]
    assert boss.tick(13).sent == [SECOND]


def test_python_machines_whose_names_are_builtins(tmp_path):
    """The same link with its address field called `len` and its data `bytes`: names a
    schema may use (a length byte is often called so) that generated machine code must
    not lose its builtins to when they become arguments; the bytes are ORDER's and ANSWER's."""
    text = SCHEMA.read_text(encoding="utf-8")
    text = text.replace("to_id", "len").replace("body", "bytes")
    schema = tmp_path / "fixed_link.yaml"
    schema.write_text(text, encoding="utf-8")
    result = build([schema], tmp_path / "out", root=tmp_path)
    assert not result.errors, result.errors
    spec = importlib.util.spec_from_file_location("_fixed_link_builtins", tmp_path / "out" / "python" / "fixed_link.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    try:
        spec.loader.exec_module(module)
    finally:
        sys.modules.pop(spec.name, None)
    boss = module.BossMachine(wait=10, me=1)
    worker = module.WorkerMachine(me=3, execute=lambda data: bytes((b + 3) & 0xFF for b in data))
    assert boss.give(0, len=3, bytes=b"\x01\x02\x03").sent == [ORDER]
    out = worker.hear(1, ORDER)
    assert (out.executed, out.sent) == ([b"\x01\x02\x03"], [ANSWER])
    assert boss.hear(2, ANSWER).delivered == [b"\x04\x05\x06"]
