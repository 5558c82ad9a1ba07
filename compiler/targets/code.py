"""Lines of generated code with indentation, for code-building backends."""
from __future__ import annotations

import math


class Code:
    """Lines of code; `indent`/`dedent` step four spaces."""

    def __init__(self) -> None:
        self.lines: list[str] = []
        self.depth = 0

    def __call__(self, line: str) -> "Code":
        self.lines.append("    " * self.depth + line)
        return self

    def indent(self) -> "Code":
        self.depth += 1
        return self

    def dedent(self) -> "Code":
        self.depth -= 1
        return self

    def text(self, base: int = 0) -> str:
        pad = "    " * base
        return "\n".join(pad + line if line else line for line in self.lines)


def times_over(value: str, times: int, over: int, divide: str, suffix: str = "") -> str:
    """`value * times / over` in whole numbers, spelt with the target's integer division
    (`//` or `/`) and literal suffix, with the common factor taken out."""
    g = math.gcd(times, over)
    times, over = times // g, over // g
    out = value if times == 1 else f"{value} * {times}{suffix}"
    return out if over == 1 else f"{out} {divide} {over}{suffix}"
