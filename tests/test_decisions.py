"""One test (at least) per numbered decision of PROTOCOLS.md, named after it.

Expected wire values come from the seeds or from hand calculation, written out
in the comments; CRC values are checked against the reference bitwise
implementation in codeword.crc, itself checked against the RevEng catalogue.
"""
from __future__ import annotations

import dataclasses

import pytest

from codeword import crc
from conftest import DATA, load_model


def seed_route_lines() -> str:
    """Lines 4-14 of the route seed: its example exchange file, verbatim."""
    text = (DATA / "seeds" / "000_2b5d4a2b27f09abb.txt").read_text(encoding="utf-8")
    return "\n".join(text.splitlines()[3:14]) + "\n"


# ---------------------------------------------------------------- route

def test_ROUTE_D1_checksum_is_sum_of_fields_mod_8(route):
    # start: 11 001 100 -> CS = (3 + 1) mod 8 = 4 -> 0xCC
    assert route.encode(route.Start()) == bytes([0b11001100])
    # end: 11 010 101 -> CS = (3 + 2) mod 8 = 5 -> 0xD5
    assert route.encode(route.End()) == bytes([0b11010101])
    assert route.encode_text(route.Start()) == "3 1 4"


def test_ROUTE_D2_text_accepts_unfilled_checksum_bits_do_not(route):
    # seed line 13, CS written as 0 ("not filled in"): accepted in text
    obj = route.decode_text("1 3 1 0 4 2 3 2 4 0")
    assert (obj.ns, obj.nl, obj.na, obj.rc) == (3, 1, 14, 3)
    # writers always fill it in: (1+3+1+0+4+2+3+2+4) mod 8 = 4
    assert route.encode_text(obj) == "1 3 1 0 4 2 3 2 4 4"
    # a wrong non-zero checksum in text is an error
    with pytest.raises(route.DecodeError) as err:
        route.decode_text("1 3 1 0 4 2 3 2 4 3")
    assert (err.value.field, err.value.rule) == ("cs", "checksum")
    # in the bit form CS must be correct: 59 11 69 20 has CS=100; CS=000 -> 59 11 69 00
    assert route.decode(bytes.fromhex("59116920")) == obj
    with pytest.raises(route.DecodeError) as err:
        route.decode(bytes.fromhex("59116900"))
    assert (err.value.field, err.value.rule) == ("cs", "checksum")


def test_ROUTE_D3_seed_file_gives_exactly_four_rc_errors(route):
    with pytest.raises(route.SequenceError) as err:
        route.decode_route_text(seed_route_lines())
    found = [(e.line, e.field, e.rule, e.value) for e in err.value.errors]
    # object lines 2, 4, 6, 8 of the block carry rc = 5, 4, 5, 5 (2-bit field: 0..3)
    assert found == [(2, "rc", "range", 5), (4, "rc", "range", 4),
                     (6, "rc", "range", 5), (8, "rc", "range", 5)]


def test_ROUTE_D4_left_aligned_word_and_bytes(route):
    start = route.Start()
    # 8-bit sentence 0xCC left-aligned in a 30-bit word: 0xCC << 22
    assert route.encode_word(start) == 0xCC << 22 == 0x33000000
    obj = route.Object(ns=0, nl=0, no=0, na=12, dl=2, rc=1, dr=2, cm=5)
    # 29 bits 01 000 000 000 010 010 01 010 0101 101 -> + 3 zero bits = 40 09 29 68
    assert route.encode(obj) == bytes.fromhex("40092968")
    assert route.encode_word(obj) == 0x40092968 >> 2
    assert route.decode_word(0x40092968 >> 2) == obj
    with pytest.raises(route.DecodeError):
        route.decode_word((0xCC << 22) | 1)  # low bits must be zero
    with pytest.raises(route.DecodeError):
        route.decode(bytes.fromhex("40092969"))  # padding bit set


def _route(route, scenes):
    return route.Route(start=route.Start(), end=route.End(),
                       scenes=[route.RouteScenes(objects=objs, scene=sc) for objs, sc in scenes])


def test_ROUTE_D5_route_grammar_and_cross_rules(route):
    o = route.Object
    s = route.Scene
    good = _route(route, [([o(ns=0, nl=0, no=0, na=12, dl=2, rc=1, dr=2, cm=5)],
                           s(ns=0, nl=0, db=route.PassSide.right, nt=720))])
    # start cc | object 40 09 29 68 | scene 80 60 b4 28 | end d5 (hand calculation)
    wire = bytes.fromhex("cc 40092968 8060b428 d5")
    assert route.encode_route(good) == wire
    assert route.decode_route(wire) == good

    def rules_broken(seq):
        with pytest.raises(route.SequenceError) as err:
            route.encode_route(seq)
        return {(e.rule, e.decision) for e in err.value.errors}

    # scene numbers consecutive from 0
    bad = _route(route, [([o(ns=1, nl=0, no=0, na=12, dl=2, rc=1, dr=2, cm=5)],
                          s(ns=1, nl=0, db=route.PassSide.right, nt=720))])
    assert ("consecutive", "ROUTE-D5") in rules_broken(bad)
    # every object's ns equals its scene's ns
    bad = _route(route, [([o(ns=2, nl=0, no=0, na=12, dl=2, rc=1, dr=2, cm=5)],
                          s(ns=0, nl=0, db=route.PassSide.right, nt=720))])
    assert ("equal", "ROUTE-D5") in rules_broken(bad)
    # the scene's reference landmark occurs among its objects
    bad = _route(route, [([o(ns=0, nl=1, no=0, na=12, dl=2, rc=1, dr=2, cm=5)],
                          s(ns=0, nl=0, db=route.PassSide.right, nt=720))])
    assert ("member", "ROUTE-D5") in rules_broken(bad)
    # (ns, nl, no) unique
    twice = o(ns=0, nl=0, no=0, na=12, dl=2, rc=1, dr=2, cm=5)
    bad = _route(route, [([twice, twice], s(ns=0, nl=0, db=route.PassSide.right, nt=720))])
    assert ("unique", "ROUTE-D5") in rules_broken(bad)
    # start first and end last
    with pytest.raises(route.SequenceError) as err:
        route.decode_route(bytes.fromhex("40092968 8060b428 d5"))
    assert err.value.errors[0].rule == "grammar"
    with pytest.raises(route.SequenceError):
        route.decode_route(bytes.fromhex("cc 40092968 8060b428"))


def test_ROUTE_D6_marker_number_offset(route):
    # wire na = 2 means ArUco marker 12 (seed: "minus 10")
    assert route.decode(bytes.fromhex("40092968")).na == 12
    bad = route.Object(ns=0, nl=0, no=0, na=9, dl=2, rc=1, dr=2, cm=5)
    with pytest.raises(route.EncodeError) as err:
        route.encode(bad)
    assert (err.value.field, err.value.rule, err.value.decision) == ("na", "range", "ROUTE-D6")


def test_ROUTE_TEXT_blank_and_comment_lines_are_ignored(route):
    lines = list(route.decode_lines("# a route\n\n3 1 4\n   \n3 2 5\n"))
    assert [(n, type(m).__name__) for n, m in lines] == [(3, "Start"), (5, "End")]


# ---------------------------------------------------------------- car

CAR_TABLE_WORD = """\
codeword: 1
protocol: car_table
title: control word as the seed's summary table gives it
source: 001_9270a2f3f56adf32.txt
framing: {kind: bits, word_bits: 32, byte_order: big}
messages:
  control:
    fields:
      - {name: c1, type: bool}
      - {name: c2, type: bool}
      - name: c3
        type: group
        fields:
          - {name: enable, type: bool}
          - {name: direction, type: u2}
          - {name: speed, type: u2}
          - {name: duration, type: u2}
      - {name: c4, type: u4}
      - {name: c5, type: u5}
      - {name: c6, type: bool}
      - {name: c7, type: bool}
      - {name: c8, type: u12, reserved: true}
      - {name: c9, type: u1, checksum: {algorithm: parity, parity: even, covers: all}}
"""


def test_CAR_D1_widths_add_up_to_32_and_the_table_reading_is_rejected(tmp_path):
    model = load_model("car")
    for name in ("header", "master_control", "slave_control"):
        assert model.message(name).bits == 32
    motor = next(f for f in model.message("master_control").layout if f.name == "motor")
    assert motor.bits == 7
    from codeword.build import compile_schema
    from codeword.diagnostics import SchemaError
    path = tmp_path / "car_table.yaml"
    path.write_text(CAR_TABLE_WORD, encoding="utf-8")
    with pytest.raises(SchemaError) as err:
        compile_schema(path)
    (diagnostic,) = err.value.diagnostics
    assert "33 bits" in diagnostic.message and "32" in diagnostic.message
    assert diagnostic.loc.line == 8  # the `fields:` of message `control`


def _master(car, **changes):
    word = car.from_dict("master_control", {
        "accept_ir": False, "forward_words": True,
        "motor": {"enable": False, "direction": "forward", "speed": 0, "duration": 0},
        "led": {"led": 0, "duration": 0},
        "ultrasonic": {"enable": False, "radius": 0, "duration": 0},
        "voice": False, "body_sensor": False})
    return dataclasses.replace(word, **changes)


def test_CAR_D2_even_parity_over_the_word(car):
    # only c2 set: one 1 bit, so c9 = 1 -> 0100 0000 ... 0001
    word = _master(car)
    assert car.encode(word) == bytes.fromhex("40000001")
    assert car.MasterControl.decode(bytes.fromhex("40000001")) == word
    with pytest.raises(car.DecodeError) as err:
        car.MasterControl.decode(bytes.fromhex("40000000"))
    assert (err.value.field, err.value.rule) == ("parity", "checksum")


def test_CAR_D3_one_hot_send_time(car):
    # h1=255, h2_count=3, h2_time level 7 -> 1<<7 = 0x80: ff 03 80 00
    header = car.Header(h1=255, h2_count=3, h2_time=7)
    assert car.encode(header) == bytes.fromhex("ff038000")
    assert car.Header.decode(bytes.fromhex("ff038000")) == header
    with pytest.raises(car.DecodeError) as err:
        car.Header.decode(bytes.fromhex("ff038100"))  # two bits: not one-hot
    assert err.value.rule == "one_hot"
    with pytest.raises(car.EncodeError) as err:
        car.encode(car.Header(h1=1, h2_count=0, h2_time=1))
    assert err.value.decision == "CAR-D3"
    with pytest.raises(car.DecodeError) as err:
        car.Header.decode(bytes.fromhex("01020000"))  # slave words but h2_time 0
    assert err.value.decision == "CAR-D3"


def test_CAR_D4_most_significant_byte_first(car):
    # h1 is the top byte of the header word and goes first on the line
    assert car.encode(car.Header(h1=4, h2_count=0, h2_time=None)) == bytes([4, 0, 0, 0])


def test_car_h1_limit_uses_the_seed_message(car):
    with pytest.raises(car.EncodeError) as err:
        car.encode(car.Header(h1=256, h2_count=0, h2_time=None))
    assert "所用的并行模块数目已经大于255" in err.value.user_message


def test_CAR_R1_master_never_accepts_infrared(car):
    with pytest.raises(car.EncodeError) as err:
        car.encode(_master(car, accept_ir=True))
    assert err.value.decision == "CAR-R1" and "无法设置主机接受红外信息" in err.value.user_message
    # 1100 0000 ... 0000: c1 and c2 set, two ones, parity 0
    with pytest.raises(car.DecodeError) as err:
        car.MasterControl.decode(bytes.fromhex("c0000000"))
    assert err.value.decision == "CAR-R1"
    # the same word is a valid slave word
    assert car.SlaveControl.decode(bytes.fromhex("c0000000")).accept_ir is True


def test_CAR_R2_master_always_forwards(car):
    # all zero: no ones, parity 0; c2 = 0 is refused in a master word only
    with pytest.raises(car.DecodeError) as err:
        car.MasterControl.decode(bytes.fromhex("00000000"))
    assert err.value.decision == "CAR-R2"
    assert car.SlaveControl.decode(bytes.fromhex("00000000")).forward_words is False


def test_car_program_counts(car):
    # header 02 01 04 00 (h1=2, one slave word, level 2), words from the schema's hand calculation
    wire = bytes.fromhex("02010400 67000001 40781000 b2848001")
    program = car.decode_program(wire)
    assert len(program.master) == 2 and len(program.slaves) == 1
    assert car.encode_program(program) == wire
    with pytest.raises(car.SequenceError) as err:
        car.decode_program(wire[:-4])  # a slave word missing
    assert err.value.errors[0].rule == "count"
    program.master.pop()
    with pytest.raises(car.EncodeError) as err:
        car.encode_program(program)
    assert err.value.rule == "count"


# ---------------------------------------------------------------- tank

SEED_LINE = "%:f,100,s,10,1,0,0,0,1;"


def test_TANK_D1_data_is_optional(tank):
    cmd = tank.decode(SEED_LINE)
    assert (cmd.move, cmd.speed, cmd.value, cmd.azimutloc) == (tank.Move.forward, 100, "s", 10)
    assert (cmd.gpio1, cmd.gpio2, cmd.gpio3, cmd.gpio4) == (1, 0, 0, 0)
    assert cmd.systemstatus == tank.SystemStatus.work and cmd.data is None
    assert tank.encode(cmd) == SEED_LINE
    with_data = dataclasses.replace(cmd, data="lights")
    assert tank.encode(with_data) == "%:f,100,s,10,1,0,0,0,1,lights;"
    with pytest.raises(tank.DecodeError) as err:
        tank.decode("%:f,100,s,10,1,0,0,0;")
    assert err.value.rule == "count"


def test_TANK_D2_status_5_and_6_only_from_the_platform(tank):
    for status in (5, 6):
        with pytest.raises(tank.DecodeError) as err:
            tank.decode(f"%:f,100,s,10,1,0,0,0,{status};")
        assert err.value.field == "systemstatus"
        assert "TANK-D2" in (err.value.decision, err.value.rule)
    telemetry = "$:f,0,s,0,0,0,0,0,0,0,0,0,0,0,55.7,37.6,12,6,0,1;"
    assert tank.decode(telemetry).systemstatus == tank.SystemStatus.exception


def test_TANK_D3_speed_range_and_any_value_char(tank):
    with pytest.raises(tank.DecodeError) as err:
        tank.decode("%:f,101,s,10,1,0,0,0,1;")
    assert (err.value.field, err.value.rule) == ("speed", "range")
    assert tank.decode("%:f,0,#,10,1,0,0,0,1;").value == "#"


def test_TANK_D4_whitespace_in_crlf_between(tank):
    cfg = tank.decode("-:1, 2, 0, 3;")
    assert [cfg.gpio1, cfg.gpio2, cfg.gpio3, cfg.gpio4] == [1, 2, 0, 3]
    assert tank.encode(cfg) == "-:1,2,0,3;"
    stream = tank.StreamDecoder()
    got = stream.feed("-:1,2,0,3;\r\n" + SEED_LINE[:7]) + stream.feed(SEED_LINE[7:] + "\r\n")
    assert [type(x).__name__ for x in got] == ["GpioConfig", "Command"]


def test_TANK_D5_writers_reject_separators_in_strings(tank):
    cmd = dataclasses.replace(tank.decode(SEED_LINE), data="a,b")
    with pytest.raises(tank.EncodeError) as err:
        tank.encode(cmd)
    assert err.value.field == "data"
    with pytest.raises(tank.EncodeError):
        tank.encode(dataclasses.replace(cmd, data="a;b"))


def test_TANK_D6_shortest_float_text(tank):
    cmd = dataclasses.replace(tank.decode(SEED_LINE), gpio1=0.1, gpio2=2.5, gpio3=-3.0, gpio4=1e-7)
    assert tank.encode(cmd) == "%:f,100,s,10,0.1,2.5,-3,1e-07,1;"
    assert tank.decode("%:f,100,s,10,1.5e2,.5,-0.0,7.,1;").gpio1 == 150.0
    with pytest.raises(tank.DecodeError) as err:
        tank.decode("%:f,100,s,10,0x1,0,0,0,1;")
    assert (err.value.field, err.value.rule) == ("gpio1", "syntax")


def test_TANK_D7_payload_command_runs_to_the_terminator(tank):
    msg = tank.decode("*:go,left 10;")
    assert msg.command == "go,left 10"
    assert tank.encode(msg) == "*:go,left 10;"


# ---------------------------------------------------------------- mtv4

# Seed layout, group 3, robot 5, SetWheelsVelocities VL=100.5 (804 = 0x0324), VR=-20 (-160 = 0xFF60)
SWV = bytes.fromhex("aa 08 03 01 20 00 24 03 60 ff") 


def with_crc(body: bytes) -> bytes:
    params = crc.lookup("CRC-16/CMS")
    return body + crc.compute(params, body[1:]).to_bytes(2, "big")


def test_MTV4_D1_crc16_cms_over_b1_to_bn2_big_endian(mtv4):
    params = crc.lookup("CRC-16/CMS")
    assert (params.poly, params.init, params.refin, params.xorout) == (0x8005, 0xFFFF, False, 0)
    assert crc.compute(params, b"123456789") == 0xAEE7
    frame = with_crc(SWV)
    msg = mtv4.decode(frame)
    assert (msg.group, msg.robots, msg.vl, msg.vr) == (3, mtv4.Robots.robot5, 100.5, -20.0)
    assert mtv4.encode(msg) == frame


def test_MTV4_D2_ack_crc_covers_b1_to_b5(mtv4):
    body = bytes.fromhex("aa 04 03 01 20 00")  # ack of 0x01 from robot 5, group 3
    frame = with_crc(body)
    ack = mtv4.decode(frame, "robot_to_host")
    assert (ack.command, ack.group) == (1, 3)
    params = crc.lookup("CRC-16/CMS")
    seed_literal = body[:4] + body[4:] + crc.compute(params, body[1:4]).to_bytes(2, "big")
    with pytest.raises(mtv4.DecodeError) as err:
        mtv4.decode(seed_literal, "robot_to_host")  # the seed's B1..B3 reading is rejected
    assert err.value.rule == "checksum"


def test_MTV4_D3_robot_mask_little_endian_one_bit(mtv4):
    msg = mtv4.decode(with_crc(SWV))
    moved = dataclasses.replace(msg, robots=mtv4.Robots.robot12)
    assert mtv4.encode(moved)[4:6] == bytes([0x00, 0x10])  # bit 12 -> B5 bit 4
    with pytest.raises(mtv4.EncodeError) as err:
        mtv4.encode(dataclasses.replace(msg, robots=mtv4.Robots.robot1 | mtv4.Robots.robot2))
    assert err.value.rule == "exactly_one"
    with pytest.raises(mtv4.DecodeError) as err:
        mtv4.decode(with_crc(SWV[:4] + bytes([0x21, 0x00]) + SWV[6:]))
    assert err.value.rule == "exactly_one"


def test_MTV4_D4_command_bit7_is_reported_not_dispatched(mtv4):
    frame = with_crc(SWV[:3] + bytes([0x81]) + SWV[4:])
    msg = mtv4.decode(frame)
    assert type(msg) is mtv4.SetWheelsVelocities and msg.radio_crc_flag == 1
    assert mtv4.encode(dataclasses.replace(msg, radio_crc_flag=0)) == with_crc(SWV)


def test_MTV4_D5_velocity_range_and_rounding(mtv4):
    msg = mtv4.decode(with_crc(SWV))
    for bad in (4096.0, -4096.125, 5000):
        with pytest.raises(mtv4.EncodeError) as err:
            mtv4.encode(dataclasses.replace(msg, vl=bad))
        assert (err.value.field, err.value.rule) == ("vl", "range")
    # 100.05 mm/s * 8 = 800.4 -> 800 = 0x0320 (nearest 1/8)
    assert mtv4.encode(dataclasses.replace(msg, vl=100.05))[6:8] == bytes([0x20, 0x03])
    # 4095.875 is the largest: 32767 = 0x7FFF
    assert mtv4.encode(dataclasses.replace(msg, vl=4095.875))[6:8] == bytes([0xFF, 0x7F])


def test_MTV4_D6_length_checked_and_stream_resynchronises(mtv4):
    with pytest.raises(mtv4.DecodeError) as err:
        mtv4.decode(with_crc(SWV[:1] + bytes([0x09]) + SWV[2:]) + b"\0")
    assert err.value.rule in ("length", "dispatch")
    good = with_crc(SWV)
    corrupt = good[:-1] + bytes([good[-1] ^ 1])
    stream = mtv4.StreamDecoder()
    out = stream.feed(b"\x00\x13\xaa" + corrupt + good[:5]) + stream.feed(good[5:] + good)
    frames = [x for x in out if not isinstance(x, mtv4.DecodeError)]
    errors = [x for x in out if isinstance(x, mtv4.DecodeError)]
    assert len(frames) == 2 and all(f == mtv4.decode(good) for f in frames)
    assert len(errors) == 1  # garbage and the corrupt frame after it: one stretch, one error
    # between two good frames, the corrupt one is its own stretch: its checksum error is the one given
    out = mtv4.StreamDecoder().feed(good + corrupt + good)
    assert [getattr(x, "rule", "frame") for x in out] == ["frame", "checksum", "frame"]


def test_MTV4_D7_code_3_per_direction(mtv4):
    model = load_model("mtv4")
    by_code = {(m.direction, m.ids) for m in model.messages if 3 in m.ids}
    assert by_code == {("host_to_robot", (3,)), ("robot_to_host", (3,))}
    # odometry reply: status 0, X=1.5, Y=-0.25, Th=3.140625 (binary32 little endian)
    body = (bytes.fromhex("aa 12 03 03 20 00 00 00") + bytes.fromhex("0000c03f")
            + bytes.fromhex("000080be") + bytes.fromhex("00004940"))
    reply = mtv4.decode(with_crc(body), "robot_to_host")
    assert type(reply) is mtv4.OdometryReply and (reply.x, reply.y, reply.th) == (1.5, -0.25, 3.140625)


def test_MTV4_D8_odometry_command_is_answered_by_the_odometry_reply_only(mtv4):
    model = load_model("mtv4")
    assert model.message("set_wheels_velocities_with_odometry").answered_by == ("odometry_reply",)
    # a 4-byte acknowledgement carrying code 0x03 is not a valid reply
    with pytest.raises(mtv4.DecodeError) as err:
        mtv4.decode(with_crc(bytes.fromhex("aa 04 03 03 20 00")), "robot_to_host")
    assert err.value.rule == "dispatch"


# ---------------------------------------------------------------- tr24

def test_TR24_D1_packet_bytes(tr24):
    # the seed's master example: command[0] = 44, 7 data bytes; seq 0 from 1 to 3
    wire = bytes.fromhex("02 00 01 03 2c 00 00 00 00 00 00 03")
    cmd = tr24.decode(wire)
    assert (cmd.seq, cmd.sender, cmd.receiver, cmd.data[0]) == (0, 1, 3, 44)
    assert tr24.encode(cmd) == wire
    reply = tr24.Reply(seq=1, sender=3, receiver=1, data=bytes(7))
    assert tr24.encode(reply)[:2] == bytes([0x02, 0b10 | 0b01])  # type bit 1, seq bit 0
    with pytest.raises(tr24.DecodeError) as err:
        tr24.decode(bytes([0x02, 0x04]) + wire[2:])  # a reserved service bit set
    assert err.value.rule == "reserved"
    model = load_model("tr24")
    assert model.message("command").size + 59 - 7 <= 64  # L <= 59 keeps a packet in the FIFO


def _machine(name):
    return next(m for m in load_model("tr24").machines if m.name == name)


def _actions(machine, state, event):
    st = next(s for s in machine.states if s.name == state)
    handler = next(h for h in st.handlers if h.event == event)
    return [(dict((c.path, (c.op, c.value)) for c in t.guard), t.actions) for t in handler.transitions]


def test_TR24_D2_slave_resends_its_cached_reply_for_a_duplicate():
    rows = _actions(_machine("slave"), "listening", "receive")
    duplicate = next(actions for guard, actions in rows if guard.get("seq", ("",))[0] == "ne_var")
    assert duplicate == ("resend_cached",)
    fresh = next(actions for guard, actions in rows if guard.get("seq", ("",))[0] == "eq_var")
    assert "execute" in fresh and "cache_reply" in fresh


def test_TR24_D3_packets_for_other_ids_are_ignored():
    for machine, state in (("slave", "listening"), ("master", "waiting")):
        rows = _actions(_machine(machine), state, "receive")
        guarded = [guard for guard, _ in rows if guard]
        assert all(g.get("receiver") == ("eq_param", "own_id") for g in guarded)
        assert rows[-1] == ({}, ()) or rows[-1][1] == ()  # otherwise: nothing happens


def test_TR24_D4_retry_limit_reports_failure():
    rows = _actions(_machine("master"), "waiting", "timer")
    assert any("fail" in actions for _, actions in rows)
    assert any(guard.get("retries", ("",))[0] == "lt_param" for guard, _ in rows)


def test_TR24_D5_machines_flip_sequence_bits_only_on_success():
    """The structure the delivery guarantee rests on; the guarantee itself is
    proved by running the machines over a lossy channel (generated machines)."""
    master = _actions(_machine("master"), "waiting", "receive")
    flips = [(guard, actions) for guard, actions in master if "flip_seq" in actions]
    assert len(flips) == 1
    guard, actions = flips[0]
    assert guard["seq"] == ("eq_var", "seq") and guard["sender"] == ("eq_var", "peer")
    assert "deliver_reply" in actions
    slave = _actions(_machine("slave"), "listening", "receive")
    executes = [(guard, actions) for guard, actions in slave if "execute" in actions]
    assert len(executes) == 1 and executes[0][0]["seq"] == ("eq_var", "expected")
    assert "flip_expected" in executes[0][1]
    for guard, actions in _actions(_machine("master"), "waiting", "timer"):
        assert "flip_seq" not in actions  # a resend keeps the same sequence number
