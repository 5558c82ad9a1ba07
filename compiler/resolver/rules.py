"""Rules: conditions and requirements over a message's fields."""
from __future__ import annotations

from ..model import Condition, Field, Rule, array_on, field_at
from .text import text
from .base import ResolverBase


class RulesMixin(ResolverBase):
    def conditions(self, raw: dict, path: tuple, layout: tuple[Field, ...]) -> tuple[Condition, ...]:
        out = []
        for key, value in raw.items():
            field = self.find_path(layout, key)
            if field is None and array_on(layout, key) is not None:
                self.error(path + (key,), f"rule names {key!r}, which is or is inside the array "
                                          f"{array_on(layout, key).name!r}",
                           "rules compare single values; an array's elements have no rules yet")
            elif field is None:
                self.error(path + (key,), f"rule names unknown field {key!r}",
                           "use a member field; dotted paths reach into groups")
            elif not field.is_member and field.kind != "group":
                self.error(path + (key,), f"rule names field {key!r}, which the codec sets itself "
                                          "(a constant, length, checksum or reserved field)",
                           "rules compare member fields")
            elif field.enum is not None:
                operands = value.values() if isinstance(value, dict) else [value]
                for operand in operands:
                    for v in operand if isinstance(operand, list) else [operand]:
                        if v is not None and v not in {m.name for m in field.enum.members} \
                                and v not in field.enum.values:
                            self.error(path + (key,), f"rule compares {key!r} with {v!r}, which is not a "
                                                      f"member of enum {field.enum.name!r}",
                                       "use a member's name: " + ", ".join(m.name for m in field.enum.members))
            if isinstance(value, dict):
                (op, operand), = value.items()
                out.append(Condition(key, op, tuple(operand) if isinstance(operand, list) else operand))
            else:
                out.append(Condition(key, "eq", value))
        return tuple(out)

    @staticmethod
    def find_path(fields: tuple[Field, ...], dotted: str):
        """The single-valued field a dotted path names; None for an unknown one or an array's."""
        return None if array_on(fields, dotted) is not None else field_at(fields, dotted)

    def resolve_rule(self, r: dict, path: tuple, layout: tuple[Field, ...]) -> Rule:
        return Rule(r.get("id"), self.conditions(r.get("when", {}), path + ("when",), layout),
                    self.conditions(r["require"], path + ("require",), layout),
                    text(r.get("message")), self.loc(*path))
