"""What every part of the resolver shares: the document, the error report, names."""
from __future__ import annotations

import re
from typing import Any

from ..diagnostics import Loc, Reporter
from ..loader import Document
from ..model import Enum, FlagSet, Parameter
from ..names import name_problem
from . import can


INT_TYPE = re.compile(r"^([ui])([0-9]+)$")
BASE_KINDS = {"bool": ("bool", 1), "f32": ("float", 32), "f64": ("float", 64),
              "char": ("char", None), "str": ("str", None), "bytes": ("bytes", None),
              "group": ("group", None)}
MAX_INT_BITS = 64
MAX_BYTES_LENGTH = 4096
# An array's values (its count times each element's), and its bytes at most MAX_BYTES_LENGTH.
MAX_ARRAY_COUNT = 4096
DEFAULT_HINT = "see docs/schema-language.md for what this key accepts"

# A double's 53-bit significand: wider raw values would not survive value → raw → value.
MAX_SCALED_BITS = 53


class ResolverBase:
    def __init__(self, doc: Document):
        self.doc = doc
        # a CAN framing is read as the bytes framing it stands for
        self.data, self.can = can.expand(doc.data)
        self.report = Reporter()
        self.enums: dict[str, Enum] = {}
        self.flags: dict[str, FlagSet] = {}
        self.parameters: dict[str, Parameter] = {}
        self.framing_kind = self.data["framing"]["kind"]

    def loc(self, *path: Any) -> Loc:
        return self.doc.loc(path)

    def error(self, path: tuple, message: str, hint: str = "") -> None:
        self.report.error(self.doc.loc(path), message, hint or DEFAULT_HINT)

    def check_name(self, name: str, path: tuple, what: str) -> None:
        problem = name_problem(name)
        if problem:
            self.error(path, f"{what} name {problem}",
                       "rename it; names must work in Python, C and C++")
