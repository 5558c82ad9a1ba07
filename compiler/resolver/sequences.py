"""Sequences: items, counts, repeats and their rules."""
from __future__ import annotations

from ..model import Message, Sequence, SequenceItem, SequenceRule
from .text import text
from .base import ResolverBase


class SequencesMixin(ResolverBase):
    def resolve_sequence(self, name: str, s: dict, messages: tuple[Message, ...]) -> Sequence:
        path = ("sequences", name)
        self.check_name(name, path, "sequence")
        by_name = {m.name: m for m in messages}
        earlier: dict[str, Message] = {}
        self_identifying = all(m.dispatch_key for m in messages)

        def item(raw: dict, p: tuple) -> SequenceItem:
            self.check_name(raw["name"], p + ("name",), "sequence item")
            if "message" in raw and raw["message"] not in by_name:
                self.error(p + ("message",), f"sequence item {raw['name']!r}: unknown message "
                                             f"{raw['message']!r}")
            count = raw.get("count")
            if count is not None:
                head, _, field = count.partition(".")
                source = earlier.get(head)
                if source is None or self.find_path(source.layout, field) is None:
                    self.error(p + ("count",), f"count {count!r} must name a field of an earlier item",
                               "write item.field, e.g. header.h1")
            if raw.get("repeat") and count is not None:
                self.error(p, "give `repeat` or `count`, not both")
            if raw.get("repeat") and not self_identifying:
                self.error(p + ("repeat",), "`repeat` needs self-identifying messages (dispatch fields)",
                           "use `count` to say how many follow")
            children = tuple(item(c, p + ("items", i)) for i, c in enumerate(raw.get("items", [])))
            if raw.get("repeat") and children and all(c.may_take_nothing for c in children):
                # a pass that takes no message makes no progress: decoding would loop forever
                self.error(p + ("repeat",), f"sequence {name!r}: repeated group {raw['name']!r} can "
                                            "match no message at all (each of its items is a repeat, "
                                            "a count or such a group), so its repetitions never end",
                           "give the group an item taken exactly once (no `repeat` or `count`), "
                           "or drop `repeat` from the group")
            if "message" in raw and raw["message"] in by_name:
                earlier[raw["name"]] = by_name[raw["message"]]
            return SequenceItem(raw["name"], self.loc(*p), raw.get("message"), count,
                                bool(raw.get("repeat")), children, text(raw.get("doc")))

        items = tuple(item(r, path + ("items", i)) for i, r in enumerate(s["items"]))
        rules = []
        for i, r in enumerate(s.get("rules", [])):
            rp = path + ("rules", i)
            for key in ("path", "to", "of"):
                if key in r and not self.sequence_path_ok(items, by_name, r[key], whole=r["kind"] == "unique" and key == "path"):
                    self.error(rp + (key,), f"sequence rule: path {r[key]!r} does not name a field",
                               "walk item names to a field, e.g. scenes.scene.ns")
            needed = {"consecutive": "from", "equal": "to", "member": "of", "unique": "key"}[r["kind"]]
            if needed not in r:
                self.error(rp, f"a {r['kind']} rule needs `{needed}`")
            rules.append(SequenceRule(r.get("id"), r["kind"], r["path"], self.loc(*rp),
                                      r.get("from"), r.get("to"), r.get("of"),
                                      tuple(r.get("key", ())), text(r.get("message"))))
        examples = tuple(self.resolve_example(e, path + ("examples", i))
                         for i, e in enumerate(s.get("examples", [])))
        return Sequence(name, self.loc(*path), text(s.get("doc")), items, tuple(rules), examples)

    def sequence_path_ok(self, items: tuple[SequenceItem, ...], by_name: dict, dotted: str,
                         whole: bool) -> bool:
        parts = dotted.split(".")
        current = items
        for i, part in enumerate(parts):
            found = next((it for it in current if it.name == part), None)
            if found is None:
                return False
            if found.message:
                rest = ".".join(parts[i + 1:])
                if not rest:
                    return whole
                message = by_name.get(found.message)
                return message is not None and self.find_path(message.layout, rest) is not None
            current = found.items
        return whole
