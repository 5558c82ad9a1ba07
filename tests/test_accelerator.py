"""The compiled accelerator (`codeword accelerate`) decodes exactly as the pure-Python
module does: the same objects, value for value and type for type, and the same errors,
on every conformance vector of the five protocols and of the examples, on damaged
frames and through the stream decoder; built with gcc and clang under strict warnings.

Without a C compiler or Python's headers the test skips on a developer's machine and
fails in CI, where scripts/install-toolchains installs them."""
from __future__ import annotations

import importlib.util
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from codeword import accelerate as accel
from codeword.build import compile_schema
from codeword.targets.accelerator.scope import servable

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


def load(path: Path, key: str, folder: Path | None):
    """The generated module at `path`, with the accelerators in `folder` (None: pure Python)."""
    saved = os.environ.get("CODEWORD_PURE_PYTHON")
    if folder is None:
        os.environ["CODEWORD_PURE_PYTHON"] = "1"
    else:
        sys.path.insert(0, str(folder))
    try:
        spec = importlib.util.spec_from_file_location(key, path)
        module = importlib.util.module_from_spec(spec)
        sys.modules[key] = module
        spec.loader.exec_module(module)
    finally:
        if folder is None:
            os.environ.pop("CODEWORD_PURE_PYTHON") if saved is None else None
        else:
            sys.path.remove(str(folder))
    return module


def outcome(call, *args):
    """What a call gives, comparable across two copies of a module: the type and repr of
    the result (repr shows every value with its type: 1, 1.0 and True differ), or the
    error's type, text and attributes."""
    try:
        result = call(*args)
    except Exception as exc:  # noqa: BLE001 - the error is the outcome compared
        return "error", type(exc).__name__, str(exc), sorted((k, repr(v)) for k, v in vars(exc).items())
    return "value", type(result).__name__, repr(result)


def damaged(frame: bytes) -> list[bytes]:
    """The frame with one bit flipped in each byte, cut short by one, and one longer."""
    out = [frame[:i] + bytes([frame[i] ^ (1 << (i % 8))]) + frame[i + 1:] for i in range(len(frame))]
    return out + [frame[:-1], frame + b"\x00"]


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
    for name in served:
        assert type(getattr(fast, f"_decode_{name}")).__name__ == "builtin_function_or_method"
    vectors = json.loads((out / "vectors" / f"{p.name}.json").read_text(encoding="utf-8"))
    compared = 0
    for case in vectors["valid"] + vectors["invalid"]:
        frame = bytes.fromhex(case["hex"])
        direction = case.get("direction")
        frames = [frame] + (damaged(frame) if case in vectors["valid"] else [])
        for data in frames:
            for args in [(data,), (bytearray(data),), (memoryview(data),)] + ([(data, direction)] if direction else []):
                assert outcome(fast.decode, *args) == outcome(pure.decode, *args), (case["name"], data.hex())
                compared += 1
            if case.get("message") in fast.MESSAGES:
                cls_fast, cls_pure = fast.MESSAGES[case["message"]], pure.MESSAGES[case["message"]]
                assert outcome(cls_fast.decode, data) == outcome(cls_pure.decode, data), (case["name"], data.hex())
    for stream in vectors.get("streams", []):
        data = bytes.fromhex(stream["hex"])
        a, b = fast.StreamDecoder(), pure.StreamDecoder()
        for at in range(0, len(data), 7):  # in pieces, frames split across feeds
            chunk = data[at:at + 7]
            assert [outcome(lambda x=x: x) for x in a.feed(chunk)] == [outcome(lambda x=x: x) for x in b.feed(chunk)]
            assert (a.spans, a.skipped, a.offset) == (b.spans, b.skipped, b.offset)
        assert [repr(x) for x in a.finish()] == [repr(x) for x in b.finish()]
    assert compared > 0


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
