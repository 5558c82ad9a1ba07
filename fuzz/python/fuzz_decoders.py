"""Coverage-guided fuzzing of one generated Python codec with atheris.

    python3 fuzz/python/fuzz_decoders.py PROTOCOL [-max_total_time=S] [CORPUS_DIR …]

Every input goes to the module's `decode` (each direction), to every message
class's own `decode`, and through a StreamDecoder in two chunks. Anything but
the codec's CodecError is a finding; an accepted binary frame must re-encode
to the same bytes, an accepted text message to a line that decodes the same.
Without atheris (no wheel for this Python) the same checks run on the seeds
with random bit flips and truncations, and random bytes, for the time given by
-max_total_time (no coverage feedback; tests/test_fuzz_python.py is the
hypothesis counterpart); the final line has the `#N DONE` form the runner reads.
"""
from __future__ import annotations

import importlib.util
import json
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent.parent


def load(name: str):
    spec = importlib.util.spec_from_file_location(f"fuzz_{name}", ROOT / "generated" / "python" / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod
    spec.loader.exec_module(mod)
    return mod


def is_text(mod) -> bool:
    return hasattr(mod, "StreamDecoder") and "text" in (mod.StreamDecoder.__doc__ or "").lower()[:20]


def checker(mod):
    text = is_text(mod)
    directions = [None] + sorted(d for d in getattr(mod, "_KEYS_BY_DIRECTION", {}) if d)

    def check(data: bytes) -> None:
        wire = data.decode("utf-8", "replace") if text else data
        for direction in directions:
            try:
                obj = mod.decode(wire, direction)
            except mod.CodecError:
                continue
            again = mod.encode(obj)
            if text:
                assert mod.decode(again, direction) == obj, (wire, again)
            else:
                assert again == wire, (wire.hex(), again.hex())
        for cls in mod.MESSAGES.values():
            try:
                obj = cls.decode(wire)
            except mod.CodecError:
                continue
            again = obj.encode()
            assert (cls.decode(again) == obj) if text else (again == wire), (cls.NAME, wire)
        if hasattr(mod, "StreamDecoder"):
            stream = mod.StreamDecoder()
            half = len(wire) // 2
            for piece in (wire[:half], wire[half:]):
                for event in stream.feed(piece):
                    assert isinstance(event, mod.CodecError) or type(event) in mod.MESSAGES.values()
    return check


def seeds(name: str) -> list[bytes]:
    vectors = json.loads((ROOT / "generated" / "vectors" / f"{name}.json").read_text())
    out = []
    for group in ("valid", "invalid", "streams"):
        for case in vectors.get(group, []):
            if "hex" in case:
                out.append(bytes.fromhex(case["hex"]))
            if "text" in case:
                out.append(case["text"].encode("utf-8"))
    return out


def fallback(name: str, check, seconds: float) -> int:
    """Random and mutated seeds until the time is up (no coverage feedback)."""
    import random
    rng = random.Random(0)
    pool = seeds(name)
    deadline, runs = time.monotonic() + seconds, 0
    while time.monotonic() < deadline:
        base = bytearray(rng.choice(pool)) if rng.random() < 0.8 else bytearray(rng.randbytes(rng.randrange(64)))
        for _ in range(rng.randrange(4)):
            if base:
                base[rng.randrange(len(base))] ^= 1 << rng.randrange(8)
        if rng.random() < 0.2 and base:
            del base[rng.randrange(len(base)):]
        check(bytes(base))
        runs += 1
    print(f"#{runs}\tDONE   cov: n/a (fallback without atheris) exec/s: {runs / seconds:.0f}")
    return 0


def main(argv: list[str]) -> int:
    name, rest = argv[1], [argv[0]] + argv[2:]
    try:
        import atheris
    except ImportError:
        seconds = next((float(a.split("=", 1)[1]) for a in rest if a.startswith("-max_total_time=")), 10.0)
        return fallback(name, checker(load(name)), seconds)
    sys.path.insert(0, str(ROOT / "generated" / "python"))
    with atheris.instrument_imports():  # coverage of the generated module only
        import importlib
        mod = importlib.import_module(name)
    check = checker(mod)
    atheris.instrument_func(check)
    atheris.Setup(rest, check)
    atheris.Fuzz()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
