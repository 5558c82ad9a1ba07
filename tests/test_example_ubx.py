"""examples/ubx.yaml against pyubx2, a widely used UBX implementation: frames that
pyubx2 builds decode to the values pyubx2 reads from them, codeword writes the
same bytes back, pyubx2 reads what codeword writes, in Python and in C, and both
stream decoders find the frames among garbage. Expected bytes come from pyubx2."""
from __future__ import annotations

import dataclasses
import random
import re

import pytest
from pyubx2 import GET, POLL, SET, UBXMessage, UBXReader  # a test extra: pip install -e ".[peers]"
from pyubx2.ubxtypes_get import UBX_PAYLOADS_GET
from pyubx2.ubxtypes_set import UBX_PAYLOADS_SET

from schema_in_a_test import build_example, c_bytes, load, run_c

# pyubx2's (class, name, mode) of each message of the example
MESSAGES = [("ACK", "ACK-ACK", GET), ("ACK", "ACK-NAK", GET), ("CFG", "CFG-RATE", SET),
            ("NAV", "NAV-POSLLH", GET), ("NAV", "NAV-PVT", GET), ("NAV", "NAV-SAT", GET)]
MOST_SATELLITES = 32  # nav_sat's max_count
MOST_EXTENSIONS = 10  # mon_ver's max_count


def random_value(rng: random.Random, spec, width: int):
    """A value of `width` bits for one pyubx2 attribute type ('U004', ('I004', 1e-07)),
    scaled as pyubx2 expects it."""
    kind, scale = (spec, None) if isinstance(spec, str) else spec
    if kind[0] == "I":
        raw = rng.randint(-(1 << (width - 1)), (1 << (width - 1)) - 1)
    else:
        raw = rng.getrandbits(width)
    return raw * scale if scale else raw


def is_repeated_group(spec) -> bool:
    """pyubx2 writes a repeated group as (count attribute, members) and an X type's
    bit fields as ('X004', bits): both a tuple holding a dict."""
    return isinstance(spec, tuple) and isinstance(spec[1], dict) and not spec[0].startswith("X")


def fields(definition: dict, suffix: str = "") -> dict:
    """pyubx2's attributes of a payload with their types and widths in bits, the
    bit fields of its X types flattened (their sizes count bits, not bytes), each
    name with `suffix` (pyubx2 names the k-th block's members `name_0k`); repeated
    groups are left to `repeated_values`."""
    out = {}
    for name, spec in definition.items():
        if is_repeated_group(spec):
            continue
        if isinstance(spec, tuple) and isinstance(spec[1], dict):
            out.update({k + suffix: (v, int(v[1:])) for k, v in spec[1].items()})
        else:
            kind = spec if isinstance(spec, str) else spec[0]
            out[name + suffix] = (spec, 8 * int(kind[1:]))
    return out


def random_values(rng: random.Random, definition: dict, suffix: str = "") -> dict:
    return {k: random_value(rng, spec, width) for k, (spec, width) in fields(definition, suffix).items()}


def repeated_values(rng: random.Random, definition: dict, blocks: int) -> dict:
    """Values of `blocks` blocks of the payload's repeated group counted by an
    attribute, that attribute included (pyubx2 builds them from these keywords)."""
    out = {}
    for spec in (s for s in definition.values() if is_repeated_group(s)):
        count, members = spec
        out[count] = blocks
        for k in range(1, blocks + 1):
            out.update(random_values(rng, members, f"_{k:02}"))
    return out


def block_counts(rng: random.Random, most: int) -> list[int]:
    """None, one, a few and the most blocks a message holds."""
    return [0, 1, rng.randint(2, most - 1), most]


def mon_ver_frame(rng: random.Random, extensions: int) -> bytes:
    """pyubx2 builds MON-VER's extension strings only from a payload (it counts the
    group from the payload's size), so the payload is its strings end to end:
    swVersion (30 bytes), hwVersion (10), then each extension (30); pyubx2 frames it."""
    def text(size: int) -> bytes:
        word = bytes(rng.choice(b"ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789=.; ") for _ in range(rng.randint(0, size)))
        return word.ljust(size, b"\0")[:size]
    payload = text(30) + text(10) + b"".join(text(30) for _ in range(extensions))
    return UBXMessage("MON", "MON-VER", GET, payload=payload).serialize()


def pyubx2_frame(rng: random.Random, cls: str, name: str, mode, blocks: int, zero: frozenset = frozenset()) -> bytes:
    """The frame pyubx2 builds of random values, with `blocks` blocks of a repeated
    group, the members named in `zero` set to 0."""
    table = UBX_PAYLOADS_SET if mode == SET else UBX_PAYLOADS_GET
    values = random_values(rng, table[name])
    values.update(repeated_values(rng, table[name], blocks))
    values.update({k: 0 for k in values if block_member(k) in zero})
    return UBXMessage(cls, name, mode, **values).serialize()


def sample_frames(seed: int) -> list[bytes]:
    rng = random.Random(seed)
    frames = []
    for _ in range(6):
        frames += [pyubx2_frame(rng, *message, blocks=rng.randint(0, 8)) for message in MESSAGES]
        frames.append(UBXMessage("CFG", "CFG-RATE", POLL).serialize())
        frames.append(mon_ver_frame(rng, rng.randint(0, 3)))
    return frames + satellite_frames(rng) + version_frames(rng)


def satellite_frames(rng: random.Random) -> list[bytes]:
    """NAV-SAT with none, one, a few and the most satellites."""
    return [pyubx2_frame(rng, "NAV", "NAV-SAT", GET, n) for n in block_counts(rng, MOST_SATELLITES)]


def version_frames(rng: random.Random) -> list[bytes]:
    """MON-VER with none, one, a few and the most extension strings."""
    return [mon_ver_frame(rng, n) for n in block_counts(rng, MOST_EXTENSIONS)]


def attributes(message) -> dict:
    """A decoded message's values named as pyubx2 names its attributes: the k-th
    element's members of an array of groups as `member_0k`."""
    out = {}
    for field in dataclasses.fields(message):
        value = getattr(message, field.name)
        if isinstance(value, list):
            for k, element in enumerate(value, start=1):
                out.update({f"{f.name}_{k:02}": getattr(element, f.name) for f in dataclasses.fields(element)})
        else:
            out[field.name] = value
    return out


def block_member(attribute: str) -> str:
    """The member's name of pyubx2's name for it in a block (`reserved13_02`)."""
    return re.sub(r"_[0-9]{2}$", "", attribute)


def pyubx2_attributes(parsed) -> dict:
    return {k: v for k, v in vars(parsed).items() if not k.startswith("_")}


def same(ours, theirs) -> bool:
    if isinstance(theirs, float):
        return ours == pytest.approx(theirs, rel=1e-9, abs=1e-12)
    return ours == theirs


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    return build_example("ubx", tmp_path_factory.mktemp("ubx"))


def mode_of(frame: bytes):
    if frame[2:4] == b"\x06\x08":
        return POLL if len(frame) == 8 else SET
    return GET


def test_python_reads_what_pyubx2_reads_and_writes_the_same_bytes(built):
    mod = load(built / "ubx.py")
    for frame in sample_frames(seed=1):
        theirs = pyubx2_attributes(UBXReader.parse(frame, msgmode=mode_of(frame)))
        ours = attributes(mod.decode(frame))
        # every value is one of pyubx2's attributes but reserved bits inside bit fields,
        # which pyubx2 does not keep (the bytes written back below cover them)
        assert {block_member(n) for n in set(ours) - set(theirs)} <= {"valid_spare", "flags3_spare", "reserved",
                                                                     "reserved1", "reserved13"}
        # and pyubx2 keeps nothing codeword drops but the count of satellites, which
        # is the length of the list
        assert set(theirs) - set(ours) <= {"numSvs"}
        if "numSvs" in theirs:
            assert theirs["numSvs"] == len(mod.decode(frame).sv)
        for name in set(ours) & set(theirs):
            assert same(ours[name], theirs[name]), (frame[2:4].hex(), name)
        assert mod.encode(mod.decode(frame)) == frame


def test_every_bytes_like_form_of_a_frame_decodes_alike(built):
    """A frame in a bytearray or a memoryview reads as it does in bytes."""
    mod = load(built / "ubx.py")
    for frame in sample_frames(seed=5):
        want = mod.decode(frame)
        for form in (bytearray(frame), memoryview(frame), memoryview(bytearray(frame))):
            assert mod.decode(form) == want


def test_pyubx2_reads_what_codeword_writes(built):
    mod = load(built / "ubx.py")
    for frame in sample_frames(seed=2):
        again = mod.encode(mod.decode(frame))
        assert UBXReader.parse(again, msgmode=mode_of(frame)).serialize() == frame


def from_pyubx2(cls, group, theirs: dict):
    """Our message of the values pyubx2 read, built without our decoder: the k-th
    element of the array of groups from pyubx2's `member_0k` attributes; the only
    value pyubx2 does not keep, the reserved bit of NAV-SAT, is 0 in these frames."""
    members = [f.name for f in dataclasses.fields(group)]
    blocks = sum(1 for k in theirs if block_member(k) == members[0])
    elements = [group(**{m: theirs.get(f"{m}_{k:02}", 0) for m in members}) for k in range(1, blocks + 1)]
    array, = (f.name for f in dataclasses.fields(cls) if f.name not in theirs)
    return cls(**{f.name: theirs[f.name] for f in dataclasses.fields(cls) if f.name != array}, **{array: elements})


def test_python_writes_pyubx2_bytes_from_the_values_pyubx2_reads(built):
    mod = load(built / "ubx.py")
    rng = random.Random(6)
    satellites = [pyubx2_frame(rng, "NAV", "NAV-SAT", GET, n, zero=frozenset({"reserved13"}))
                  for n in block_counts(rng, MOST_SATELLITES)]
    for frames, cls, group in ((satellites, mod.NavSat, mod.NavSatSv), (version_frames(rng), mod.MonVer, mod.MonVerExt)):
        for frame in frames:
            ours = from_pyubx2(cls, group, pyubx2_attributes(UBXReader.parse(frame)))
            assert mod.encode(ours) == frame


def too_many_satellites(rng: random.Random) -> bytes:
    return pyubx2_frame(rng, "NAV", "NAV-SAT", GET, MOST_SATELLITES + 1)


def payload_of(frame: bytes) -> bytes:
    return UBXReader.parse(frame).payload


def nav_sat_claiming(rng: random.Random, count: int, blocks: int) -> bytes:
    """A NAV-SAT whose numSvs says `count` with `blocks` blocks after it (pyubx2
    frames the payload given)."""
    payload = payload_of(pyubx2_frame(rng, "NAV", "NAV-SAT", GET, blocks))
    return UBXMessage("NAV", "NAV-SAT", GET, payload=payload[:5] + bytes([count]) + payload[6:]).serialize()


def half_an_extension(rng: random.Random) -> bytes:
    return UBXMessage("MON", "MON-VER", GET, payload=payload_of(mon_ver_frame(rng, 1))[:-15]).serialize()


# frames beyond what the schema holds, their message, and the rule and field each
# breaks for the decoder of any frame and for the message's own: a frame of a size
# no message of its id has matches no message (`dispatch`)
REFUSED = [(too_many_satellites, "NavSat", ("dispatch", None), ("length", None)),
           (lambda rng: nav_sat_claiming(rng, MOST_SATELLITES + 1, 2), "NavSat", ("range", "numSvs"),
            ("range", "numSvs")),
           (lambda rng: nav_sat_claiming(rng, 2, 1), "NavSat", ("length", "sv"), ("length", "sv")),
           (lambda rng: mon_ver_frame(rng, MOST_EXTENSIONS + 1), "MonVer", ("dispatch", None), ("length", None)),
           (half_an_extension, "MonVer", ("dispatch", None), ("length", "ext"))]


def test_frames_beyond_the_schema_are_refused(built):
    mod = load(built / "ubx.py")
    rng = random.Random(7)
    for make, message, anyone, own in REFUSED:
        frame = make(rng)
        UBXReader.parse(frame)  # well formed for pyubx2, which holds any count
        for decode, expected in ((mod.decode, anyone), (getattr(mod, message).decode, own)):
            with pytest.raises(mod.DecodeError) as err:
                decode(frame)
            assert (err.value.rule, err.value.field) == expected


def test_encoders_refuse_more_elements_than_the_most(built):
    mod = load(built / "ubx.py")
    sv = mod.decode(pyubx2_frame(random.Random(8), "NAV", "NAV-SAT", GET, 1, zero=frozenset({"reserved13"}))).sv[0]
    with pytest.raises(mod.EncodeError) as err:
        mod.encode(mod.NavSat(iTOW=0, version=1, reserved0=0, sv=[sv] * (MOST_SATELLITES + 1)))
    assert (err.value.rule, err.value.field) == ("count", "sv")
    with pytest.raises(mod.EncodeError) as err:
        mod.encode(mod.MonVer(swVersion=bytes(30), hwVersion=bytes(10),
                              ext=[mod.MonVerExt(extension=bytes(30))] * (MOST_EXTENSIONS + 1)))
    assert (err.value.rule, err.value.field) == ("count", "ext")


def test_a_flipped_checksum_byte_is_refused(built):
    mod = load(built / "ubx.py")
    frame = bytearray(UBXMessage("ACK", "ACK-ACK", GET, clsID=6, msgID=8).serialize())
    frame[-1] ^= 0x40
    with pytest.raises(mod.DecodeError) as err:
        mod.decode(bytes(frame))
    assert (err.value.rule, err.value.field) == ("checksum", "checksum")


def garbage_stream(frames: list[bytes], seed: int = 3) -> bytes:
    rng = random.Random(seed)
    out = b""
    for frame in frames:  # garbage with false starts: B5 alone, B5 62 with an unknown class
        out += rng.choice([b"", b"\xb5", b"\x00\xb5\x00", b"\xb5\x62\x99\x99\x00\x00", bytes([rng.getrandbits(8)])])
        out += frame
    return out


def test_python_stream_finds_every_frame(built):
    mod = load(built / "ubx.py")
    frames = sample_frames(seed=3)
    stream = garbage_stream(frames)
    dec = mod.StreamDecoder()
    found = [x for i in range(0, len(stream), 13) for x in dec.feed(stream[i:i + 13])]
    assert [mod.encode(x) for x in found if not isinstance(x, Exception)] == frames


def raw(spec, value):
    """The integer sent for a value pyubx2 scaled by its type ('I002', 0.1)."""
    return round(value / spec[1]) if isinstance(spec, tuple) else value


SATELLITE = fields(UBX_PAYLOADS_GET["NAV-SAT"]["sv_grp"][1])  # pyubx2's members of a satellite's block
SHOWN = [name for name in SATELLITE if not name.startswith("reserved")]  # those pyubx2 keeps


def values_seen(frame: bytes) -> list[str]:
    """The lines the C driver prints of the values it decoded of a NAV-SAT or MON-VER
    frame, from what pyubx2 reads of it."""
    theirs = pyubx2_attributes(UBXReader.parse(frame))
    if frame[2:4] == b"\x01\x35":
        return ["sat " + " ".join(str(raw(SATELLITE[n][0], theirs[f"{n}_{k:02}"])) for n in SHOWN)
                for k in range(1, theirs["numSvs"] + 1)]
    if frame[2:4] == b"\x0a\x04":
        blocks = sum(1 for k in theirs if block_member(k) == "extension")
        return (["sw " + theirs["swVersion"].hex(), "hw " + theirs["hwVersion"].hex()]
                + ["ext " + theirs[f"extension_{k:02}"].hex() for k in range(1, blocks + 1)])
    return []


def test_c_reads_and_writes_pyubx2_frames(built):
    frames = sample_frames(seed=4)
    stream = garbage_stream(frames, seed=5)
    rng = random.Random(9)
    refused = [make(rng) for make, *_ in REFUSED]

    def table(rows):
        return "\n".join(f"    {{{len(f)}u, {{{c_bytes(f)}}}}}," for f in rows)
    driver = r"""
#include <stdio.h>
#include "ubx.h"
struct frame { size_t len; uint8_t bytes[LONGEST]; };  /* refused frames may be longer than UBX_MAX_FRAME */
static const struct frame frames[] = {
TABLE
};
static const struct frame refused[] = {
REFUSED
};
static const uint8_t stream[] = {STREAM};
static void show(const char *tag, const uint8_t *buf, int n) {
    int i;
    printf("%s", tag);
    for (i = 0; i < n; i++) printf("%02x", buf[i]);
    printf("\n");
}
static void show_values(const ubx_message_t *m) {
    size_t k;
    if (m->kind == UBX_MSG_NAV_SAT) {
        for (k = 0; k < m->as.nav_sat.sv_count; k++) printf("sat SAT_FORMAT\n", SAT_ARGS);
    } else if (m->kind == UBX_MSG_MON_VER) {
        show("sw ", m->as.mon_ver.swVersion, 30);
        show("hw ", m->as.mon_ver.hwVersion, 10);
        for (k = 0; k < m->as.mon_ver.ext_count; k++) show("ext ", m->as.mon_ver.ext[k].extension, 30);
    }
}
int main(void) {
    ubx_message_t m;
    ubx_parser_t p;
    uint8_t out[UBX_MAX_FRAME];
    size_t i;
    int rc, n;
    for (i = 0; i < sizeof frames / sizeof frames[0]; i++) {
        rc = ubx_decode(frames[i].bytes, frames[i].len, UBX_DIR_ANY, &m);
        n = rc == 0 ? ubx_encode(&m, out, sizeof out) : rc;
        if (n < 0) { printf("error %d\n", n); continue; }
        show("", out, n);
        show_values(&m);
    }
    for (i = 0; i < sizeof refused / sizeof refused[0]; i++) {
        printf("refused %s\n", cw_error_name(ubx_decode(refused[i].bytes, refused[i].len, UBX_DIR_ANY, &m)));
    }
    ubx_parser_init(&p, UBX_DIR_ANY);
    for (i = 0; i < sizeof stream; i++) {
        ubx_parser_feed(&p, stream[i]);
        while ((rc = ubx_parser_next(&p, &m)) != 0) {
            if (rc == 1) {
                n = ubx_encode(&m, out, sizeof out);
                show("stream ", out, n);
            }
        }
    }
    return 0;
}
""".replace("TABLE", table(frames)).replace("REFUSED", table(refused)).replace("STREAM", c_bytes(stream))
    driver = driver.replace("LONGEST", str(max(map(len, frames + refused))))
    driver = driver.replace("SAT_FORMAT", " ".join(["%ld"] * len(SHOWN)))
    driver = driver.replace("SAT_ARGS", ", ".join(f"(long)m->as.nav_sat.sv[k].{n}" for n in SHOWN))
    # no debug information: tracking the variables of NAV-SAT's 32 satellites, each
    # value unrolled, takes gcc minutes (the sanitizers stay)
    lines = run_c(built, driver, extra_flags=("-g0",))
    expected = [line for f in frames for line in [f.hex(), *values_seen(f)]]
    assert lines[:len(expected)] == expected
    assert lines[len(expected):len(expected) + len(refused)] == ["refused " + rule for _, _, (rule, _), _ in REFUSED]
    assert lines[len(expected) + len(refused):] == ["stream " + f.hex() for f in frames]
