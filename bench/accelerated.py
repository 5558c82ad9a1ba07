"""Python with the compiled accelerator (`codeword accelerate`): decode per message and
the mtv4 stream, against the same calls in pure Python and against pymavlink.

The accelerated modules are second copies of generated/python's modules, imported
with their accelerators; bench/protocols.py keeps the pure-Python ones. Every
accelerated decode is checked equal (repr: values and their types) to the pure one
before timing.
"""

import importlib.util
import sys

from bench import messages, streams, timing
from bench.protocols import ROOT

NAMES = ("route", "car", "mtv4", "tr24")  # tank is a text protocol: no accelerator
DECODE_MIN = 5.0  # pymavlink decode / accelerated mtv4.decode
STREAM_MIN = 5.0  # accelerated stream MB/s / pymavlink MB/s


class NotBuilt(Exception):
    """No accelerator for a module: `codeword accelerate` was not run."""


def load(name):
    path = ROOT / "generated" / "python" / f"{name}.py"
    spec = importlib.util.spec_from_file_location(f"_accelerated_{name}", path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up
    spec.loader.exec_module(module)  # generated/python is on sys.path (bench/protocols.py)
    if module.ACCELERATOR is None:
        raise NotBuilt(f"no accelerator for {name}: run `codeword accelerate` (scripts/setup does)")
    return module


def contenders(cases):
    """{(case key, contender): decode call} for the accelerated modules, with the
    pure-Python and pymavlink calls they are compared with; checked first."""
    fast = {name: load(name) for name in NAMES}
    out = {}
    for case in cases:
        if case.key not in fast:
            continue
        pure_call = case.contenders["codeword"].decode
        cls = type(pure_call())
        fast_cls = getattr(fast[case.key], cls.__name__)
        wire = case.wire

        def call(c=fast_cls, w=wire):
            return c.decode(w)
        if repr(call()) != repr(pure_call()):
            raise AssertionError(f"{case.key}: the accelerated decode differs from the pure-Python one")
        out[(case.key, "pure Python")] = pure_call
        out[(case.key, "accelerated")] = call
        pure_object, fast_object = pure_call(), call()
        if fast_object.encode() != pure_object.encode() or fast_object.encode() != wire:
            raise AssertionError(f"{case.key}: the accelerated encode differs from the pure-Python one")
        out[(case.key, "pure Python encode")] = pure_object.encode
        out[(case.key, "accelerated encode")] = fast_object.encode
        if type(fast_object).NAME not in fast[case.key].ACCELERATOR.ENCODES:
            out[(case.key, "encoded in Python")] = None
        if case.key == "mtv4":
            module = fast["mtv4"]
            if repr(module.decode(wire)) != repr(pure_call()):
                raise AssertionError("mtv4.decode: the accelerated decode differs from the pure-Python one")
            out[("mtv4", "accelerated, any message")] = lambda m=module, w=wire: m.decode(w)
            out[("mtv4", "pure Python, any message")] = case.contenders[messages.DISPATCHING].decode
            out[("mtv4", "pymavlink ATTITUDE")] = case.contenders["pymavlink ATTITUDE (40 B)"].decode
            out[("mtv4", "pymavlink ATTITUDE encode")] = case.contenders["pymavlink ATTITUDE (40 B)"].encode
    return out, fast


def measure(cases, repeats, target, stream_bytes, stream_repeats):
    calls, fast = contenders(cases)
    python_encoded = [key for key, call in calls.items() if call is None]
    calls = {key: call for key, call in calls.items() if call is not None}
    per_message = timing.interleaved(calls, repeats, target)
    cap, good = streams.mtv4_capture(stream_bytes)
    mcap, mgood = streams.mavlink_capture(min(stream_bytes, 20_000_000))
    chunks, mchunks = streams._chunks(cap), streams._chunks(mcap)

    def accelerated_stream(parts, module=fast["mtv4"]):
        dec, found = module.StreamDecoder(), 0
        for chunk in parts:
            for item in dec.feed(chunk):
                if not isinstance(item, module.DecodeError):
                    found += 1
        return found
    found = {"accelerated": [], "pure Python": [], "pymavlink parse_buffer": []}
    jobs = {"accelerated": streams.timed(accelerated_stream, chunks, good, found["accelerated"]),
            "pure Python": streams.timed(streams.codeword_stream, chunks, good, found["pure Python"]),
            "pymavlink parse_buffer": streams.timed(streams.pymavlink_stream, mchunks, mgood,
                                                    found["pymavlink parse_buffer"])}
    seconds = timing.interleaved_once(jobs, stream_repeats)
    sizes = {"accelerated": len(cap), "pure Python": len(cap), "pymavlink parse_buffer": len(mcap)}
    sent = {"accelerated": good, "pure Python": good, "pymavlink parse_buffer": mgood}
    if found["accelerated"] != found["pure Python"]:
        raise AssertionError("the accelerated stream decoder found other frames than the pure-Python one")
    return {"per_message": per_message, "python_encoded": python_encoded,
            "streams": {k: (sizes[k] / seconds[k] / 1e6, sizes[k], sent[k], min(found[k])) for k in jobs}}


def report(r, verdicts, met):
    """The section's Markdown lines; appends each target's verdict to `verdicts`."""
    pm, s = r["per_message"], r["streams"]
    lines = ["", "## 6. Python with the compiled accelerator", "",
             "`codeword accelerate` compiles each binary protocol's decoders and encoders from the generated C "
             "(`generated/python/_<name>_accel.c`) into an extension module beside the Python module, "
             "which uses it when it was built from the same schema and decodes in pure Python otherwise. "
             "Decoding per message through the class's `decode`, and `mtv4.decode` finding the message by "
             "its id as pymavlink's `decode` does; then the stream of section 2. "
             "Every accelerated result is checked equal to the pure-Python one before timing. `bench/accelerated.py`.",
             "Encoding through the object's `encode`, the accelerated result checked equal to the "
             "pure-Python one and to the example's frame.",
             "", "| message | decode, pure Python ns | accelerated ns | speed-up | encode, pure Python ns | "
             "accelerated ns | speed-up |", "|---|---:|---:|---:|---:|---:|---:|"]
    for key in NAMES:
        if (key, "accelerated") in pm:
            a, p = pm[(key, "accelerated")], pm[(key, "pure Python")]
            ea, ep = pm[(key, "accelerated encode")], pm[(key, "pure Python encode")]
            lines.append(f"| {key} | {p:,.0f} | {a:,.0f} | {p / a:.2f} | {ep:,.0f} | {ea:,.0f} | {ep / ea:.2f} |")
    a, p = pm[("mtv4", "accelerated, any message")], pm[("mtv4", "pure Python, any message")]
    lines.append(f"| mtv4.decode (any message) | {p:,.0f} | {a:,.0f} | {p / a:.2f} | | | |")
    python_encoded = [key for key in NAMES if (key, "encoded in Python") in r["python_encoded"]]
    if python_encoded:
        lines += ["", f"Encoded in Python by the accelerated module: {', '.join(python_encoded)} (`ACCELERATOR.ENCODES` "
                      "leaves the message out: a rule between its fields, which C would test on raw values)."]
    mav, mav_encode = pm[("mtv4", "pymavlink ATTITUDE")], pm[("mtv4", "pymavlink ATTITUDE encode")]
    encode_ratio = mav_encode / pm[("mtv4", "accelerated encode")]
    lines += ["", f"pymavlink decodes ATTITUDE (40 B) in {mav:,.0f} ns and encodes it in {mav_encode:,.0f} ns: "
                  f"pymavlink encode / accelerated mtv4 encode = {encode_ratio:.2f}.", "",
              "| stream contender | MB/s | stream bytes | good frames sent | found |", "|---|---:|---:|---:|---:|"]
    for name, (mbs, size, sent, found) in s.items():
        lines.append(f"| {name} | {mbs:.2f} | {size:,} | {sent:,} | {found:,} |")
    decode_ratio = mav / a
    stream_ratio = s["accelerated"][0] / s["pymavlink parse_buffer"][0]
    verdicts += [decode_ratio >= DECODE_MIN, stream_ratio >= STREAM_MIN]
    lines += ["", f"- pymavlink decode / accelerated `mtv4.decode` = {decode_ratio:.2f} "
                  f"(target ≥ {DECODE_MIN}): {met(decode_ratio >= DECODE_MIN)}",
              f"- accelerated stream MB/s / pymavlink MB/s = {stream_ratio:.2f} "
              f"(target ≥ {STREAM_MIN}): {met(stream_ratio >= STREAM_MIN)}",
              "- identical results: `tests/test_accelerator.py` checks every conformance vector, damaged frames "
              "and the stream vectors of the five protocols and the examples, accelerated against pure Python."]
    return lines
