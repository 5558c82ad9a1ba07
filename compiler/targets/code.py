"""Lines of generated code with indentation, for code-building backends."""
from __future__ import annotations


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
