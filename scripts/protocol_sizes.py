"""Flash of whole protocols for scripts/size-report: every message's encoder and decoder
of each generated header, on Cortex-M0 and on AVR, beside the same messages compiled
from MAVLink's generated C (pymavlink's mavgen) and cantools' generated C.

A program keeps the functions by storing their addresses in a `volatile` function
pointer; its figure is its flash (.text + .rodata + .data) above the same program that
keeps none of them. Peer code is generated into a temporary directory, never committed.
"""

import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
HEADERS = [ROOT / "generated" / "c", ROOT / "generated" / "examples" / "c"]
DBC = ROOT / "bench" / "route_car.dbc"
CAN_MIXED_DBC = ROOT / "examples" / "can_mixed.dbc"  # the DBC of examples/can_mixed.yaml's messages

TARGETS = [
    ("Cortex-M0", ["arm-none-eabi-gcc", "-std=c99", "-Os", "-mcpu=cortex-m0", "-mthumb", "--specs=nosys.specs",
                   "-ffunction-sections", "-fdata-sections", "-Wl,--gc-sections"], "arm-none-eabi-size"),
    ("AVR", ["avr-gcc", "-std=c99", "-Os", "-mmcu=atmega2560", "-ffunction-sections", "-fdata-sections",
             "-Wl,--gc-sections"], "avr-size"),
]

# The MAVLink messages of examples/mavlink2.yaml, as mavgen names them.
MAVLINK_MESSAGES = ["heartbeat", "sys_status", "param_value", "gps_raw_int", "attitude", "command_ack"]
# A firmware's few messages of the whole common.xml dialect (`codeword import mavlink`).
FIRMWARE_MESSAGES = ["heartbeat", "attitude", "gps_raw_int", "command_long", "param_value"]

PROGRAM = """\
{includes}
void (*volatile sr_keep)(void);

int main(void)
{{
{keeps}
    return 0;
}}
"""


class ToolError(Exception):
    pass


def run(cmd, cwd=None):
    proc = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if proc.returncode != 0:
        raise ToolError(f"command failed ({proc.returncode}): {' '.join(map(str, cmd))}\n{proc.stdout}{proc.stderr}")
    return proc.stdout


def codec_functions(header: Path) -> list[str]:
    """Each message's own encoder and decoder in a generated header (not the framing's dispatchers)."""
    px = header.stem
    text = header.read_text(encoding="utf-8")
    pattern = (rf"static inline int ({px}_(\w+?)_(?:encode|decode))\("
               rf"(?:const {px}_\2_t \*m|const (?:uint8_t|char) \*\w+, size_t len, {px}_\2_t \*m)")
    return sorted({m.group(1) for m in re.finditer(pattern, text)})


def flash(target, work: Path, name: str, includes: list[str], functions: list[str], flags: list[str]) -> int:
    """Flash of a program keeping `functions`, above the same program keeping none."""
    label, cmd, size_tool = target
    figures = []
    for kept in (functions, []):
        keeps = "\n".join(f"    sr_keep = (void (*)(void))&{f};" for f in kept)
        src = work / f"{name}_{label}_{len(kept)}.c"
        elf = src.with_suffix(".elf")
        src.write_text(PROGRAM.format(includes="\n".join(f'#include "{i}"' for i in includes), keeps=keeps),
                       encoding="utf-8")
        run([*cmd, *flags, str(src), "-o", str(elf)])
        figures.append(flash_of(size_tool, elf))
    return figures[0] - figures[1]


def flash_of(size_tool: str, elf: Path) -> int:
    """The bytes a program takes in flash: its .text, .rodata and .data (initial values)."""
    sections = {}
    for line in run([size_tool, "-A", str(elf)]).splitlines():
        m = re.match(r"^(\.\S+)\s+(\d+)\s+\d+\s*$", line)
        if m:
            sections[m.group(1)] = int(m.group(2))
    return sum(sections.get(s, 0) for s in (".text", ".rodata", ".data"))


def generate_mavlink(out: Path) -> Path:
    run([sys.executable, "-m", "pymavlink.tools.mavgen", "--lang=C", "--wire-protocol=2.0", f"--output={out}",
         str(common_xml())])
    return out


def common_xml() -> Path:
    import pymavlink
    return Path(pymavlink.__file__).resolve().parent / "dialects" / "v20" / "common.xml"


def import_common(out: Path) -> Path:
    """The C header of the whole common.xml dialect, imported and built by codeword."""
    run([sys.executable, "-m", "codeword", "import", "mavlink", str(common_xml()), "--out", str(out)])
    run([sys.executable, "-m", "codeword", "build", str(out / "common.yaml"), "--out", str(out), "--targets", "c"])
    return out / "c"


def firmware_peers(work: Path, mavlink: Path) -> list:
    """A firmware of FIRMWARE_MESSAGES over the whole dialect: the byte-at-a-time parser and
    the messages' encoders and decoders, from codeword's imported common.xml (with the
    messages selected, and without) and from mavgen's common.xml."""
    include = import_common(work / "import")
    ours = ["common_parser_init", "common_parser_feed", "common_parser_next"] + \
        [f"common_{m}_{op}" for m in FIRMWARE_MESSAGES for op in ("encode", "decode")]
    selected = ["-DCOMMON_SELECTED_MESSAGES"] + [f"-DCOMMON_SELECT_{m.upper()}" for m in FIRMWARE_MESSAGES]
    theirs = ["mavlink_parse_char"] + [f"mavlink_msg_{m}_{op}" for m in FIRMWARE_MESSAGES for op in ("pack", "decode")]
    flags = ["-I", str(mavlink / "common"), "-DMAVLINK_NO_SIGN_PACKET", "-DMAVLINK_NO_SIGNATURE_CHECK"]
    names = ", ".join(m.upper() for m in FIRMWARE_MESSAGES)
    rows = []
    for how, extra in (("selected (`-DCOMMON_SELECTED_MESSAGES` and `-DCOMMON_SELECT_<M>`)", selected),
                       ("not selected: the dispatching decoder holds all of them", [])):
        rows.append((f"MAVLink 2 C from mavgen (common.xml), a firmware of {names}: `mavlink_parse_char` and "
                     "each one's `_pack` and `_decode`, signing compiled out; codeword's imported common.xml: "
                     f"`common_parser_*` and each one's `_encode` and `_decode`, the messages {how}",
                     "common (imported)",
                     {t[0]: (flash(t, work, "mavlink_firmware", ["mavlink.h"], theirs, flags),
                             flash(t, work, "common_firmware", ["common.h"], ours, ["-I", str(include), *extra]))
                      for t in TARGETS}))
    return rows


def generate_cantools(out: Path) -> Path:
    out.mkdir(parents=True, exist_ok=True)
    for dbc in (DBC, CAN_MIXED_DBC):
        subprocess.run([sys.executable, "-m", "cantools", "generate_c_source", str(dbc)], check=True,
                       capture_output=True, cwd=out, env=dict(os.environ))
    return out


def cantools_functions(source: Path) -> list[str]:
    """The `_pack` and `_unpack` functions of a cantools-generated source."""
    text = source.read_text(encoding="utf-8")
    return sorted(set(re.findall(rf"^int ({source.stem}_\w+_(?:pack|unpack))\(", text, re.M)))


def measure() -> dict:
    """{"protocols": [(name, messages, {target: bytes})], "peers": [(label, ours, {target: (theirs, ours)})]}"""
    rows, peers = [], []
    with tempfile.TemporaryDirectory(prefix="codeword-protocol-size-") as tmp:
        work = Path(tmp)
        for folder in HEADERS:
            for header in sorted(folder.glob("*.h")):
                functions = codec_functions(header)
                if not functions:
                    continue
                sizes = {t[0]: flash(t, work, header.stem, [header.name], functions, ["-I", str(folder)])
                         for t in TARGETS}
                rows.append((header.stem, len(functions) // 2, sizes))
        by_name = {name: sizes for name, _n, sizes in rows}
        mavlink = generate_mavlink(work / "mavlink")
        theirs = [f"mavlink_msg_{n}_{op}" for n in MAVLINK_MESSAGES for op in ("pack", "decode")]
        theirs.append("mavlink_parse_char")
        flags = ["-I", str(mavlink / "common"), "-DMAVLINK_NO_SIGN_PACKET", "-DMAVLINK_NO_SIGNATURE_CHECK"]
        peers.append(("MAVLink 2 C from mavgen (common.xml): `mavlink_msg_<m>_pack` and `_decode` of the six "
                      "messages and `mavlink_parse_char`, signing compiled out", "mavlink2",
                      {t[0]: (flash(t, work, "mavlink", ["mavlink.h"], theirs, flags), by_name["mavlink2"][t[0]])
                       for t in TARGETS}))
        peers += firmware_peers(work, mavlink)
        cantools_dir = generate_cantools(work / "cantools")
        theirs = cantools_functions(cantools_dir / "route_car.c")
        ours = [f"{m}_{op}" for m in ("route_object", "car_master_control") for op in ("encode", "decode")]
        peers.append(("cantools C (`generate_c_source`) of bench/route_car.dbc: `<m>_pack` and `_unpack` of its "
                      "two messages (RouteObject, CarMasterControl)", "route's object and car's master_control",
                      {t[0]: (flash(t, work, "cantools", ["route_car.c"], theirs, ["-I", str(cantools_dir), "-x", "c"]),
                              flash(t, work, "route_car_ours", ["route.h", "car.h"], ours, ["-I", str(HEADERS[0])]))
                       for t in TARGETS}))
        theirs = cantools_functions(cantools_dir / "can_mixed.c")
        peers.append(("cantools C (`generate_c_source`) of examples/can_mixed.dbc: `<m>_pack` and `_unpack` of its "
                      f"{len(theirs) // 2} messages", "can_mixed",
                      {t[0]: (flash(t, work, "cantools_can_mixed", ["can_mixed.c"], theirs,
                                    ["-I", str(cantools_dir), "-x", "c"]), by_name["can_mixed"][t[0]])
                       for t in TARGETS}))
    return {"protocols": rows, "peers": peers}


def compiler_versions() -> list[str]:
    return [run([cmd[0], "--version"]).splitlines()[0].strip() for _label, cmd, _size in TARGETS]


def report_lines(result: dict) -> list[str]:
    labels = [t[0] for t in TARGETS]
    lines = [
        "## Whole protocols",
        "",
        "Every message's own encoder and decoder of each generated header (`<protocol>_<message>_encode` and "
        "`_decode`; not the framing's dispatchers and stream readers), kept by a program that stores their "
        "addresses in a `volatile` function pointer; the figure is its flash (`.text` + `.rodata` + `.data`) "
        "above the same program keeping none. Flags: " + "; ".join(
            f"{label} `{' '.join(cmd[1:])}`" for label, cmd, _size in TARGETS) + ". Compilers: "
        + "; ".join(f"`{v}`" for v in compiler_versions()) + ".",
        "",
        "| protocol | messages | " + " | ".join(f"{label} flash (bytes)" for label in labels) + " |",
        "|---|---:|" + "---:|" * len(labels),
    ]
    for name, messages, sizes in result["protocols"]:
        lines.append(f"| {name} | {messages} | " + " | ".join(str(sizes[label]) for label in labels) + " |")
    lines += [
        "",
        "The same messages compiled from their own libraries' generated C, with the same flags "
        "(codeword's decoders check the frame and every value; a peer's decoder may leave that to other "
        "functions, named here when they are part of the figure):",
        "",
        "| peer | codeword protocol | " + " | ".join(f"{label}: peer, codeword, ratio" for label in labels) + " |",
        "|---|---|" + "---|" * len(labels),
    ]
    for label_text, ours_name, sizes in result["peers"]:
        cells = [f"{theirs} B, {ours} B, {ours / theirs:.2f}×" for theirs, ours in (sizes[l] for l in labels)]
        lines.append(f"| {label_text} | {ours_name} | " + " | ".join(cells) + " |")
    lines.append("")
    return lines
