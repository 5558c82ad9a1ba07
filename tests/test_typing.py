"""The generated Python is typed: mypy --strict and pyright's strict mode accept every
generated module and a user's script that uses them correctly, and report the mistakes a
type checker should catch. Messages go to plain JSON data and back (to_dict, from_dict),
exactly, for every conformance vector's values."""
from __future__ import annotations

import ast
import importlib
import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import needs

ROOT = Path(__file__).resolve().parent.parent
FOLDERS = [ROOT / "generated" / "python", ROOT / "generated" / "examples" / "python"]
MODULES = sorted(path for folder in FOLDERS for path in folder.glob("*.py"))
VECTORS = {path.stem: path for folder in (ROOT / "generated" / "vectors", ROOT / "generated" / "examples" / "vectors")
           for path in folder.glob("*.json")}

GOOD_SCRIPT = '''
import json
from typing import Any, Union

import tr24
import tank
from tr24 import Command, Reply, decode

command = Command(seq=0, sender=1, receiver=3, data=bytes(7))
frame: bytes = command.encode()
same: Command = Command.decode(frame)
answer = Reply(seq=0, sender=3, receiver=1, data=bytes(7)).encode()
reply: Reply = decode(answer, "slave_to_master")  # a direction narrows what decode returns
either: Union[Command, Reply] = decode(frame)
plain = json.loads(json.dumps(same.to_dict()))
again: Command = Command.from_dict(plain)
values: dict[str, Any] = VALUES
line: str = tank.encode(tank.Telemetry.from_dict(values))  # a text protocol encodes to str
status: tank.SystemStatus = tank.Telemetry.decode(line).systemstatus  # fields typed with their enums
total: int = same.seq + len(frame) + len(tr24.StreamDecoder().feed(frame))
assert again == command and either == command and reply.sender == 3 and status is tank.SystemStatus.work
print("ok", total)
'''

# each mistake, with what mypy and pyright say about it
BAD_SCRIPTS = [
    ("import tr24\nprint(tr24.Command.decode(b'').sequence)\n",
     '"Command" has no attribute "sequence"', 'Cannot access attribute "sequence"'),
    ("import tr24\nn: int = tr24.encode(tr24.Command(seq=0, sender=1, receiver=3, data=bytes(7)))\n",
     'expression has type "bytes", variable has type "int"', 'Type "bytes" is not assignable to declared type "int"'),
    ("import tr24\nr: tr24.Reply = tr24.decode(b'', 'master_to_slave')\n",
     'expression has type "Command", variable has type "Reply"', 'Type "Command" is not assignable to declared type "Reply"'),
    ("import tank\ndef f(t: tank.Telemetry) -> int:\n    return t.encode() + 1\n",
     'Unsupported operand types for + ("str" and "int")', 'Operator "+" not supported for types "str"'),
]


@pytest.fixture(scope="module")
def cache(tmp_path_factory) -> Path:
    """One mypy cache for the module's runs: the standard library is analysed once."""
    return tmp_path_factory.mktemp("mypy-cache")


def _mypy(paths: list[Path], cwd: Path, cache: Path) -> subprocess.CompletedProcess[str]:
    try:
        import mypy  # noqa: F401 - only whether it is there
    except ImportError:
        needs("mypy", "pip install mypy (the test extra)")
    return subprocess.run([sys.executable, "-m", "mypy", "--strict", "--cache-dir", str(cache), *map(str, paths)],
                          cwd=cwd, capture_output=True, text=True,
                          env={"MYPYPATH": str(FOLDERS[0]), "PATH": "/usr/bin:/bin"})


def _pyright(paths: list[Path], cwd: Path) -> subprocess.CompletedProcess[str]:
    if shutil.which("pyright") is None:
        needs("pyright", "pip install pyright (the test extra)")
    config = cwd / "pyrightconfig.json"
    config.write_text(json.dumps({"typeCheckingMode": "strict", "extraPaths": [str(FOLDERS[0])]}), encoding="utf-8")
    return subprocess.run(["pyright", "-p", str(config), *map(str, paths)], cwd=cwd, capture_output=True, text=True)


def test_mypy_strict_accepts_every_generated_module(tmp_path, cache):
    proc = _mypy(MODULES, tmp_path, cache)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert f"no issues found in {len(MODULES)} source files" in proc.stdout


def test_pyright_strict_accepts_every_generated_module(tmp_path):
    proc = _pyright(MODULES, tmp_path)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "0 errors" in proc.stdout


def test_a_correct_typed_script_passes_both_checkers_and_runs(tmp_path, cache):
    script = tmp_path / "good.py"
    values = json.loads(VECTORS["tank"].read_text(encoding="utf-8"))["valid"][0]["values"]
    script.write_text(GOOD_SCRIPT.replace("VALUES", repr(values)), encoding="utf-8")
    mypy = _mypy([script], tmp_path, cache)
    assert mypy.returncode == 0, mypy.stdout + mypy.stderr
    pyright = _pyright([script], tmp_path)
    assert pyright.returncode == 0, pyright.stdout
    run = subprocess.run([sys.executable, str(script)], cwd=tmp_path, capture_output=True, text=True,
                         env={"PYTHONPATH": str(FOLDERS[0])})
    assert run.returncode == 0 and run.stdout.startswith("ok"), run.stderr


def test_a_typed_script_with_a_mistake_fails_both_checkers(tmp_path, cache):
    scripts = []
    for n, (source, _, _) in enumerate(BAD_SCRIPTS):
        scripts.append(tmp_path / f"bad{n}.py")
        scripts[-1].write_text(source, encoding="utf-8")
    mypy = _mypy(scripts, tmp_path, cache)
    pyright = _pyright(scripts, tmp_path)
    assert mypy.returncode == 1 and pyright.returncode == 1
    for script, (_, mypy_says, pyright_says) in zip(scripts, BAD_SCRIPTS):
        said = [line for line in mypy.stdout.splitlines() if line.startswith(script.name + ":")]
        assert any(mypy_says in line for line in said), mypy.stdout
        reported = [line for line in pyright.stdout.splitlines() if f"{script.name}:" in line]
        assert any(pyright_says in line for line in reported), pyright.stdout


def _module(name: str):
    folder = next(f for f in FOLDERS if (f / f"{name}.py").is_file())
    sys.path.insert(0, str(folder))
    try:
        return importlib.import_module(name)
    finally:
        sys.path.remove(str(folder))


@pytest.mark.parametrize("name", sorted(VECTORS))
def test_to_dict_and_from_dict_round_trip_every_vector_through_json(name):
    mod = _module(name)
    cases = json.loads(VECTORS[name].read_text(encoding="utf-8"))["valid"]
    for case in cases:
        cls = mod.MESSAGES[case["message"]]
        built = cls.from_dict(case["values"])
        assert built.to_dict() == case["values"], case["name"]
        text = json.dumps(built.to_dict())  # JSON-ready: no enum, flag or bytes object left
        assert cls.from_dict(json.loads(text)) == built, case["name"]
        assert mod.from_dict(case["message"], json.loads(text)) == built
        wire = case.get("text") or (bytes.fromhex(case["hex"]) if "hex" in case else None)
        if wire is not None:
            assert cls.decode(wire).to_dict() == case["values"], case["name"]


def test_to_dict_names_enum_members_and_flags():
    mtv4 = _module("mtv4")
    reply = next(c for c in json.loads(VECTORS["mtv4"].read_text(encoding="utf-8"))["valid"]
                 if any(isinstance(v, list) for v in c["values"].values()))
    plain = mtv4.from_dict(reply["message"], reply["values"]).to_dict()
    flags = [v for v in plain.values() if isinstance(v, list)]
    assert flags and all(isinstance(n, str) for f in flags for n in f)
    tank = _module("tank")
    values = json.loads(VECTORS["tank"].read_text(encoding="utf-8"))["valid"][0]["values"]
    telemetry = tank.Telemetry.from_dict(values)
    assert telemetry.systemstatus is tank.SystemStatus.work and telemetry.to_dict()["systemstatus"] == "work"


@pytest.mark.parametrize("change, field, rule", [
    ({"colour": 1}, "colour", "type"),  # an unknown key
    ({"seq": "0"}, "seq", "type"),  # a str for an int
    ({"seq": True}, "seq", "type"),  # a bool is not an int here
    ({"data": 7}, "data", "type"),  # bytes are hex text
    ({"data": "zz"}, "data", "type"),
    ({"seq": None}, "seq", "type"),  # not optional
])
def test_from_dict_refuses_unknown_keys_and_wrong_types(change, field, rule):
    tr24 = _module("tr24")
    values = {"seq": 0, "sender": 1, "receiver": 3, "data": "00" * 7}
    with pytest.raises(tr24.CodecError) as err:
        tr24.Command.from_dict(dict(values, **change))
    assert (err.value.field, err.value.rule) == (field, rule)
    with pytest.raises(tr24.DecodeError):
        tr24.from_dict("command", dict(values, **change))


def test_from_dict_refuses_a_wrong_enum_name_and_a_missing_field():
    tank = _module("tank")
    values = json.loads(VECTORS["tank"].read_text(encoding="utf-8"))["valid"][0]["values"]
    with pytest.raises(tank.DecodeError) as err:
        tank.Telemetry.from_dict(dict(values, systemstatus="flying"))
    assert err.value.field == "systemstatus"
    with pytest.raises(tank.DecodeError) as err:
        tank.Telemetry.from_dict({k: v for k, v in values.items() if k != "speed"} | {"speed": [1]})
    assert err.value.field == "speed"


def _classes(path: Path) -> list[ast.ClassDef]:
    return [node for node in ast.parse(path.read_text(encoding="utf-8")).body if isinstance(node, ast.ClassDef)]


@pytest.mark.parametrize("path", MODULES, ids=lambda p: p.stem)
def test_every_class_has_a_docstring_and_none_reads_None(path):
    for cls in _classes(path):
        doc = ast.get_docstring(cls)
        assert doc and doc != "None", f"{path.stem}.{cls.name}"


def test_field_docs_are_attribute_docstrings_editors_show():
    heartbeat = next(c for c in _classes(FOLDERS[1] / "mavlink1.py") if c.name == "Heartbeat")
    body = heartbeat.body
    at = next(i for i, node in enumerate(body) if isinstance(node, ast.AnnAssign) and node.target.id == "seq")
    doc = body[at + 1]
    assert isinstance(doc, ast.Expr) and doc.value.value == "packet sequence number, wraps at 255"


@pytest.mark.parametrize("path", MODULES, ids=lambda p: p.stem)
def test_crc_tables_are_constants_in_the_source(path):
    """No table is computed from its polynomial at import: the byte table is a literal, and
    the two-byte table is combined from two literal halves when a checksum first needs it."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    names = {node.name for node in tree.body if isinstance(node, ast.FunctionDef)}
    assert not {n for n in names if n.startswith(("_make", "_tables_"))}
    for node in tree.body:
        if isinstance(node, ast.AnnAssign) and node.target.id.startswith(("_TABLE_", "_HIGH16_", "_LOW16_")):
            assert isinstance(node.value, ast.Tuple) and len(node.value.elts) == 256
            assert all(isinstance(x, ast.Constant) for x in node.value.elts)


# Features no committed schema uses, each where a type checker once disagreed with the
# generated code: a conditional group (its presence check narrowed the group to
# `Group | None` for good), an open enum (`Union[Enum, int]`).
FEATURES = """codeword: 1
protocol: typedfeatures
title: t
source: s
flags:
  parts: {type: u8, bits: [{name: gps, bit: 1}]}
enums:
  mode: {type: u8, open: true, values: [{name: idle, value: 0}]}
framing:
  kind: bytes
  layout:
    - {name: kind, type: u8, dispatch: true}
    - {name: len, type: u8, length_of: {from: payload, to: payload}}
    - {payload: true}
messages:
  fix:
    id: 1
    fields:
      - {name: have, type: u8, flags: parts}
      - {name: mode, type: u8, enum: mode}
      - name: pos
        type: group
        present_if: {field: have, has: gps}
        fields:
          - {name: lat, type: u16, scale: 0.25}
          - {name: lon, type: i16}
"""


def test_modules_of_conditional_groups_and_open_enums_type_check(tmp_path, cache):
    from schema_in_a_test import render
    render(tmp_path, "typedfeatures", FEATURES)
    module = tmp_path / "typedfeatures.py"
    mypy = _mypy([module], tmp_path, cache)
    assert mypy.returncode == 0, mypy.stdout + mypy.stderr
    pyright = _pyright([module], tmp_path)
    assert pyright.returncode == 0, pyright.stdout
