"""Resolve a validated schema document into the immutable protocol model: the top
level (protocol, roles, directions, transports, notes, history) and the order in
which the concerns' mixins resolve the rest. Every semantic rule of the language
is checked in this package, before any backend runs, and every error is
collected with its file:line:col and a hint.
"""
from __future__ import annotations

import hashlib
from dataclasses import replace

from ..diagnostics import SchemaError
from ..loader import Document
from ..model import Direction, HistoryEntry, Machine, Message, Note, Parameter, Protocol, Role, Transport
from ..name_clashes import generated_name_clashes
from ..names import protocol_name_problem
from .machines import MachineResolver
from .line_bound import line_max
from .text import text
from ..validate import structure_errors
from .types import TypesMixin
from .fields import FieldsMixin
from .checksums import ChecksumsMixin
from .framing import FramingMixin
from .messages import MessagesMixin
from .shortening import ShorteningMixin
from .rules import RulesMixin
from .sequences import SequencesMixin
from .streams import StreamsMixin
from .stuffing import StuffingMixin
from .can import CanMixin
from .delivery import DeliveryMixin
from .placement import PlacementMixin


class Resolver(TypesMixin, FieldsMixin, ChecksumsMixin, FramingMixin, PlacementMixin, MessagesMixin,
               ShorteningMixin, RulesMixin, SequencesMixin, DeliveryMixin, StreamsMixin,
               StuffingMixin, CanMixin):
    """The whole document: each concern's rules come from its mixin module."""

    def resolve(self) -> Protocol:
        d = self.data
        problem = protocol_name_problem(d["protocol"])
        if problem:
            self.error(("protocol",), f"protocol name {problem}",
                       "rename it; it names the generated module and header")
        for path, clash in generated_name_clashes(d):
            self.error(path, clash, "rename one of them")
        roles = tuple(Role(n, text(r.get("doc"))) for n, r in d.get("roles", {}).items())
        for n in d.get("roles", {}):
            self.check_name(n, ("roles", n), "role")
        directions = []
        for n, r in d.get("directions", {}).items():
            self.check_name(n, ("directions", n), "direction")
            for end in ("from", "to"):
                if r[end] not in d.get("roles", {}):
                    self.error(("directions", n, end), f"direction {n!r}: unknown role {r[end]!r}",
                               "declare it under `roles`")
            directions.append(Direction(n, r["from"], r["to"], text(r.get("doc"))))
        for n, p in d.get("parameters", {}).items():
            self.check_name(n, ("parameters", n), "parameter")
            rng = tuple(p["range"]) if "range" in p else None
            if rng and "default" in p and not rng[0] <= p["default"] <= rng[1]:
                self.error(("parameters", n, "default"),
                           f"parameter {n!r}: default {p['default']} is outside {rng[0]}..{rng[1]}")
            self.parameters[n] = Parameter(n, p.get("default"), rng, p.get("unit"), text(p.get("doc")))
        for n, e in d.get("enums", {}).items():
            self.enums[n] = self.resolve_enum(n, e)
        for n, f in d.get("flags", {}).items():
            self.flags[n] = self.resolve_flags(n, f)
        self.check_type_cycles()
        self.report.raise_if_any()  # a cyclic type would make every later error misleading
        group_types = tuple(
            (n, self.resolve_field({"name": n, **t}, ("types", n), allow_payload=False))
            for n, t in d.get("types", {}).items() if self.base_type(t, ("types", n)) == "group")
        framing = self.resolve_framing(d["framing"])
        messages = tuple(self.resolve_message(n, m, framing) for n, m in d["messages"].items())
        self.check_messages(messages, d)
        framing = self.resolve_stuffing(d["framing"], framing, messages)
        if framing.kind == "text":
            framing = replace(framing, line_max=line_max(framing, messages))
        sequences = tuple(self.resolve_sequence(n, s, messages)
                          for n, s in d.get("sequences", {}).items())
        self.machine_packets_checked: set[str] = set()  # messages whose packer field names are checked
        machines = tuple(self.resolve_machine(n, m, messages)
                         for n, m in d.get("machines", {}).items())
        delivery = self.resolve_delivery(d["delivery"], machines, messages) if "delivery" in d else None
        streams = self.resolve_streams(d.get("streams", []), framing, messages)
        self.report.raise_if_any()
        return Protocol(
            name=d["protocol"], file=self.doc.file,
            sha256=hashlib.sha256(self.doc.text.encode("utf-8")).hexdigest(),
            title=text(d["title"]), version=d.get("version"), source=d["source"],
            doc=text(d.get("doc")),
            notes=tuple(Note(n["id"], text(n["text"])) for n in d.get("notes", [])),
            history=tuple(HistoryEntry(h["version"], h.get("date", ""), h.get("author", ""),
                                       tuple(text(c) for c in h.get("changes", [])))
                          for h in d.get("history", [])),
            roles=roles, directions=tuple(directions),
            transports=tuple(Transport(t["name"], t["kind"], text(t.get("doc")),
                                       tuple(sorted(t.get("params", {}).items())))
                             for t in d.get("transports", [])),
            parameters=tuple(self.parameters.values()), enums=tuple(self.enums.values()),
            flags=tuple(self.flags.values()), framing=framing, messages=messages,
            sequences=sequences, machines=machines, group_types=group_types, delivery=delivery,
            streams=streams)

    def resolve_machine(self, name: str, m: dict, messages: tuple[Message, ...]) -> Machine:
        return MachineResolver(self, name, m, messages).resolve()


def resolve(doc: Document) -> Protocol:
    """Validate the structure, then resolve and check the meaning; raise SchemaError."""
    problems = structure_errors(doc)
    if problems:
        raise SchemaError(problems)
    return Resolver(doc).resolve()
