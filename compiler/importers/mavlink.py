"""`codeword import mavlink DIALECT.xml`: a MAVLink XML dialect as one codeword schema.

One schema per dialect, its `<include>`s resolved into it: the language has no
includes, and a dialect's wire (message ids, CRC_EXTRA, enum values merged across
files) is only whole with everything it includes, so the schema a person builds is
the dialect as mavgen sees it. A comment names the file each message came from."""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from .mavlink_framing import DOC, FRAME_FLAG_SETS, FRAME_FLAGS, FRAME_MEMBERS, FRAMING
from .mavlink_names import member_name, protocol_name
from .naming import usable
from .mavlink_xml import Dialect, MavlinkXmlError, XmlEnum, XmlField, XmlMessage, read_dialect
from .yaml_writer import Writer

TYPES = {"uint8_t": "u8", "int8_t": "i8", "uint16_t": "u16", "int16_t": "i16", "uint32_t": "u32",
         "int32_t": "i32", "uint64_t": "u64", "int64_t": "i64", "float": "f32", "double": "f64"}
V1_LARGEST_ID = 255  # MAVLink 1's message id is one byte


@dataclass
class ImportedField:
    xml: XmlField
    name: str


@dataclass
class ImportedMessage:
    xml: XmlMessage
    name: str
    fields: list[ImportedField]  # wire order


@dataclass
class Imported:
    protocol: str
    version: int
    dialect: Dialect
    messages: list[ImportedMessage] = field(default_factory=list)
    enum_count: int = 0
    flag_count: int = 0
    text: str = ""

    def summary(self) -> str:
        return f"{len(self.messages)} messages, {self.enum_count} enums, {self.flag_count} flag sets"


def import_dialect(path: Path, version: int = 2) -> Imported:
    """The dialect at `path` as the text of a codeword schema for MAVLink `version` (1 or 2)."""
    if version not in (1, 2):
        raise ValueError(f"MAVLink version {version}: 1 or 2")
    dialect = read_dialect(Path(path))
    imported = Imported(protocol_name(dialect.name), version, dialect)
    w = Writer()
    _header(w, imported)
    enum_names = _enums_and_flags(w, imported)
    _messages(w, imported, enum_names)
    imported.text = w.text()
    return imported


def _header(w: Writer, imported: Imported) -> None:
    d, v = imported.dialect, imported.version
    w.comment(f"MAVLink {v} dialect {d.path.name}, imported by `codeword import mavlink`; the files read, "
              f"includes first: {', '.join(d.files)}.")
    w.comment("One schema for the whole dialect, its <include>s resolved into it: a dialect's messages, ids and "
              "enums are only whole with what it includes, and codeword schemas do not include one another.")
    w.comment("Fields are in MAVLink wire order: the base fields sorted by type size, largest first (stable), "
              "then the extension fields as the XML lists them. Each message's crc_extra is derived by the "
              "compiler from its definition as mavgen derives it (`extra: mavlink`); `mavlink_name` keeps "
              "the name MAVLink hashes where codeword's differs.")
    w.comment("MAVLink enums are open (a receiver takes values it does not know, and dialects add entries): "
              "each is an `open: true` enum, and a field of one has `enum:`, so a value no entry names decodes "
              "as its number. A bitmask enum is a flag set, which is closed: its fields name it in a comment "
              "and their doc rather than with `flags:`, so that every value MAVLink sends decodes. MAVLink sends NaN in "
              "float fields for 'unknown' or 'no change', and any float may be one: every float field is "
              "`finite: false` (NaN and the infinities are values; a NaN is sent as the quiet NaN).")
    if d.dialect_number is not None:
        w.comment(f"<dialect>{d.dialect_number}</dialect>: the dialect's number.")
    for note in d.notes:
        w.comment(note.text)
    w.blank()
    w.item("codeword", 1, 0)
    w.item("protocol", imported.protocol, 0)
    w.item("title", f"MAVLink {v} ({d.name})", 0)
    if d.version is not None:
        w.item("version", str(d.version), 0)
    w.item("source", d.path.name, 0)
    w.prose("doc", " ".join(DOC[v].split()), 0)
    w.blank()
    w.raw(FRAMING[v])


def _type_for(values: list[int], least: int = 8) -> str:
    """The smallest integer type that holds every value."""
    signed = any(x < 0 for x in values)
    for bits in (8, 16, 32, 64):
        if bits < least:
            continue
        lo, hi = (-(1 << (bits - 1)), (1 << (bits - 1)) - 1) if signed else (0, (1 << bits) - 1)
        if all(lo <= x <= hi for x in values):
            return f"{'i' if signed else 'u'}{bits}"
    raise ValueError(f"enum values {min(values)}..{max(values)} do not fit 64 bits")


def _entry_doc(entry) -> str:
    doc = entry.doc
    for index, attrs, text in entry.params:
        label = attrs.get("label", "")
        details = ", ".join(f"{k} {v}" for k, v in sorted(attrs.items()) if k != "label" and v)
        head = f"param {index}" + (f" ({label})" if label else "") + (f" [{details}]" if details else "")
        doc += f"{' ' if doc else ''}{head}: {text or '-'}."
    return doc


def _enums_and_flags(w: Writer, imported: Imported) -> dict[str, str]:
    """Writes `flags:` and `enums:`; the codeword name of each MAVLink enum."""
    v = imported.version
    taken = set(FRAME_FLAGS[v])
    names = {}
    for enum in imported.dialect.enums:
        names[enum.name] = usable(enum.name.lower(), taken)
        taken.add(names[enum.name])
    flag_sets = [e for e in imported.dialect.enums if e.bitmask and _flag_bits(e)]
    if flag_sets or FRAME_FLAG_SETS[v]:
        w.blank()
        w.key("flags", 0)
        w.raw(FRAME_FLAG_SETS[v])
    for enum in flag_sets:
        _flag_set(w, enum, names[enum.name])
        imported.flag_count += 1
    enums = [e for e in imported.dialect.enums if e not in flag_sets]
    if any(e.entries for e in enums):
        w.blank()
        w.key("enums", 0)
    for enum in enums:
        if not enum.entries:
            w.comment(f"enum {enum.name} has no entries in this dialect (a codeword enum needs one): "
                      f"{enum.doc}", 2)
            continue
        _enum(w, enum, names[enum.name])
        imported.enum_count += 1
    return names


def _flag_bits(enum: XmlEnum) -> list:
    """The entries of a bitmask enum that are one bit each."""
    return [e for e in enum.entries if e.value > 0 and e.value & (e.value - 1) == 0]


def _lifecycle(w: Writer, what: str, notes, indent: int) -> None:
    for note in notes:
        w.comment(f"{what}: {note.text}", indent)


def _flag_set(w: Writer, enum: XmlEnum, name: str) -> None:
    bits = _flag_bits(enum)
    if name != enum.name.lower():
        w.comment(f"MAVLink's {enum.name}, renamed: codeword refuses {enum.name.lower()!r}", 2)
    _lifecycle(w, enum.name, enum.notes, 2)
    w.key(name, 2)
    w.item("type", _type_for([1 << max(e.value.bit_length() - 1 for e in bits)]), 4)
    if enum.doc:
        w.prose("doc", enum.doc, 4)
    w.key("bits", 4)
    taken: set = set()
    for entry in enum.entries:
        if entry not in bits:
            w.comment(f"{entry.name} = {entry.value}: not a single bit, which a flag set cannot name; "
                      f"{_entry_doc(entry)}", 6)
            continue
        member = member_name(entry.name, enum.name, taken)
        taken.add(member)
        _member(w, entry, member, {"bit": entry.value.bit_length() - 1})


def _enum(w: Writer, enum: XmlEnum, name: str) -> None:
    if name != enum.name.lower():
        w.comment(f"MAVLink's {enum.name}, renamed: codeword refuses {enum.name.lower()!r}", 2)
    if enum.bitmask:
        w.comment(f"{enum.name} is a bitmask enum, but none of its entries is a single bit: an enum here", 2)
    _lifecycle(w, enum.name, enum.notes, 2)
    w.key(name, 2)
    w.item("type", _type_for([e.value for e in enum.entries]), 4)
    w.item("open", True, 4)
    if enum.doc:
        w.prose("doc", enum.doc, 4)
    w.key("values", 4)
    taken: set = set()
    seen: dict[int, str] = {}
    for entry in enum.entries:
        if entry.value in seen:
            w.comment(f"{entry.name} = {entry.value}, the value of {seen[entry.value]} too: an enum names a "
                      f"value once; {_entry_doc(entry)}", 6)
            continue
        seen[entry.value] = entry.name
        member = member_name(entry.name, enum.name, taken)
        taken.add(member)
        _member(w, entry, member, {"value": entry.value})


def _member(w: Writer, entry, member: str, where: dict) -> None:
    _lifecycle(w, entry.name, entry.notes, 6)
    if member != entry.name.lower() and not entry.name.lower().endswith("_" + member):
        w.comment(f"MAVLink's {entry.name}", 6)
    w.item("name", member, 6, first=True)
    for k, v in where.items():
        w.item(k, v, 8)
    doc = _entry_doc(entry)
    if doc:
        w.prose("doc", doc, 8)


def _messages(w: Writer, imported: Imported, enum_names: dict[str, str]) -> None:
    v = imported.version
    if v == 1 and not any(m.id <= V1_LARGEST_ID for m in imported.dialect.messages):
        raise MavlinkXmlError(f"{imported.dialect.path.name}: no message has an id up to {V1_LARGEST_ID}, "
                              "so MAVLink 1 carries none of them: import it for MAVLink 2")
    if not imported.dialect.messages:
        raise MavlinkXmlError(f"{imported.dialect.path.name}: no messages (a schema needs one)")
    w.blank()
    w.key("messages", 0)
    taken: set = set()
    source = None
    for message in imported.dialect.messages:
        if message.source != source:
            source = message.source
            w.blank()
            w.comment(f"from {source}", 2)
        if v == 1 and message.id > V1_LARGEST_ID:
            w.comment(f"{message.name} (id {message.id}) is not imported: MAVLink 1's message id is one byte "
                      f"(ids up to {V1_LARGEST_ID})", 2)
            continue
        name = usable(message.name.lower(), taken)
        taken.add(name)
        _message(w, imported, message, name, enum_names)


def _open_enum(imported: Imported, f: XmlField) -> bool:
    """Whether the field's MAVLink enum is written as an open enum its values fit."""
    enum = next((e for e in imported.dialect.enums if e.name == f.enum), None)
    if enum is None or not enum.entries or enum.bitmask and _flag_bits(enum) or f.type not in TYPES \
            or TYPES[f.type][0] not in "ui":
        return False
    bits = int(TYPES[f.type][1:])
    lo, hi = (-(1 << (bits - 1)), (1 << (bits - 1)) - 1) if TYPES[f.type][0] == "i" else (0, (1 << bits) - 1)
    return all(lo <= e.value <= hi for e in enum.entries)


def _message(w: Writer, imported: Imported, message: XmlMessage, name: str, enum_names: dict[str, str]) -> None:
    v = imported.version
    if name != message.name.lower():
        w.comment(f"MAVLink's {message.name}, renamed: codeword refuses {message.name.lower()!r}", 2)
    _lifecycle(w, message.name, message.notes, 2)
    w.key(name, 2)
    w.item("id", message.id, 4)
    if name.upper() != message.name:
        w.item("mavlink_name", message.name, 4)
    if message.doc:
        w.prose("doc", message.doc, 4)
    fields = message.wire_fields
    dropped = [f for f in fields if f.extension and v == 1]
    fields = [f for f in fields if not (f.extension and v == 1)]
    taken = set(FRAME_MEMBERS[v])
    out = []
    if not fields:
        w.comment("no fields", 4)
        w.key("fields", 4)
        w.lines[-1] += " []"
    else:
        w.key("fields", 4)
    for f in fields:
        fname = usable(f.name, taken)
        taken.add(fname)
        out.append(ImportedField(f, fname))
        _field(w, f, fname, enum_names, _open_enum(imported, f))
    if dropped:
        w.comment(f"MAVLink 1 has no extension fields: {', '.join(f.name for f in dropped)} not imported", 6)
    imported.messages.append(ImportedMessage(message, name, out))


def _field(w: Writer, f: XmlField, name: str, enum_names: dict[str, str], open_enum: bool) -> None:
    notes = []
    if name != f.name:
        notes.append(f"MAVLink's {f.name}, renamed: codeword refuses {f.name!r} here")
    if f.enum and not open_enum:
        notes.append(f"values: MAVLink enum {f.enum}" + (f" (codeword {enum_names[f.enum]})" if f.enum in enum_names
                                                         else " (not in this dialect)"))
    if f.display:
        notes.append(f'display="{f.display}"')
    for k, value in sorted(f.attributes.items()):
        notes.append(f'{k}="{value}"')
    if f.version_field:
        notes.append("uint8_t_mavlink_version: the sender writes the dialect's <version> here")
    if f.type == "char" and not f.array_length:
        notes.append("char: one byte, any value (bytes of length 1)")
    for note in notes:
        w.comment(note, 6)
    item: dict = {"name": name}
    if f.type == "char":
        item.update(type="bytes", length=f.array_length or 1)
    else:
        item["type"] = TYPES[f.type]
        if f.array_length:
            item["count"] = f.array_length
    if name != f.name:
        item["mavlink_name"] = f.name
    if f.units:
        item["unit"] = f.units
    if open_enum:
        item["enum"] = enum_names[f.enum]
    if f.type in ("float", "double"):
        item["finite"] = False
    if f.extension:
        item["extension"] = True
    doc = f.doc
    if f.type == "char" and f.array_length:
        doc = f"{doc}{' ' if doc else ''}(text, NUL-padded)".strip()
    if f.enum and not open_enum:
        doc = f"{doc}{' ' if doc else ''}Values: {f.enum}."
    first = True
    for k, value in item.items():
        w.item(k, value, 6 if first else 8, first=first)
        first = False
    if doc:
        w.prose("doc", doc, 8)
