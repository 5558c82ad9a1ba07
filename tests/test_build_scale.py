"""What keeps a build of thousands of messages fast and small: the vector file
written a case at a time, dispatch collisions found without trying every pair,
generated code compiled in pieces, libyaml with the pure parser's behaviour,
and compiled templates that never change what is rendered."""
from __future__ import annotations

import io
import json
import random
import subprocess
import sys
from types import SimpleNamespace

import pytest

import codeword.loader as loader
from codeword import jsontext, pyload
from codeword.diagnostics import SchemaError
from codeword.dispatch_pairs import candidate_pairs
from codeword.loader import MAX_DEPTH, load_text
from codeword.resolver import Resolver
from codeword.spool import Spool
from conftest import ROOT, SCHEMAS


def test_json_text_is_what_json_dumps_writes():
    data = json.loads((ROOT / "generated" / "vectors" / "car.json").read_text(encoding="utf-8"))
    assert jsontext.dumps(data) == json.dumps(data, indent=1, ensure_ascii=True)
    odd = {"empty": [], "none": {}, 1: 2.5, 2.5: True, None: None,
           "floats": [float("nan"), float("inf"), -float("inf"), -0.0, 1e300],
           "text": "é\n\"\\\x00", "deep": [[[]], [{}], {"x": (1, 2)}]}
    assert jsontext.dumps(odd) == json.dumps(odd, indent=1, ensure_ascii=True)


def test_a_list_written_item_by_item_is_the_whole_list():
    for items in ([], [1], [{"a": [1, {}]}, "b"]):
        out = io.StringIO()
        out.write('{\n "k": ')
        writer = jsontext.ListWriter(out, 1)
        for item in items:
            writer.item(item)
        writer.close()
        out.write("\n}")
        assert out.getvalue() == json.dumps({"k": items}, indent=1)


def test_dispatch_candidates_hold_every_ambiguous_pair_in_loop_order():
    rng = random.Random(7)
    for _ in range(2000):
        framing = rng.choice(["bits", "bytes", "text"])
        messages = []
        for _ in range(rng.randint(1, 10)):
            if framing == "bits":
                key = tuple((k, rng.randint(0, 2)) for k in rng.sample("abc", rng.randint(1, 3)))
            elif framing == "bytes":
                key = (("kind", tuple(rng.sample(range(5), rng.randint(1, 2)))),)
            else:
                key = (("prefix", (rng.choice("XYZ"),)),)
            size = rng.randint(1, 3)  # some frames may be cut short: sizes min_size..size
            ids = key[0][1] if framing == "text" else ()  # a text message's id is its prefix, no talker field
            messages.append(SimpleNamespace(dispatch_key=key, size=size, min_size=rng.randint(1, size),
                                            ids=ids, prefix_field=None))
        every_pair = [(i, j) for i in range(len(messages)) for j in range(i + 1, len(messages))
                      if Resolver.ambiguous(messages[i], messages[j], framing)]
        found = [(i, j) for i, j in candidate_pairs(messages, framing)
                 if Resolver.ambiguous(messages[i], messages[j], framing)]
        assert found == every_pair


def test_generated_code_compiled_in_pieces_keeps_its_line_numbers():
    lines = ["from __future__ import annotations", "X = 1"]
    for i in range(pyload.CHUNK_LINES):
        lines += [f"def f{i}(a: Undefined) -> int:", f"    return {i} + X", ""]
    source = "\n".join(lines) + "\n"
    assert len(pyload._chunks(source)) > 1
    module = pyload.load_module("_chunked_test", source, "chunked.py")
    last = pyload.CHUNK_LINES - 1
    assert getattr(module, f"f{last}")(None) == last + 1
    assert getattr(module, f"f{last}").__code__.co_firstlineno == 3 + 3 * last
    assert getattr(module, f"f{last}").__annotations__["a"] == "Undefined"  # the future import holds
    del sys.modules["_chunked_test"]


def test_a_cut_inside_a_statement_falls_back_to_the_whole_source():
    body = ["x = '''"] + ["def not_code():"] * (pyload.CHUNK_LINES + 2) + ["'''", "def f():", "    return x"]
    module = pyload.load_module("_cut_test", "\n".join(body) + "\n", "cut.py")
    assert module.f().count("def not_code") == pyload.CHUNK_LINES + 2
    del sys.modules["_cut_test"]


def test_libyaml_and_the_pure_parser_give_the_same_document():
    for path in sorted(SCHEMAS.glob("*.yaml")):
        text = path.read_text(encoding="utf-8")
        fast = load_text(text, path.name)
        saved, loader._FastLoader = loader._FastLoader, None
        try:
            pure = load_text(text, path.name)
        finally:
            loader._FastLoader = saved
        assert fast.data == pure.data and fast.locs == pure.locs, path.name


def test_a_document_nested_too_deep_for_libyaml_does_not_crash_the_build(tmp_path):
    deep = tmp_path / "deep.yaml"
    deep.write_text("codeword: 1\nx: " + "[" * 200_000 + "]" * 200_000 + "\n", encoding="utf-8")
    proc = subprocess.run([sys.executable, "-m", "codeword", "lint", str(deep)], cwd=ROOT,
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode in (1, 2), proc  # a diagnostic or an internal error, not a signal
    with pytest.raises(SchemaError, match=f"nesting deeper than {MAX_DEPTH}"):
        load_text("a: " + "[" * (MAX_DEPTH + 5) + "]" * (MAX_DEPTH + 5) + "\n", "t.yaml")


def test_a_spool_compares_like_read_text(tmp_path):
    spool = Spool()
    spool.file.write("a\nb\n")
    same, crlf, longer = tmp_path / "same", tmp_path / "crlf", tmp_path / "longer"
    same.write_bytes(b"a\nb\n")
    crlf.write_bytes(b"a\r\nb\r\n")
    longer.write_bytes(b"a\nb\nc")
    assert spool.same_as(same) and spool.same_as(crlf)
    assert not spool.same_as(longer) and not spool.same_as(tmp_path / "missing")
    spool.write_to(tmp_path / "out")
    assert (tmp_path / "out").read_bytes() == b"a\nb\n"
    spool.close()


def test_a_damaged_template_cache_only_costs_a_compile(tmp_path):
    code = ("import sys\n"
            "from pathlib import Path\n"
            "from codeword.targets import render\n"
            "from codeword.targets.template_cache import TemplateCache\n"
            "cache = TemplateCache(Path(sys.argv[1]), 'test')\n"
            "cache.write = True\n"
            "env = render.jinja2.Environment(loader=render.jinja2.FileSystemLoader(str(render.TEMPLATES)),\n"
            "                                bytecode_cache=cache, **render.OPTIONS)\n"
            "env.filters.update(render.FILTERS)\n"
            "print(env.get_template('docs/index.md.j2').render(protocols=[]))\n")
    runs = []
    for damage in (None, b"", b"j2 garbage"):
        if damage is not None:
            for cached in tmp_path.iterdir():
                cached.write_bytes(damage)
        proc = subprocess.run([sys.executable, "-c", code, str(tmp_path)], cwd=ROOT,
                              capture_output=True, text=True)
        assert proc.returncode == 0, proc.stderr
        runs.append(proc.stdout)
    assert len(set(runs)) == 1 and len(list(tmp_path.iterdir())) == 1


def _one_message_schema(fields: str) -> str:
    return ("codeword: 1\nprotocol: wide\ntitle: t\nsource: s\nframing:\n  kind: bytes\n  byte_order: big\n"
            "  layout:\n    - {name: kind, type: u8, dispatch: true}\n    - {payload: true}\n"
            "messages:\n  m:\n    id: 1\n    fields:\n" + fields)


@pytest.mark.parametrize("fields, frame", [
    ("".join(f"      - {{name: f{i}, type: u8}}\n" for i in range(2000)), 2001),
    ("".join(f"      - {{name: b{i}, type: bytes, length: 4096}}\n" for i in range(64)), 1 + 64 * 4096),
], ids=["2000 u8 fields", "64 fields of 4 KiB"])
def test_vector_cases_grow_with_the_message_not_its_square(tmp_path, fields, frame):
    """2,000 fields took 285 s and 64 fields of 4 KiB did not end (a case per field and edge,
    each drawing every field; 200 random frames of 256 KiB). The cases are bounded by
    counting them, not by timing the build."""
    from codeword.build import compile_schema, render_with_codec
    from codeword.vectors import FRAME_BUDGET, RANDOM_PER_MESSAGE, write_vectors
    path = tmp_path / "wide.yaml"
    path.write_text(_one_message_schema(fields), encoding="utf-8")
    protocol = compile_schema(path)
    out = io.StringIO()
    write_vectors(protocol, render_with_codec(protocol)[1], out)
    vectors = json.loads(out.getvalue())
    edges = [c for c in vectors["valid"] if c["name"].startswith("m every field")]
    assert [c["name"] for c in edges] == ["m every field min", "m every field max", "m every field zero"]
    assert len(vectors["valid"]) <= 3 + min(RANDOM_PER_MESSAGE, FRAME_BUDGET // frame) + 24 * 5
    assert all(len(c["hex"]) == 2 * frame for c in vectors["valid"])
    assert sum(len(s["hex"]) // 2 for s in vectors["streams"]) <= 16 * FRAME_BUDGET


def test_a_large_protocol_shares_its_random_and_mutated_cases_among_its_messages(tmp_path):
    """Every message keeps its edges (every field at each), some random cases and
    mutated frames; the file grows with the message count, not 350 cases a message."""
    from codeword.build import compile_schema, render_with_codec
    from codeword.vectors import FULL_MESSAGES, RANDOM_FLOOR, MUTATED_FLOOR, cases_per_message, write_vectors
    n = 3 * FULL_MESSAGES
    randoms, mutated = cases_per_message(n)
    assert (randoms, mutated) == (4000 // n, 480 // n) and randoms >= RANDOM_FLOOR and mutated >= MUTATED_FLOOR
    assert cases_per_message(5000) == (RANDOM_FLOOR, MUTATED_FLOOR)
    assert cases_per_message(FULL_MESSAGES) == (200, 24)  # small protocols keep every case
    messages = "".join(f"  m{i}:\n    id: {i + 1}\n    fields:\n      - {{name: a, type: u8, range: [1, 9]}}\n"
                       f"      - {{name: b, type: i16}}\n" for i in range(n))
    path = tmp_path / "many.yaml"
    path.write_text(_one_message_schema("").split("messages:")[0] + "messages:\n" + messages, encoding="utf-8")
    protocol = compile_schema(path)
    out = io.StringIO()
    write_vectors(protocol, render_with_codec(protocol)[1], out)
    vectors = json.loads(out.getvalue())
    for i in range(n):
        names = [c["name"] for c in vectors["valid"] if c["name"].startswith(f"m{i} ")]
        assert names[:3] == [f"m{i} every field {edge}" for edge in ("min", "max", "zero")]
        assert sum(name.startswith(f"m{i} random") for name in names) == randoms
    # mutations: five per frame here (a bit flipped, truncated, extended, last and second byte changed)
    assert len(vectors["valid"]) + len(vectors["invalid"]) <= n * (3 + randoms + 5 * mutated)
    assert len(vectors["invalid"]) >= n * mutated
    edges = {c["name"]: c["values"] for c in vectors["valid"] if c["name"].startswith("m0 every")}
    assert edges["m0 every field min"] == {"a": 1, "b": -32768}
    assert edges["m0 every field max"] == {"a": 9, "b": 32767}
