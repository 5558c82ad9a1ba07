"""Where check results go: text lines or one JSON document, both written as
findings arrive so that memory does not grow with the number of findings."""
from __future__ import annotations

import json
from typing import TextIO

from .finding import Finding
from .sources import Tally

JSON_FORMAT_VERSION = 1  # docs/check.md describes this shape; bump it on any incompatible change


def _tally_json(t: Tally, findings: int) -> dict:
    return {"read": t.read, "valid": t.valid, "invalid": t.invalid, "skipped_bytes": t.skipped,
            "findings": findings}


class TextReport:
    def __init__(self, out: TextIO, write=None):
        self.out = out
        self.write = write or (lambda line: print(line, file=out))

    def start(self, schema: str, protocol: str, fingerprint: str) -> None:
        self.protocol = protocol

    def finding(self, f: Finding, unit: str) -> None:
        self.write(f.as_text(unit))

    def input_done(self, file: str, fmt: str, unit: str, tally: Tally, findings: int) -> None:
        text = (f"{file}: {tally.read} {unit}(s) read ({fmt}), {tally.valid} valid, {tally.invalid} invalid")
        if tally.skipped:
            text += f", {tally.skipped} byte(s) skipped while resynchronising"
        self.write(text + (f"; {findings} finding(s)" if findings else ""))

    def finish(self, total: Tally, findings: int, inputs: int) -> None:
        if inputs > 1:
            self.write(f"total: {total.read} read, {total.valid} valid, {total.invalid} invalid, "
                       f"{total.skipped} byte(s) skipped; {findings} finding(s)")
        verdict = "INVALID" if findings else "all valid" if total.read else "nothing read (empty input)"
        self.write(f"{self.protocol}: {verdict}")


class JsonReport:
    """{"format": 1, "schema", "protocol", "fingerprint", "findings": [...],
    "inputs": [...], "summary": {...}, "valid": bool}"""

    def __init__(self, out: TextIO):
        self.out = out
        self.count = 0
        self.inputs: list[dict] = []

    def start(self, schema: str, protocol: str, fingerprint: str) -> None:
        head = {"format": JSON_FORMAT_VERSION, "schema": schema, "protocol": protocol,
                "fingerprint": fingerprint}
        self.out.write(json.dumps(head, ensure_ascii=False)[:-1] + ', "findings": [')

    def finding(self, f: Finding, unit: str) -> None:
        self.out.write(("," if self.count else "") + "\n  " + json.dumps(f.as_json(), ensure_ascii=False))
        self.count += 1

    def input_done(self, file: str, fmt: str, unit: str, tally: Tally, findings: int) -> None:
        self.inputs.append({"file": file, "input_format": fmt, "unit": unit, **_tally_json(tally, findings)})

    def finish(self, total: Tally, findings: int, inputs: int) -> None:
        tail = {"inputs": self.inputs, "summary": _tally_json(total, findings), "valid": findings == 0}
        self.out.write("\n], " + json.dumps(tail, ensure_ascii=False, indent=None)[1:] + "\n")
