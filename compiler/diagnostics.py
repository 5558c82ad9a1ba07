"""Diagnostics: every problem found in a schema, with where it is and how to fix it."""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True, order=True)
class Loc:
    """A position in a schema file; line and column are 1-based."""

    file: str
    line: int
    col: int

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.col}"


@dataclass(frozen=True)
class Diagnostic:
    loc: Loc
    message: str
    hint: str = ""
    severity: str = "error"  # or "warning": the schema builds, but its author should look

    def __str__(self) -> str:
        text = f"{self.loc}: {self.severity}: {self.message}"
        if self.hint:
            text += f"\n  hint: {self.hint}"
        return text


class SchemaError(Exception):
    """Raised when a schema has one or more errors; carries all of them."""

    def __init__(self, diagnostics: list[Diagnostic]):
        self.diagnostics = sorted(diagnostics, key=lambda d: (d.loc, d.message))
        super().__init__("\n".join(str(d) for d in self.diagnostics))


class Reporter:
    """Collects diagnostics so that a pass can report every error, not only the first."""

    def __init__(self) -> None:
        self.diagnostics: list[Diagnostic] = []

    def error(self, loc: Loc, message: str, hint: str = "") -> None:
        self.diagnostics.append(Diagnostic(loc, message, hint))

    def raise_if_any(self) -> None:
        if self.diagnostics:
            raise SchemaError(self.diagnostics)
