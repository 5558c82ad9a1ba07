"""The seed protocols' hand-worked streams (the `streams` sections of mtv4.yaml and
tr24.yaml: bytes in, events worked out by hand from the framing rules, not from a
decoder). After a bad frame a decoder resumes one byte after the frame's first byte,
never a whole claimed frame later: a false sync with a plausible length must not
hide the real frame after it.

The build checks each against the pure-Python StreamDecoder; here each also runs
through the pure-Python decoder in pieces, the accelerated one, the C scan and the C
byte parser. An event is (message, end offset) or (error, rule); a rule of None is
any rule (where the schema does not say which of several faults a decoder reports
first)."""
from __future__ import annotations

import shutil

import pytest

from conftest import ROOT, load_model
from schema_in_a_test import load
from stream_events import accelerated, c_events, python_events, without_ends

MESSAGES = {"mtv4": ["set_wheels_velocities", "set_led", "set_wheels_velocities_with_odometry", "ack",
                     "odometry_reply"], "tr24": ["command", "reply"]}


def matches(got: list[tuple], expected: list[tuple]) -> bool:
    return len(got) == len(expected) and all(
        g == e or (e[0] == "error" and e[1] is None and g[0] == "error") for g, e in zip(got, expected))


def cases(name: str) -> list[tuple[str, bytes, list[tuple]]]:
    return [(s.name, s.data, [("message", e.message, e.end) if e.message else ("error", e.rule) for e in s.events])
            for s in load_model(name).streams]


def test_the_seed_schemas_carry_their_cases():
    """The cases the tests below run: a false sync with a plausible length among them."""
    assert len(cases("mtv4")) == 8 and len(cases("tr24")) == 3
    false_sync = dict((label, events) for label, _, events in cases("mtv4"))[
        "a false sync with a plausible length, then a frame"]
    assert false_sync == [("error", None), ("message", "set_wheels_velocities", 14)]


@pytest.fixture
def seed(tmp_path, request):
    """The seed protocol's schema, generated module and headers, copied into tmp_path."""
    name = request.param
    shutil.copy(ROOT / "schemas" / f"{name}.yaml", tmp_path)
    shutil.copy(ROOT / "generated" / "python" / f"{name}.py", tmp_path)
    for header in (f"{name}.h", "codeword.h"):
        shutil.copy(ROOT / "generated" / "c" / header, tmp_path)
    return tmp_path, name


@pytest.mark.parametrize("seed", sorted(MESSAGES), indirect=True)
def test_python(seed):
    where, name = seed
    mod = load(where / f"{name}.py")
    for label, data, expected in cases(name):
        for piece in (0, 1):
            got = python_events(mod, data, piece)
            assert matches(got, expected), f"{name}, {label} (pieces of {piece or 'all'}): {got}"


@pytest.mark.parametrize("seed", sorted(MESSAGES), indirect=True)
def test_accelerator(seed):
    where, name = seed
    fast = accelerated(where, name)
    for label, data, expected in cases(name):
        for piece in (0, 5):
            got = python_events(fast, data, piece)
            assert matches(got, expected), f"{name}, {label} (pieces of {piece or 'all'}): {got}"


@pytest.mark.parametrize("seed", sorted(MESSAGES), indirect=True)
def test_c(seed):
    where, name = seed
    for label, data, expected in cases(name):
        scan, parser = c_events(where, name, MESSAGES[name], data)
        assert matches(scan, expected), f"{name}, {label}: scan {scan}"
        assert matches(parser, without_ends(expected)), f"{name}, {label}: parser {parser}"
