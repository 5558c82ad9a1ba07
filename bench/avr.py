"""C on AVR: flash and static RAM of one message's codec, codeword next to
MAVLink's and cantools' generated C.

The approach of scripts/size-report, applied to every row alike: a program
reads its inputs from a `volatile` source and writes its results to a
`volatile` sink so the optimiser keeps the codec; its cost is its avr-size
figures minus those of an empty program with the same scaffolding. All are
built with -Os and gc-sections for an ATmega1284P, the same AVR core as the
ATmega32 of docs/c-size.md with more RAM: MAVLink's generated C for
common.xml keeps its message table (CRC extras and lengths of every message)
in `.data`, which overflows the ATmega32's 2 KB of RAM.
"""

import re
import subprocess
from pathlib import Path

from bench.protocols import ROOT
from codeword.targets.c.crc import METHODS

MCU = "atmega1284p"
CFLAGS = ["-std=gnu99", "-Os", f"-mmcu={MCU}", "-ffunction-sections", "-fdata-sections",
          "-Wl,--gc-sections", "-w"]

PROGRAM = """\
#include <stddef.h>
#include <stdint.h>
{include}
volatile uint8_t src;
volatile uint8_t snk;

static void __attribute__((noinline)) fill(void *p, size_t n)
{{
    uint8_t *b = (uint8_t *)p;
    while (n--) *b++ = src;
}}

static void __attribute__((noinline)) drain(const void *p, size_t n)
{{
    const uint8_t *b = (const uint8_t *)p;
    while (n--) snk = *b++;
}}

int main(void)
{{
#ifdef EMPTY
    uint8_t x[1];
    fill(x, 1);
    drain(x, 1);
#else
{body}
#endif
    return 0;
}}
"""

ENCODE = """\
    {type} m;
    uint8_t buf[{size}];
    int rc;
    fill(&m, sizeof m);
    rc = {encode};
    drain(&rc, sizeof rc);
    drain(buf, sizeof buf);
"""

DECODE = """\
    size_t len;
    fill(buf, sizeof buf);
    fill(&len, sizeof len);
    rc = {decode};
    drain(&rc, sizeof rc);
    drain(&m, sizeof m);
"""

MAVLINK_PACK = """\
    mavlink_message_t msg;
    uint8_t buf[MAVLINK_MAX_PACKET_LEN];
    float f[6];
    uint32_t t;
    uint16_t n;
    fill(f, sizeof f);
    fill(&t, sizeof t);
    mavlink_msg_attitude_pack(1, 1, &msg, t, f[0], f[1], f[2], f[3], f[4], f[5]);
    n = mavlink_msg_to_send_buffer(buf, &msg);
    drain(buf, n);
"""

MAVLINK_UNPACK = """\
    mavlink_status_t st;
    mavlink_attitude_t att;
    size_t len;
    fill(buf, sizeof buf);
    fill(&len, sizeof len);
    for (size_t k = 0; k < len; k++) {
        if (mavlink_parse_char(MAVLINK_COMM_0, buf[k], &msg, &st)) {
            mavlink_msg_attitude_decode(&msg, &att);
            drain(&att, sizeof att);
        }
    }
"""


def _codeword(header, typ, size, encode, decode, folder=ROOT / "generated" / "c"):
    body = ENCODE.format(type=typ, size=size, encode=f"{encode}(&m, buf, sizeof buf)")
    return {
        "include": f'#include "{header}"',
        "encode only": body,
        "encode + decode": body + DECODE.format(decode=f"{decode}(buf, len, &m)"),
        "flags": ["-I", str(folder)], "sources": [],
    }


def _cantools(cantools_dir: Path, database: str, message: str, size: int):
    """cantools' generated `<database>_<message>_pack` and `_unpack` of one message."""
    body = ENCODE.format(type=f"struct {database}_{message}_t", size=size,
                         encode=f"{database}_{message}_pack(buf, &m, sizeof buf)")
    return {"include": f'#include "{database}.h"', "encode only": body,
            "encode + decode": body + DECODE.format(decode=f"{database}_{message}_unpack(&m, buf, len)"),
            "flags": ["-I", str(cantools_dir)], "sources": [str(cantools_dir / f"{database}.c")]}


EXAMPLES_C = ROOT / "generated" / "examples" / "c"
# rows of the same message from codeword and from cantools' generated C, compared
CANTOOLS_PAIRS = (("codeword can_mixed steering (both byte orders)", "cantools can_mixed Steering (same DBC message)"),
                  ("codeword can_mixed extended (multiplexed)", "cantools can_mixed Extended (same DBC message)"),
                  ("codeword route object (29-bit record)", "cantools route object (same DBC record)"))


def against_cantools(results) -> list[str]:
    """codeword's flash over cantools' for the same message, each mode (goal: ≤ 1.0)."""
    flash = {(label, mode): f for label, mode, f, _ in results}
    out = []
    for ours, theirs in CANTOOLS_PAIRS:
        ratios = [f"{mode} {flash[(ours, mode)] / flash[(theirs, mode)]:.2f}×"
                  for mode in ("encode only", "encode + decode") if (theirs, mode) in flash]
        met = all(flash[(ours, m)] <= flash[(theirs, m)] for m in ("encode only", "encode + decode"))
        out.append(f"- {ours.removeprefix('codeword ')}: codeword / cantools flash {', '.join(ratios)} "
                   f"(goal ≤ 1.0: {'met' if met else '**NOT met**'})")
    return out


def rows(mavlink_dir: Path, cantools_dir: Path):
    """(label, what, program parts) for every measured row."""
    cantools_route = ENCODE.format(type="struct route_car_route_object_t", size=4,
                                   encode="route_car_route_object_pack(buf, &m, sizeof buf)")
    return [
        ("codeword route object (29-bit record)", _codeword(
            "route.h", "route_object_t", "ROUTE_OBJECT_SIZE", "route_object_encode", "route_object_decode")),
        ("cantools route object (same DBC record)", {
            "include": '#include "route_car.h"', "encode only": cantools_route,
            "encode + decode": cantools_route + DECODE.format(
                decode="route_car_route_object_unpack(&m, buf, len)"),
            "flags": ["-I", str(cantools_dir)], "sources": [str(cantools_dir / "route_car.c")]}),
        ("codeword car master control word", _codeword(
            "car.h", "car_master_control_t", "CAR_MASTER_CONTROL_SIZE", "car_master_control_encode",
            "car_master_control_decode")),
        ("codeword mtv4 SetWheelsVelocities (12 B)", _codeword(
            "mtv4.h", "mtv4_set_wheels_velocities_t", "MTV4_SET_WHEELS_VELOCITIES_SIZE",
            "mtv4_set_wheels_velocities_encode", "mtv4_set_wheels_velocities_decode")),
        ("codeword mtv4 SetWheelsVelocitiesWithOdometry (26 B)", _codeword(
            "mtv4.h", "mtv4_set_wheels_velocities_with_odometry_t",
            "MTV4_SET_WHEELS_VELOCITIES_WITH_ODOMETRY_SIZE",
            "mtv4_set_wheels_velocities_with_odometry_encode",
            "mtv4_set_wheels_velocities_with_odometry_decode")),
        ("MAVLink ATTITUDE (40 B, MAVLINK_NO_SIGN_PACKET)", {
            "include": '#include "common/mavlink.h"', "encode only": MAVLINK_PACK,
            "encode + decode": MAVLINK_PACK + MAVLINK_UNPACK,
            "flags": ["-I", str(mavlink_dir), "-DMAVLINK_NO_SIGN_PACKET", "-DMAVLINK_COMM_NUM_BUFFERS=1"],
            "sources": []}),
        ("codeword tr24 command (12 B)", _codeword(
            "tr24.h", "tr24_command_t", "TR24_COMMAND_SIZE", "tr24_command_encode", "tr24_command_decode")),
        # a CAN message of both byte orders and a multiplexed one: codeword's frame holds the
        # identifier and length (5 bytes) before the 8 bytes of data cantools packs
        ("codeword can_mixed steering (both byte orders)", _codeword(
            "can_mixed.h", "can_mixed_steering_t", "CAN_MIXED_STEERING_SIZE", "can_mixed_steering_encode",
            "can_mixed_steering_decode", EXAMPLES_C)),
        ("cantools can_mixed Steering (same DBC message)", _cantools(cantools_dir, "can_mixed", "steering", 8)),
        ("codeword can_mixed extended (multiplexed)", _codeword(
            "can_mixed.h", "can_mixed_extended_t", "CAN_MIXED_EXTENDED_SIZE", "can_mixed_extended_encode",
            "can_mixed_extended_decode", EXAMPLES_C)),
        ("cantools can_mixed Extended (same DBC message)", _cantools(cantools_dir, "can_mixed", "extended", 8)),
    ]


def _size(elf: Path):
    out = subprocess.run(["avr-size", "-A", str(elf)], capture_output=True, text=True, check=True).stdout
    sections = {}
    for line in out.splitlines():
        m = re.match(r"(\.\w+)\s+(\d+)", line)
        if m:
            sections[m.group(1)] = int(m.group(2))
    text, data, bss = (sections.get(s, 0) for s in (".text", ".data", ".bss"))
    return text + data, data + bss


def _build(tmp: Path, name: str, include: str, body: str, flags, sources, empty=False):
    src = tmp / f"{name}.c"
    src.write_text(PROGRAM.format(include=include, body=body))
    elf = tmp / f"{name}.elf"
    subprocess.run(["avr-gcc", *CFLAGS, *flags, *(["-DEMPTY"] if empty else []), str(src), *sources,
                    "-o", str(elf)], check=True, capture_output=True, text=True)
    return _size(elf)


def measure(tmp: Path, mavlink_dir: Path, cantools_dir: Path):
    """[(label, mode, flash, ram)] above the empty program."""
    tmp.mkdir(parents=True, exist_ok=True)
    results = []
    for n, (label, parts) in enumerate(rows(mavlink_dir, cantools_dir)):
        base = _build(tmp, f"row{n}_empty", parts["include"], "", parts["flags"], parts["sources"], True)
        for mode in ("encode only", "encode + decode"):
            flash, ram = _build(tmp, f"row{n}_{mode.split()[-1]}", parts["include"], parts[mode],
                                parts["flags"], parts["sources"])
            results.append((label, mode, flash - base[0], ram - base[1]))
    return results


def compiler_version():
    return subprocess.run(["avr-gcc", "--version"], capture_output=True, text=True,
                          check=True).stdout.splitlines()[0]


# The CRC methods (codeword.targets.c.crc.METHODS): flash and cycles on the ATmega32 of
# docs/c-size.md, under simavr (cycle-accurate), Timer1 counting CPU cycles.
CRC_MCU = "atmega32"
CRC_FRAMES = 8

CRC_PROGRAM = """\
#include <avr/interrupt.h>
#include <avr/io.h>
#include <avr/sleep.h>
#include <stdio.h>
#include "mtv4.h"

#define SIZE MTV4_SET_WHEELS_VELOCITIES_WITH_ODOMETRY_SIZE
static uint8_t stream[{frames} * SIZE];

static int uart_putchar(char c, FILE *f)
{{
    (void)f;
    while (!(UCSRA & (1 << UDRE))) {{
    }}
    UDR = (uint8_t)c;
    return 0;
}}
static FILE uart_out = FDEV_SETUP_STREAM(uart_putchar, NULL, _FDEV_SETUP_WRITE);

int main(void)
{{
    mtv4_set_wheels_velocities_with_odometry_t m = {{0}};
    mtv4_scan_state_t s;
    mtv4_message_t out;
    size_t pos = 0;
    uint8_t i;
    uint16_t t0, crc;
    uint32_t scan_cycles = 0, crc_cycles;
    int good = 0;
    stdout = &uart_out;
    for (i = 0; i < {frames}; i++) {{
        m.group = i;
        m.robots = (uint16_t)(1u << i);
        m.vl = (int16_t)(100 * i - 300);
        m.x = 0.5f * i;
        if (mtv4_set_wheels_velocities_with_odometry_encode(&m, stream + i * SIZE, SIZE) != (int)SIZE) {{
            printf("encode failed\\n");
        }}
    }}
    TCCR1B = 1 << CS10;  /* Timer1 counts CPU cycles */
    mtv4_scan_start(&s, MTV4_DIR_ANY);
    while (pos < sizeof stream) {{
        size_t used;
        int rc;
        t0 = TCNT1;
        rc = mtv4_scan(&s, stream + pos, sizeof stream - pos, &used, &out);
        scan_cycles += (uint16_t)(TCNT1 - t0);
        pos += used;
        good += rc == 1;
        if (rc == 0) {{
            break;
        }}
    }}
    t0 = TCNT1;
    crc = mtv4_crc16_8005_ffff_nn_0(stream + 1, SIZE - 3u);
    crc_cycles = (uint16_t)(TCNT1 - t0);
    printf("frames %d scan %lu crc %lu %u\\n", good, (unsigned long)scan_cycles, (unsigned long)crc_cycles, crc);
    cli();
    sleep_cpu();
    return 0;
}}
"""


def crc_choice(tmp: Path):
    """{method: (flash, scan cycles per frame, CRC cycles per frame)} for mtv4's 26-byte
    frame: mtv4_scan (sync, length, CRC, decode) and the CRC alone over its 23 bytes."""
    tmp.mkdir(parents=True, exist_ok=True)
    src = tmp / "crc_choice.c"
    src.write_text(CRC_PROGRAM.format(frames=CRC_FRAMES))
    out = {}
    for method in METHODS:
        variant, defines = method.guard.lower(), [f"-DMTV4_CRC_{method.guard}"]
        elf = tmp / f"crc_{variant}.elf"
        subprocess.run(["avr-gcc", "-std=gnu99", "-Os", f"-mmcu={CRC_MCU}", "-ffunction-sections", "-fdata-sections",
                        "-Wl,--gc-sections", "-Wall", "-Wextra", "-Werror", *defines,
                        "-I", str(ROOT / "generated" / "c"), str(src), "-o", str(elf)],
                       check=True, capture_output=True, text=True)
        run = subprocess.run(["simavr", "-m", CRC_MCU, "-f", "16000000", str(elf)],
                             capture_output=True, text=True, timeout=120)
        m = re.search(r"frames (\d+) scan (\d+) crc (\d+)", run.stdout + run.stderr)
        if not m or int(m.group(1)) != CRC_FRAMES:
            raise AssertionError(f"simavr run of the {variant} CRC program: {run.stdout}{run.stderr}")
        out[variant] = (_size(elf)[0], int(m.group(2)) / CRC_FRAMES, int(m.group(3)))
    return out
