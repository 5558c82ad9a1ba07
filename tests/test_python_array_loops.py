"""Arrays the generated Python reads and writes in a loop (model.Repeat): the module grows
with the schema and not with the count, and an error inside an element names that element
and its bits in the frame, as one written out element by element did. The schema and frames
are test_c_array_loops's, worked out by hand there: A5, the id, the payload's length, the
payload, then the sum of the bytes from the id to the payload's end, modulo 256. In `tracks`,
n sits in byte 3 and track k fills bytes 4 + 3k .. 6 + 3k: its speed (i16, little-endian),
then a byte holding lane (3 bits), lit (1 bit) and 4 reserved bits, most significant first,
so track k's lane starts at bit 8 * (6 + 3k) and its reserved bits 4 bits later."""
from __future__ import annotations

import pytest

from schema_in_a_test import load, render
from test_c_array_loops import TRACK_LANE_6, TRACKS, schema

# the first track's reserved bits 0001 and the second track's lane 6 (110): sum a5
SPARE_AND_LANE_6 = "a5 01 07 02 fe ff b1 2c 01 c0 a5"


@pytest.fixture(scope="module")
def rally(tmp_path_factory):
    where = tmp_path_factory.mktemp("rally_py")
    render(where, "rally", schema())
    return load(where / "rally.py")


def test_the_module_grows_with_the_schema_not_the_count(tmp_path):
    """Seven times the elements cost no code: only the counts in the module change."""
    sizes = []
    for most, count in ((12, 10), (80, 80)):
        where = tmp_path / str(most)
        where.mkdir()
        render(where, "rally", schema(most, count))
        sizes.append(len((where / "rally.py").read_text(encoding="utf-8")))
    assert abs(sizes[1] - sizes[0]) < 300, sizes


def test_a_wrong_value_in_an_element_names_the_element_and_its_bits(rally):
    with pytest.raises(rally.DecodeError) as caught:
        rally.decode(bytes.fromhex(TRACK_LANE_6))
    e = caught.value
    assert (e.field, e.value, e.rule, e.offset) == ("track[1].lane", 6, "range", 8 * (6 + 3 * 1))


def test_the_first_element_that_is_wrong_is_the_one_reported(rally):
    with pytest.raises(rally.DecodeError) as caught:
        rally.decode(bytes.fromhex(SPARE_AND_LANE_6))
    e = caught.value
    assert (e.field, e.value, e.rule, e.offset) == ("track[0].spare", 1, "reserved", 8 * 6 + 4)


def test_the_encoder_names_the_element_it_refuses(rally):
    tracks = rally.decode(bytes.fromhex(TRACKS))
    tracks.track.append(rally.TracksTrack(speed=1, lane=6, lit=False))
    with pytest.raises(rally.EncodeError) as caught:
        tracks.encode()
    assert (caught.value.field, caught.value.value, caught.value.rule) == ("track[2].lane", 6, "range")
    tracks.track[2] = "not a track"
    with pytest.raises(rally.EncodeError) as caught:
        tracks.encode()
    assert (caught.value.field, caught.value.rule) == ("track[2]", "type")
    table = rally.Table(mode=1, reg=[0] * 10, tail=2)
    table.reg[7] = 0x10000
    with pytest.raises(rally.EncodeError) as caught:
        table.encode()
    assert (caught.value.field, caught.value.value, caught.value.rule) == ("reg[7]", 0x10000, "range")
    table.reg[7] = True  # a bool is no register value, though struct would pack it as 1
    with pytest.raises(rally.EncodeError) as caught:
        table.encode()
    assert (caught.value.field, caught.value.rule) == ("reg[7]", "type")


def test_elements_past_the_count_are_neither_sent_nor_read(rally):
    tracks = rally.Tracks(track=[rally.TracksTrack(speed=-2, lane=5, lit=True)] * 12)
    frame = tracks.encode()
    assert len(frame) == 4 + 3 * 12 + 1 and frame[3] == 12
    assert rally.decode(frame).track == tracks.track
    assert rally.decode(bytes.fromhex("a5 01 01 00 02")).track == []  # n 0: no tracks, sum 01 + 01 + 00
