"""`codeword import mavlink` against pymavlink, the reference MAVLink implementation:
common.xml imported and built; for every one of its messages, random values (edge
values, arrays full and partly zero, extension fields sent and left off) packed by
pymavlink decode with codeword's Python to pymavlink's values and encode back to
pymavlink's bytes, and frames codeword's Python builds from the values parse in
pymavlink to them; every message's crc_extra, which the compiler derives from the
schema, is pymavlink's (mavgen's). The whole dialect's C passes its conformance
vectors under the strict warning flags. Every dialect pymavlink ships imports and
resolves, in MAVLink 1 and 2, with mavgen's crc_extra for every message."""
from __future__ import annotations

import importlib
import json
import math
import os
import random
import struct
import subprocess
import sys
from pathlib import Path

import pytest

os.environ["MAVLINK20"] = "1"  # before pymavlink is imported: its v2 framing
import pymavlink  # noqa: E402  (a test extra: pip install -e ".[peers]")
from pymavlink.dialects.v10 import common as mavlink1  # noqa: E402
from pymavlink.dialects.v20 import common as mavlink2  # noqa: E402

from codeword.build import compile_schema  # noqa: E402
from codeword.importers.mavlink import import_dialect  # noqa: E402
from codeword.importers.mavlink_xml import MavlinkXmlError  # noqa: E402
from cdriver import Driver  # noqa: E402
from schema_in_a_test import load  # noqa: E402

DIALECTS = Path(pymavlink.__file__).parent / "dialects" / "v20"
COMMON = DIALECTS / "common.xml"
# dialects whose every message id is above 255: nothing of them for MAVLink 1
V2_ONLY = {"csAirLink.xml", "icarous.xml", "test.xml"}
ROOT = Path(__file__).resolve().parent.parent

INT_RANGES = {"int8_t": (-128, 127), "uint8_t": (0, 255), "int16_t": (-1 << 15, (1 << 15) - 1),
              "uint16_t": (0, 0xFFFF), "int32_t": (-1 << 31, (1 << 31) - 1), "uint32_t": (0, 0xFFFFFFFF),
              "int64_t": (-1 << 63, (1 << 63) - 1), "uint64_t": (0, (1 << 64) - 1)}
F32_MAX = struct.unpack("<f", b"\xff\xff\x7f\x7f")[0]
F32_TINY = struct.unpack("<f", b"\x01\x00\x00\x00")[0]  # the smallest subnormal
F64_MAX = struct.unpack("<d", b"\xff\xff\xff\xff\xff\xff\xef\x7f")[0]


def f32(x: float) -> float:
    return struct.unpack("<f", struct.pack("<f", x))[0]


def scalar(rng: random.Random, ctype: str):
    """A value of a MAVLink element type: an edge of its range a third of the time."""
    if ctype in INT_RANGES:
        lo, hi = INT_RANGES[ctype]
        return rng.choice([lo, hi, 0, rng.randint(lo, hi)]) if rng.random() < 0.3 else rng.randint(lo, hi)
    if ctype == "float":  # NaN as a sender's C writes it (NAN: the quiet NaN), and the infinities
        edges = [0.0, -0.0, F32_MAX, -F32_MAX, F32_TINY, -F32_TINY, 1.0, math.nan, math.inf, -math.inf]
        return rng.choice(edges) if rng.random() < 0.3 else f32(rng.uniform(-1e6, 1e6))
    edges = [0.0, -0.0, F64_MAX, -F64_MAX, 5e-324, 1.0, math.nan, math.inf, -math.inf]
    return rng.choice(edges) if rng.random() < 0.3 else rng.uniform(-1e12, 1e12)


def value(rng: random.Random, field, shape: str):
    """A field's value as pymavlink takes it; `shape` says how much of an array or text is filled."""
    n = field.array_length
    if field.type == "char" and not n:  # one char: pymavlink packs exactly one byte
        return bytes([0 if shape == "zero" else rng.randint(0x20, 0x7E)])
    if field.type == "char":
        size = {"full": n, "zero": 0}.get(shape, rng.randint(0, max(n - 1, 0)))
        return bytes(rng.randint(0x20, 0x7E) for _ in range(size))
    if not n:
        return 0 if shape == "zero" else scalar(rng, field.type)
    filled = {"full": n, "zero": 0}.get(shape, rng.randint(1, n))
    return [scalar(rng, field.type) for _ in range(filled)] + [0] * (n - filled)


def samples(imported, module, rounds: int, seed: int):
    """pymavlink messages of every message of the dialect with random values; in a third
    of the rounds as an older sender, its extension fields zero (pymavlink then leaves
    them off the wire)."""
    rng = random.Random(seed)
    out = []
    for round_ in range(rounds):
        for m in imported.messages:
            values = {}
            for f in (imported_field.xml for imported_field in m.fields):  # MAVLink 1: no extensions
                shape = rng.choice(["full", "part", "zero", "full"])
                if f.extension and round_ % 3 == 0:
                    shape = "zero"
                values[f.name] = value(rng, f, shape)
            out.append((m, module.mavlink_map[m.xml.id](**values)))
    return out


def same(mine, theirs, ctype: str) -> bool:
    if isinstance(mine, bytes):  # pymavlink gives a char array as text up to its first NUL
        theirs = theirs.encode() if isinstance(theirs, str) else theirs
        return mine.split(b"\0")[0] == theirs.split(b"\0")[0]
    if isinstance(mine, list):
        return len(mine) == len(theirs) and all(same(a, b, ctype) for a, b in zip(mine, theirs))
    if isinstance(mine, float) and mine != mine:
        return theirs != theirs
    if isinstance(mine, float):
        return mine == theirs and math.copysign(1, mine) == math.copysign(1, theirs)
    return mine == theirs


def import_and_build(tmp: Path, version: int, targets: str) -> Path:
    """`codeword import mavlink common.xml` and `codeword build`, as a user runs them."""
    run = subprocess.run([sys.executable, "-m", "codeword", "import", "mavlink", str(COMMON), "--out", str(tmp),
                          "--version", str(version)], capture_output=True, text=True, timeout=300, cwd=ROOT)
    assert run.returncode == 0 and "210 messages" in run.stdout if version == 2 else run.returncode == 0, \
        run.stdout + run.stderr
    run = subprocess.run([sys.executable, "-m", "codeword", "build", str(tmp / "common.yaml"), "--out",
                          str(tmp / "built"), "--targets", targets], capture_output=True, text=True, timeout=600,
                         cwd=ROOT)
    assert run.returncode == 0, run.stdout + run.stderr
    return tmp


@pytest.fixture(scope="module")
def v2(tmp_path_factory):
    return import_and_build(tmp_path_factory.mktemp("mavimport2"), 2, "python,c,docs,vectors")


@pytest.fixture(scope="module")
def v1(tmp_path_factory):
    return import_and_build(tmp_path_factory.mktemp("mavimport1"), 1, "python")


def test_the_fields_are_in_mavgens_wire_order_for_every_message_of_common():
    imported = import_dialect(COMMON)
    assert len(imported.messages) == len(mavlink2.mavlink_map) == 210
    for m in imported.messages:
        assert [f.xml.name for f in m.fields] == list(mavlink2.mavlink_map[m.xml.id].ordered_fieldnames), m.xml.name


def test_the_compiler_derives_mavgens_crc_extra_for_every_message(v2):
    """The schema declares no crc_extra (`extra: mavlink`): the compiler derives each."""
    assert "crc_extra:" not in (v2 / "common.yaml").read_text(encoding="utf-8")
    protocol = compile_schema(v2 / "common.yaml")
    by_id = {m.ids[0]: m for m in protocol.messages}
    assert len(by_id) == len(mavlink2.mavlink_map)
    imported = {m.xml.id: m for m in import_dialect(COMMON).messages}
    for msgid, theirs in mavlink2.mavlink_map.items():
        assert by_id[msgid].crc_extra == theirs.crc_extra, theirs.msgname
        assert [f.name for f in by_id[msgid].layout if f.is_member][5:5 + len(theirs.ordered_fieldnames)] == \
            [f.name for f in imported[msgid].fields]


def test_importing_twice_gives_the_same_schema(v2, tmp_path):
    again = import_dialect(COMMON).text
    assert again == (v2 / "common.yaml").read_text(encoding="utf-8")
    assert import_dialect(COMMON).text == again


def check_round_trip(mod, imported, module, seed: int) -> int:
    mav = module.MAVLink(None, srcSystem=42, srcComponent=190)
    parser = module.MAVLink(None)
    checked = 0
    for n, (m, message) in enumerate(samples(imported, module, rounds=3, seed=seed)):
        mav.seq = n & 0xFF
        frame = bytes(message.pack(mav))
        ours = mod.decode(frame)
        assert type(ours).NAME == m.name
        for f in m.fields:
            assert same(getattr(ours, f.name), getattr(message, f.xml.name), f.xml.type), (m.name, f.name)
        assert mod.encode(ours) == frame, m.name
        # a frame codeword builds from the values alone parses in pymavlink to them
        values = {f.name: getattr(ours, f.name) for f in m.fields}
        mine = type(ours)(**{k: getattr(ours, k) for k in ("seq", "sysid", "compid")}, **values,
                          **({"incompat_flags": mod.IncompatFlags(0), "compat_flags": 0}
                             if hasattr(ours, "compat_flags") else {}))
        parsed = parser.decode(bytearray(mod.encode(mine)))
        assert parsed.get_type() == m.xml.name
        for f in m.fields:
            assert same(values[f.name], getattr(parsed, f.xml.name), f.xml.type), (m.name, f.name)
        checked += 1
    return checked


def test_every_message_of_common_round_trips_with_pymavlink_in_mavlink2(v2):
    mod = load(v2 / "built" / "python" / "common.py")
    imported = import_dialect(COMMON)
    assert check_round_trip(mod, imported, mavlink2, seed=31) == 3 * 210


def test_every_message_of_common_round_trips_with_pymavlink_in_mavlink1(v1):
    mod = load(v1 / "built" / "python" / "common.py")
    imported = import_dialect(COMMON, version=1)
    assert len(imported.messages) == len(mavlink1.mavlink_map)
    assert check_round_trip(mod, imported, mavlink1, seed=32) == 3 * len(mavlink1.mavlink_map)


SIGNING_KEY = bytes(range(100, 132))  # a test key, as pymavlink takes it
SIGNING_START = 0x0123456789  # 10 us units since 2015: pymavlink's first timestamp


def test_every_message_of_common_signed_by_pymavlink_verifies_and_the_other_way(v2):
    """Signed frames both ways, every message of the imported common.xml: what pymavlink
    signs decodes with the key, keeps its link id, timestamp and signature, and encodes
    with the key to the same bytes; what codeword signs passes pymavlink's check, and a
    frame whose timestamp was changed after signing does not."""
    mod = load(v2 / "built" / "python" / "common.py")
    imported = import_dialect(COMMON)
    sender = mavlink2.MAVLink(None, srcSystem=42, srcComponent=190)
    sender.signing.secret_key, sender.signing.link_id = SIGNING_KEY, 7
    sender.signing.timestamp, sender.signing.sign_outgoing = SIGNING_START, True
    receiver = mavlink2.MAVLink(None)
    receiver.signing.secret_key = SIGNING_KEY
    mine = []
    for n, (m, message) in enumerate(samples(imported, mavlink2, rounds=1, seed=33)):
        frame = bytes(message.pack(sender))
        ours = mod.decode(frame, key=SIGNING_KEY)
        assert (ours.link_id, ours.timestamp, ours.signature) == (7, SIGNING_START + n, frame[-6:]), m.name
        assert mod.encode(ours, key=SIGNING_KEY) == frame, m.name
        ours.link_id, ours.timestamp, ours.signature = 3, SIGNING_START + 100 * n, None
        mine.append((m, mod.encode(ours, key=SIGNING_KEY)))
    assert len(mine) == 210
    for m, frame in mine:
        good = receiver.signing.goodsig_count
        parsed = receiver.parse_char(bytearray(frame))
        assert parsed is not None and parsed.get_type() == m.xml.name, m.name
        assert receiver.signing.goodsig_count == good + 1, m.name
    tampered = bytearray(mine[0][1])
    tampered[-7] ^= 0x01  # the timestamp's last byte, after the signature was made
    bad = receiver.signing.badsig_count
    try:
        receiver.parse_char(tampered)
    except mavlink2.MAVError:
        pass
    assert receiver.signing.badsig_count == bad + 1


def test_the_samples_truncate_and_leave_extensions_off():
    imported = import_dialect(COMMON)
    mav = mavlink2.MAVLink(None)
    frames = [(m, bytes(message.pack(mav))) for m, message in samples(imported, mavlink2, rounds=3, seed=31)]
    full = {m.name: sum(f.xml.size * max(f.xml.array_length, 1) for f in m.fields) for m in imported.messages}
    assert sum(f[1] < full[m.name] for m, f in frames) > 200  # truncated payloads
    with_ext = [m for m in imported.messages if any(f.xml.extension for f in m.fields)]
    assert len(with_ext) > 50
    base = {m.name: sum(f.xml.size * max(f.xml.array_length, 1) for f in m.fields if not f.xml.extension)
            for m in with_ext}
    assert sum(m.name in base and f[1] <= base[m.name] for m, f in frames) > 50  # no extension byte sent


def pymavlink_stream(frames: list[bytes], seed: int) -> bytes:
    """The frames back to back with garbage between them: random bytes, MAVLink 2's start
    byte among them, and frames cut short or with a bit flipped."""
    rng = random.Random(seed)
    parts = []
    for frame in frames:
        shape = rng.random()
        if shape < 0.2:
            parts.append(bytes(rng.choice([0xFD, rng.randrange(256)]) for _ in range(rng.randint(1, 6))))
        elif shape < 0.3:
            parts.append(frame[:rng.randint(1, len(frame) - 1)])
        elif shape < 0.4:
            damaged = bytearray(frame)
            damaged[rng.randrange(1, len(damaged))] ^= 1 << rng.randrange(8)
            parts.append(bytes(damaged))
        parts.append(frame)
    return b"".join(parts)


def found_by_pymavlink(stream: bytes) -> list[bytes]:
    """The MAVLink 2 frames of known messages pymavlink's parser finds in a stream, as it
    received them (it also passes on, unchecked, frames of ids it does not know, and
    takes MAVLink 1 frames)."""
    mav = mavlink2.MAVLink(None)
    mav.robust_parsing = True
    found = []
    for at in range(0, len(stream), 64):
        for message in mav.parse_buffer(stream[at:at + 64]) or []:
            frame = bytes(message.get_msgbuf())
            if message.get_type() != "BAD_DATA" and not message.get_type().startswith("UNKNOWN") \
                    and frame[:1] == b"\xfd":
                found.append(frame)
    return found


def found_by(mod, stream: bytes) -> list[bytes]:
    """The frames a codeword module's StreamDecoder finds in a stream, as it received them."""
    decoder = mod.StreamDecoder()
    found = []
    for at in range(0, len(stream), 64):
        for item in decoder.feed(stream[at:at + 64]):
            if not isinstance(item, mod.DecodeError):
                found.append(mod.encode(item))
    return found


def in_order(part: list[bytes], whole: list[bytes]) -> bool:
    """Whether `part` is `whole` with some items left out."""
    items = iter(whole)
    return all(any(x == y for y in items) for x in part)


def pymavlink_cases(mod, imported, seed: int) -> tuple[list[dict], list[bytes], bytes]:
    """Conformance cases of frames pymavlink packed (random values, extension fields left off,
    payloads truncated), one per message, whose values are pymavlink's (checked so through
    the Python module); the frames; and a stream of them with garbage between them."""
    from codeword.vectors import plain
    mav = mavlink2.MAVLink(None)
    cases, frames = [], []
    for m, message in samples(imported, mavlink2, rounds=1, seed=seed):
        frame = bytes(message.pack(mav))
        ours = mod.decode(frame)
        for f in m.fields:
            assert same(getattr(ours, f.name), getattr(message, f.xml.name), f.xml.type), (m.name, f.name)
        cases.append({"name": f"packed by pymavlink: {m.name}", "message": m.name, "hex": frame.hex(),
                      "values": plain(ours)})
        frames.append(frame)
    return cases, frames, pymavlink_stream(frames, seed)


def test_a_stream_with_garbage_yields_every_frame_pymavlink_finds(v2, tmp_path):
    """Frames of all of common.xml packed by pymavlink, with garbage, cut and damaged frames
    between them: the Python StreamDecoder, with and without the compiled accelerator,
    finds every frame pymavlink's parser finds (which loses the frames after a cut one whose
    length it believed) and no other; the C parser is held to the Python one's events in
    the strict C test below."""
    from fuzz.schema.accelerated import load as load_module
    from codeword import accelerate
    mod = load(v2 / "built" / "python" / "common.py")
    _, frames, stream = pymavlink_cases(mod, import_dialect(COMMON), seed=35)
    theirs, ours = found_by_pymavlink(stream), found_by(mod, stream)
    assert len(theirs) > 50 and in_order(theirs, frames)
    assert in_order(theirs, ours) and in_order(ours, frames) and len(ours) > len(theirs)
    if accelerate.compiler() is None or accelerate.python_headers() is None:
        if os.environ.get("CI"):
            pytest.fail("a C compiler and Python's headers are missing; scripts/install-toolchains installs them")
        return
    accelerate.accelerate([v2 / "common.yaml"], tmp_path)
    fast = load_module(v2 / "built" / "python" / "common.py", "_common_accelerated", tmp_path)
    assert fast.ACCELERATOR is not None and len(fast.ACCELERATOR.DECODES) == 210
    assert found_by(fast, stream) == ours


def test_the_whole_dialect_passes_its_vectors_in_strict_c(v2, tmp_path):
    """Compiles the conformance driver of all 210 messages with gcc under the strict flags
    (about a minute on a loaded machine) and runs it: the dialect's vectors, and frames
    pymavlink packed, decoded to pymavlink's values and in a stream with garbage."""
    from codeword.vectors import Generator
    vectors = json.loads((v2 / "built" / "vectors" / "common.json").read_text())
    mod = load(v2 / "built" / "python" / "common.py")
    cases, _, stream = pymavlink_cases(mod, import_dialect(COMMON), seed=36)
    vectors["valid"] += cases
    vectors["streams"].append(Generator(compile_schema(v2 / "common.yaml"), mod).stream_events("pymavlink's", stream))
    src, exe = tmp_path / "conf.c", tmp_path / "conf"
    src.write_text(Driver(compile_schema(v2 / "common.yaml")).source(vectors))
    build = subprocess.run(["gcc", "-std=c99", "-O1", "-Wall", "-Wextra", "-Wpedantic", "-Wconversion",
                            "-Wsign-conversion", "-Wshadow", "-Werror", "-I", str(v2 / "built" / "c"), str(src),
                            "-o", str(exe)], capture_output=True, text=True, timeout=900)
    assert build.returncode == 0, build.stderr[-3000:]
    run = subprocess.run([str(exe)], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0 and "CONFORMANCE common PASS" in run.stdout and " 0 failures" in run.stdout, \
        run.stdout[-3000:]


def test_the_schema_keeps_what_it_cannot_say_in_comments():
    text = import_dialect(COMMON).text
    assert "# values: MAVLink enum MAV_SYS_STATUS_SENSOR (codeword mav_sys_status_sensor)" in text  # flags: closed
    assert "enum: mav_type" in text and "type: u8\n    open: true" in text  # an enum: open
    assert "deprecated since" in text and "work in progress" in text
    assert "type: f32\n        finite: false" in text  # MAVLink sends NaN for "no value"
    assert "param 1" in text  # MAV_CMD's parameters in its entries' docs


@pytest.mark.parametrize("dialect", sorted(p.name for p in DIALECTS.glob("*.xml")))
def test_every_dialect_pymavlink_ships_imports_and_resolves(dialect, tmp_path):
    for version in (2, 1):
        if version == 1 and dialect in V2_ONLY:
            with pytest.raises(MavlinkXmlError, match="MAVLink 1 carries none of them"):
                import_dialect(DIALECTS / dialect, version=version)
            continue
        imported = import_dialect(DIALECTS / dialect, version=version)
        path = tmp_path / f"{imported.protocol}{version}.yaml"
        path.write_text(imported.text, encoding="utf-8")
        protocol = compile_schema(path)
        assert len(protocol.messages) == len(imported.messages)
        # each crc_extra the compiler derives is mavgen's, as pymavlink's module of the dialect has it
        theirs = importlib.import_module(f"pymavlink.dialects.v{'20' if version == 2 else '10'}.{Path(dialect).stem}")
        assert {m.ids[0]: m.crc_extra for m in protocol.messages} == \
            {i: c.crc_extra for i, c in theirs.mavlink_map.items() if i in {m.ids[0] for m in protocol.messages}}


# The whole set is the long run (CODEWORD_FUZZ_LONG=1, recorded in fuzz/RESULTS.md); by
# default, three small dialects, MAVLink 2 only test.xml among them.
LONG = os.environ.get("CODEWORD_FUZZ_LONG") == "1"
WHOLE = sorted(p.name for p in DIALECTS.glob("*.xml")) if LONG else ["minimal.xml", "standard.xml", "test.xml"]


@pytest.mark.parametrize("dialect", WHOLE)
def test_a_dialect_builds_for_every_target_and_agrees_with_pymavlink_on_every_message(dialect, tmp_path):
    """A dialect imported in MAVLink 2 and 1 and built for every target: random values of
    every message (edges, NaN, arrays partly zero, extensions left off) packed by pymavlink
    decode to them in codeword's Python and encode back to the same bytes, and its frames
    parse in pymavlink to them; and the C of the MAVLink 2 schema passes the conformance
    vectors under the strict warnings."""
    from codeword.build import build
    for version in (2, 1):
        if version == 1 and dialect in V2_ONLY:
            continue
        imported = import_dialect(DIALECTS / dialect, version=version)
        path = tmp_path / f"{imported.protocol}.yaml"
        path.write_text(imported.text, encoding="utf-8")
        out = tmp_path / f"v{version}"
        assert not build([path], out, root=tmp_path).errors
        mod = load(out / "python" / f"{imported.protocol}.py")
        theirs = importlib.import_module(f"pymavlink.dialects.v{'20' if version == 2 else '10'}.{Path(dialect).stem}")
        assert check_round_trip(mod, imported, theirs, seed=40 + version) == 3 * len(imported.messages)
        if version == 2:
            src, exe = tmp_path / "conf.c", tmp_path / "conf"
            vectors = json.loads((out / "vectors" / f"{imported.protocol}.json").read_text(encoding="utf-8"))
            src.write_text(Driver(compile_schema(path)).source(vectors), encoding="utf-8")
            made = subprocess.run(["gcc", "-std=c99", "-O1", "-Wall", "-Wextra", "-Wpedantic", "-Wconversion",
                                   "-Wsign-conversion", "-Wshadow", "-Werror", "-I", str(out / "c"), str(src),
                                   "-o", str(exe)], capture_output=True, text=True, timeout=1800)
            assert made.returncode == 0, made.stderr[-3000:]
            ran = subprocess.run([str(exe)], capture_output=True, text=True, timeout=600)
            assert ran.returncode == 0 and f"CONFORMANCE {imported.protocol} PASS" in ran.stdout, ran.stdout[-3000:]


def test_diff_of_two_versions_of_a_dialect_names_the_message_whose_wire_changed(tmp_path):
    """ATTITUDE's yawspeed made an int32_t: its CRC_EXTRA (mavgen's, from pymavlink) and the
    field's kind change, and nothing else; the same dialect imported twice shows no change."""
    from codeword.diff import BREAKING, compare
    for name in ("common.xml", "standard.xml", "minimal.xml"):
        (tmp_path / name).write_text((DIALECTS / name).read_text(encoding="utf-8"), encoding="utf-8")
    before = tmp_path / "before.yaml"
    before.write_text(import_dialect(tmp_path / "common.xml").text, encoding="utf-8")
    xml = (tmp_path / "common.xml").read_text(encoding="utf-8")
    start = xml.index('<message id="30" name="ATTITUDE">')
    end = xml.index("</message>", start)
    edited = xml[start:end].replace('<field type="float" name="yawspeed"', '<field type="int32_t" name="yawspeed"')
    assert edited != xml[start:end]
    (tmp_path / "common.xml").write_text(xml[:start] + edited + xml[end:], encoding="utf-8")
    after = tmp_path / "after.yaml"
    after.write_text(import_dialect(tmp_path / "common.xml").text, encoding="utf-8")
    old, new = compile_schema(before), compile_schema(after)
    assert compare(old, old).changes == []
    found = {(c.subject, c.what) for c in compare(old, new).of_kind(BREAKING)}
    from pymavlink.generator import mavparse  # mavgen's own reading of the edited XML
    edited_extra = next(m.crc_extra for m in mavparse.MAVXML(str(tmp_path / "common.xml"), "2.0").message
                        if m.name == "ATTITUDE")
    assert edited_extra != mavlink2.MAVLink_attitude_message.crc_extra
    assert found == {("message attitude", f"crc_extra changed from {mavlink2.MAVLink_attitude_message.crc_extra} "
                                          f"to {edited_extra}"),
                     ("field yawspeed", "kind changed from 'float' to 'int'")}
