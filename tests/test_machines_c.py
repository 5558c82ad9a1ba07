"""The generated C machines against the generated Python ones: the same inputs,
taken from seeded simulator runs, must give byte-identical outputs (TR24-D1…D5)."""
from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

from codeword.sim import Link
from conftest import simulation

ROOT = Path(__file__).resolve().parent.parent
DRIVER = Path(__file__).resolve().parent / "c" / "machine_driver.c"
FLAGS = ["-std=c99", "-Wall", "-Wextra", "-Wpedantic", "-Wconversion", "-Wshadow", "-Werror"]


@pytest.fixture(scope="module")
def driver(tmp_path_factory) -> Path:
    gcc = shutil.which("gcc")
    assert gcc, "gcc is needed for the C machine tests (.ci/run installs it)"
    exe = tmp_path_factory.mktemp("machines") / "machine_driver"
    build = subprocess.run([gcc, *FLAGS, "-I", str(ROOT / "generated" / "c"), str(DRIVER), "-o", str(exe)],
                           capture_output=True, text=True, timeout=120)
    assert build.returncode == 0, build.stderr
    return exe


SCENARIOS = [
    # seed, link, slaves, data_length, timeout, retry_limit, commands
    (1, Link(), 1, 7, 20, 0, 50),
    (2, Link(p_fwd=0.3, p_ack=0.3, duplicate=0.2, delay=(0, 8)), 4, 7, 25, 0, 400),
    (3, Link(p_fwd=0.5, p_ack=0.5, corrupt=0.1), 3, 1, 15, 2, 400),
    (4, Link(p_fwd=0.2, p_ack=0.4, duplicate=0.1), 2, 59, 30, 3, 300),
]


@pytest.mark.parametrize("seed, link, slaves, data_length, timeout, retry_limit, commands", SCENARIOS)
def test_c_machines_trace_equals_python(driver, seed, link, slaves, data_length, timeout, retry_limit, commands):
    sim = simulation("tr24", seed, link, receivers=slaves, parameters={"data_length": data_length},
                     timeout=timeout, retry_limit=retry_limit, trace=True)
    sim.run(commands)
    args = [str(data_length), str(timeout), str(retry_limit)] + [str(s) for s in sim.receiver_ids]
    run = subprocess.run([str(driver), *args], input=sim.trace.script(), capture_output=True, text=True,
                         timeout=120)
    assert run.returncode == 0, run.stderr
    expected = sim.trace.text().splitlines()
    got = run.stdout.splitlines()
    for i, (a, b) in enumerate(zip(expected, got)):
        assert a == b, f"first difference at trace line {i + 1}: python {a!r}, C {b!r}"
    assert len(got) == len(expected)
    assert any("executed" in line for line in got) and any("delivered" in line for line in got)
    if retry_limit and link.p_fwd >= 0.5:
        assert any("failed" in line for line in got)


def test_c_master_refuses_a_second_command_and_bad_data(driver):
    # m3 is the master's machine for slave 3; the second send while waiting is refused.
    script = "0 m3 send 0300000000000000\n1 m3 send 0300000000000001\n2 m3 send 03ff\n"
    run = subprocess.run([str(driver), "7", "20", "0", "3"], input=script, capture_output=True, text=True,
                         timeout=60)
    assert run.returncode == 0, run.stderr
    lines = run.stdout.splitlines()
    # hand-built from TR24-D1: 02, service 00 (command, seq 0), sender 01, receiver 03, 7 zero bytes, 03
    assert lines[:2] == ["0 m3 send 0300000000000000", "  sent 0200010300000000000000" + "03"]
    assert lines[2:] == ["1 m3 send 0300000000000001", "  refused", "2 m3 send 03ff", "  refused"]
