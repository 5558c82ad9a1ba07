"""Every hand-written example in the schemas, through the committed generated
codecs, both ways (the same check `codeword build` runs before writing)."""
from __future__ import annotations

import pytest

from codeword.examples import ExampleChecker
from conftest import PROTOCOLS, load_generated, load_model


def cases():
    for name in PROTOCOLS:
        model = load_model(name)
        for m in model.messages:
            for ex in m.examples:
                yield pytest.param(name, m.name, None, ex.name, id=f"{name}-{m.name}-{ex.name}")
        for s in model.sequences:
            for ex in s.examples:
                yield pytest.param(name, None, s.name, ex.name, id=f"{name}-{s.name}-{ex.name}")


@pytest.mark.parametrize("protocol,message,sequence,example", list(cases()))
def test_example(protocol, message, sequence, example):
    model = load_model(protocol)
    checker = ExampleChecker(model, load_generated(protocol))
    if message:
        m = model.message(message)
        checker.check_message(m, next(e for e in m.examples if e.name == example))
    else:
        s = next(s for s in model.sequences if s.name == sequence)
        checker.check_sequence(s, next(e for e in s.examples if e.name == example))
    assert checker.problems == []


def test_every_message_has_an_example():
    for name in PROTOCOLS:
        for m in load_model(name).messages:
            assert any(not e.errors for e in m.examples), f"{name}.{m.name} has no valid example"


def test_examples_cite_their_source():
    for name in PROTOCOLS:
        model = load_model(name)
        for ex in [e for m in model.messages for e in m.examples] + [e for s in model.sequences for e in s.examples]:
            assert ex.source, f"{name}: example {ex.name!r} does not say where it comes from"


def test_route_example_file_is_a_whole_sequence():
    model = load_model("route")
    (route,) = model.sequences
    assert any(ex.text and not ex.errors for ex in route.examples)
    assert any(len(ex.errors) == 4 for ex in route.examples)  # ROUTE-D3
