"""The build cache (compiler/cache.py): a result stored under the hash of its
inputs is reused, a damaged or absent entry only costs the computation, and the
tr24 page's efficiency table is the same measured or remembered."""
from __future__ import annotations

import sys

from codeword import cache, pyload
from codeword.build import compile_schema, render_protocol
from conftest import SCHEMAS


def test_a_result_is_computed_once_and_then_remembered(tmp_path, monkeypatch):
    monkeypatch.setenv("CODEWORD_CACHE", str(tmp_path))
    calls = []

    def compute():
        calls.append(1)
        return [{"p": 0.1, "measured": 1.2345678901234567}]

    place, wanted = cache.slot("test", "p/q.py"), cache.key("test", 1, "a")
    assert cache.remembered(place, wanted, compute) == compute() and len(calls) == 2
    assert cache.remembered(place, wanted, compute) == compute() and len(calls) == 3  # from the file: no call
    (tmp_path / place).write_bytes(wanted.encode("ascii") + b'\n{"val')  # damaged: computed again
    assert cache.remembered(place, wanted, compute) == compute() and len(calls) == 5
    assert cache.remembered(place, cache.key("test", 2, "a"), lambda: 9) == 9  # another key: the slot's is stale
    assert cache.remembered(place, cache.key("test", 2, "a"), compute) == 9
    assert [p.name for p in tmp_path.iterdir()] == [place]  # one result a slot


def test_every_input_is_part_of_the_key():
    keys = {cache.key("k", 1, "a"), cache.key("k", 2, "a"), cache.key("k", 1, "b"), cache.key("j", 1, "a"),
            cache.key("k", [1], "a")}
    assert len(keys) == 5 and cache.key("k", 1, "a") == cache.key("k", 1, "a")


def test_off_keeps_nothing(tmp_path, monkeypatch):
    monkeypatch.setenv("CODEWORD_CACHE", "off")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    assert cache.folder() is None
    assert cache.remembered("test", cache.key("test"), lambda: 7) == 7
    assert list(tmp_path.iterdir()) == []


def test_an_unwritable_cache_only_costs_the_computation(tmp_path, monkeypatch):
    blocker = tmp_path / "file"
    blocker.write_text("", encoding="utf-8")
    monkeypatch.setenv("CODEWORD_CACHE", str(blocker / "below"))
    assert cache.remembered("test", cache.key("test"), lambda: 7) == 7


def test_the_delivery_table_is_the_same_measured_or_remembered(tmp_path, monkeypatch):
    monkeypatch.setenv("CODEWORD_CACHE", str(tmp_path))
    protocol = compile_schema(SCHEMAS / "tr24.yaml")
    measured = render_protocol(protocol)["docs/tr24.md"]
    assert (tmp_path / "efficiency-tr24").is_file() and (tmp_path / "codec-python_tr24.py").is_file()
    remembered = render_protocol(protocol)["docs/tr24.md"]
    assert remembered == measured
    monkeypatch.setenv("CODEWORD_CACHE", "off")
    assert render_protocol(protocol)["docs/tr24.md"] == measured


def test_a_module_loaded_from_cached_code_is_the_module_compiled(tmp_path, monkeypatch):
    monkeypatch.setenv("CODEWORD_CACHE", str(tmp_path))
    source = "def f(x):\n    return x + 1\n\n\ndef g():\n    raise ValueError('line 6')\n"
    modules = []
    for run in range(3):
        if run == 2:  # damaged: compiled again
            place = next(tmp_path.iterdir())
            place.write_bytes(place.read_bytes()[:80])
        modules.append(pyload.load_module(f"_cached_{run}", source, "python/cached.py"))
        del sys.modules[f"_cached_{run}"]
    for module in modules:
        assert module.f(1) == 2 and module.g.__code__.co_firstlineno == 5
        assert module.g.__code__.co_filename == "python/cached.py"
    assert [p.name for p in tmp_path.iterdir()] == ["codec-python_cached.py"]


def test_vectors_already_in_place_are_not_made_again_and_a_changed_file_is_noticed(tmp_path, monkeypatch):
    from codeword import build as build_module
    from codeword.build import build
    monkeypatch.setenv("CODEWORD_CACHE", str(tmp_path / "cache"))
    schema, out = SCHEMAS / "tr24.yaml", tmp_path / "out"
    made = []
    real = build_module.vector_spool
    monkeypatch.setattr(build_module, "vector_spool", lambda p, codec: made.append(p.name) or real(p, codec))
    assert not build([schema], out).errors and made == ["tr24"]
    vectors = out / "vectors" / "tr24.json"
    first = vectors.read_bytes()
    result = build([schema], out, check=True)
    assert made == ["tr24"] and vectors in result.unchanged and not result.stale  # in place: not made
    vectors.write_bytes(first.replace(b'"valid"', b'"valid" ', 1))
    assert vectors in build([schema], out, check=True).stale and made == ["tr24"] * 2
    build([schema], out)
    assert vectors.read_bytes() == first
    vectors.unlink()
    assert vectors in build([schema], out, check=True).stale
