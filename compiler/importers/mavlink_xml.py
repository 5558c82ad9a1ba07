"""MAVLink XML dialects read into plain records, `<include>`s resolved: the messages
and enums of the dialect and of every file it includes, as mavgen sees them.
The format: https://mavlink.io/en/guide/xml_schema.html"""
from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

# MAVLink's field types and their sizes on the wire
TYPE_SIZES = {"char": 1, "int8_t": 1, "uint8_t": 1, "int16_t": 2, "uint16_t": 2, "int32_t": 4,
              "uint32_t": 4, "int64_t": 8, "uint64_t": 8, "float": 4, "double": 8}
# heartbeat's mavlink_version: a uint8_t the sender fills with the dialect's <version>
VERSION_TYPE = "uint8_t_mavlink_version"


class MavlinkXmlError(Exception):
    """An XML file that is not a MAVLink dialect mavgen would read."""


@dataclass
class Note:
    """Something the XML says that a codeword schema has no key for: a deprecation,
    work in progress, an attribute."""
    text: str


@dataclass
class XmlField:
    name: str
    type: str               # the element type, as mavgen names it (uint8_t, float, char …)
    array_length: int       # 0: not an array
    extension: bool
    doc: str = ""
    units: str = ""
    enum: str = ""
    display: str = ""
    attributes: dict = field(default_factory=dict)  # the others (invalid, multiplier, instance …)
    version_field: bool = False  # uint8_t_mavlink_version

    @property
    def size(self) -> int:
        return TYPE_SIZES[self.type]


@dataclass
class XmlMessage:
    name: str
    id: int
    source: str             # the file that defines it
    doc: str = ""
    fields: list[XmlField] = field(default_factory=list)
    notes: list[Note] = field(default_factory=list)

    @property
    def wire_fields(self) -> list[XmlField]:
        """Wire order: the base fields by type size, largest first (a stable sort), then
        the extension fields as written."""
        base = [f for f in self.fields if not f.extension]
        return sorted(base, key=lambda f: -f.size) + [f for f in self.fields if f.extension]


@dataclass
class XmlEntry:
    name: str
    value: int
    doc: str = ""
    notes: list[Note] = field(default_factory=list)
    params: list[tuple[str, dict, str]] = field(default_factory=list)  # (index, attributes, text)


@dataclass
class XmlEnum:
    name: str
    bitmask: bool
    sources: list[str]
    doc: str = ""
    entries: list[XmlEntry] = field(default_factory=list)
    notes: list[Note] = field(default_factory=list)


@dataclass
class Dialect:
    name: str               # the file's stem: common, ardupilotmega …
    path: Path
    version: int | None = None
    dialect_number: int | None = None
    files: list[str] = field(default_factory=list)   # every file read, includes first
    messages: list[XmlMessage] = field(default_factory=list)
    enums: list[XmlEnum] = field(default_factory=list)
    notes: list[Note] = field(default_factory=list)


def text_of(element: ET.Element | None) -> str:
    """An element's text with its whitespace runs made single spaces."""
    if element is None:
        return ""
    return " ".join("".join(element.itertext()).split())


def lifecycle_notes(element: ET.Element) -> list[Note]:
    """<deprecated>, <superseded> and <wip> of a message, enum or entry, as notes."""
    notes = []
    for tag in ("deprecated", "superseded"):
        for child in element.findall(tag):
            what = f"{tag} since {child.get('since', '?')}"
            if child.get("replaced_by"):
                what += f", replaced by {child.get('replaced_by')}"
            explanation = text_of(child)
            notes.append(Note(f"{what}{': ' + explanation if explanation else ''}"))
    if element.find("wip") is not None:
        notes.append(Note("work in progress (<wip/>): it may still change"))
    return notes


def read_dialect(path: Path) -> Dialect:
    """The dialect at `path` with its includes, as one set of messages and enums."""
    path = Path(path)
    dialect = Dialect(name=path.stem, path=path)
    enums: dict[str, XmlEnum] = {}
    _read_file(path, dialect, enums, seen=set(), top=True)
    dialect.enums = list(enums.values())
    ids: dict[int, str] = {}
    names: set[str] = set()
    for message in dialect.messages:
        if message.id in ids:
            raise MavlinkXmlError(f"{message.source}: message {message.name} has id {message.id}, "
                                  f"as {ids[message.id]} has")
        if message.name in names:
            raise MavlinkXmlError(f"{message.source}: message {message.name} is defined twice")
        ids[message.id] = message.name
        names.add(message.name)
    return dialect


def _read_file(path: Path, dialect: Dialect, enums: dict[str, XmlEnum], seen: set, top: bool) -> None:
    key = path.resolve()
    if key in seen:  # included along two paths (all.xml): read once
        return
    seen.add(key)
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as exc:
        raise MavlinkXmlError(f"{path}: cannot read: {exc}") from None
    if root.tag != "mavlink":
        raise MavlinkXmlError(f"{path}: the root element is <{root.tag}>, not <mavlink>")
    for include in root.findall("include"):
        target = path.parent / text_of(include)
        if not target.is_file():
            raise MavlinkXmlError(f"{path}: <include>{text_of(include)}</include>: no such file beside it")
        _read_file(target, dialect, enums, seen, top=False)
    dialect.files.append(path.name)
    version, number = root.find("version"), root.find("dialect")
    if version is not None:  # the dialect's own, else the last included file's
        dialect.version = int(text_of(version))
    if number is not None and top:
        dialect.dialect_number = int(text_of(number))
    known = {"include", "version", "dialect", "enums", "messages"}
    for child in root:
        if child.tag not in known and isinstance(child.tag, str):
            dialect.notes.append(Note(f"{path.name}: <{child.tag}> is not imported: {text_of(child)[:200]}"))
    for enum in root.iter("enum"):
        _read_enum(enum, path.name, enums)
    for message in root.iter("message"):
        dialect.messages.append(_read_message(message, path.name))


def _read_enum(element: ET.Element, source: str, enums: dict[str, XmlEnum]) -> None:
    name = element.get("name")
    if not name:
        raise MavlinkXmlError(f"{source}: an <enum> without a name")
    bitmask = element.get("bitmask") == "true"
    enum = enums.get(name)
    if enum is None:  # dialects extend an included enum with more entries (mavgen merges them)
        enum = enums[name] = XmlEnum(name, bitmask, [source], text_of(element.find("description")))
    else:
        enum.sources.append(source)
        enum.doc = enum.doc or text_of(element.find("description"))
    enum.notes += lifecycle_notes(element)
    for entry in element.findall("entry"):
        if "value" in entry.attrib:
            value = int(entry.get("value"), 0)
        else:  # mavgen: one more than the highest so far
            value = max((e.value for e in enum.entries), default=-1) + 1
        params = [(p.get("index", "?"), {k: v for k, v in p.attrib.items() if k != "index"}, text_of(p))
                  for p in entry.findall("param")]
        extra = {k: v for k, v in entry.attrib.items() if k not in ("name", "value")}
        notes = lifecycle_notes(entry)
        if extra:
            notes.append(Note(", ".join(f'{k}="{v}"' for k, v in sorted(extra.items()))))
        enum.entries.append(XmlEntry(entry.get("name", ""), value, text_of(entry.find("description")),
                                     notes, params))


def _read_message(element: ET.Element, source: str) -> XmlMessage:
    name, ident = element.get("name"), element.get("id")
    if not name or ident is None:
        raise MavlinkXmlError(f"{source}: a <message> needs a name and an id")
    message = XmlMessage(name, int(ident), source, text_of(element.find("description")),
                         notes=lifecycle_notes(element))
    extension = False
    for child in element:
        if child.tag == "extensions":
            extension = True
        elif child.tag == "field":
            message.fields.append(_read_field(child, message, extension))
    return message


def _read_field(element: ET.Element, message: XmlMessage, extension: bool) -> XmlField:
    name, spelled = element.get("name"), element.get("type", "")
    match = re.fullmatch(r"([a-z0-9_]+)(?:\[(\d+)\])?", spelled)
    if not name or not match:
        raise MavlinkXmlError(f"{message.source}: message {message.name}: field {name!r} has type {spelled!r}")
    base, length = match.group(1), int(match.group(2) or 0)
    version_field = base == VERSION_TYPE
    if version_field:
        base = "uint8_t"
    if base == "array":  # mavgen's old spelling of int8_t arrays
        base = "int8_t"
    if base not in TYPE_SIZES and base + "_t" in TYPE_SIZES:
        base += "_t"
    if base not in TYPE_SIZES:
        raise MavlinkXmlError(f"{message.source}: message {message.name}: field {name}: unknown type {spelled!r}")
    known = {"name", "type", "units", "enum", "display"}
    return XmlField(name, base, length, extension, text_of(element), element.get("units", ""),
                    element.get("enum", ""), element.get("display", ""),
                    {k: v for k, v in element.attrib.items() if k not in known}, version_field)
