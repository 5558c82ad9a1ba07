"""The command line as a user's project meets it: configuration, starter, exit
status, options, and builds of some schemas among several."""
from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from codeword import cli
from codeword.project import ProjectError, load_project

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

ROOT = Path(__file__).resolve().parent.parent
SCHEMAS = ROOT / "schemas"
STRICT = ["-std=c99", "-Wall", "-Wextra", "-Wpedantic", "-Wconversion", "-Wsign-conversion", "-Wshadow",
          "-Werror"]


def codeword(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, [os.environ.get("PYTHONPATH"), str(ROOT)])))
    return subprocess.run([sys.executable, "-m", "codeword", *args], cwd=cwd, env=env, capture_output=True,
                          text=True, timeout=300)


def test_version_is_the_package_version():
    version = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]["version"]
    proc = codeword("--version", cwd=ROOT)
    assert proc.returncode == 0 and proc.stdout.strip() == f"codeword {version}"


def test_global_options_work_after_the_command():
    proc = codeword("lint", "schemas/car.yaml", "--debug", cwd=ROOT)
    assert proc.returncode == 0, proc.stderr
    assert codeword("--debug", "lint", "schemas/car.yaml", cwd=ROOT).returncode == 0


def test_every_option_has_help():
    top = cli.parser()
    parsers = [top]
    for action in top._actions:
        if isinstance(action, argparse._SubParsersAction):
            parsers.extend(action.choices.values())
    assert len(parsers) >= 7
    for parser in parsers:
        for action in parser._actions:
            if action.option_strings or parser is not top:
                assert action.help, f"{parser.prog}: {action.option_strings or action.dest} has no help"


def test_an_internal_error_exits_3_with_one_line(monkeypatch, capsys):
    def broken(args):
        raise KeyError("boom")

    monkeypatch.setattr(cli, "cmd_lint", broken)
    assert cli.main(["lint"]) == 3
    err = capsys.readouterr().err
    assert "internal error: KeyError" in err and "Traceback" not in err and len(err.splitlines()) == 1


def test_nothing_to_build_is_an_error_naming_the_folder(tmp_path):
    for command in ("build", "lint"):
        proc = codeword(command, cwd=tmp_path)
        assert proc.returncode == 2
        assert "no schemas in schemas/" in proc.stderr and "codeword init" in proc.stderr


def test_an_unknown_schema_name_is_a_usage_error():
    proc = codeword("build", "--check", "nosuch", cwd=ROOT)
    assert proc.returncode == 2 and "no schema 'nosuch'" in proc.stderr


def test_a_schema_with_errors_stops_build_with_status_2_and_lint_with_1(tmp_path):
    shutil.copy(ROOT / "tests" / "broken" / "car_33_bits.yaml", tmp_path / "bad.yaml")
    assert codeword("build", "bad.yaml", cwd=tmp_path).returncode == 2
    assert codeword("lint", "bad.yaml", cwd=tmp_path).returncode == 1


def test_a_protocol_is_named_by_its_name(tmp_path):
    capture = tmp_path / "capture.hex"
    capture.write_text("aa 08 03 01 20 00 24 03 60 ff 40 00\n")  # README.md's mtv4 frame
    proc = codeword("check", "mtv4", str(capture), cwd=ROOT)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert codeword("build", "--check", "mtv4", "car", cwd=ROOT).returncode == 0


def test_check_mode_names_the_output_folder_it_compared(tmp_path):
    out = tmp_path / "elsewhere"
    proc = codeword("build", "--check", "--out", str(out), "car", cwd=ROOT)
    assert proc.returncode == 1
    assert f"{out}/c/" in proc.stderr and "generated/" not in proc.stderr


def test_building_schemas_one_at_a_time_keeps_the_index_and_the_others(tmp_path):
    (tmp_path / "schemas").mkdir()
    for name in ("car", "tank"):
        shutil.copy(SCHEMAS / f"{name}.yaml", tmp_path / "schemas")
    assert codeword("build", "car", cwd=tmp_path).returncode == 0
    assert codeword("build", "tank", cwd=tmp_path).returncode == 0
    index = (tmp_path / "generated" / "docs" / "index.md").read_text(encoding="utf-8")
    assert "[car](car.md)" in index and "[tank](tank.md)" in index
    proc = codeword("build", "--check", cwd=tmp_path)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    proc = codeword("build", "--check", "car", cwd=tmp_path)
    assert proc.returncode == 0, proc.stdout + proc.stderr


def test_targets_option_writes_only_those_targets(tmp_path):
    (tmp_path / "schemas").mkdir()
    shutil.copy(SCHEMAS / "car.yaml", tmp_path / "schemas")
    proc = codeword("build", "--targets", "c,python", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert sorted(p.name for p in (tmp_path / "generated").iterdir()) == ["c", "python"]
    proc = codeword("build", "--targets", "c,rust", cwd=tmp_path)
    assert proc.returncode == 2 and "unknown target 'rust'" in proc.stderr


def test_configuration_places_each_target_and_the_python_package(tmp_path):
    (tmp_path / "proto").mkdir()
    shutil.copy(SCHEMAS / "car.yaml", tmp_path / "proto")
    (tmp_path / "codeword.toml").write_text(
        'schemas = ["proto"]\ntargets = ["python", "c"]\nout = "gen"\n'
        '[outputs]\nc = "firmware/include"\n[python]\npackage = "robotlink"\n', encoding="utf-8")
    sub = tmp_path / "sub"
    sub.mkdir()  # the configuration is found from a folder below it
    proc = codeword("build", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "firmware" / "include" / "car.h").is_file()
    assert (tmp_path / "firmware" / "include" / "codeword.h").is_file()
    package = tmp_path / "gen" / "python" / "robotlink"
    assert sorted(p.name for p in package.iterdir()) == ["__init__.py", "_car_accel.c", "car.py", "py.typed"]
    check = subprocess.run([sys.executable, "-c", "import robotlink.car as c; print(c.__name__)"],
                           cwd=tmp_path / "gen" / "python", capture_output=True, text=True)
    assert check.stdout.strip() == "robotlink.car", check.stderr
    assert not (tmp_path / "gen" / "docs").exists()
    assert codeword("build", "--check", cwd=sub).returncode == 0


@pytest.mark.parametrize("text, says", [
    ('targets = ["python", "java"]\n', "unknown target 'java'"),
    ('colour = "blue"\n', "unknown key 'colour'"),
    ('schemas = 5\n', "schemas must be a list"),
    ('[python]\npackage = "class"\n', "python.package"),
    ('schemas = [\n', "codeword.toml"),
])
def test_a_bad_configuration_is_a_usage_error_naming_the_file(tmp_path, text, says):
    (tmp_path / "codeword.toml").write_text(text, encoding="utf-8")
    with pytest.raises(ProjectError, match=says.replace("(", r"\(")):
        load_project(tmp_path)
    proc = codeword("build", cwd=tmp_path)
    assert proc.returncode == 2 and "codeword.toml" in proc.stderr and "Traceback" not in proc.stderr


def test_pyproject_tool_table_configures_a_project(tmp_path):
    (tmp_path / "pyproject.toml").write_text('[project]\nname = "robot"\n', encoding="utf-8")
    proc = codeword("init", "rover", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert not (tmp_path / "codeword.toml").exists()
    table = tomllib.loads((tmp_path / "pyproject.toml").read_text())["tool"]["codeword"]
    assert table["schemas"] == ["schemas"]
    assert codeword("build", cwd=tmp_path).returncode == 0
    assert (tmp_path / "generated" / "python" / "rover.py").is_file()


def test_init_writes_a_starter_that_builds_compiles_and_decodes(tmp_path):
    project = tmp_path / "Line Follower"
    project.mkdir()
    proc = codeword("init", cwd=project)
    assert proc.returncode == 0, proc.stderr
    name = "line_follower"  # from the folder's name
    schema = project / "schemas" / f"{name}.yaml"
    first_line = schema.read_text(encoding="utf-8").splitlines()[0]
    assert first_line == "# yaml-language-server: $schema=../.codeword/codeword.schema.json"
    editor = json.loads((project / ".codeword" / "codeword.schema.json").read_text(encoding="utf-8"))
    assert editor == json.loads((ROOT / "compiler" / "schema" / "codeword.schema.json").read_text())
    settings = json.loads((project / ".vscode" / "settings.json").read_text(encoding="utf-8"))
    assert settings["yaml.schemas"] == {".codeword/codeword.schema.json": "schemas/*.yaml"}
    assert codeword("init", cwd=project).returncode == 2  # never overwrites
    proc = codeword("build", cwd=project)
    assert proc.returncode == 0, proc.stderr
    out = project / "generated"
    assert (out / "docs" / f"{name}.md").is_file() and (out / "docs" / "index.md").is_file()
    # the starter's hand-calculated frame: CRC-16/XMODEM of 05 01 64 00 9c ff is 0x3905
    frame = "a5 05 01 64 00 9c ff 39 05"
    script = (f"import {name} as m\nf = m.encode(m.Drive(left=100, right=-100))\n"
              f"assert f == bytes.fromhex('{frame}'), f.hex(' ')\nprint(m.decode(f))\n")
    proc = subprocess.run([sys.executable, "-c", script], cwd=out / "python", capture_output=True, text=True)
    assert proc.stdout.strip() == "Drive(left=100, right=-100)", proc.stderr
    driver = out / "c" / "main.c"
    driver.write_text(f"""#include <stdio.h>
#include "{name}.h"
int main(void) {{
    {name}_drive_t d = {{0}};
    uint8_t buf[{name.upper()}_MAX_FRAME];
    int n;
    d.left = 100; d.right = -100;
    n = {name}_drive_encode(&d, buf, sizeof buf);
    for (int i = 0; i < n; i++) printf("%02x ", buf[i]);
    printf("\\n");
    return 0;
}}
""", encoding="utf-8")
    for compiler in ("gcc", "clang"):
        exe = out / "c" / f"main-{compiler}"
        built = subprocess.run([compiler, *STRICT, "-I", str(out / "c"), str(driver), "-o", str(exe)],
                               capture_output=True, text=True)
        assert built.returncode == 0, built.stderr
        ran = subprocess.run([str(exe)], capture_output=True, text=True)
        assert ran.stdout.strip() == frame


def test_schema_command_prints_and_writes_the_json_schema(tmp_path):
    proc = codeword("schema", cwd=tmp_path)
    shipped = json.loads((ROOT / "compiler" / "schema" / "codeword.schema.json").read_text())
    assert json.loads(proc.stdout) == shipped
    proc = codeword("schema", "--write", "editor/cw.json", cwd=tmp_path)
    assert proc.returncode == 0 and json.loads((tmp_path / "editor" / "cw.json").read_text()) == shipped


@pytest.mark.parametrize("text, line", [
    ('out = "../elsewhere"\n', 1),
    ('schemas = ["schemas"]\nout = "gen/../../elsewhere"\n', 2),
    ('out = "gen"\n\n[outputs]\nc = "{outside}"\n', 4),
    ('[docs]\nsite = "../mkdocs.yml"\n', 2),
    ('out = "link/gen"\n', 1),  # a folder inside that is a link to one outside
])
def test_a_configuration_never_writes_outside_its_project(tmp_path, text, line):
    """A configuration from someone else may name no folder outside the project (absolute,
    `../`, or through a link) to write to: refused at its file and line, nothing written;
    the command line may name such a folder."""
    project, outside = tmp_path / "project", tmp_path / "elsewhere"
    (project / "schemas").mkdir(parents=True)
    shutil.copy(SCHEMAS / "car.yaml", project / "schemas")
    (project / "link").symlink_to(tmp_path, target_is_directory=True)
    (project / "codeword.toml").write_text(text.replace("{outside}", str(outside)), encoding="utf-8")
    for command in ("build", "accelerate"):
        proc = codeword(command, cwd=project)
        assert proc.returncode == 2, proc.stdout + proc.stderr
        assert f"codeword.toml:{line}: " in proc.stderr and "outside the project" in proc.stderr, proc.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["project"]
    assert sorted(p.name for p in project.iterdir()) == ["codeword.toml", "link", "schemas"]
    if "site" not in text:
        named = codeword("build", "--out", "../elsewhere", cwd=project)
        assert named.returncode == 0, named.stderr
        assert (outside / "c" / "car.h").is_file()
