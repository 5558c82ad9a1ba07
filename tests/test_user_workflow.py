"""README's "Use codeword in your project", run as a new user would: a wheel
built from this checkout, installed into a fresh virtual environment, and every
command of the section run in order from an empty folder."""
from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import tty
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
SECTION = "## Use codeword in your project"
INSTALL = "pip install path/to/codeword"
FRAME = "a5 05 01 64 00 9c ff 39 05"  # the starter's drive example, worked out by hand in its schema


def clean_env() -> dict[str, str]:
    """The environment without this checkout on the path: a user's has none."""
    return {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}


def section_blocks() -> list[str]:
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    start = readme.index(SECTION)
    end = readme.find("\n## ", start + len(SECTION))
    return re.findall(r"```sh\n(.*?)```", readme[start:end], flags=re.S)


def test_the_section_installs_builds_compiles_and_imports():
    blocks = section_blocks()
    assert blocks and INSTALL in blocks[0]
    text = "".join(blocks)
    for command in ("codeword init", "codeword build", "cc ", "./drive", "python3 -c", "ls generated/docs",
                    "codeword encode", "codeword decode", "codeword monitor"):
        assert command in text


@pytest.fixture(scope="module")
def venv(tmp_path_factory) -> Path:
    where = tmp_path_factory.mktemp("wheel")
    built = subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q",
                            "-w", str(where / "dist"), str(ROOT)], capture_output=True, text=True, timeout=600)
    assert built.returncode == 0, built.stderr
    (wheel,) = (where / "dist").glob("codeword-*.whl")
    env = where / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(env)], check=True, timeout=300)
    installed = subprocess.run([str(env / "bin" / "python"), "-m", "pip", "install", "-q",
                                "--disable-pip-version-check", str(wheel)],
                               capture_output=True, text=True, timeout=600, env=clean_env())
    assert installed.returncode == 0, installed.stderr
    return env


def test_the_wheel_has_codeword_and_no_compiler_package(venv):
    python = str(venv / "bin" / "python")
    assert subprocess.run([python, "-c", "import codeword"], cwd="/", env=clean_env()).returncode == 0
    shadow = subprocess.run([python, "-c", "import compiler"], cwd="/", capture_output=True, text=True,
                            env=clean_env())
    assert shadow.returncode != 0 and "No module named 'compiler'" in shadow.stderr


def test_the_wheel_ships_what_the_docs_site_needs(venv):
    """The MkDocs configuration's template and the Mermaid script the build copies next to the pages."""
    check = ("from codeword.targets.markdown.site import MERMAID; from codeword.targets.render import TEMPLATES; "
             "assert MERMAID.stat().st_size > 1_000_000 and (TEMPLATES / 'docs' / 'mkdocs.yml.j2').is_file()")
    proc = subprocess.run([str(venv / "bin" / "python"), "-c", check], cwd="/", capture_output=True, text=True,
                          env=clean_env())
    assert proc.returncode == 0, proc.stderr


def test_every_command_of_the_section_runs_in_an_empty_folder(venv, tmp_path):
    wheel = next((venv.parent / "dist").glob("codeword-*.whl"))
    script = ["set -euo pipefail"]
    for i, block in enumerate(section_blocks()):
        script.append(f"echo '@@ block {i}'")
        script.append(block.replace(INSTALL, f"pip install -q --disable-pip-version-check {wheel}"))
    env = clean_env()
    env["PATH"] = f"{venv / 'bin'}:{env['PATH']}"
    env["HOME"] = str(tmp_path)
    work = tmp_path / "empty"
    work.mkdir()
    proc = subprocess.run(["bash", "-c", "\n".join(script)], cwd=work, env=env, capture_output=True,
                          text=True, timeout=600)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    out = dict(re.findall(r"@@ block (\d+)\n(.*?)(?=@@ block |\Z)", proc.stdout, flags=re.S))
    assert "created schemas/rover.yaml" in out["0"] and "wrote generated/c/rover.h" in out["0"]
    assert out["1"].splitlines()[-1].strip() == FRAME  # ./drive, compiled with -Werror
    assert (work / "rover" / "firmware" / "c" / "rover.h").is_file()
    assert out["2"].strip() == "Drive(left=100, right=-100)"
    assert out["3"].split() == ["codeword.css", "index.md", "rover.md"]
    frames = out["4"].splitlines()
    assert frames[0].strip() == FRAME  # encode, against the hand-worked frame
    table = [line.split() for line in frames[1:4]]
    assert table[0] == ["offset", "frame", "message"]
    assert table[1][:9] == ["0", "a5", "04", "02", "d4", "30", "03", "e8", "cc"]  # the starter's status example
    assert table[1][9:] == ["status", "battery=12500", "mV", "mode=docked"]
    assert table[2][:4] == ["8", "78", "78", "error"] and "skipped" in frames[3]
    assert frames[4].split()[:2] == ["10", "a5"] and "drive" in frames[4] and "left=100 mm/s" in frames[4]
    assert frames[5] == "exit status 1: the noise is a finding"
    first = json.loads(frames[6])
    assert first["message"] == "status" and first["values"] == {"battery": 12500, "mode": "docked"}


def test_monitor_in_the_starter_project_reads_a_pty(venv, tmp_path):
    """The wheel's monitor on the starter's frames, through a pseudo-terminal pair."""
    env = clean_env()
    env["PATH"] = f"{venv / 'bin'}:{env['PATH']}"
    work = tmp_path / "rover"
    work.mkdir()
    subprocess.run(["codeword", "init"], cwd=work, env=env, check=True, capture_output=True, timeout=120)
    master, slave = os.openpty()
    tty.setraw(slave)
    try:
        monitor = subprocess.Popen(["codeword", "monitor", "rover", "--port", os.ttyname(slave), "--baud", "9600",
                                    "--count", "2", "--duration", "60"], cwd=work, env=env,
                                   stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        assert monitor.stderr.readline().startswith("monitoring ")  # the port is open
        os.write(master, bytes.fromhex(FRAME) + bytes.fromhex("a5 04 02 d4 30 03 e8 cc"))
        out, err = monitor.communicate(timeout=90)
    finally:
        os.close(master)
        os.close(slave)
    assert monitor.returncode == 0, err
    drive, status = out.splitlines()
    assert "drive left=100 mm/s right=-100 mm/s" in drive
    assert "status battery=12500 mV mode=docked" in status
    assert "2 frames, 0 errors, 0 bytes skipped, 17 bytes read" in err
