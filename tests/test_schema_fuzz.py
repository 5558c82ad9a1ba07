"""Schema-space fuzzing in the default run: random valid schemas over the
language (fuzz/schema/generate.py), each built for every target, its Python codec
run on its vectors and on damaged frames, and its C codec compiled with the
strict warning flags and run against the same vectors; and random mutations of
such schemas, each refused at a file:line or built. Features listed in
fuzz/schema/features.py KNOWN_OPEN are off here (each names what fails).

CODEWORD_SCHEMA_FUZZ=N checks N schemas (default 300); the long run is
`python3 -m fuzz.schema --count 10000 --record` (fuzz/RESULTS.md)."""
from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from fuzz.schema.check import check_seed  # noqa: E402
from fuzz.schema.mutate import check_mutant  # noqa: E402

COUNT = int(os.environ.get("CODEWORD_SCHEMA_FUZZ", "300"))
BATCH = 25
FIRST_SEED = 100_000  # apart from the seeds a developer tries by hand


def batches() -> list[range]:
    seeds = range(FIRST_SEED, FIRST_SEED + COUNT)
    return [seeds[i:i + BATCH] for i in range(0, COUNT, BATCH)]


@pytest.mark.parametrize("seeds", batches(), ids=lambda r: f"{r.start}-{r.stop - 1}")
def test_generated_schemas_build_and_agree(seeds):
    failed = [check_seed(seed) for seed in seeds]
    failed = [o for o in failed if not o.ok]
    assert not failed, "\n".join(f"{o.line()}  (python3 -m fuzz.schema --seed {o.seed} --show)"
                                 for o in failed)


@pytest.mark.parametrize("seeds", batches(), ids=lambda r: f"{r.start}-{r.stop - 1}")
def test_mutated_schemas_are_refused_at_a_line_or_build(seeds):
    problems = [p for p in map(check_mutant, seeds) if p]
    assert not problems, "\n".join(problems)


def test_the_checks_catch_a_broken_codec(monkeypatch):
    """The harness fails when C and Python disagree: the C driver is handed one
    valid frame with a bit flipped, and the check must report it."""
    from fuzz.schema import check as harness
    from fuzz.schema.generate import generate
    original = harness.Driver.source

    def sabotaged(self, vectors):
        wire = bytearray.fromhex(vectors["valid"][0]["hex"])
        wire[-1] ^= 0x01
        vectors["valid"][0]["hex"] = wire.hex()
        return original(self, vectors)

    monkeypatch.setattr(harness.Driver, "source", sabotaged)
    seed = next(s for s in range(FIRST_SEED, FIRST_SEED + 100) if "kind: bytes" in generate(s))
    outcome = check_seed(seed)
    assert outcome.stage == "c" and "C disagrees" in outcome.detail


def test_a_seed_that_hangs_is_a_finding_not_a_wait(monkeypatch):
    import time

    from fuzz.schema import check

    monkeypatch.setattr(check, "SEED_SECONDS", 1)
    monkeypatch.setattr(check, "generate", lambda seed, features: time.sleep(30))  # a generator that never ends
    started = time.monotonic()
    outcome = check.check_seed(1)
    assert time.monotonic() - started < 10
    assert (outcome.stage, outcome.detail) == ("generate", "TimeoutError: the seed took over 1 s")


# long-run findings, each fixed: a seed or mutant that failed before its fix passes now
FOUND = {"seeds": (910940, 940291), "mutants": (880684, 910810, 911166)}


@pytest.mark.parametrize("seed", FOUND["seeds"])
def test_a_long_run_finding_builds_and_agrees(seed):
    outcome = check_seed(seed)
    assert outcome.ok, outcome.line()


@pytest.mark.parametrize("seed", FOUND["mutants"])
def test_a_long_run_mutant_is_refused_at_a_line_or_builds(seed):
    assert check_mutant(seed) == ""


class _Stream:
    """A stand-in for a generated module's StreamDecoder: it returns the spans it is given."""

    class DecodeError(Exception):
        pass

    def __init__(self, feed_spans, finish_spans=()):
        outer = self

        class StreamDecoder:
            def __init__(self, direction=None):
                self.spans = []

            def feed(self, data):
                self.spans = list(feed_spans)
                return [object() for _ in self.spans]

            def finish(self):
                self.spans = list(finish_spans)
                return [object() for _ in self.spans]

        outer.StreamDecoder = StreamDecoder


def test_the_stream_end_check_takes_a_frame_inside_the_false_start_but_not_one_lost(monkeypatch):
    """Seed 940291: seven zero bytes inside a false start are a valid frame of that schema
    (a message of zeros, its Fletcher checksum zero), which the stream decoder rightly
    decodes. The check allows a frame there, and still reports a frame sent whole that is
    not decoded where it was sent, and a frame that reaches past the false start."""
    from fuzz.schema import stream_end

    monkeypatch.setattr(stream_end, "applies", lambda p: True)
    frames = ["0102", "0a0b0c0d0e0f", "0304"]  # the longest is cut in half for the false start
    vectors = {"valid": [{"message": "m", "hex": h} for h in frames]}
    # stream: 0102 | 0a0b0c (false start, 3 bytes at offset 2) | 0102 (at 5)
    # (whole frames after it: room = 6 - 3 - 1 = 2 bytes, the shortest first: 0102)
    whole = [(0, 2), (5, 2)]
    assert stream_end.stream_end_problem(_Stream(whole), None, vectors) == ""
    assert stream_end.stream_end_problem(_Stream([(0, 2), (3, 2)], [(5, 2)]), None, vectors) == ""
    assert "not" in stream_end.stream_end_problem(_Stream([(0, 2)]), None, vectors)
    assert "not" in stream_end.stream_end_problem(_Stream([(0, 2), (4, 2)]), None, vectors)  # past it
