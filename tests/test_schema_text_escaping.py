"""Schema text never becomes code, in any output.

Every string-valued key of the language (found by walking the JSON Schema) is
either prose, which gets a hostile payload for every output context, or a key
whose value the front end reads as a name, a number or wire syntax, listed in
NOT_PROSE with the reason. Each seed schema is rebuilt with every prose value it
has extended by the payloads (and its file name and rule ids too). Then: the C
compiles with -Werror and, comments and strings removed, contains no payload; the
Python, imported from disk, has the payloads only in comment and string tokens;
the Promela model keeps them in comments; the Markdown pages, rendered as MkDocs
renders them, hold no tag or attribute that came from the schema.
"""
from __future__ import annotations

import html.parser
import importlib.util
import json
import re
import shutil
import subprocess
import sys
import tokenize
from pathlib import Path

import markdown
import pytest
import yaml

from codeword.build import build
from codeword.loader import _Loader as YAML12  # `no` is a string, as codeword reads it
from conftest import SCHEMAS

SCHEMA = json.loads((Path(__file__).resolve().parent.parent / "compiler/schema/codeword.schema.json")
                    .read_text(encoding="utf-8"))

# Each payload carries a marker (QZ plus a number) that must never reach code.
PAYLOADS = [
    "*/ #include </nonexistent/QZ1.h> /*",                  # closes a C comment
    "\n#define QZ2 1\n#error QZ2\n",                        # newline then a directive
    '""" ; QZ3 = 1 ; """',                                    # closes a Python docstring
    "''' ; QZ4 = 1 ; '''",
    "{{ QZ5 }} {% if QZ5 %}",                                 # template syntax
    "<script>QZ6()</script>",
    "<img src=x onerror=QZ7()>",
    "--> <b>QZ8</b> <!--",                                    # closes an HTML comment
    "` <i>QZ9</i> `` ```",                                    # ends a code span
    "]] [QZ10](javascript:QZ10()) ![x](javascript:QZ10())",   # Markdown links
    "/* QZ11 ??/",                                            # opens a Promela/C comment; trigraph
    "coding: utf-7 +AAo-QZ12 = 1",                            # an encoding declaration (Python)
    "\r\nQZ13 = 1\tQZ13 '\" \\",                             # CR LF, tab; quotes
]
MARKERS = sorted({m for p in PAYLOADS for m in re.findall(r"QZ\d+", p)})
# Two orders, so that each end of the text is met by a quote, a backslash and a newline.
VARIANTS = {"forward": " ".join(PAYLOADS) + " \\", "reversed": " ".join(reversed(PAYLOADS)) + ' "'}

# String-valued keys that are not prose, and why. Paths: `.key` a property, `[a]` any
# key of a map, `[i]` a list item, `#def` a shared definition.
NOT_PROSE = {
    "#fields[i].checksum.algorithm": "a checksum algorithm name",
    "#fields[i].type": "a type name",
    "#fields[i].rule": "a note id (renamed with the note, below)",
    "#machine_action.fail": "a name of the machine",
    "#seq_item.count": "a field path",
    "#fields[i].count.from": "a field name",
    "#fields[i].length.from": "a field name",
    ".types[a].count.from": "a field name",
    "#fields[i].present_if.field": "a field name",
    ".types[a].present_if.field": "a field name",
    "#fields[i].present_if.has": "a flag name",
    ".types[a].present_if.has": "a flag name",
    "#fields[i].present_if.equals": "an enum member name",
    ".types[a].present_if.equals": "an enum member name",
    "#fields[i].present_if.equals[i]": "an enum member name",
    ".types[a].present_if.equals[i]": "an enum member name",
    ".types[a].length.from": "a field name",
    ".types[a].checksum.algorithm": "a checksum algorithm name",
    ".types[a].type": "a type name",
    ".types[a].rule": "a note id (renamed with the note, below)",
    ".enums[a].type": "a type name",
    ".flags[a].type": "a type name",
    ".machines[a].variables[a].type": "a type name",
    ".framing.ignore_between": "wire syntax",
    ".framing.prefix_separator": "wire syntax",
    ".framing.separator": "wire syntax",
    ".framing.terminator": "wire syntax",
    ".framing.start": "wire syntax",
    ".framing.checksum.suffix": "wire syntax",
    ".framing.text_form.comment": "wire syntax",
    ".framing.text_form.separator": "wire syntax",
    ".messages[a].id": "a wire value",
    ".messages[a].examples[i].text": "wire text the codec must read",
    ".sequences[a].examples[i].text": "wire text the codec must read",
    ".streams[i].text": "wire text the codec must read",
    ".framing.stuffing.after": "wire bytes",
    ".framing.trailer.fields[i].name": "a field name",
    ".framing.trailer.fields[i].type": "a type name",
    ".framing.trailer.fields[i].signature.covers.from": "a field name",
    ".framing.trailer.fields[i].signature.covers.to": "a field name",
    ".framing.trailer.present_if.field": "a field name",
    ".framing.trailer.present_if.has": "a flag name",
    ".streams[i].events[i].error": "a rule name a decoder reports",
    ".streams[i].events[i].message": "a message name",
    ".messages[a].examples[i].error.field": "a field path",
    ".messages[a].examples[i].errors[i].field": "a field path",
    ".sequences[a].examples[i].error.field": "a field path",
    ".sequences[a].examples[i].errors[i].field": "a field path",
    ".messages[a].examples[i].error.rule": "a rule id (renamed with the rule, below)",
    ".messages[a].examples[i].errors[i].rule": "a rule id (renamed with the rule, below)",
    ".sequences[a].examples[i].error.rule": "a rule id (renamed with the rule, below)",
    ".sequences[a].examples[i].errors[i].rule": "a rule id (renamed with the rule, below)",
    ".sequences[a].rules[i].of": "a field path",
    ".sequences[a].rules[i].path": "a field path",
    ".sequences[a].rules[i].to": "a field path",
    ".transports[i].kind": "a transport kind",
    "#fields[i].const": "a wire value",
    "#fields[i].default": "a value (an enum member's name)",
    "#fields[i].values[i]": "a wire value",
    ".types[a].const": "a wire value",
    ".types[a].default": "a value (an enum member's name)",
    ".types[a].values[i]": "a wire value",
    ".enums[a].values[i].value": "a wire value (char enums)",
    ".messages[a].rules[i].when[a]": "a value a field is compared with",
    ".messages[a].rules[i].when[a].in[i]": "a value a field is compared with",
    ".messages[a].rules[i].when[a].ne": "a value a field is compared with",
    ".messages[a].rules[i].require[a]": "a value a field is compared with",
    ".messages[a].rules[i].require[a].in[i]": "a value a field is compared with",
    ".messages[a].rules[i].require[a].ne": "a value a field is compared with",
    ".machines[a].states[a].on[a].guard[a]": "a value a variable is compared with",
    ".machines[a].states[a].on[a].guard[a].in[i]": "a value a variable is compared with",
    ".machines[a].states[a].on[a].guard[a].ne": "a value a variable is compared with",
    ".machines[a].states[a].on[a][i].guard[a]": "a value a variable is compared with",
    ".machines[a].states[a].on[a][i].guard[a].in[i]": "a value a variable is compared with",
    ".machines[a].states[a].on[a][i].guard[a].ne": "a value a variable is compared with",
}
# Ids that other keys refer to: every reference is renamed with them.
IDS = {".messages[a].rules[i].id", ".sequences[a].rules[i].id", ".notes[i].id"}
REFS = {p for p, why in NOT_PROSE.items() if "renamed with" in why}


def resolve(node: dict) -> tuple[dict, str | None]:
    ref = node.get("$ref")
    if ref:
        name = ref.rsplit("/", 1)[1]
        return SCHEMA["$defs"][name], name
    return node, None


def string_paths(node: dict, path: str, out: set[str], seen: set[str]) -> None:
    """Every path of the JSON Schema whose value may be a free string (no pattern, enum or const)."""
    node, ref = resolve(node)
    if ref:
        path = "#" + ref if ref != "text" else path
        if ref in seen and ref != "text":
            return
        seen = seen | {ref}
    if node.get("type") == "string" or "string" in (node.get("type") or []):
        if not any(k in node for k in ("pattern", "enum", "const", "format")):
            out.add(path)
    for key in ("oneOf", "anyOf", "allOf"):
        for branch in node.get(key, []):
            string_paths(branch, path, out, seen)
    for key, sub in node.get("properties", {}).items():
        string_paths(sub, f"{path}.{key}", out, seen)
    if isinstance(node.get("additionalProperties"), dict):
        string_paths(node["additionalProperties"], path + "[a]", out, seen)
    for sub in node.get("patternProperties", {}).values():
        string_paths(sub, path + "[a]", out, seen)
    if isinstance(node.get("items"), dict):
        string_paths(node["items"], path + "[i]", out, seen)


def text_key(path: str) -> str:
    """A text value may be a string or {en: …, ru: …}: the paths of its parts are the text's."""
    return re.sub(r"(\.en|\[a\])$", "", path)


ALL_STRINGS: set[str] = set()
string_paths(SCHEMA, "", ALL_STRINGS, set())
PROSE = {p for p in ALL_STRINGS if p not in NOT_PROSE and p not in IDS}


def test_every_string_key_of_the_language_is_prose_or_has_a_reason():
    assert ALL_STRINGS >= set(NOT_PROSE) | IDS, sorted((set(NOT_PROSE) | IDS) - ALL_STRINGS)
    # the keys a reader writes prose in are all here (a sample a walk must find)
    for key in (".title", ".doc", ".notes[i].text", ".parameters[a].unit", ".history[i].changes[i]",
                ".messages[a].rules[i].message", ".enums[a].values[i].doc", ".flags[a].bits[i].doc",
                ".transports[i].doc", ".roles[a].doc", ".directions[a].doc", ".machines[a].doc",
                ".messages[a].examples[i].source", ".messages[a].examples[i].name", "#fields[i].doc",
                "#fields[i].unit", "#fields[i].message", ".source", ".version"):
        assert key in PROSE, key


def poison(data, node: dict, path: str, payload: str, ids: dict, hit: set) -> object:
    """The document with `payload` appended to every prose string; ids collected for renaming."""
    node, ref = resolve(node)
    if ref and ref != "text":
        path = "#" + ref
    if isinstance(data, str):
        if path in PROSE or text_key(path) in PROSE:
            hit.add(text_key(path))
            return data + " " + payload
        if path in IDS:
            ids[data] = data + " " + payload
            return ids[data]
        if path in REFS:
            return ids.get(data, data)
        return data
    branches = node.get("oneOf") or node.get("anyOf") or []
    if branches and not node.get("properties"):
        kind = dict if isinstance(data, dict) else list if isinstance(data, list) else str
        for branch in branches:
            b, _ = resolve(branch)
            t = b.get("type")
            if (kind is dict and (t == "object" or "properties" in b)) or (kind is list and t == "array") \
                    or (kind is str and t == "string"):
                return poison(data, branch, path, payload, ids, hit)
        return data
    if isinstance(data, dict):
        out = {}
        props = node.get("properties", {})
        extra = node.get("additionalProperties")
        pattern = next(iter(node.get("patternProperties", {}).values()), None)
        for key, value in data.items():
            if key in props:
                out[key] = poison(value, props[key], f"{path}.{key}", payload, ids, hit)
            elif isinstance(extra, dict) or pattern:
                out[key] = poison(value, extra if isinstance(extra, dict) else pattern, path + "[a]", payload, ids, hit)
            else:
                out[key] = value
        return out
    if isinstance(data, list) and isinstance(node.get("items"), dict):
        return [poison(x, node["items"], path + "[i]", payload, ids, hit) for x in data]
    return data


SEEDS = sorted(SCHEMAS.glob("*.yaml"))
CASES = [(seed, variant) for seed in SEEDS for variant in VARIANTS]
HIT: dict[str, set] = {}


@pytest.fixture(scope="module")
def poisoned(tmp_path_factory):
    """Built outputs per (seed, variant), built on first use."""
    cache: dict = {}

    def get(seed: Path, variant: str) -> Path:
        if (seed, variant) not in cache:
            payload = VARIANTS[variant]
            data = yaml.load(seed.read_text(encoding="utf-8"), Loader=YAML12)
            ids: dict = {}
            hit: set = set()
            poison(data, SCHEMA, "", payload, ids, set())  # the ids first, then every reference to them
            data = poison(data, SCHEMA, "", payload, ids, hit)
            HIT.setdefault(seed.stem, set()).update(hit)
            # the file name too: the payload's slashes become folders (a name holds any
            # byte but '/' and NUL, at most 255 of them)
            where = tmp_path_factory.mktemp(seed.stem)
            folder = where
            for part in payload.split("/"):
                for at in range(0, max(len(part), 1), 80):
                    folder = folder / (part[at:at + 80].replace(".", ",") or "_")
            folder.mkdir(parents=True)
            schema = folder / f"{seed.stem}.yaml"
            schema.write_text(yaml.safe_dump(data, allow_unicode=True, sort_keys=False), encoding="utf-8")
            out = where / "generated"
            result = build([schema], out)
            assert not result.errors, "\n".join(map(str, result.errors))
            cache[seed, variant] = out
        return cache[seed, variant]
    return get


def test_every_prose_key_of_the_language_is_exercised_by_some_seed(poisoned):
    for seed in SEEDS:
        poisoned(seed, "forward")
    reached = set().union(*HIT.values())
    missing = {text_key(p) for p in PROSE} - reached
    # prose keys no seed schema uses yet: a schema that uses them belongs here
    assert missing <= UNREACHED, sorted(missing - UNREACHED)


def markers_in(text: str) -> list[str]:
    return [m for m in MARKERS if re.search(m + r"(?!\d)", text)]


def c_code_only(source: str) -> str:
    """What the C compiler reads: comments removed by the preprocessor, then string and
    character literals."""
    proc = subprocess.run(["gcc", "-fpreprocessed", "-dD", "-E", "-P", "-x", "c", "-"], input=source,
                          capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0, proc.stderr
    return re.sub(r'"(?:[^"\\\n]|\\.)*"|\'(?:[^\'\\\n]|\\.)*\'', '""', proc.stdout)


def check_c(out: Path, tmp: Path) -> None:
    for header in sorted((out / "c").glob("*.h")):
        if header.name == "codeword.h":
            continue
        code = c_code_only(header.read_text(encoding="utf-8"))
        assert not markers_in(code), (header.name, markers_in(code))
        main = tmp / "main.c"
        main.write_text(f'#include "{header.name}"\nint main(void) {{ return 0; }}\n', encoding="utf-8")
        for cc, std in (("gcc", "-std=c99"), ("g++", "-std=c++11")):
            lang = ["-x", "c++"] if cc == "g++" else []
            proc = subprocess.run([shutil.which(cc) or cc, std, "-Wall", "-Wextra", "-Wpedantic", "-Werror",
                                   "-Wtrigraphs", "-Wcomment", "-fsyntax-only", "-I", str(out / "c"), *lang,
                                   str(main)], capture_output=True, text=True, timeout=120)
            assert proc.returncode == 0, proc.stderr[-3000:]


def check_python(out: Path) -> None:
    for path in sorted((out / "python").glob("*.py")):
        raw = path.read_bytes()
        with path.open("rb") as fh:  # as Python reads the file: its encoding declaration applies
            tokens = list(tokenize.tokenize(fh.readline))
        assert tokens[0].string == "utf-8", tokens[0]
        code = " ".join(t.string for t in tokens if t.type not in (tokenize.COMMENT, tokenize.STRING))
        assert not markers_in(code), (path.name, markers_in(code))
        name = f"_escaping_{path.stem}"
        spec = importlib.util.spec_from_file_location(name, path)
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        try:
            spec.loader.exec_module(module)
        finally:
            del sys.modules[name]
        for marker in MARKERS:
            assert not hasattr(module, marker), marker
        assert raw.decode("utf-8")


def check_promela(out: Path) -> None:
    for path in sorted((out / "promela").glob("*.pml")) if (out / "promela").exists() else []:
        code = c_code_only(path.read_text(encoding="utf-8"))
        assert not markers_in(code), (path.name, markers_in(code))


class Tags(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.found: list[tuple[str, list]] = []
        self.comments: list[str] = []

    def handle_starttag(self, tag, attrs):
        self.found.append((tag, attrs))

    def handle_comment(self, data):
        self.comments.append(data)


def check_docs(out: Path) -> None:
    for page in sorted((out / "docs").glob("*.md")):
        source = page.read_text(encoding="utf-8")
        rendered = markdown.markdown(source, extensions=["tables", "toc", "md_in_html", "pymdownx.superfences"])
        assert "<script" not in rendered.lower(), page.name
        parser = Tags()
        parser.feed(rendered)
        for tag, attrs in parser.found:
            assert tag not in ("b", "i", "img", "script"), (page.name, tag, attrs)
            for key, value in attrs:
                assert not key.startswith("on"), (page.name, tag, key)
                assert not (value or "").strip().lower().startswith("javascript:"), (page.name, tag, value)
                assert not markers_in(key + "=" + (value or "")) or key in ("id", "href") and "qz" in (value or ""), \
                    (page.name, tag, key, value)
        # the generated-from comment stays one comment
        assert source.startswith("<!--") and source.index("-->") == source.index("\n") - 3, page.name
        for comment in parser.comments:
            assert "--" not in comment.strip("- "), (page.name, comment)


@pytest.mark.parametrize("seed,variant", CASES, ids=[f"{s.stem}-{v}" for s, v in CASES])
def test_payload_in_every_prose_key_stays_text_in_every_output(seed, variant, poisoned, tmp_path):
    out = poisoned(seed, variant)
    check_python(out)
    check_c(out, tmp_path)
    check_promela(out)
    check_docs(out)
    json.loads((out / "vectors" / f"{seed.stem}.json").read_text(encoding="utf-8"))


UNREACHED = {
    "#seq_item.doc",
    ".framing.trailer.doc",
    ".framing.trailer.fields[i].doc",
    ".framing.trailer.fields[i].title",
    ".framing.trailer.fields[i].unit",
    ".enums[a].title",
    ".flags[a].title",
    ".machines[a].states[a].on[a].doc",
    ".machines[a].states[a].on[a][i].doc",
    ".messages[a].examples[i].doc",
    ".messages[a].rules[i].doc",
    ".roles[a].title",
    ".sequences[a].examples[i].doc",
    ".sequences[a].rules[i].message",
    ".types[a].message",
}


def test_state_docs_stay_inside_the_mermaid_diagram(tmp_path):
    """A state's doc is a Mermaid state description inside a ```mermaid fence: a backtick
    run would end the fence and put the rest of the doc on the page as Markdown/HTML,
    a newline or `;` would start a new diagram statement."""
    from codeword.build import compile_schema, render_protocol
    payload = "x```\\n<script>alert(1)</script>;\\n    idle --> waiting: injected %% #quot; [a]"
    text = (SCHEMAS / "tr24.yaml").read_text(encoding="utf-8")
    text = text.replace("doc: no command outstanding", f'doc: "{payload}"', 1)
    path = tmp_path / "tr24.yaml"
    path.write_text(text, encoding="utf-8")
    page = next(v for k, v in render_protocol(compile_schema(path)).items() if k.startswith("docs/") and "mermaid" in v)
    block = page.split("```mermaid\n", 1)[1].split("\n```", 1)[0]
    line = next(x for x in block.splitlines() if "alert" in x)
    assert "`" not in block and "<" not in block and ">" not in line.split(":", 1)[1]
    assert line.strip().startswith("idle: idle — ") and line.count(":") == 1
    assert [x for x in block.splitlines() if "injected" in x] == [line]  # no statement of its own
