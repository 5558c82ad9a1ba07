"""The compiled accelerator (`codeword accelerate`) decodes exactly as the pure-Python
module does: the same objects, value for value and type for type, and the same errors,
on every conformance vector of the five protocols and of the examples, on damaged
frames and through the stream decoder; built with gcc and clang under strict warnings.

Without a C compiler or Python's headers the test skips on a developer's machine and
fails in CI, where scripts/install-toolchains installs them."""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import test_conditional_fields as conditional
import test_counted_bytes as counted
import test_rest_of_payload as rest

from codeword import accelerate as accel
from codeword.build import compile_schema
from codeword.targets.accelerator.encode import encodable
from codeword.targets.accelerator.scope import servable
from fuzz.schema.accelerated import buffer_difference, damaged, difference, load, stream_state_difference

ROOT = Path(__file__).resolve().parent.parent
SETS = {"schemas": (ROOT / "schemas", ROOT / "generated"),
        "examples": (ROOT / "examples", ROOT / "generated" / "examples")}
STRICT = ("-Wall", "-Wextra", "-Werror", "-Wstrict-prototypes")


def needs(what: str) -> None:
    if os.environ.get("CI"):
        pytest.fail(f"{what} is missing; scripts/install-toolchains installs it")
    pytest.skip(f"{what} is not installed")


def schemas() -> list[tuple[str, Path]]:
    return [(name, path) for name, (folder, _) in SETS.items() for path in sorted(folder.glob("*.yaml"))]


@pytest.fixture(scope="module", params=["gcc", "clang"])
def built(request, tmp_path_factory):
    """Every accelerator, built by one compiler into a folder of its own."""
    if shutil.which(request.param) is None:
        needs(request.param)
    if accel.python_headers() is None:
        needs("Python's headers (Python.h)")
    folder = tmp_path_factory.mktemp(f"accel-{request.param}")
    old = os.environ.get("CC")
    os.environ["CC"] = request.param
    try:
        outcome = accel.accelerate([path for _, path in schemas()], folder, STRICT)
    finally:
        os.environ.pop("CC") if old is None else os.environ.__setitem__("CC", old)
    return folder, outcome


@pytest.mark.parametrize("group,schema", schemas(), ids=[path.stem for _, path in schemas()])
def test_accelerated_decoding_is_pure_pythons(built, group, schema):
    folder, result = built
    p = compile_schema(schema)
    out = SETS[group][1]
    module_path = out / "python" / f"{p.name}.py"
    served = [m.name for m in p.messages if servable(p, m)]
    fast = load(module_path, f"_accel_fast_{folder.name}_{p.name}", folder)
    pure = load(module_path, f"_accel_pure_{folder.name}_{p.name}", None)
    assert pure.ACCELERATOR is None if served else not hasattr(pure, "ACCELERATOR")
    if not served:
        assert not hasattr(fast, "ACCELERATOR")
        return
    assert fast.ACCELERATOR is not None, f"{p.name}: the accelerator built in {folder} was not used"
    encoded = {m.name for m in p.messages if encodable(p, m)}
    assert fast.ACCELERATOR.DECODES == set(served) and fast.ACCELERATOR.ENCODES == encoded
    for name in served:
        assert type(getattr(fast, f"_decode_{name}")).__name__ == "builtin_function_or_method"
    for name in encoded:
        assert type(getattr(fast, f"_encode_{name}")).__name__ == "builtin_function_or_method"
    vectors = json.loads((out / "vectors" / f"{p.name}.json").read_text(encoding="utf-8"))
    valid = [bytes.fromhex(case["hex"]) for case in vectors["valid"]]
    # the vectors' frames back to back, with garbage, a damaged frame and a cut one between them
    noisy = b"".join(frame + b"\x00\xff" + damaged(frame)[1] + frame[:-1] for frame in valid[:40])
    problem, compared = difference(fast, pure, vectors, [b"".join(valid), noisy])
    assert not problem, problem
    assert compared > len(valid)


def test_a_stale_accelerator_is_left_alone(built, tmp_path):
    """A module finds an accelerator built from another version of its schema by its
    tag, and decodes in Python."""
    folder, _ = built
    source = (ROOT / "generated" / "python" / "mtv4.py").read_text(encoding="utf-8")
    tag = compile_schema(ROOT / "schemas" / "mtv4.yaml")
    from codeword.targets.accelerator.scope import source_tag
    assert f"== '{source_tag(tag)}'" in source
    (tmp_path / "mtv4.py").write_text(source.replace(source_tag(tag), "0" * 16), encoding="utf-8")
    stale = load(tmp_path / "mtv4.py", f"_accel_stale_{folder.name}", folder)
    assert stale.ACCELERATOR is None
    assert type(stale._decode_ack).__name__ == "function"


def test_the_command_builds_once_and_build_check_ignores_it(tmp_path):
    if shutil.which("cc") is None and shutil.which("gcc") is None or accel.python_headers() is None:
        needs("a C compiler and Python's headers")
    shutil.copytree(ROOT / "schemas", tmp_path / "schemas", ignore=shutil.ignore_patterns("tank.yaml", "car.yaml", "route.yaml"))

    def codeword(*args):
        return subprocess.run([sys.executable, "-m", "codeword", *args], cwd=tmp_path, capture_output=True, text=True)
    assert codeword("build").returncode == 0
    first = codeword("accelerate")
    assert first.returncode == 0, first.stderr
    assert "2 built, 0 unchanged" in first.stdout
    module = tmp_path / "generated" / "python" / f"_mtv4_accel{accel.extension_suffix()}"
    assert module.is_file()
    again = codeword("accelerate")
    assert "0 built, 2 unchanged" in again.stdout
    check = codeword("build", "--check")
    assert check.returncode == 0, check.stdout + check.stderr
    run = subprocess.run([sys.executable, "-c", "import mtv4; print(mtv4.ACCELERATOR is not None)"],
                         cwd=tmp_path / "generated" / "python", capture_output=True, text=True)
    assert run.stdout.strip() == "True", run.stderr


def test_without_a_compiler_nothing_is_built(tmp_path, monkeypatch):
    monkeypatch.setattr(accel, "compiler", lambda: None)
    result = accel.accelerate([ROOT / "schemas" / "mtv4.yaml"], tmp_path)
    assert result.built == [] and not list(tmp_path.iterdir())
    assert "no accelerators built: a C compiler" in result.notes[0]


def test_two_copies_of_a_module_each_build_their_own_objects(built):
    """Each copy of a module binds the accelerator for itself: a decoder of one copy
    never builds the classes of another."""
    folder, _ = built
    path = ROOT / "generated" / "python" / "mtv4.py"
    one = load(path, f"_accel_one_{folder.name}", folder)
    two = load(path, f"_accel_two_{folder.name}", folder)
    assert one.ACCELERATOR is not None and two.ACCELERATOR is not None
    vectors = json.loads((ROOT / "generated" / "vectors" / "mtv4.json").read_text(encoding="utf-8"))
    for case in vectors["valid"]:
        frame = bytes.fromhex(case["hex"])
        assert type(one.decode(frame, case["direction"])) is one.MESSAGES[case["message"]]
        assert type(two.decode(frame, case["direction"])) is two.MESSAGES[case["message"]]
        assert type(one.StreamDecoder(case["direction"]).feed(frame)[0]) is one.MESSAGES[case["message"]]


@pytest.mark.parametrize("group,schema", schemas(), ids=[path.stem for _, path in schemas()])
def test_input_of_any_type_decodes_as_in_pure_python(built, group, schema):
    """bytes, bytearray, memoryviews of every shape and format (strided, 2-D, 'b', 'c',
    'H', released), arrays, mmap, subclasses, str, numbers and None: the accelerated
    module returns the message or raises the error pure Python does, and its
    StreamDecoder agrees from any offset (huge, negative, not an int) and direction."""
    folder, _ = built
    p = compile_schema(schema)
    if not any(servable(p, m) for m in p.messages):
        return
    out = SETS[group][1]
    module_path = out / "python" / f"{p.name}.py"
    fast = load(module_path, f"_accel_types_{folder.name}_{p.name}", folder)
    pure = load(module_path, f"_accel_types_pure_{folder.name}_{p.name}", None)
    assert fast.ACCELERATOR is not None
    vectors = json.loads((out / "vectors" / f"{p.name}.json").read_text(encoding="utf-8"))
    firsts = {case["message"]: bytes.fromhex(case["hex"]) for case in reversed(vectors["valid"])}
    for message, frame in firsts.items():
        for data in (frame, frame[:-1], b""):
            problem = buffer_difference(fast, pure, data, message)
            assert not problem, problem
    if hasattr(pure, "StreamDecoder"):
        directions = sorted({case["direction"] for case in vectors["valid"] if case.get("direction")})
        problem = stream_state_difference(fast, pure, b"".join(firsts.values()), directions)
        assert not problem, problem


HOSTILE_CALLS = r"""
import json, sys
from pathlib import Path
from fuzz.schema.accelerated import load

fast = load(Path(sys.argv[1]), "_hostile_mtv4", Path(sys.argv[2]))
bind = fast.ACCELERATOR.bind
frame = bytes.fromhex(sys.argv[3])
mine = dict(vars(fast))
run_frames = bind(mine)["_run_frames"]


class Other:
    __slots__ = ("x",)


def foreign_members(cls):
    # a class holding another class's member descriptors, whose offsets are not its own
    return type("Foreign", (), {name: getattr(cls, name) for name in cls.__slots__})


def attempt(label, call):
    print(label, end=": ", flush=True)
    try:
        result = call()
    except Exception as exc:
        print(type(exc).__name__, flush=True)
        return
    print("returned", type(result).__name__, flush=True)


def bound_with(**changes):
    table = bind({**mine, **changes})  # refused here, or the decoders below are used
    for name, fn in table.items():
        if name.startswith("_decode_"):
            fn(frame)
    return table


cls = type(fast.decode(frame, "host_to_robot")).__name__
flags = sorted(name for name in mine if name.startswith("_FLAGS_"))[0]
for label, value in [("an int", 5), ("dict", dict), ("int", int), ("a class with another's slots",
                     foreign_members(mine[cls])), ("a class of another layout", Other),
                     ("the capsule", run_frames.__self__), ("None", None)]:
    attempt(f"bind: {cls} is {label}", lambda: bound_with(**{cls: value}))
attempt("bind: flags table is a list", lambda: bound_with(**{flags: [1, 2]}))
attempt("bind: a str", lambda: bind("globals"))
attempt("bind: no globals", lambda: bind({}))
out, spans = [], []
for args in [(), (frame,) * 6, (frame, 0, None, out, spans, 2 ** 70), (frame, 2 ** 70, None, out, spans, 0),
             (frame, -2 ** 70, None, out, spans, 0), (frame, 0, None, out, spans, sys.maxsize),
             (frame, 0, None, out, spans, "x"), (frame, 0, None, out, spans, None), (frame, 0, 5, out, spans, 0),
             (frame, 0, None, (), spans, 0), (bytearray(frame), 0, None, out, spans, 0)]:
    attempt(f"_run_frames{tuple(type(a).__name__ for a in args)}", lambda: run_frames(*args))
message = fast.decode(frame, "host_to_robot")
unset = object.__new__(type(message))  # its slots never set
Sub = type("Sub", (type(message),), {"__slots__": ()})
sub = object.__new__(Sub)
for field in type(message)._NAMES:
    setattr(sub, field, getattr(message, field))
for name, fn in sorted(bind(mine).items()):
    if name.startswith("_decode_"):
        attempt(f"{name}(None)", lambda: fn(None))
    if name.startswith("_encode_"):
        for label, value in [("None", None), ("an int", 5), ("another class", Other()), ("unset slots", unset),
                             ("a subclass", sub), ("the class", type(message))]:
            attempt(f"{name}({label})", lambda: fn(value))
# a message class bound in another's place: the encoder reads only objects of the class it is given
other_cls = next(n for n, c in mine.items() if isinstance(c, type) and hasattr(c, "NAME") and n != cls and
                 getattr(c, "_NAMES", ()))
swapped = bind({**mine, cls: mine[other_cls]})
for name, fn in sorted(swapped.items()):
    if name.startswith("_encode_"):
        attempt(f"swapped {name}", lambda: fn(message))
print("done", flush=True)
"""


def test_no_entry_point_crashes_the_interpreter(built, tmp_path):
    """bind() given anything but the module's own globals (a class replaced by an int,
    a built-in type, the capsule, a class with another's slot descriptors, another
    message's class), and the bound stream loop, decoders and encoders given hostile
    arguments (an object of another class or of a subclass, one whose slots were never
    set): each returns or raises, and bind() refuses every class that is not one whose
    instances it may fill."""
    folder, _ = built
    frame = bytes.fromhex(json.loads((ROOT / "generated" / "vectors" / "mtv4.json").read_text())["valid"][0]["hex"])
    run = subprocess.run([sys.executable, "-c", HOSTILE_CALLS, str(ROOT / "generated" / "python" / "mtv4.py"),
                          str(folder), frame.hex()], cwd=ROOT, capture_output=True, text=True, timeout=120)
    lines = run.stdout.splitlines()
    assert run.returncode == 0 and lines[-1:] == ["done"], \
        f"the interpreter died (status {run.returncode}) at {lines[-1:]}: {run.stderr[-2000:]}"
    bound = [line for line in lines if line.startswith("bind: ")]
    assert len(bound) == 10 and not any("returned" in line for line in bound), bound
    # what acc_new cannot make safely, or whose slots are not its own, is refused by bind()
    unsafe = ("an int", "dict", "int", "a class with another's slots", "the capsule", "None")
    assert {line for line in bound if line.endswith("TypeError")} >= {f"bind: {cls} is {x}: TypeError" for x in unsafe
                                                                       for cls in [bound[0].split()[1]]}, bound


def test_an_accelerator_elsewhere_on_sys_path_is_not_loaded(tmp_path):
    """A module loads `_<name>_accel` only from its own folder: one found first on
    sys.path (here a Python module with the right tag and a bind() that would replace
    every decoder) is never imported."""
    from codeword.targets.accelerator.scope import source_tag
    tag = source_tag(compile_schema(ROOT / "schemas" / "mtv4.yaml"))
    elsewhere, beside = tmp_path / "elsewhere", tmp_path / "module"
    elsewhere.mkdir()
    beside.mkdir()
    (elsewhere / "_mtv4_accel.py").write_text(
        f"SOURCE = {tag!r}\nimport builtins\nbuiltins.planted = True\n"
        "def bind(g):\n    return {'decode': lambda *a: 'planted'}\n", encoding="utf-8")
    shutil.copyfile(ROOT / "generated" / "python" / "mtv4.py", beside / "mtv4.py")
    script = ("import builtins, mtv4; print(mtv4.ACCELERATOR, getattr(builtins, 'planted', False), "
              "mtv4.decode(b'') if False else '')")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(elsewhere), str(beside)])}
    env.pop("CODEWORD_PURE_PYTHON", None)
    run = subprocess.run([sys.executable, "-c", script], cwd=tmp_path, env=env, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert run.stdout.split()[:2] == ["None", "False"], run.stdout


def test_text_lines_that_may_end_early_are_left_to_python(built):
    """The accelerator serves no text framing: NMEA's RMC and VTG, whose lines end before their
    extension fields or after them, are decoded by the Python module, with or without an
    accelerator folder on its path, and read the 2.0 and the 2.3 sentence alike."""
    folder, _ = built
    schema = ROOT / "examples" / "nmea0183.yaml"
    p = compile_schema(schema)
    assert p.message("rmc").text_places.varies and not any(servable(p, m) for m in p.messages)
    module_path = ROOT / "generated" / "examples" / "python" / "nmea0183.py"
    fast = load(module_path, f"_accel_text_{folder.name}", folder)
    pure = load(module_path, f"_accel_text_pure_{folder.name}", None)
    assert not hasattr(fast, "ACCELERATOR")
    for line in ("$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A\r\n",
                 "$GPRMC,083559.00,A,4717.11437,N,00833.91522,E,0.004,77.52,091202,,,A*57\r\n"):
        assert fast.decode(line).to_dict() == pure.decode(line).to_dict() and fast.encode(fast.decode(line)) == line


SCHEMAS_WITH_GAPS = {"tele": conditional.SCHEMA, "blob": counted.SCHEMA, "rest": rest.SCHEMA}


def worked_frames(name: str, mod) -> list[tuple[bytes, object]]:
    """[(frame, the message it holds)]: frames worked by hand in the tests of conditional
    fields, counted bytes and arrays that fill the rest of the payload."""
    if name == "tele":
        return [(conditional.frame(payload), message) for payload, message in conditional.messages(mod)]
    if name == "blob":
        return [(bytes.fromhex(frame), mod.Chunk(tag=9, data=data)) for data, frame in counted.FRAMES]
    return [(bytes.fromhex("55 01 06 0102 0a0b 0c0d aa"), mod.Registers(start=0x0102, values=[0x0A0B, 0x0C0D])),
            (bytes.fromhex("55 02 01 09 aa"), mod.Blob(tag=9, data=b"")),
            (bytes.fromhex("55 03 02 64 ff aa"), mod.Pairs(pts=[mod.PairsPts(a=100, b=-1)]))]


@pytest.mark.parametrize("name", sorted(SCHEMAS_WITH_GAPS))
def test_values_a_frame_may_leave_out_are_built_in_c(built, tmp_path, name):
    """Conditional fields (None when absent), counted arrays of groups, counted bytes and
    arrays that fill the rest of the payload: the compiled decoder builds each message
    of the hand-worked frames, and agrees with pure Python on every vector."""
    folder, _ = built
    schema = tmp_path / f"{name}.yaml"
    schema.write_text(SCHEMAS_WITH_GAPS[name], encoding="utf-8")
    out = tmp_path / "out"
    run = subprocess.run([sys.executable, "-m", "codeword", "build", str(schema), "--out", str(out)],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stdout + run.stderr
    p = compile_schema(schema)
    assert all(servable(p, m) for m in p.messages)
    accel.accelerate([schema], tmp_path, STRICT)
    fast = load(out / "python" / f"{name}.py", f"{name}_fast_{folder.name}", tmp_path)
    pure = load(out / "python" / f"{name}.py", f"{name}_pure_{folder.name}", None)
    assert fast.ACCELERATOR is not None
    for frame, message in worked_frames(name, fast):
        decoder = fast.MESSAGES[message.NAME].decode
        assert type(decoder).__name__ == "builtin_function_or_method"
        assert decoder(frame) == message and fast.decode(frame) == message
        assert repr(fast.decode(frame)) == repr(pure.decode(frame))
    vectors = json.loads((out / "vectors" / f"{name}.json").read_text(encoding="utf-8"))
    problem, compared = difference(fast, pure, vectors)
    assert not problem, problem
    assert compared > len(vectors["valid"])
