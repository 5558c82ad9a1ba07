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

from codeword import accelerate as accel
from codeword.build import compile_schema
from codeword.targets.accelerator.scope import servable
from fuzz.schema.accelerated import damaged, difference, load

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
    for name in served:
        assert type(getattr(fast, f"_decode_{name}")).__name__ == "builtin_function_or_method"
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
