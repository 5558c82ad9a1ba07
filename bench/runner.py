"""Runs every benchmark in one process and renders bench/RESULTS.md."""

import importlib.metadata
import platform
import re
import sys
import time
from pathlib import Path

from bench import accelerated, avr, c_host, examples, imports, messages, peers_c, scaling, streams, timing

# The targets.
FLOOR_MAX = 1.2  # codeword / hand-written, Python, encode and decode
PYMAVLINK_MIN = 3.0  # pymavlink decode / codeword decode (comparable frame)
CONSTRUCT_MIN = 5.0
CANTOOLS_MIN = 2.0
STREAM_MIN = 3.0  # codeword MB/s / pymavlink MB/s
C_FLOOR_MAX = 1.2
SCAN_DEFAULT_MIN = 2.0  # mtv4_scan MB/s / mavlink_parse_char MB/s, the default CRC method
SCAN_BEST_MIN = 4.0  # the same, the fastest CRC method
EXPONENT_MAX = 1.2  # "near-linear"
SEEDS_MAX_S = 1.0
MAVGEN_MAX = 1.0  # codeword build CPU / mavgen C + Python CPU, same message count


def _progress(what, start):
    print(f"[{time.perf_counter() - start:6.0f} s] {what}", file=sys.stderr, flush=True)


def run(tmp: Path, repeats, stream_bytes, c_rounds, scaling_sizes, timing_target=timing.TARGET_SECONDS,
        stream_repeats=1, scaling_repeats=1, import_messages=imports.MESSAGES):
    results = {"repeats": repeats, "stream_repeats": stream_repeats, "c_rounds": c_rounds,
               "scaling_repeats": scaling_repeats}
    start = time.perf_counter()
    _progress("Python per message", start)
    cases = messages.cases()
    problems = [p for case in cases for p in messages.check(case)]
    if problems:
        raise AssertionError("contenders disagree:\n" + "\n".join(problems))
    contenders = {}
    for case in cases:
        for name, c in case.contenders.items():
            contenders[(case.key, name, "encode")] = c.encode
            contenders[(case.key, name, "decode")] = c.decode
    results["cases"] = cases
    results["per_message"] = timing.interleaved(contenders, repeats, timing_target)
    _progress("Python streams", start)
    # MB/s does not depend on the stream's length: pymavlink's stream is capped to keep the run short
    jobs = streams.contenders(stream_bytes, min(stream_bytes, 20_000_000))
    seconds = timing.interleaved_once({k: v[0] for k, v in jobs.items()}, stream_repeats)
    results["streams"] = {k: (jobs[k][1] / seconds[k] / 1e6, jobs[k][2] / seconds[k], jobs[k][1],
                              jobs[k][2], min(jobs[k][3])) for k in jobs}
    _progress("Python with the accelerator", start)
    results["accelerator"] = run_accelerator(repeats, stream_bytes, timing_target, stream_repeats)
    _progress("the examples against their peer libraries", start)
    results["examples"] = run_examples(repeats, timing_target)
    _progress("C on the host and on AVR", start)
    mavlink_dir = peers_c.generate_mavlink(tmp / "mavlink")
    cantools_dir = peers_c.generate_cantools(tmp / "cantools")
    results["c_host"] = c_host.run(tmp, mavlink_dir, c_rounds, min(stream_bytes, 20_000_000))
    results["c_can"] = c_host.run_can(tmp, cantools_dir, c_rounds)
    results["c_host_bytes"] = min(stream_bytes, 20_000_000)
    results["avr"] = avr.measure(tmp / "avr", mavlink_dir, cantools_dir)
    results["crc_choice"] = avr.crc_choice(tmp / "avr")
    _progress("compiler scaling", start)
    results["scaling"] = scaling.scaling(tmp / "scaling", scaling_repeats, scaling_sizes)
    results["seeds"] = scaling.seed_build(tmp, 3 if scaling_repeats > 1 else 1)
    results["mavgen"] = scaling.versus_mavgen(tmp / "versus-mavgen", max(1, scaling_repeats), peers_c.COMMON_XML)
    results["dialects"] = scaling.versus_mavgen_dialects(tmp / "dialects", max(1, scaling_repeats), peers_c.DIALECTS)
    _progress("importing a large module", start)
    results["imports"] = run_imports(tmp / "imports", repeats, import_messages)
    results["versions"] = versions()
    _progress("done", start)
    return results


def versions():
    out = {"Python": platform.python_version(), "machine": platform.machine(),
           "CPU": _cpu(), "gcc": c_host.compiler_version(), "avr-gcc": avr.compiler_version()}
    for pkg in ("construct", "cantools", "pymavlink", "bitstruct"):
        out[pkg] = importlib.metadata.version(pkg)
    return out


def _cpu():
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def compiler_section(r, verdicts):
    """Section 5, the compiler: its lines; appends its verdicts."""
    lines = []
    figures, exp, failures = r["scaling"]
    lines += ["## 5. Compiler scaling", "",
              "`codeword build` of synthetic byte-framed schemas (`bench/scaling.py`: n messages of four "
              "fields each) in a new process each, with no build cache; CPU seconds are the primary figure (on a shared machine "
              "wall time also counts waits for a core). The build writes Python, C, Markdown and the "
              "conformance vectors.", "",
              "| messages | CPU s | wall s | peak RSS MiB |", "|---:|---:|---:|---:|"]
    for n, (cpu, wall, mib) in sorted(figures.items()):
        lines.append(f"| {n:,} | {cpu:.2f} | {wall:.2f} | {mib:.0f} |")
    for n, error in sorted(failures.items()):
        lines.append(f"| {n:,} | build failed: {error} | | |")
    if 5000 not in figures and 5000 not in failures:
        lines.append("| 5,000 | not in this run (`--scaling-sizes` left it out; the default includes it) | | |")
    ok = exp <= EXPONENT_MAX and not failures
    verdicts.append(ok)
    seeds = r["seeds"]
    ok_seeds = seeds["first"][0] <= SEEDS_MAX_S
    verdicts.append(ok_seeds)
    lines += ["", f"- growth exponent of CPU time (fit over n ≥ 100) = {exp:.2f} (near-linear, target ≤ {EXPONENT_MAX}): {_met(ok)}",
              f"- cold build of the five seed protocols (a new process, empty build cache): {seeds['first'][0]:.2f} s CPU, "
              f"{seeds['first'][1]:.2f} s wall (target ≤ {SEEDS_MAX_S} s): {_met(ok_seeds)}"
              + ("" if ok_seeds else "; about half of it simulates tr24's delivery for the docs' efficiency "
                 "table and makes the conformance vectors, which the build cache keeps"),
              f"- the same again, with the build cache the first build left (`compiler/cache.py`: the validation "
              f"verdict, the compiled codecs, the tr24 delivery table, the hash of the vectors in place): "
              f"{seeds['again'][0]:.2f} s CPU, {seeds['again'][1]:.2f} s wall"]
    versus, n, stages = r["mavgen"]
    ratio = versus["codeword"][0] / versus["mavgen"][0]
    ok_mavgen = ratio <= MAVGEN_MAX
    verdicts.append(ok_mavgen)
    lines += ["", "### codeword and mavgen, same message count", "",
              f"pymavlink's mavgen generating C and Python (MAVLink 2) for common.xml ({n} messages with its "
              f"includes) in one process, against `codeword build` of a synthetic protocol framed as MAVLink 2 "
              f"with {n} messages of eight fields (`scaling.mavlink_shaped_schema`), writing Python, C, Markdown "
              "and the conformance vectors, with no build cache (`CODEWORD_CACHE=off`) and again with the cache "
              "a build of the same schema left (`compiler/cache.py`: the validation verdict, the compiled "
              "codec, the hash of the vectors in place); new processes, interleaved rounds, medians.", "",
              "| generator | CPU s | wall s |", "|---|---:|---:|",
              f"| mavgen C + Python, common.xml | {versus['mavgen'][0]:.2f} | {versus['mavgen'][1]:.2f} |",
              f"| codeword build, {n} × 8 fields | {versus['codeword'][0]:.2f} | {versus['codeword'][1]:.2f} |",
              f"| codeword build again, the build cache filled | {versus['codeword again'][0]:.2f} | "
              f"{versus['codeword again'][1]:.2f} |", "",
              f"- codeword CPU / mavgen CPU = {ratio:.2f} (target ≤ {MAVGEN_MAX}): {_met(ok_mavgen)}",
              f"- codeword again / mavgen = {versus['codeword again'][0] / versus['mavgen'][0]:.2f}", "",
              f"Where a cold build of the {n}-message protocol spends its CPU time (one more build, each stage's "
              "functions timed; `scaling.PHASES_CHILD`):", "", "| stage | CPU s | share |", "|---|---:|---:|"]
    total = sum(stages.values())
    for stage, seconds in stages.items():
        lines.append(f"| {stage} | {seconds:.2f} | {100 * seconds / total:.0f}% |")
    lines += ["", "mavgen validates the XML and fills its templates with text substitution; a codeword build also "
              "resolves and checks every rule of the schema, writes the docs, loads the Python it generated to run "
              "the schema's examples through it, and makes the conformance vectors with it (every message at its "
              "edges, random and damaged frames). Loading (compiling) the generated Python and the vectors are "
              "the work mavgen has no counterpart for; the build cache removes both from a build of an unchanged "
              "schema."]
    if "dialects" in r:
        lines += dialect_lines(r["dialects"])
    return lines


def dialect_lines(dialects: dict) -> list[str]:
    """The imported dialects against mavgen: CPU, wall time and peak memory."""
    lines = ["", "### MAVLink dialects, imported and built, against mavgen", "",
             "pymavlink's mavgen writing C and Python (MAVLink 2) for a dialect of pymavlink's, in one process, "
             "against `codeword import mavlink` of the same XML followed by `codeword build --targets c,python` of "
             "the schema it wrote, in one process, with no build cache; new processes, interleaved rounds, medians. "
             "Peak memory is the process's high-water mark (VmHWM).", "",
             "| dialect | mavgen CPU s | codeword CPU s | × | mavgen peak MiB | codeword peak MiB | × |",
             "|---|---:|---:|---:|---:|---:|---:|"]
    for name, d in dialects.items():
        (mc, _mw, mp), (cc, _cw, cp) = d["mavgen"], d["codeword"]
        lines.append(f"| {name} | {mc:.2f} | {cc:.2f} | {cc / mc:.2f} | {mp:.0f} | {cp:.0f} | {cp / mp:.2f} |")
    lines += [""] + [f"- {name}: codeword CPU / mavgen CPU = {d['codeword'][0] / d['mavgen'][0]:.2f} (goal ≤ 1.0: "
                     f"{_met(d['codeword'][0] <= d['mavgen'][0])}); peak memory {d['codeword'][2] / d['mavgen'][2]:.2f}× "
                     f"(goal ≤ 1.5: {_met(d['codeword'][2] <= 1.5 * d['mavgen'][2])})" for name, d in dialects.items()]
    return lines


def _met(ok):
    return "met" if ok else "**NOT met**"


def report(r):
    pm = r["per_message"]
    lines = ["# Benchmarks", "",
             "Written by `python3 -m bench` (see the README); do not edit by hand, run it again.", "",
             "Medians of interleaved repeats in one process; ratios compare medians of the same run. "
             "The machine is shared, so absolute times vary between runs; ratios are the figures to read.",
             "", "## Machine and versions", ""]
    for k, v in r["versions"].items():
        lines.append(f"- {k}: {v}")
    lines += ["", f"Repeats: {r['repeats']} (per message), {r['stream_repeats']} (streams), "
              f"{r['c_rounds']} (C), {r['scaling_repeats']} (compiler scaling).", ""]
    verdicts = []

    # 1
    lines += ["## 1. Python, per message", "",
              "Each call encodes one message object to bytes (text for tank) or decodes bytes to an object. "
              "The hand-written floor (`bench/handwritten.py`) is what a competent engineer writes for each "
              "message: a precompiled `struct.Struct` or one `int.from_bytes` and shifts, one compiled regular "
              "expression for a well-formed tank line, enum and flag values looked up in tables built at "
              "import, a CRC-16 table of the kind codeword uses (65,536 entries, two bytes a lookup, built at "
              "import, looped over the frame's pairs) and message classes of its own, with `__slots__` and a "
              "positional `__init__`. It checks the rules codeword checks on each message (ranges, constants, "
              "exactly one bit, finiteness, checksums, reserved bits, the cross-field rules; its docstring "
              "lists them) and leaves out only what is codeword's API: error objects naming the field and "
              "the rule, the per-field type checks on encode, raw values accepted for enums and flags. Its "
              "input objects hold the example's values and, like its decoded objects, are compared with "
              "codeword's field by field. codeword is called per message (`obj.encode()` and "
              "`Cls.decode(data)`), and the row `codeword, any message` times `mtv4.encode`/`mtv4.decode`, "
              "which find the message by its id first, as pymavlink's `decode` does. bitstruct, construct and "
              "cantools take and return their own form (tuple, dict, Container) and check only what the "
              "library checks; the wrappers compute the checksums the libraries cannot (`bench/peers.py`). "
              "Every contender's bytes and decoded values are checked equal before timing. pymavlink encodes "
              "and decodes ATTITUDE, a MAVLink 2 frame of 40 bytes, next to the 26-byte mtv4 frame.", "",
              "| message | contender | encode ns | decode ns | encode × codeword | decode × codeword |",
              "|---|---|---:|---:|---:|---:|"]
    for case in r["cases"]:
        cw_e, cw_d = pm[(case.key, "codeword", "encode")], pm[(case.key, "codeword", "decode")]
        for name in case.contenders:
            e, d = pm[(case.key, name, "encode")], pm[(case.key, name, "decode")]
            lines.append(f"| {case.title} | {name} | {e:,.0f} | {d:,.0f} | {e / cw_e:.2f} | {d / cw_d:.2f} |")
    lines += ["", "`× codeword` is the contender's time over codeword's: above 1, codeword is faster.", "",
              "Targets:", ""]
    missed = set()
    for case in r["cases"]:
        for op in ("encode", "decode"):
            ratio = pm[(case.key, "codeword", op)] / pm[(case.key, "hand-written", op)]
            ok = ratio <= FLOOR_MAX
            verdicts.append(ok)
            missed |= set() if ok else {op}
            lines.append(f"- {case.key} {op}: codeword / hand-written = {ratio:.2f} (target ≤ {FLOOR_MAX}): {_met(ok)}")
    if "encode" in missed:
        lines.append("- where an encode misses: codeword's encoders check every value's type before packing it "
                     "(a bool is not an int, an enum value must be one of its members) and name the field in a "
                     "typed error, which the floor leaves to Python's own errors; on a message of a few small "
                     "fields those checks are most of the difference")
    if "decode" in missed:
        lines.append("- where a decode misses: codeword's decoders also take any bytes-like input, and its "
                     "errors name the field, the rule and the bit offset")
    mav = "pymavlink ATTITUDE (40 B)"
    ratio = pm[("mtv4", mav, "decode")] / pm[("mtv4", messages.DISPATCHING, "decode")]
    verdicts.append(ratio >= PYMAVLINK_MIN)
    lines.append(f"- pymavlink decode / codeword `mtv4.decode` (both find the message by its id) = {ratio:.2f} "
                 f"(target ≥ {PYMAVLINK_MIN}): {_met(ratio >= PYMAVLINK_MIN)}")
    for peer, target in (("construct", CONSTRUCT_MIN), ("cantools", CANTOOLS_MIN)):
        for key in ("route", "car"):
            for op in ("encode", "decode"):
                ratio = pm[(key, peer, op)] / pm[(key, "codeword", op)]
                verdicts.append(ratio >= target)
                lines.append(f"- {peer} / codeword, {key} {op} = {ratio:.2f} (target ≥ {target}): {_met(ratio >= target)}")

    # 2
    s = r["streams"]
    lines += ["", "## 2. Python, streams", "",
              f"An mtv4 capture of {s['codeword'][2] / 1e6:.1f} MB (SetWheelsVelocitiesWithOdometry frames, "
              "1% of the bytes garbage, 1% of the frames corrupted) fed in 4 KiB chunks to "
              "`mtv4.StreamDecoder` and to a hand-written resynchronising reader; a MAVLink 2 stream of "
              "ATTITUDE frames built the same way fed to pymavlink's `parse_buffer` (robust parsing on). "
              "`bench/streams.py`.", "",
              "| contender | MB/s | frames/s | stream bytes | good frames sent | found |",
              "|---|---:|---:|---:|---:|---:|"]
    for name, (mbs, fps, size, sent, found) in s.items():
        lines.append(f"| {name} | {mbs:.2f} | {fps:,.0f} | {size:,} | {sent:,} | {found:,} |")
    ratio = s["codeword"][0] / s["pymavlink parse_buffer"][0]
    floor = s["codeword"][0] / s["hand-written"][0]
    verdicts.append(ratio >= STREAM_MIN)
    lines += ["", f"- codeword MB/s / pymavlink MB/s = {ratio:.2f} (target ≥ {STREAM_MIN}): {_met(ratio >= STREAM_MIN)}",
              f"- codeword MB/s / hand-written MB/s = {floor:.2f}",
              "- pymavlink finds fewer good frames than were sent: after a corrupted frame it can lose the next "
              "one while resynchronising."]

    lines += c_sections(r, verdicts)

    # 5, 6
    lines += [""] + compiler_section(r, verdicts)
    lines += accelerator_section(r["accelerator"], verdicts)

    # 7, 8, 9
    lines += [""] + examples_sections(r["examples"], verdicts)
    lines += [""] + imports.section(r["imports"], verdicts, _met)
    lines += ["", "## Summary", "", f"{sum(verdicts)} of {len(verdicts)} targets met; the misses are marked "
              "**NOT met** above.", ""]
    return "\n".join(lines)


def c_sections(r, verdicts) -> list[str]:
    """Sections 3 and 4: C on the host, C on AVR and its CRC methods."""
    c = r["c_host"]
    lines = ["", "## 3. C on the host", "",
              f"`bench/c/host_bench.c`, gcc -O2 ({' '.join(c_host.CFLAGS)}): one encode and one decode per "
              "iteration over 64 prepared messages; the hand-written C (`bench/c/handwritten.h`) fills the "
              "same structs and must write the same bytes, checked before timing (for the tank line also "
              "the same text and, read back, the same values; both keep its decimals as `cw_decimal_t`, "
              "digits and a power of ten, written as Python's repr writes them). MAVLink: "
              "`mavlink_msg_attitude_pack` + `mavlink_msg_to_send_buffer`, then `mavlink_parse_char` over "
              f"the frame and `mavlink_msg_attitude_decode`. Parsers run over {r['c_host_bytes'] / 1e6:.0f} MB "
              "captures built as in section 2. Times are the process's CPU time: on a shared machine, its "
              "waits for a core are not its own.", "",
              "| message | codeword ns | hand-written ns | codeword / hand-written |", "|---|---:|---:|---:|"]
    for key in ("route", "car", "mtv4", "tr24", "tank"):
        cw, hw = c[f"{key} codeword"], c[f"{key} hand-written"]
        ok = cw / hw <= C_FLOOR_MAX
        verdicts.append(ok)
        lines.append(f"| {key} | {cw:.1f} | {hw:.1f} | {cw / hw:.2f} ({_met(ok)}, target ≤ {C_FLOOR_MAX}) |")
    mav, copy = c["parser mavlink_parse_char MB/s"], c["memcpy MB/s"]
    lines += [f"| MAVLink ATTITUDE | | | {c['mavlink ATTITUDE']:.1f} ns |", "",
              "Stream parsers, side by side in each round: `mtv4_parser_feed`/`next` take one byte at a time "
              "(as from an ISR), `mtv4_scan` decodes in place from the capture in memory "
              "(`bench/c/mtv4_stream.c`, built once for each CRC method, `-DMTV4_CRC_<METHOD>`; "
              f"`{c_host.DEFAULT}` is the default); `mavlink_parse_char` runs over the MAVLink capture and `memcpy` copies the "
              "mtv4 capture once.", "",
              "| stream parser | MB/s | good frames | × `mavlink_parse_char` | share of `memcpy` |",
              "|---|---:|---:|---:|---:|"]
    for key in c_host.PARSERS:
        mbs = c[f"parser {key} MB/s"]
        lines.append(f"| codeword `{key.split(',')[0]}`,{key.split(',')[1]} | {mbs:.1f} | "
                     f"{c[f'parser {key} frames']:,.0f} | {mbs / mav:.2f} | {mbs / copy:.1%} |")
    lines += [f"| MAVLink `mavlink_parse_char` | {mav:.1f} | {c['parser mavlink_parse_char frames']:,.0f} | 1.00 | "
              f"{mav / copy:.1%} |", f"| `memcpy` | {copy:.1f} | | {copy / mav:.2f} | 100.0% |", ""]
    ok = c["parser mtv4_parser_feed/next, CRC table MB/s"] >= mav
    verdicts.append(ok)
    lines.append(f"- byte-at-a-time parser throughput codeword ≥ MAVLink: {_met(ok)}")
    ratio = c[f"parser mtv4_scan, CRC {c_host.DEFAULT} MB/s"] / mav
    best = max(c_host.CRC_METHODS, key=lambda m: c[f"parser mtv4_scan, CRC {m} MB/s"])
    fastest = c[f"parser mtv4_scan, CRC {best} MB/s"] / mav
    verdicts += [ratio >= SCAN_DEFAULT_MIN, fastest >= SCAN_BEST_MIN]
    lines += [f"- in-place `mtv4_scan` / `mavlink_parse_char` = {ratio:.2f} with the default CRC method, "
              f"`{c_host.DEFAULT}` (target ≥ {SCAN_DEFAULT_MIN}): {_met(ratio >= SCAN_DEFAULT_MIN)}",
              f"- in-place `mtv4_scan` / `mavlink_parse_char` = {fastest:.2f} with the fastest, `{best}` "
              f"(target ≥ {SCAN_BEST_MIN}): {_met(fastest >= SCAN_BEST_MIN)}"]

    lines += can_c_lines(r["c_can"])
    lines += ["", "## 4. C on AVR", "", avr.__doc__.split("\n\n", 1)[1].replace("\n", " ").strip(), "",
              f"Flags: `{' '.join(avr.CFLAGS)}`; {r['versions']['avr-gcc']}. Figures are bytes above the "
              "empty program; static RAM = `.data` + `.bss`. These programs differ from docs/c-size.md's "
              "(which subtract a baseline with the same struct scaffolding), so compare rows within this table.",
              "", "| codec | what | flash (B) | static RAM (B) |", "|---|---|---:|---:|"]
    for label, mode, flash, ram in r["avr"]:
        lines.append(f"| {label} | {mode} | {flash:,} | {ram:,} |")
    lines += [""] + avr.against_cantools(r["avr"]) + [
        "- where codeword's is larger: its encoders check every value against its field's range and its decoders "
        "the frame's constants (a CAN frame's identifier and length, 5 bytes of it), where cantools' pack masks "
        "each value into its bits and its unpack reads the bits it is given; a multiplexed message also has each "
        "value's presence checked against its multiplexors; and codeword's encoder first fills an array of raw "
        "values, one word as wide as the widest field (the CAN identifier's 32 bits) per field, then shifts each "
        "into its bytes, where cantools shifts each value of its own width"]
    lines += crc_choice(r["crc_choice"], c)
    return lines


def can_c_lines(c) -> list[str]:
    """Section 3's CAN table: codeword's C for examples/can_mixed.yaml against cantools' C
    for examples/can_mixed.dbc, the same values and data (`bench/c/can_bench.c`)."""
    lines = ["", "CAN messages (`bench/c/can_bench.c`, gcc -O2): codeword's encoder and decoder of a can_mixed "
             "message (its frame: the identifier and length, then the 8 bytes of data) against cantools' "
             "generated `pack` and `unpack` of the same DBC message on the same values and data; medians of "
             "interleaved batches of CPU time. codeword checks each value's range and the frame's constants; "
             "cantools masks and reads.", "",
             "| message | codeword encode ns | cantools pack ns | × | codeword decode ns | cantools unpack ns | × |",
             "|---|---:|---:|---:|---:|---:|---:|"]
    for m in c_host.CAN_MESSAGES:
        ce, te = c[f"{m} codeword encode"], c[f"{m} cantools encode"]
        cd, td = c[f"{m} codeword decode"], c[f"{m} cantools decode"]
        lines.append(f"| {m} | {ce:.1f} | {te:.1f} | {te / ce:.2f} | {cd:.1f} | {td:.1f} | {td / cd:.2f} |")
    lines += ["", "`×` is cantools' time over codeword's: above 1, codeword is faster."]
    return lines


def run_compiler(tmp: Path, scaling_sizes, scaling_repeats=1):
    """Section 5 alone (`python3 -m bench --only compiler`)."""
    start = time.perf_counter()
    _progress("compiler scaling", start)
    results = {"scaling": scaling.scaling(tmp / "scaling", scaling_repeats, scaling_sizes),
               "seeds": scaling.seed_build(tmp, 3 if scaling_repeats > 1 else 1),
               "mavgen": scaling.versus_mavgen(tmp / "versus-mavgen", max(1, scaling_repeats), peers_c.COMMON_XML),
               "dialects": scaling.versus_mavgen_dialects(tmp / "dialects", max(1, scaling_repeats), peers_c.DIALECTS)}
    _progress("done", start)
    return results


def run_c(tmp: Path, c_rounds, stream_bytes):
    """Sections 3 and 4 alone (`python3 -m bench --only c`)."""
    start = time.perf_counter()
    _progress("C on the host and on AVR", start)
    mavlink_dir = peers_c.generate_mavlink(tmp / "mavlink")
    cantools_dir = peers_c.generate_cantools(tmp / "cantools")
    results = {"c_host": c_host.run(tmp, mavlink_dir, c_rounds, min(stream_bytes, 20_000_000)),
               "c_can": c_host.run_can(tmp, cantools_dir, c_rounds),
               "c_host_bytes": min(stream_bytes, 20_000_000), "avr": avr.measure(tmp / "avr", mavlink_dir, cantools_dir),
               "crc_choice": avr.crc_choice(tmp / "avr"), "versions": versions()}
    _progress("done", start)
    return results


def run_accelerator(repeats, stream_bytes, timing_target=timing.TARGET_SECONDS, stream_repeats=1):
    """Section 6 alone (`python3 -m bench --only accelerator`)."""
    try:
        return accelerated.measure(messages.cases(), repeats, timing_target, stream_bytes, stream_repeats)
    except accelerated.NotBuilt as exc:
        return str(exc)


def run_imports(tmp: Path, repeats, messages=imports.MESSAGES):
    """Section 9 alone (`python3 -m bench --only imports`)."""
    return imports.measure(tmp, max(3, repeats), messages)


def run_examples(repeats, timing_target=timing.TARGET_SECONDS):
    """Sections 7 and 8: each example against its peer library (`python3 -m bench --only examples`)."""
    return examples.measure(repeats, timing_target)


def examples_sections(r, verdicts) -> list[str]:
    all_rows, ns = r
    return examples.nmea_report(all_rows, ns, verdicts, _met) + [""] + examples.report(all_rows, ns, verdicts, _met)


def accelerator_section(r, verdicts) -> list[str]:
    if isinstance(r, str):  # not built: the section says why
        return ["", "## 6. Python with the compiled accelerator", "", f"Not measured: {r}."]
    return accelerated.report(r, verdicts, _met)


def splice(text: str, number, lines: list[str], command: str) -> str:
    """RESULTS.md with one section (or a tuple of adjacent ones) measured again and the summary
    counted again; the other sections stay as their run wrote them, and a note says so."""
    numbers = number if isinstance(number, tuple) else (number,)
    named = " and ".join(str(n) for n in numbers)
    sections = re.split(r"(?m)^(?=## )", text)
    new = "\n".join(lines).strip("\n") + "\n\n" + (
        f"Section{'s' if len(numbers) > 1 else ''} {named} {'were' if len(numbers) > 1 else 'was'} measured again "
        f"on {'their' if len(numbers) > 1 else 'its'} own (`{command}`, {time.strftime('%Y-%m-%d')}); "
        "the other sections are from the last full run.\n\n")
    kept, placed = [], False
    for part in sections:
        if part.startswith("## Summary"):
            continue
        if any(part.startswith(f"## {n}.") for n in numbers):
            if not placed:
                kept.append(new)
                placed = True
            continue
        kept.append(part)
    if not placed:
        kept.append(new)
    body = "".join(kept)
    met = len(re.findall(r"(?<!NOT )\bmet\b", body))
    missed = body.count("**NOT met**")
    summary = ["## Summary", "", f"{met} of {met + missed} targets met; the misses are marked **NOT met** above.", ""]
    return body + "\n".join(summary)


def crc_choice(avr_figures, c):
    """The CRC methods: flash and cycles on AVR, MB/s on the host (docs/c-size.md, "CRC methods",
    adds Cortex-M0 flash)."""
    frame = f"{avr.CRC_FRAMES} mtv4 frames of 26 bytes"
    lines = ["", "### The CRC methods", "",
             f"An ATmega32 at 16 MHz under simavr (cycle-accurate; Timer1 counts CPU cycles, `bench/avr.py`): "
             f"`mtv4_scan` over {frame} in RAM, and the CRC alone over one frame's 23 bytes; flash is the "
             "whole program's. The host figures are the in-place scan's above.", "",
             "| CRC method | AVR flash (B) | AVR cycles per frame, scan | AVR cycles, CRC alone | host `mtv4_scan` MB/s |",
             "|---|---:|---:|---:|---:|"]
    for method in c_host.CRC_METHODS:
        flash, scan, crc = avr_figures[method]
        name = f"`MTV4_CRC_{method.upper()}`" + (" (default)" if method == c_host.DEFAULT else "")
        lines.append(f"| {name} | {flash:,} | {scan:,.0f} | {crc:,} | {c[f'parser mtv4_scan, CRC {method} MB/s']:.1f} |")
    bit, default = avr_figures["bitwise"], avr_figures[c_host.DEFAULT]
    # a UART at 115200 baud, 8N1, brings 11,520 bytes a second
    load = [scan / 26 * 11520 / 16e6 for _, scan, _ in (bit, default)]
    lines += ["", f"- the default method costs {default[0] - bit[0]:,} B of flash more than bitwise and saves "
                  f"{bit[1] - default[1]:,.0f} cycles a frame on AVR ({bit[1] / default[1]:.1f}× faster); on the host "
                  f"the scan runs {c[f'parser mtv4_scan, CRC {c_host.DEFAULT} MB/s'] / c['parser mtv4_scan, CRC bitwise MB/s']:.1f}× "
                  "faster with it",
              f"- parsing a saturated 115200-baud UART takes {load[0]:.1%} of a 16 MHz AVR with the bitwise CRC, "
              f"{load[1]:.1%} with the default"]
    return lines
