"""Which of the module's own helpers and imports its code calls.

The views record each helper as they write a call to it; the template writes a helper, or
an import, only when it is needed: strict type checkers report an unused one
(fuzz/schema/unused.py checks every generated module for them)."""
from __future__ import annotations

# helpers the template's own helpers call
_WITHIN = {
    "_faults": ("_int_fault", "_float_fault"),
    "_nonfinite": ("_float_fault", "struct"),
    "_absent_or_list_of": ("_is_list_of",),
    "_parse_int": ("_int_of",),
    "_parse_float": ("_significant",),
}


class Calls:
    """The helpers and modules that generated code calls, as the views write it."""

    def __init__(self) -> None:
        self.names: set[str] = set()

    def use(self, *names: str) -> None:
        self.names.update(names)

    def closure(self) -> frozenset[str]:
        """The names used, with every helper the used helpers call."""
        found, todo = set(self.names), list(self.names)
        while todo:
            for name in _WITHIN.get(todo.pop(), ()):
                if name not in found:
                    found.add(name)
                    todo.append(name)
        return frozenset(found)
