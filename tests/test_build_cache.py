"""The build cache (compiler/cache.py): a result stored under the hash of its
inputs is reused, a damaged or absent entry only costs the computation, and the
tr24 page's efficiency table is the same measured or remembered."""
from __future__ import annotations

from codeword import cache
from codeword.build import compile_schema, render_protocol
from conftest import SCHEMAS


def test_a_result_is_computed_once_and_then_remembered(tmp_path, monkeypatch):
    monkeypatch.setenv("CODEWORD_CACHE", str(tmp_path))
    calls = []

    def compute():
        calls.append(1)
        return [{"p": 0.1, "measured": 1.2345678901234567}]

    name = cache.key("test", 1, "a")
    assert cache.remembered(name, compute) == compute() and len(calls) == 2
    assert cache.remembered(name, compute) == compute() and len(calls) == 3  # from the file: no call
    (tmp_path / f"{name}.json").write_text('{"val', encoding="utf-8")  # damaged: computed again
    assert cache.remembered(name, compute) == compute() and len(calls) == 5


def test_every_input_is_part_of_the_key():
    keys = {cache.key("k", 1, "a"), cache.key("k", 2, "a"), cache.key("k", 1, "b"), cache.key("j", 1, "a"),
            cache.key("k", [1], "a")}
    assert len(keys) == 5 and cache.key("k", 1, "a") == cache.key("k", 1, "a")


def test_off_keeps_nothing(tmp_path, monkeypatch):
    monkeypatch.setenv("CODEWORD_CACHE", "off")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    assert cache.folder() is None
    assert cache.remembered(cache.key("test"), lambda: 7) == 7
    assert list(tmp_path.iterdir()) == []


def test_an_unwritable_cache_only_costs_the_computation(tmp_path, monkeypatch):
    blocker = tmp_path / "file"
    blocker.write_text("", encoding="utf-8")
    monkeypatch.setenv("CODEWORD_CACHE", str(blocker / "below"))
    assert cache.remembered(cache.key("test"), lambda: 7) == 7


def test_the_delivery_table_is_the_same_measured_or_remembered(tmp_path, monkeypatch):
    monkeypatch.setenv("CODEWORD_CACHE", str(tmp_path))
    protocol = compile_schema(SCHEMAS / "tr24.yaml")
    measured = render_protocol(protocol)["docs/tr24.md"]
    stored = list(tmp_path.glob("efficiency-*.json"))
    assert len(stored) == 1
    remembered = render_protocol(protocol)["docs/tr24.md"]
    assert remembered == measured
    monkeypatch.setenv("CODEWORD_CACHE", "off")
    assert render_protocol(protocol)["docs/tr24.md"] == measured
