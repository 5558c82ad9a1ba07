"""The README's two set-up commands do their own set-up: the test command installs
the toolchains the tests use, with the same installer CI uses."""
from __future__ import annotations

import os
import re
import shutil
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
INSTALLER = ROOT / "scripts" / "install-toolchains"
# Every external tool a test runs (test_c, test_machines_c, test_fuzz_static_analysis, test_spin,
# test_docs_browser, test_typing's pyright, …).
TOOLS = ["gcc", "g++", "clang", "avr-gcc", "simavr", "arm-none-eabi-gcc", "qemu-system-arm", "cppcheck", "spin",
         "chromium", "node", "s390x-linux-gnu-gcc", "qemu-s390x"]


def test_the_readme_test_command_installs_toolchains_then_runs_the_tests():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert "./scripts/test" in readme
    steps = [line for line in (ROOT / "scripts" / "test").read_text().splitlines()
             if line and not line.startswith("#")]
    install = steps.index("./scripts/install-toolchains")
    assert install < next(i for i, line in enumerate(steps) if "pytest" in line)
    assert "./scripts/test" in (ROOT / ".ci" / "run").read_text()


def test_the_installer_checks_every_tool_the_tests_run():
    text = INSTALLER.read_text()
    commands = re.search(r"COMMANDS=\(([^)]*)\)", text).group(1).split()
    assert sorted(commands) == sorted(TOOLS)


def _fake_system(tmp_path: Path, missing: str) -> tuple[dict, Path]:
    """A PATH holding every tool but `missing`, and an apt-get that records its calls."""
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    for name in TOOLS + ["dpkg", "dpkg-query", "id", "bash", "env"]:
        if name != missing:
            os.symlink(shutil.which(name), bin_dir / name)
    log = tmp_path / "apt.log"
    apt = bin_dir / "apt-get"
    apt.write_text(f"#!/bin/sh\necho \"$@\" >> {log}\n")
    apt.chmod(0o755)
    sudo = bin_dir / "sudo"
    sudo.write_text("#!/bin/sh\nexec \"$@\"\n")
    sudo.chmod(0o755)
    return dict(os.environ, PATH=str(bin_dir)), log


def test_a_machine_with_every_toolchain_installs_nothing(tmp_path):
    env, log = _fake_system(tmp_path, missing="")
    proc = subprocess.run(["bash", str(INSTALLER)], env=env, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert not log.exists()


def test_a_missing_toolchain_is_installed_from_debian(tmp_path):
    env, log = _fake_system(tmp_path, missing="simavr")
    proc = subprocess.run(["bash", str(INSTALLER)], env=env, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    update, install = log.read_text().splitlines()
    assert update.startswith("update")
    assert install.startswith("install") and {"simavr", "gcc-avr", "avr-libc", "clang", "spin"} <= set(install.split())
