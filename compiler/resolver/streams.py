"""`streams`: byte streams with the events a stream decoder gives on them, worked
out by hand from the framing rules. The build runs each through the generated
Python decoder (compiler/examples.py) and the vectors carry them to every other
target, so the resynchronisation rules a spec states are checked where it states them."""
from __future__ import annotations

from typing import Optional

from ..model import Framing, Message, StreamEvent, StreamExample
from .base import ResolverBase
from .text import text

ANY_ERROR = "error"  # an event written as this word alone: an error of any rule


class StreamsMixin(ResolverBase):
    def resolve_streams(self, raw: list, framing: Framing,
                        messages: tuple[Message, ...]) -> tuple[StreamExample, ...]:
        if raw and framing.kind == "bits":
            self.error(("streams",), "a bits framing has no stream decoder: its words are decoded one by one",
                       "drop `streams`, or give the messages examples")
            return ()
        return tuple(filter(None, (self.resolve_stream(s, ("streams", i), framing, messages)
                                   for i, s in enumerate(raw))))

    def resolve_stream(self, s: dict, path: tuple, framing: Framing,
                       messages: tuple[Message, ...]) -> Optional[StreamExample]:
        data = self.stream_data(s, path, framing)
        names = {m.name for m in messages}
        events: list[StreamEvent] = []
        last_end = 0
        for i, e in enumerate(s["events"]):
            here = path + ("events", i)
            if e == ANY_ERROR:
                events.append(StreamEvent())
            elif "error" in e:
                events.append(StreamEvent(rule=e["error"]))
            else:
                if e["message"] not in names:
                    self.error(here + ("message",), f"stream {s['name']!r}: unknown message {e['message']!r}",
                               f"name a message ({', '.join(sorted(names))})")
                end = e.get("end")
                if end is not None and data is not None and not last_end < end <= len(data):
                    self.error(here + ("end",), f"stream {s['name']!r}: a frame cannot end at byte {end}: "
                                                f"the previous one ends at {last_end} and the stream is "
                                                f"{len(data)} bytes", "count the bytes again")
                last_end = end if end is not None else last_end
                events.append(StreamEvent(message=e["message"], end=end))
        if data is None:
            return None
        return StreamExample(name=s["name"], loc=self.loc(*path), data=data, events=tuple(events),
                             doc=text(s.get("doc")), text="text" in s)

    def stream_data(self, s: dict, path: tuple, framing: Framing) -> Optional[bytes]:
        forms = [k for k in ("hex", "text") if k in s]
        if len(forms) != 1:
            self.error(path, f"stream {s['name']!r} needs its bytes as `hex` or `text`, one of them",
                       "write hex: \"aa 08 …\" (any framing) or text: \"…\" (a text framing)")
            return None
        if forms[0] == "text":
            if framing.kind != "text":
                self.error(path + ("text",), f"stream {s['name']!r}: `text` is for text framings",
                           "write the bytes as hex")
                return None
            try:
                return s["text"].encode("latin-1")
            except UnicodeEncodeError:
                self.error(path + ("text",), f"stream {s['name']!r}: characters beyond one byte",
                           "write those bytes as hex")
                return None
        digits = "".join(s["hex"].split())
        if len(digits) % 2:
            self.error(path + ("hex",), f"stream {s['name']!r}: hex has an odd number of digits")
            return None
        return bytes.fromhex(digits)
