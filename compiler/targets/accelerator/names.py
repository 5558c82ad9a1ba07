"""The Python objects an accelerator's C code uses, each given a slot of its state."""
from __future__ import annotations

from dataclasses import dataclass, field


@dataclass
class Names:
    """The Python objects the C code uses, each given a slot: module globals (classes,
    tables, the Python decoders), attribute names and numeric constants."""

    globals: list[str] = field(default_factory=list)
    attributes: list[str] = field(default_factory=list)
    constants: list[str] = field(default_factory=list)  # Python literals: ints and floats
    slots: list[tuple[int, int]] = field(default_factory=list)  # (class, attribute): an instance's slot
    places: dict[tuple[int, object], int] = field(default_factory=dict)  # (table, entry) → index
    classes: set[int] = field(default_factory=set)  # globals whose instances C makes: bind() checks each
    dicts: set[int] = field(default_factory=set)  # globals C reads as dicts: bind() checks each

    def _slot(self, table: list, name) -> int:
        key = (id(table), name)
        if key not in self.places:
            self.places[key] = len(table)
            table.append(name)
        return self.places[key]

    def g(self, name: str) -> str:
        return f"st->G[{self._slot(self.globals, name)}]"

    def a(self, name: str) -> str:
        return f"st->A[{self._slot(self.attributes, name)}]"

    def class_global(self, name: str) -> str:
        """A class global whose instances the C code makes."""
        self.classes.add(self._slot(self.globals, name))
        return self.g(name)

    def dict_global(self, name: str) -> str:
        """A global the C code reads with the dict API."""
        self.dicts.add(self._slot(self.globals, name))
        return self.g(name)

    def s(self, cls: str, attribute: str) -> str:
        """The index of the slot that holds `attribute` in instances of `cls`."""
        pair = (self._slot(self.globals, cls), self._slot(self.attributes, attribute))
        return str(self._slot(self.slots, pair))

    def k(self, literal: str) -> str:
        return f"st->K[{self._slot(self.constants, literal)}]"
