"""The MkDocs site `codeword build` configures: for a user's own protocols as for
the repository's, with nothing loaded from the network, and pages without the
empty sections or seed wording of a protocol that has no roles, directions,
transports or notes. tests/test_docs_browser.py opens the site in a browser."""
from __future__ import annotations

import hashlib
import re
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import yaml

from codeword.build import build
from codeword.project import load_project
from codeword.targets.escape import yaml_string
from codeword.targets.markdown.site import GENERATED_MARK, MERMAID, MERMAID_VERSION
from conftest import ROOT

# sha256 of dist/mermaid.min.js in the npm package mermaid 11.17.2 (npm pack mermaid@11.17.2)
MERMAID_SHA256 = "581ed7d74bd9048d0e3a91363927d72ef22942d7722546b27f7cc29e35390eb8"


def codeword(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "codeword", *args], cwd=cwd, capture_output=True, text=True,
                          timeout=600)


def site_config(path: Path) -> dict:
    """mkdocs.yml as MkDocs reads it (its one python/name tag kept as text)."""
    class Loader(yaml.SafeLoader):
        pass
    Loader.add_multi_constructor("tag:yaml.org,2002:python/", lambda loader, tag, node: tag)
    return yaml.load(path.read_text(encoding="utf-8"), Loader=Loader)


def bare_project(folder: Path) -> Path:
    """`codeword init`'s starter without roles and directions: the smallest protocol."""
    assert codeword("init", "rover", cwd=folder).returncode == 0
    schema = folder / "schemas" / "rover.yaml"
    text = schema.read_text(encoding="utf-8")
    text = re.sub(r"^(roles|directions):\n(  .*\n)+\n", "", text, flags=re.M)
    text = re.sub(r"^    direction: .*\n", "", text, flags=re.M)
    schema.write_text(text, encoding="utf-8")
    return schema


def headings_without_content(page: str) -> list[str]:
    """Headings followed directly by a heading of the same or a higher level."""
    lines = [line for line in page.splitlines() if line.strip() and not line.startswith("<a id=")]
    empty = []
    for line, following in zip(lines, lines[1:] + ["# end"]):
        level = len(line) - len(line.lstrip("#"))
        if line.startswith("#") and following.startswith("#"):
            if len(following) - len(following.lstrip("#")) <= level:
                empty.append(line)
    return empty


def test_the_vendored_mermaid_is_the_pinned_release():
    assert hashlib.sha256(MERMAID.read_bytes()).hexdigest() == MERMAID_SHA256
    assert MERMAID_VERSION.startswith("11.")  # the major version Material for MkDocs 9 drives
    assert "MIT License" in (MERMAID.parent / "mermaid.LICENSE").read_text(encoding="utf-8")


def test_a_users_protocol_gets_a_page_and_a_site(tmp_path):
    schema = bare_project(tmp_path)
    assert "roles:" not in schema.read_text(encoding="utf-8")
    proc = codeword("build", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert "wrote mkdocs.yml" in proc.stdout
    page = (tmp_path / "generated" / "docs" / "rover.md").read_text(encoding="utf-8")
    assert headings_without_content(page) == []
    for absent in ("### Roles", "### Directions", "### Transports", "## Spec notes", "## Overview",
                   "#spec-notes", "#overview"):
        assert absent not in page
    index = (tmp_path / "generated" / "docs" / "index.md").read_text(encoding="utf-8")
    assert not re.search(r"seed", page + index, re.I)

    config = site_config(tmp_path / "mkdocs.yml")
    assert config["docs_dir"] == "generated/docs"
    assert config["nav"] == [{"Protocols": "index.md"}, {"rover": "rover.md"}]
    assert config["theme"]["font"] is False
    assert "extra_javascript" not in config  # no state machine, no diagram script
    assert not (tmp_path / "generated" / "docs" / "mermaid.min.js").exists()
    assert codeword("build", "--check", cwd=tmp_path).returncode == 0
    site = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict"], cwd=tmp_path,
                          capture_output=True, text=True, timeout=600)
    assert site.returncode == 0, site.stderr
    assert (tmp_path / "build" / "site" / "rover.html").is_file()


def test_the_site_follows_the_configuration_and_leaves_a_hand_written_one_alone(tmp_path):
    bare_project(tmp_path)
    config = tmp_path / "codeword.toml"
    config.write_text(config.read_text(encoding="utf-8") + '\n[outputs]\ndocs = "site/pages"\n', encoding="utf-8")
    assert codeword("build", cwd=tmp_path).returncode == 0
    assert site_config(tmp_path / "mkdocs.yml")["docs_dir"] == "site/pages"

    (tmp_path / "mkdocs.yml").write_text("site_name: mine\n", encoding="utf-8")
    proc = codeword("build", cwd=tmp_path)
    assert proc.returncode == 0 and "mkdocs.yml: not written by codeword" in proc.stderr
    assert (tmp_path / "mkdocs.yml").read_text(encoding="utf-8") == "site_name: mine\n"

    config.write_text(config.read_text(encoding="utf-8") + '\n[docs]\nsite = "docs.yml"\n', encoding="utf-8")
    assert codeword("build", cwd=tmp_path).returncode == 0
    assert (tmp_path / "docs.yml").read_text(encoding="utf-8").startswith(GENERATED_MARK)


def test_the_repositorys_site_is_generated_and_checked(tmp_path):
    config = site_config(ROOT / "mkdocs.yml")
    assert (ROOT / "mkdocs.yml").read_text(encoding="utf-8").startswith(GENERATED_MARK)
    schemas = sorted(p.stem for p in (ROOT / "schemas").glob("*.yaml"))
    examples = sorted(p.stem for p in (ROOT / "examples").glob("*.yaml"))
    assert config["nav"] == ([{"Protocols": "index.md"}] + [{name: f"{name}.md"} for name in schemas]
                             + [{"Examples": ["examples/index.md"]
                                 + [{name: f"examples/{name}.md"} for name in examples]}])
    assert config["extra_javascript"] == ["mermaid.min.js"]  # tr24 draws its state machines
    assert (ROOT / "generated" / "docs" / "mermaid.min.js").read_bytes() == MERMAID.read_bytes()
    assert not (ROOT / "examples" / "mkdocs.yml").exists()  # examples/ joins this site

    project = replace(load_project(ROOT), schema_paths=(ROOT / "schemas",), out=ROOT / "generated",
                      site=ROOT / "mkdocs.yml")
    schemas = project.schema_files()
    result = build(schemas, project, check=True, root=ROOT, all_schemas=schemas)
    assert ROOT / "mkdocs.yml" in result.unchanged and not result.stale
    edited = tmp_path / "mkdocs.yml"
    edited.write_text(GENERATED_MARK + "\nsite_name: edited\n", encoding="utf-8")
    result = build(schemas, replace(project, site=edited), check=True, root=ROOT, all_schemas=schemas)
    assert result.stale == [edited]


def test_names_and_paths_are_yaml_strings():
    for text in ("yes", "null", "1.0", "a: b", "x\ny", "ü"):
        assert yaml.safe_load(f"key: {yaml_string(text)}")["key"] == text
