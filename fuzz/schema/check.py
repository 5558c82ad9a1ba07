"""One generated schema through every target: build (Python, C, docs, vectors,
Promela), the Python codec on its vectors and on damaged frames, the C codec
compiled with the strict warning flags and run against the same vectors, and the
compiled accelerator of the Python module against its pure-Python decoders.

The C codec runs once, built by gcc at -O0 with UBSan, its CRCs computed by each
method the generated C offers in turn (crc_method). Warnings that only inlining
and flow analysis raise (-Wmaybe-uninitialized, -Wtype-limits on folded constants)
need the optimisers, so the conformance driver, with a firmware-style unit that
encodes into and decodes from buffers on the stack (tests/cdriver.py
firmware_source), is also compiled (-c) at the other points of MATRIX: gcc at
-O1/-O2/-Os, clang at -O0/-O2/-Os, and the firmware unit alone with avr-gcc -Os
for an ATmega32 (16-bit int, an older gcc). Compiling at all seven more than doubles
the time of a schema (about 4.3 s instead of 1.6 s on one core; rotate: about 2 s), so
`--c-matrix rotate`, the default, compiles each seed at one of them, MATRIX[seed % 7]:
seven consecutive seeds cover every compiler and level, a long run each of them
thousands of times. `--c-matrix full` compiles every seed at all seven."""
from __future__ import annotations

import importlib.util
import json
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import traceback
from dataclasses import dataclass, field
from pathlib import Path

from codeword import accelerate
from codeword.build import build, compile_schema
from codeword.diff.compare import compare
from codeword.targets.c.crc import DEFAULT as CRC_DEFAULT, METHODS as CRC_METHOD_LIST

from . import accelerated
from .stream_end import stream_end_problem
from .features import DEFAULT
from .generate import generate
from .machines import machine_checks
from .unused import unused_names

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests"))  # the conformance driver writer, shared with tests/test_c.py
from cdriver import Driver, firmware_source, selection_applies, selection_flags, selection_source  # noqa: E402
from wrong_values import refusals  # noqa: E402 - shared with tests/test_codec_inputs.py

WARNINGS = ["-std=c99", "-Wall", "-Wextra", "-Wpedantic", "-Wconversion", "-Wsign-conversion", "-Wshadow", "-Werror"]
STRICT = [*WARNINGS, "-O0", "-fsanitize=undefined", "-fno-sanitize-recover=all"]
# compile-only points beside the run build (gcc -O0); gcc -O1 warns of uninitialised
# locals that -O2 (gcc 12) does not follow
MATRIX = [("gcc", "-O1"), ("gcc", "-O2"), ("gcc", "-Os"), ("clang", "-O0"), ("clang", "-O2"), ("clang", "-Os"),
          ("avr-gcc", "-Os")]
# an 8-bit target whose int is 16 bits, with an older gcc's flow analysis: the firmware
# unit alone (the host driver's vectors do not fit it), as the conformance tests build it
AVR = ["-std=gnu99", "-mmcu=atmega32", "-Wall", "-Wextra", "-Werror"]
C_MATRIX = ("rotate", "full")
SELECTION_SHARE = 0.2  # the seeds whose C is also built with some messages selected, and with none
MUTATIONS = 40


@dataclass
class Outcome:
    seed: int
    stage: str = "ok"  # where it failed: build, python, c, or ok
    detail: str = ""
    checks: int = 0
    notes: list[str] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return self.stage == "ok"

    def line(self) -> str:
        return f"seed {self.seed}: {self.stage}" + (f": {self.detail}" if self.detail else "")


# A seed that takes longer than this hangs somewhere (the generator, a codec, a tool): it is
# reported as a finding rather than holding up the rest of a run.
SEED_SECONDS = 1200


def _too_long(signum, frame) -> None:
    raise TimeoutError(f"the seed took over {SEED_SECONDS} s")


def check_seed(seed: int, features: frozenset[str] = DEFAULT, keep: Path | None = None,
               c_matrix: str = "rotate") -> Outcome:
    outcome = Outcome(seed)
    previous = signal.signal(signal.SIGALRM, _too_long)
    signal.alarm(SEED_SECONDS)
    with tempfile.TemporaryDirectory(prefix=f"fz{seed}-") as tmp:
        where = keep or Path(tmp)
        where.mkdir(parents=True, exist_ok=True)
        try:
            outcome.stage = "generate"
            text = generate(seed, features)
            outcome.stage = "ok"
            check_text(text, f"fz{seed}", where, outcome, matrix_points(seed, c_matrix), features)
        except Exception:  # anything but a finding is an internal error somewhere
            outcome.stage = outcome.stage if outcome.stage != "ok" else "internal"
            outcome.detail = traceback.format_exc(limit=-3).strip().splitlines()[-1]
            outcome.notes.append(traceback.format_exc(limit=-6))
        finally:
            signal.alarm(0)
            signal.signal(signal.SIGALRM, previous)
    return outcome


def matrix_points(seed: int, c_matrix: str) -> list[tuple[str, str]]:
    """The (compiler, level) points the seed's C is compiled at beside its run build."""
    if c_matrix not in C_MATRIX:
        raise ValueError(f"--c-matrix is one of {', '.join(C_MATRIX)}, not {c_matrix!r}")
    return list(MATRIX) if c_matrix == "full" else [MATRIX[seed % len(MATRIX)]]


def check_text(text: str, name: str, where: Path, outcome: Outcome,
               points: list[tuple[str, str]] | None = None, features: frozenset[str] = DEFAULT) -> None:
    path = where / f"{name}.yaml"
    path.write_text(text, encoding="utf-8")
    out = where / "out"
    outcome.stage = "build"
    result = build([path], out, root=where)
    if result.errors:
        outcome.detail = str(result.errors[0]).splitlines()[0]
        return
    protocol = compile_schema(path)
    outcome.stage = "diff"
    same = compare(protocol, protocol).changes  # the schema against itself: no change of any kind
    if same:
        outcome.detail = f"diff of the schema with itself: {same[0].subject}: {same[0].what}"
        return
    vectors = json.loads((out / "vectors" / f"{name}.json").read_text(encoding="utf-8"))
    outcome.stage = "python"
    unused = unused_names((out / "python" / f"{name}.py").read_text(encoding="utf-8"))
    if unused:  # a strict type checker's error in the user's project
        outcome.detail = f"the module defines and never uses: {', '.join(unused)}"
        return
    module = _load(out / "python" / f"{name}.py")
    problem = python_checks(module, vectors, protocol.framing.kind == "text", random.Random(outcome.seed),
                            nonfinite_fields(protocol))
    if problem:
        outcome.detail = problem
        return
    if "stream_end" in features:
        problem = stream_end_problem(module, protocol, vectors)
        if problem:
            outcome.detail = problem
            return
    outcome.stage = "c"
    problem, checks = c_checks(protocol, vectors, out / "c", where, points or [], crc_method(outcome.seed))
    outcome.checks = checks
    if not problem and "selected_messages" in features:
        problem = selection_checks(protocol, vectors, out / "c", where, outcome.seed)
    if problem:
        outcome.detail = problem
        return
    outcome.stage = "machines"
    problem = machine_checks(protocol, module, out, where, STRICT)
    if problem:
        outcome.detail = problem
        return
    outcome.stage = "accelerator"
    problem = accelerator_checks(path, out / "python", where / "accelerators", thin(vectors))
    if problem:
        outcome.detail = problem
        return
    outcome.stage = "ok"


def accelerator_checks(schema: Path, python: Path, folder: Path, vectors: dict) -> str:
    """Where the module has an accelerator: built (-O0, warnings as errors), used, and
    deciding every vector, damaged frame and stream as the pure-Python module does."""
    name = schema.stem
    if not (python / f"_{name}_accel.c").exists() or accelerate.compiler() is None \
            or accelerate.python_headers() is None:
        return ""
    accelerate.accelerate([schema], folder, ("-O0", "-Wall", "-Wextra", "-Werror"))
    fast = accelerated.load(python / f"{name}.py", f"_fuzz_fast_{name}", folder)
    pure = accelerated.load(python / f"{name}.py", f"_fuzz_pure_{name}", None)
    for module in (fast, pure):
        sys.modules.pop(module.__name__, None)
    if fast.ACCELERATOR is None:
        return "the accelerator was built but the module does not use it"
    valid = [bytes.fromhex(case["hex"]) for case in vectors["valid"]]
    return accelerated.difference(fast, pure, vectors, [b"".join(valid)])[0]


def _load(path: Path):
    key = f"_fuzz_{path.stem}"
    spec = importlib.util.spec_from_file_location(key, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[key] = module
    try:
        spec.loader.exec_module(module)
    finally:
        sys.modules.pop(key, None)
    return module


def _wire(case: dict, text: bool):
    return case["text"] if text else bytes.fromhex(case["hex"])


def python_checks(mod, vectors: dict, text: bool, rng: random.Random, nonfinite=frozenset()) -> str:
    """Every message has a valid vector; every valid vector decodes and encodes back;
    every invalid one is refused with
    a DecodeError; a value of the wrong type, shape or size in any field of a decoded
    message is refused with an EncodeError; damaged frames give only codec errors, and
    what decodes encodes."""
    frames = []
    objects = {}  # one decoded message of each class
    for case in vectors["valid"]:
        wire = _wire(case, text)
        obj = mod.decode(wire, case.get("direction"))
        objects.setdefault(type(obj), obj)
        again = mod.encode(obj)
        # kept spellings: the decoded message writes its numbers as received
        canonical = case.get("kept", case.get("canonical", case.get("text") if text else case.get("hex")))
        if again != (canonical if text else bytes.fromhex(canonical)):
            return f"valid {case['name']!r}: encode(decode(x)) = {again!r}, not {wire!r}"
        frames.append(wire)
    unserved = sorted(set(mod.MESSAGES) - {o.NAME for o in objects.values()}) \
        if hasattr(mod, "MESSAGES") else []
    if unserved:  # a message without a valid vector is a message nothing below checks
        return f"no valid vector of {', '.join(unserved)}"
    key = bytes.fromhex(vectors["signing_key"]) if "signing_key" in vectors else None
    for case in vectors["valid"]:  # a signed frame verifies with the vectors' key
        if case.get("verify") and mod.encode(mod.decode(_wire(case, text), case.get("direction"), key=key), key=key) \
                != _wire(case, text):
            return f"valid {case['name']!r}: not the frame its key signs"
    for case in vectors["invalid"]:
        try:
            if case.get("verify"):  # refused only by a decoder given the vectors' key
                mod.decode(_wire(case, text), case.get("direction"), key=key)
            else:
                mod.decode(_wire(case, text), case.get("direction"))
        except mod.DecodeError:
            continue
        return f"invalid {case['name']!r} decoded"
    problem = can_checks(mod, vectors) if hasattr(mod, "decode_can") else ""
    if problem:
        return problem
    problem = stream_checks(mod, vectors, frames) if hasattr(mod, "StreamDecoder") else ""
    refused = "" if problem else refusals(mod, objects.values(), nonfinite)
    if problem or refused:
        return problem or f"wrong value: {refused}"
    for frame in frames[:10]:
        for _ in range(MUTATIONS // 10 or 1):
            bad = _damage(frame, rng)
            try:
                obj = mod.decode(bad)
            except mod.CodecError:
                continue
            again = mod.encode(obj)
            if not _same(mod, mod.decode(again), obj):
                return f"damaged {bad!r} decodes to {obj!r}, whose encoding decodes differently"
    return ""


def _same(mod, a, b) -> bool:
    """Two decoded messages alike: equal, or (a NaN equals nothing, itself neither) written
    as the same bytes."""
    return a == b or type(a) is type(b) and mod.encode(a) == mod.encode(b)


def nonfinite_fields(protocol) -> frozenset[tuple[str, str]]:
    """(message, field) of each float field whose NaN and infinities are values."""
    return frozenset((m.name, leaf.field.name) for m in protocol.messages for leaf in m.wire.leaves
                     if leaf.field.kind == "float" and not leaf.field.finite)


def can_checks(mod, vectors: dict) -> str:
    """A CAN frame given as its identifier and its data decodes to the message its whole
    frame does, and the message gives back that identifier and data; an invalid frame's
    data is refused (a DecodeError) or, given as the header says, is the frame refused."""
    for case in vectors["valid"]:
        frame = bytes.fromhex(case["hex"])
        ident, data = int.from_bytes(frame[:4], "big"), frame[5:]
        obj = mod.decode_can(ident, data)
        if not _same(mod, obj, mod.decode(frame)):
            return f"valid {case['name']!r}: decode_can gives {obj!r}, decode {mod.decode(frame)!r}"
        canonical = bytes.fromhex(case.get("canonical", case["hex"]))
        if obj.encode_can() != (int.from_bytes(canonical[:4], "big"), canonical[5:]):
            return f"valid {case['name']!r}: encode_can gives {obj.encode_can()!r}"
    for case in vectors["invalid"]:
        frame = bytes.fromhex(case["hex"])
        if len(frame) < 5 or frame[4] != len(frame) - 5:
            continue  # no CAN controller gives a frame whose length is not its data's
        try:
            mod.decode_can(int.from_bytes(frame[:4], "big"), frame[5:])
        except mod.DecodeError:
            continue
        return f"invalid {case['name']!r} decoded by decode_can"
    return ""


def stream_checks(mod, vectors: dict, frames: list[bytes]) -> str:
    """Frames back to back give their messages, in order and nothing else; in a stuffed
    framing, a run of short stretches between delimiters gives one error, never two."""
    alone = []
    for frame in frames[:40]:
        try:
            alone.append(mod.decode(frame))  # a frame that needs its direction is left out
        except mod.CodecError:
            continue
    if alone:
        encoded = [mod.encode(m) for m in alone]
        stream = "".join(encoded) if isinstance(encoded[0], str) else b"".join(encoded)  # text lines or frames
        d = mod.StreamDecoder()
        got = d.feed(stream) + d.finish()
        if len(got) != len(alone) or not all(_same(mod, a, b) for a, b in zip(got, alone)):
            return f"stream of {len(alone)} frames back to back {stream!r}: decoded as {got!r}"
    for case in vectors.get("streams", []):
        kinds = ["error" if "error" in e else "message" for e in case["events"]]
        if case["name"] == "runs of short garbage" and ("error", "error") in zip(kinds, kinds[1:]):
            return f"stream {case.get('hex')}: two errors in one run of garbage ({' '.join(kinds)})"
    return ""


def _damage(frame, rng: random.Random):
    if isinstance(frame, str):
        chars = list(frame)
        i = rng.randrange(len(chars))
        chars[i] = rng.choice("0123456789-.,;:|=*#abcXYZ \n")
        return "".join(chars)
    data = bytearray(frame)
    if rng.random() < 0.5 and data:
        data[rng.randrange(len(data))] ^= 1 << rng.randrange(8)
    elif data:
        del data[rng.randrange(len(data))]
    return bytes(data)


# The CRC method the run build compiles in ("": the default, with no macro): one in turn
# by seed, independently of the MATRIX point.
CRC_METHODS = tuple("" if m.guard == CRC_DEFAULT else m.guard for m in CRC_METHOD_LIST)


def crc_method(seed: int) -> str:
    return CRC_METHODS[seed // len(MATRIX) % len(CRC_METHODS)]


def c_checks(protocol, vectors: dict, include: Path, where: Path,
             points: list[tuple[str, str]], crc: str = "") -> tuple[str, int]:
    gcc = shutil.which("gcc")
    if gcc is None:
        return "gcc is not installed", 0
    src, exe = where / "driver.c", where / "driver"
    driver = Driver(protocol).source(thin(vectors))
    src.write_text(driver, encoding="utf-8")
    method = [f"-D{protocol.name.upper()}_CRC_{crc}"] if crc else []
    built = subprocess.run([gcc, *STRICT, *method, "-I", str(include), str(src), "-o", str(exe)], capture_output=True,
                           text=True, timeout=300)
    if built.returncode != 0:
        return "does not compile: " + _first_error(built.stderr, where), 0
    ran = subprocess.run([str(exe)], capture_output=True, text=True, timeout=120)
    verdict = re.search(rf"CONFORMANCE {protocol.name} PASS (\d+)", ran.stdout)
    if ran.returncode != 0 or verdict is None:
        lines = [x for x in (ran.stdout + ran.stderr).splitlines() if x.strip()]
        return "C disagrees: " + " | ".join(lines[:3]), 0
    unit = where / "matrix.c"
    unit.write_text(driver + "\n" + firmware_source(protocol, include=False), encoding="utf-8")
    for compiler, level in points:
        path = shutil.which(compiler)
        if path is None:
            return f"{compiler} is not installed", 0
        if compiler == "avr-gcc":
            firmware = where / "firmware.c"
            firmware.write_text(firmware_source(protocol), encoding="utf-8")
            command = [path, *AVR, level, "-I", str(include), "-c", str(firmware), "-o", str(where / "avr.o")]
        else:
            command = [path, *WARNINGS, level, "-I", str(include), "-c", str(unit), "-o", str(where / "matrix.o")]
        built = subprocess.run(command, capture_output=True, text=True, timeout=300)
        if compiler == "avr-gcc":
            problem = sixteen_bit_sizes(protocol, built.returncode, built.stderr, where)
            if problem is not None:
                return problem, 0
            continue
        if built.returncode != 0:
            return f"does not compile with {compiler} {level}: " + _first_error(built.stderr, where), 0
    return "", int(verdict.group(1))


def selection_checks(protocol, vectors: dict, include: Path, where: Path, seed: int) -> str:
    """In a fifth of the seeds (drawn apart from the schema's draws): the conformance driver
    and the firmware unit compile under the strict warnings with no message selected
    (`<PX>_SELECTED_MESSAGES` alone), and, where the dispatching decoder reads the vectors'
    frames as they are, a program with some messages selected, built with the strict
    warnings, decodes the selected messages' frames and encodes them back and finds the
    others CW_ERR_DISPATCH ("" when all hold)."""
    px = protocol.name.upper()
    rng = random.Random(f"selected_messages {seed}")
    if rng.random() >= SELECTION_SHARE:
        return ""
    chosen = [m.name for m in protocol.messages if rng.random() < 0.5]
    path = shutil.which("clang") or shutil.which("gcc")
    if path is None:
        return "no C compiler is installed"
    built = subprocess.run([path, *WARNINGS, "-O2", f"-D{px}_SELECTED_MESSAGES", "-I", str(include), "-c",
                            str(where / "matrix.c"), "-o", str(where / "selected.o")],
                           capture_output=True, text=True, timeout=300)
    if built.returncode != 0:
        return "selecting no messages: does not compile: " + _first_error(built.stderr, where)
    if not selection_applies(protocol):
        return ""
    src, exe = where / "selection.c", where / "selection"
    src.write_text(selection_source(protocol, vectors, chosen), encoding="utf-8")
    flags = selection_flags(px, chosen)
    built = subprocess.run([shutil.which("gcc") or "gcc", *STRICT, *flags, "-I", str(include), str(src), "-o",
                            str(exe)], capture_output=True, text=True, timeout=300)
    if built.returncode != 0:
        return f"selecting {chosen}: does not compile: " + _first_error(built.stderr, where)
    ran = subprocess.run([str(exe)], capture_output=True, text=True, timeout=120)
    if ran.returncode != 0 or f"SELECTION {protocol.name} PASS" not in ran.stdout:
        lines = [x for x in (ran.stdout + ran.stderr).splitlines() if x.strip()]
        return f"selecting {chosen}: " + " | ".join(lines[:3])
    return ""


def sixteen_bit_sizes(protocol, returncode: int, stderr: str, where: Path) -> str | None:
    """On a target with a 16-bit size_t, a header whose frames are over 65,535 bytes must
    stop the build with its #error (frames up to twice as long once stuffed may): an
    error, or None when the build went as it should."""
    longest = max((m.size or 0 for m in protocol.messages), default=0)
    refused = returncode != 0 and "size_t cannot count them" in stderr
    if longest > 0xFFFF and not refused:
        return f"avr-gcc -Os: frames of {longest} bytes, yet the header does not stop the build"
    if refused and 2 * longest + 64 > 0xFFFF:
        return None
    if returncode != 0:
        return "does not compile with avr-gcc -Os: " + _first_error(stderr, where)
    return None


def thin(vectors: dict, large: int = 4096, keep: int = 2) -> dict:
    """The vectors the C driver embeds, with at most `keep` valid and `keep` invalid
    frames of over `large` bytes per message: a schema with frames over 64 KiB would
    otherwise give a driver of tens of megabytes. Python has checked them all."""
    def few(cases: list[dict]) -> list[dict]:
        seen: dict[str, int] = {}
        out = []
        for case in cases:
            size = len(case.get("hex", "")) // 2
            if size > large:
                seen[case["message"]] = seen.get(case["message"], 0) + 1
                if seen[case["message"]] > keep:
                    continue
            out.append(case)
        return out
    return dict(vectors, valid=few(vectors["valid"]), invalid=few(vectors["invalid"]))


def _first_error(stderr: str, where: Path) -> str:
    first = next((line for line in stderr.splitlines() if "error" in line), stderr[:300])
    return first.replace(str(where) + "/", "")
