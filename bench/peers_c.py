"""Peer C code generated at bench time into a temporary directory (never committed):
MAVLink's C for common.xml (pymavlink's mavgen) and cantools' C for bench/route_car.dbc and
examples/can_mixed.dbc."""

import os
import subprocess
import sys
from pathlib import Path

import pymavlink

from bench.peers import DBC

COMMON_XML = Path(pymavlink.__file__).resolve().parent / "dialects" / "v20" / "common.xml"
# the dialects imported whole in section 5: common.xml, and all.xml, which includes every other
DIALECTS = [COMMON_XML, COMMON_XML.with_name("all.xml")]


def generate_mavlink(out: Path) -> Path:
    """MAVLink 2 C headers for common.xml in out/; returns the include directory."""
    subprocess.run([sys.executable, "-m", "pymavlink.tools.mavgen", "--lang=C", "--wire-protocol=2.0",
                    f"--output={out}", str(COMMON_XML)], check=True, capture_output=True)
    if not (out / "common" / "mavlink.h").exists():
        raise RuntimeError("mavgen wrote no common/mavlink.h")
    return out


CAN_MIXED_DBC = Path(__file__).resolve().parent.parent / "examples" / "can_mixed.dbc"


def generate_cantools(out: Path) -> Path:
    """route_car.c / .h from bench/route_car.dbc and can_mixed.c / .h from
    examples/can_mixed.dbc in out/."""
    out.mkdir(parents=True, exist_ok=True)
    # can_mixed twice: as can_mixed.c for the AVR rows, built alone, and as cantools_can_mixed.c
    # for the host's program, which includes codeword's can_mixed.h too
    for dbc, name in ((DBC, []), (CAN_MIXED_DBC, []), (CAN_MIXED_DBC, ["--database-name", "cantools_can_mixed"])):
        subprocess.run([sys.executable, "-m", "cantools", "generate_c_source", *name, str(dbc)],
                       check=True, capture_output=True, cwd=out, env=dict(os.environ))
    return out
