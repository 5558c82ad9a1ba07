"""`codeword import dbc FILE.dbc`: a CAN database as one codeword schema.

cantools reads the file (it is the DBC reader CAN users already trust, lenient where
real files are); this module writes what it read as a schema a person keeps editing:
`framing: {kind: can}`, each message at its identifier with its signals placed by
start bit in their own byte order, scale and offset, units, multiplexing, the nodes as
roles, value tables as open enums, initial values as defaults. What the language has
no key for (minimum and maximum, cycle times and other attributes) is written in the
message's or field's doc and in comments at its place, never dropped."""
from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Optional

from ..can import FD_LENGTHS
from ..resolver.placement import msb_position
from ..names import protocol_name_problem
from .naming import distinct, snake, usable
from .yaml_writer import Writer, number

ENVELOPE_NAMES = frozenset({"can_id", "data_length"})  # the CAN framing's header fields


class DbcError(Exception):
    """A file cantools cannot read as a DBC database."""


@dataclass
class ImportedSignal:
    name: str  # codeword's
    signal: Any  # cantools.database.Signal


@dataclass
class Imported:
    protocol: str
    path: Path
    messages: list[str] = field(default_factory=list)  # codeword names, in file order
    skipped: list[str] = field(default_factory=list)  # what the schema could not carry, in words
    text: str = ""

    def summary(self) -> str:
        carried = f"; not carried, with a comment at its place: {', '.join(self.skipped)}" if self.skipped else ""
        return f"{len(self.messages)} messages{carried}"


def import_database(path: Path) -> Imported:
    """The DBC file at `path` as the text of a codeword schema."""
    db = _load(Path(path))
    imported = Imported(_protocol_name(Path(path).stem), Path(path))
    w = Writer()
    _header(w, db, imported, Path(path).read_text(encoding="latin-1"))
    roles = _roles(w, db)
    classes: set[str] = set()  # the Python classes of enums and messages: one name each
    enums = _value_tables(w, db, classes)
    w.blank()
    w.key("framing", 0)
    w.item("kind", "can", 2)
    if any(m.is_fd or m.length > 8 for m in db.messages):
        w.item("fd", True, 2)
    w.blank()
    w.key("messages", 0)
    taken: set[str] = set()
    for message in db.messages:
        _message(w, message, roles, enums, (taken, classes), imported)
    imported.text = w.text()
    return imported


def _load(path: Path) -> Any:
    try:
        import cantools
    except ImportError:
        raise DbcError("importing DBC needs cantools: pip install 'codeword[dbc]'") from None
    try:
        return cantools.database.load_file(str(path), database_format="dbc", strict=False)
    except OSError as exc:
        raise DbcError(f"{path}: cannot read: {exc.strerror or exc}") from None
    except Exception as exc:  # cantools' parse errors have no common base class
        raise DbcError(f"{path}: not a DBC database cantools can read: {' '.join(str(exc).split())}") from None


def _protocol_name(stem: str) -> str:
    name = snake(stem)
    return name if not protocol_name_problem(name) else usable(f"can_{name}")


# Sections of a DBC file that cantools reads past: each is named in a comment when present.
UNREAD = (("EV_", "environment variables"), ("ENVVAR_DATA_", "environment variable data"),
          ("SGTYPE_", "signal types"), ("SIG_TYPE_REF_", "signal type references"),
          ("CAT_DEF_", "categories"), ("FILTER", "filters"), ("BA_DEF_REL_", "relation attribute definitions"),
          ("BA_REL_", "relation attributes"), ("BU_SG_REL_", "node-signal relations"),
          ("BU_EV_REL_", "node-environment relations"), ("BU_BO_REL_", "node-message relations"))
NETWORK_COMMENT = re.compile(r'^CM_\s+"((?:[^"\\]|\\.)*)"\s*;', re.M)


def _header(w: Writer, db: Any, imported: Imported, source: str) -> None:
    w.comment(f"CAN database {imported.path.name}, imported by `codeword import dbc` (read by cantools).")
    w.comment("Each message is at its identifier (extended: true for a 29-bit one) with its DBC length as "
              "payload_bytes; each signal is a field at its DBC start bit, in its own byte order (big = "
              "Motorola, little = Intel). Names are in snake_case; each message's title and each field's doc "
              "keep the DBC's own name.")
    w.comment("Value tables (VAL_) of unscaled integer signals are open enums: a value the table does not "
              "name decodes as its number, as cantools reads it. A signal's initial value (GenSigStartValue) "
              "is its field's default. Not carried as schema keys, kept in docs instead: other value tables, "
              "signal minimum and maximum (decoders take every raw value, as cantools does), the initial "
              "values of multiplexed signals, cycle times and other attributes (BA_).")
    tables = getattr(db.dbc, "value_tables", None) if db.dbc else None
    for name, choices in (tables or {}).items():
        w.comment(f"value table {name} (VAL_TABLE_): " + _choices_text(choices))
    for name, definition in ((db.dbc.attribute_definitions or {}).items() if db.dbc else ()):
        kind = getattr(definition, "kind", None) or ""
        default = getattr(definition, "default_value", None)
        w.comment(f"attribute {name} ({kind or 'network'} {definition.type_name})"
                  + (f", default {default}" if default not in (None, "") else ""))
    for name, attribute in ((db.dbc.attributes or {}).items() if db.dbc else ()):
        w.comment(f"network attribute {name} = {attribute.value}")
    for keyword, what in UNREAD:
        count = len(re.findall(rf"^{keyword}\s+\S", source, re.M))  # a statement, not the NS_ list's entry
        if count:
            w.comment(f"not carried: {count} {keyword} line{'s' if count > 1 else ''} ({what})")
            imported.skipped.append(f"{keyword} ({what})")
    w.blank()
    w.item("codeword", 1, 0)
    w.item("protocol", imported.protocol, 0)
    w.item("title", f"CAN database {imported.path.stem}", 0)
    if db.version:
        w.item("version", str(db.version), 0)
    w.item("source", imported.path.name, 0)
    comment = NETWORK_COMMENT.search(source)
    if comment:
        w.prose("doc", " ".join(comment.group(1).split()), 0)


def _roles(w: Writer, db: Any) -> dict[str, str]:
    """Writes `roles:`, one for each node; the codeword name of each node."""
    names: dict[str, str] = {}
    for node in db.nodes:
        names[node.name] = usable(snake(node.name), set(names.values()))
    if not names:
        return names
    w.blank()
    w.key("roles", 0)
    for node in db.nodes:
        w.key(names[node.name], 2)
        w.prose("doc", _doc(node.name, _comment(node.comment), names[node.name]), 4)
    return names


def _value_tables(w: Writer, db: Any, classes: set[str]) -> dict[tuple[int, str], str]:
    """Writes `enums:`: an open enum for each value table (VAL_) of an unscaled integer
    signal whose values its width holds (a receiver takes values the table does not
    name, as cantools does); signals of one table and type share it, named as the
    file's VAL_TABLE_ of the same values where there is one. The enum of each
    (message's id, signal)."""
    tables = {tuple((int(k), str(v)) for k, v in choices.items()): name
              for name, choices in ((getattr(db.dbc, "value_tables", None) or {}).items() if db.dbc else ())}
    names: dict[tuple[str, tuple], str] = {}
    taken: set[str] = set()
    out: dict[tuple[int, str], str] = {}
    for m in db.messages:
        for s in m.signals:
            if not s.choices or s.is_float or s.scale != 1 or s.offset != 0 or s.is_multiplexer or _unplaceable(s):
                continue
            items = tuple((int(k), str(v)) for k, v in s.choices.items())
            lo, hi = _raw_range(s)
            if not all(lo <= k <= hi for k, _ in items):
                continue  # a value the signal cannot carry: the table stays in its doc
            key = (_type(s), items)
            if key not in names:
                names[key] = distinct(snake(tables.get(items, s.name)), taken, classes)
            out[(id(m), s.name)] = names[key]
    if not names:
        return out
    w.blank()
    w.key("enums", 0)
    for (kind, items), name in names.items():
        w.key(name, 2)
        w.item("type", kind, 4)
        w.item("open", True, 4)
        w.key("values", 4)
        members: set[str] = set()
        for value, text in items:
            member = usable(snake(text), members)
            members.add(member)
            w.flow_item({"name": member, "value": value, "doc": text}, 6)
    return out


def _message(w: Writer, message: Any, roles: dict[str, str], enums: dict[tuple[int, str], str],
             taken: tuple[set[str], set[str]], imported: Imported) -> None:
    where = f"message {message.name} (0x{message.frame_id:X})"
    if message.length not in FD_LENGTHS or message.length == 0 and message.signals:
        w.comment(f"{where}: {message.length} bytes of data, a length CAN does not carry "
                  "(0..8, or the CAN FD steps up to 64)", 2)
        imported.skipped.append(where)
        return
    name = distinct(snake(message.name), *taken)
    imported.messages.append(name)
    w.key(name, 2)
    w.code("id", f"0x{message.frame_id:X}", 4)
    if message.is_extended_frame:
        w.item("extended", True, 4)
    w.item("title", message.name, 4)
    doc = _message_doc(message)
    if doc:
        w.prose("doc", doc, 4)
    if message.senders and message.senders[0] in roles:
        w.item("role", roles[message.senders[0]], 4)
    if not message.length:
        w.code("fields", "[]", 4)
        return
    w.item("payload_bytes", message.length, 4)
    w.key("fields", 4)
    fields: set[str] = set(ENVELOPE_NAMES)
    names: dict[str, str] = {}
    signals = _muxes_first(message.signals)
    for signal in signals:
        names[signal.name] = usable(snake(signal.name), fields)
        fields.add(names[signal.name])
    placed: list[Any] = []
    by_name = {s.name: s for s in signals}
    for signal in signals:
        clash = next((other for other in placed if _overlap(signal, other, by_name)), None)
        if clash is not None:  # cantools reads such a file leniently; codeword refuses overlapping fields
            w.comment(f"signal {signal.name} ({signal.start}|{signal.length}@{'0' if signal.byte_order == 'big_endian' else '1'}) "
                      f"takes bits of {clash.name} in frames that carry both: not carried", 6)
            imported.skipped.append(f"{where} signal {signal.name}")
            continue
        if _signal(w, signal, names, enums.get((id(message), signal.name)), where, imported):
            placed.append(signal)


def _muxes_first(signals: list) -> list:
    """The signals in the file's order, but each after the multiplexor that selects it
    (cantools sorts them by start bit; a codeword field names an earlier one)."""
    out: list = []
    pending = list(signals)
    while pending:
        ready = [s for s in pending if s.multiplexer_signal is None
                 or any(o.name == s.multiplexer_signal for o in out)]
        if not ready:  # a multiplexor the message does not have: the schema's error names it
            ready = pending[:1]
        out.append(ready[0])
        pending.remove(ready[0])
    return out


def _bits(s: Any) -> set[int]:
    """The DBC bit numbers a signal takes (bit k is bit k % 8 of byte k // 8)."""
    if s.byte_order == "little_endian":
        return set(range(s.start, s.start + s.length))
    first = msb_position(s.start)
    return {msb_position(q) for q in range(first, first + s.length)}


def _selectors(s: Any, by_name: dict[str, Any]) -> dict[str, set[int]]:
    """The values of each multiplexor above a signal that a frame carrying it holds."""
    out: dict[str, set[int]] = {}
    while s.multiplexer_signal is not None and s.multiplexer_signal not in out:
        out[s.multiplexer_signal] = set(s.multiplexer_ids or ())
        s = by_name.get(s.multiplexer_signal)
        if s is None:
            break
    return out


def _overlap(a: Any, b: Any, by_name: dict[str, Any]) -> bool:
    """Whether two signals share bits in a frame that may carry both: signals that one
    multiplexor (or one above them) selects for different values never meet."""
    above_a, above_b = _selectors(a, by_name), _selectors(b, by_name)
    exclusive = any(not values & above_b[mux] for mux, values in above_a.items() if mux in above_b)
    return not exclusive and bool(_bits(a) & _bits(b))


def _signal(w: Writer, s: Any, names: dict[str, str], enum: Optional[str], where: str, imported: Imported) -> bool:
    """Writes the field of a signal, or a comment saying why there is none; whether it wrote one."""
    name = names[s.name]
    problem = _unplaceable(s)
    if problem:
        w.comment(f"signal {s.name}: {problem}", 6)
        imported.skipped.append(f"{where} signal {s.name}")
        return False
    w.item("name", name, 6, first=True)
    w.item("type", _type(s), 8)
    w.item("start_bit", s.start, 8)
    w.item("byte_order", "big" if s.byte_order == "big_endian" else "little", 8)
    if s.scale != 1 and not s.is_float:
        w.item("scale", s.scale, 8)
    if s.offset != 0 and not s.is_float:
        w.item("offset", s.offset, 8)
    if s.unit and s.unit.strip():
        w.item("unit", s.unit.strip(), 8)
    if enum is not None:
        w.item("enum", enum, 8)
    initial = _initial(s)
    if initial is not None:
        w.item("default", initial, 8)
    if s.multiplexer_signal is not None and s.multiplexer_ids:
        w.key("multiplexed_by", 8)
        w.item("field", names[s.multiplexer_signal], 10)
        w.code("values", "[" + ", ".join(str(v) for v in s.multiplexer_ids) + "]", 10)
    doc = _signal_doc(s, name, enum is None)
    if doc:
        w.prose("doc", doc, 8)
    if s.is_multiplexer and s.is_signed:
        w.comment("the DBC gives this multiplexor a sign; codeword's are unsigned (the values it selects "
                  "are not negative)", 8)
    return True


def _raw_range(s: Any) -> tuple[int, int]:
    """The raw values a signal's width and sign hold."""
    return (-(1 << (s.length - 1)), (1 << (s.length - 1)) - 1) if s.is_signed else (0, (1 << s.length) - 1)


def _initial(s: Any) -> Optional[float]:
    """A signal's initial value (GenSigStartValue, raw) as the field's default, in
    physical units; none for 0 (the attribute's usual default), a float signal, or a
    signal a frame may leave out (multiplexed) or that selects others."""
    raw = s.raw_initial
    if raw is None or raw == 0 or s.is_float or s.multiplexer_signal is not None or s.is_multiplexer:
        return None
    lo, hi = _raw_range(s)
    if raw != int(raw) or not lo <= raw <= hi:
        return None  # no value of the signal: its doc keeps it
    value = int(raw) * s.scale + s.offset
    if float(value).is_integer() and s.scale == int(s.scale) and s.offset == int(s.offset):
        return int(value)
    short = float(f"{value:.12g}")  # 0.3, not 0.30000000000000004, where it is the same raw value
    return short if round((short - s.offset) / s.scale) == int(raw) else value


def _unplaceable(s: Any) -> Optional[str]:
    """Why a signal cannot be a field, or None."""
    if s.is_float and s.length not in (32, 64):
        return f"a float of {s.length} bits (SIG_VALTYPE_ takes 32 or 64), not carried"
    if s.is_float and (s.scale != 1 or s.offset != 0):
        return "a float signal with scale or offset, not carried"
    if s.length < 1 or s.length > 64:
        return f"an integer of {s.length} bits, not carried"
    return None


def _type(s: Any) -> str:
    if s.is_float:
        return f"f{s.length}"
    signed = s.is_signed and not s.is_multiplexer
    return f"{'i' if signed else 'u'}{s.length}"


def _comment(comment: Any) -> str:
    """A DBC comment as one paragraph (cantools gives a string, or one per language)."""
    if comment is None:
        return ""
    if isinstance(comment, dict):
        comment = next(iter(comment.values()), "")
    return " ".join(str(comment).split())


def _sentence(text: str) -> str:
    """Text that ends as a sentence does, so that the next one can follow it."""
    return text if not text or text[-1] in ".!?" else text + "."


def _doc(dbc_name: str, comment: str, name: str) -> str:
    """A doc that names the DBC's own spelling where codeword's differs."""
    parts = [f"DBC {dbc_name}."] if dbc_name != name else []
    return " ".join(parts + ([_sentence(comment)] if comment else [])) or dbc_name


def _choices_text(choices: Any) -> str:
    return ", ".join(f"{int(k)} = {v}" for k, v in choices.items())


def _message_doc(m: Any) -> str:
    parts = [_sentence(_comment(m.comment))] if _comment(m.comment) else []
    if m.senders:
        parts.append("Sent by " + ", ".join(m.senders) + ".")
    if m.cycle_time:
        parts.append(f"Cycle time {m.cycle_time} ms.")
    if m.send_type:
        parts.append(f"Send type {m.send_type}.")
    attributes = _attributes(m, skip={"GenMsgCycleTime", "GenMsgSendType", "VFrameFormat"})
    if attributes:
        parts.append("DBC attributes: " + attributes + ".")
    for group in m.signal_groups or ():
        parts.append(f"Signal group {group.name}: {', '.join(group.signal_names)}.")
    return " ".join(parts)


def _signal_doc(s: Any, name: str, choices: bool) -> str:
    parts = [f"DBC {s.name}."] if s.name != name else []
    if _comment(s.comment):
        parts.append(_sentence(_comment(s.comment)))
    if s.choices and choices:  # a table its field's enum does not carry
        parts.append("Values: " + _choices_text(s.choices) + ".")
    if s.minimum is not None or s.maximum is not None:
        parts.append(f"Range {number(s.minimum) if s.minimum is not None else '…'} to "
                     f"{number(s.maximum) if s.maximum is not None else '…'} (DBC minimum and maximum).")
    if s.raw_initial is not None and s.raw_initial != 0 and _initial(s) is None:
        parts.append(f"Initial raw value {number(s.raw_initial)}.")
    if s.receivers:
        parts.append("Received by " + ", ".join(s.receivers) + ".")
    attributes = _attributes(s, skip={"GenSigStartValue"})
    if attributes:
        parts.append("DBC attributes: " + attributes + ".")
    return " ".join(parts)


def _attributes(item: Any, skip: set[str]) -> str:
    dbc = getattr(item, "dbc", None)
    if dbc is None or not dbc.attributes:
        return ""
    return ", ".join(f"{k} = {a.value}" for k, a in sorted(dbc.attributes.items()) if k not in skip)
