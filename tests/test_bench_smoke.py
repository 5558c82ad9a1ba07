"""One quick repetition of the benchmark harness (python3 -m bench runs the real thing).

Checks that every contender of a benchmark does the same work as codeword:
the same bytes out of the same message, the same values back, and, for the
streams, the same good frames found; then that the timing and report code run.
The expected frames are the schemas' hand-calculated examples (see bench/messages.py).
"""

import tempfile
from pathlib import Path

from bench import c_host, imports, messages, peers_c, runner, streams, timing
from bench import handwritten as hw
from bench.protocols import car, mtv4, route, tank, tr24


def test_every_contender_writes_the_expected_bytes_and_reads_back_the_same_values():
    for case in messages.cases():
        assert messages.check(case) == [], case.key


def test_a_changed_field_is_noticed_by_the_agreement_check():
    case = next(c for c in messages.cases() if c.key == "route")
    # route object example with cm=4; a wire with cm=5 must be reported, not silently accepted
    case.wire = bytes.fromhex("59116960")
    assert any("route/hand-written: encodes" in p for p in messages.check(case))


def test_one_round_of_interleaved_timing_gives_a_time_per_call():
    case = messages.cases()[0]
    calls = {name: c.decode for name, c in case.contenders.items()}
    medians = timing.interleaved(calls, repeats=1, target=0.001)
    assert set(medians) == set(calls) and all(t > 0 for t in medians.values())


def test_stream_readers_find_every_good_frame_of_a_small_capture():
    jobs = streams.contenders(100_000, 50_000)
    for name, (job, size, sent, found) in jobs.items():
        assert job() > 0
        if name == "pymavlink parse_buffer":
            assert 0.9 * sent <= found[0] <= sent  # it may lose a frame after a corrupted one
        else:
            assert found == [sent], name
    # 1% of the frames are corrupted: roughly that share is missing from the good count
    size, sent = jobs["codeword"][1], jobs["codeword"][2]
    assert 0.95 * size / 26 < sent < size / 26


def test_host_c_harness_builds_and_generated_and_hand_written_c_agree():
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        figures = c_host.run(tmp, peers_c.generate_mavlink(tmp / "mavlink"), 1, 20_000)
    assert figures["mtv4 codeword"] > 0 and figures["parser mavlink_parse_char MB/s"] > 0
    assert all(figures[f"parser {key} MB/s"] > 0 for key in c_host.PARSERS) and figures["memcpy MB/s"] > 0


def test_the_can_harness_builds_and_codeword_and_cantools_write_the_same_data():
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        figures = c_host.run_can(tmp, peers_c.generate_cantools(tmp / "cantools"), 1)
    assert all(figures[f"{m} agree"] == 1 for m in c_host.CAN_MESSAGES)  # else run_can raises
    assert all(figures[f"{m} {side} {op}"] > 0 for m in c_host.CAN_MESSAGES for side in ("codeword", "cantools")
               for op in ("encode", "decode"))
    report = runner.can_c_lines(figures)
    assert sum(line.startswith(("| steering |", "| extended |")) for line in report) == 2


def test_the_crc_methods_are_measured_under_simavr_and_reported():
    from bench import avr
    with tempfile.TemporaryDirectory() as tmp:
        figures = avr.crc_choice(Path(tmp))
    assert set(figures) == set(c_host.CRC_METHODS)
    flash = {m: f[0] for m, f in figures.items()}
    cycles = {m: f[1] for m, f in figures.items()}
    crc = {m: f[2] for m, f in figures.items()}
    assert flash["table"] - flash["bitwise"] >= 400  # its 512-byte table, less the bitwise loop
    # flash grows with the tables: 0, 16, 32, 256, 1024, 2048 entries of two bytes
    assert flash["bitwise"] < flash["nibble"] <= flash["split"] < flash["table"] < flash["slice4"] < flash["slice8"]
    # on AVR each method up to the 256-entry table is faster than the smaller ones
    assert crc["table"] < crc["split"] < crc["nibble"] < crc["bitwise"]
    assert cycles["table"] < cycles["split"] < cycles["nibble"] < cycles["bitwise"]
    host = {f"parser mtv4_scan, CRC {m} MB/s": 100.0 for m in c_host.CRC_METHODS}
    report = runner.crc_choice(figures, host)
    assert any("| `MTV4_CRC_SPLIT` (default) |" in line for line in report)
    assert sum(line.startswith("| `MTV4_CRC_") for line in report) == len(c_host.CRC_METHODS)


def test_exponent_of_a_linear_and_a_quadratic_series():
    assert abs(runner.scaling.exponent({10: 1.0, 100: 10.0, 1000: 100.0}) - 1.0) < 1e-9
    assert abs(runner.scaling.exponent({100: 1.0, 1000: 100.0}) - 2.0) < 1e-9


def test_the_profile_names_the_generated_function_of_every_message():
    from bench import profile
    text = profile.profile(top=5, calls=50)
    for fn in ("_encode_object", "_decode_object", "_encode_master_control", "_decode_master_control",
               "_decode_set_wheels_velocities_with_odometry", "_decode_telemetry", "_encode_command"):
        assert fn in text, fn


def test_peer_wrappers_count_parity_bits_rather_than_add_field_values():
    from bench import peers
    # master word: forward_words, motor enable, speed 2 (binary 10), duration 0:
    # bits 30, 29 and 26 set = 0x64000000, three ones, so even parity sets bit 0 -> 64 00 00 01
    raw = dict.fromkeys(peers.CAR_FIELDS[:-1], 0)
    raw.update(forward_words=1, motor_enable=1, motor_speed=2)
    expected = bytes.fromhex("64000001")
    assert peers.bitstruct_car_encode(tuple(raw.values())) == expected
    assert peers.construct_car_encode(raw) == expected
    assert peers.cantools_car_encode(raw) == expected


def _outcome(decode, data):
    try:
        return decode(data)
    except ValueError:
        return None


def _damaged(case):
    """The example's frame with each bit flipped (an mtv4 frame also with its CRC made right
    again, so the checks behind the CRC are reached), or the tank line with each token
    replaced by text some rule refuses or accepts."""
    if isinstance(case.wire, str):
        tokens = case.wire[2:-1].split(",")
        for i in range(len(tokens)):
            for bad in ("", " 7 ", "nan", "inf", "1e400", "1_0", "1e-310", "0.1234567890123456", "-0", "5.", "101",
                        "256", "6", "x y", "ab", ";", "9" * 25, "x" * 33):
                yield "$:" + ",".join(tokens[:i] + [bad] + tokens[i + 1:]) + ";"
        return
    for bit in range(8 * len(case.wire)):
        frame = bytearray(case.wire)
        frame[bit // 8] ^= 0x80 >> bit % 8
        yield bytes(frame)
        if case.key == "mtv4":
            frame[24:26] = hw.crc16_cms(frame).to_bytes(2, "big")
            yield bytes(frame)


def test_the_floor_refuses_what_codeword_refuses_and_reads_the_same_values():
    decoders = {"route": (route.Object.decode, hw.route_object_decode),
                "car": (car.MasterControl.decode, hw.car_master_decode),
                "mtv4": (mtv4.SetWheelsVelocitiesWithOdometry.decode, hw.mtv4_odometry_decode),
                "tank": (tank.Telemetry.decode, hw.tank_telemetry_decode),
                "tr24": (tr24.Command.decode, hw.tr24_command_decode)}
    for case in messages.cases():
        cw, own = decoders[case.key]
        for data in _damaged(case):
            a, b = _outcome(cw, data), _outcome(own, data)
            assert (a is None) == (b is None), (case.key, data)
            if a is not None:
                assert messages.differences(b, a) == [], (case.key, data)


def test_the_import_benchmark_times_both_modules_from_bytecode_and_from_source(tmp_path):
    r = imports.measure(tmp_path, repeats=1, messages=10)
    assert all(r[(name, cached)][0] > 0 for name in ("codeword", "pymavlink common") for cached in (True, False))
    verdicts = []
    text = "\n".join(imports.section(r, verdicts, runner._met))
    assert "pymavlink common" in text and len(verdicts) == 2


def test_every_example_and_its_peer_read_the_same_values_and_write_the_same_bytes():
    from bench import examples
    rows = examples.rows()
    assert examples.check(rows) == []
    assert {row.example for row in rows} == {"mavlink2", "mavlink1", "ubx", "modbus_rtu", "ipv4", "nmea0183", "can_mixed"}


def test_an_example_writing_other_bytes_than_its_peer_is_noticed(monkeypatch):
    from bench import examples
    rows = [row for row in examples.rows() if row.key == "mavlink2 attitude"]
    monkeypatch.setattr(examples.mavlink2, "encode", lambda message: b"\xfd")
    assert examples.check(rows) == ["mavlink2 attitude: encodes differ"] * 3


def test_the_examples_sections_time_every_message_and_report_the_targets():
    from bench import examples, runner
    verdicts: list[bool] = []
    lines = runner.examples_sections(runner.run_examples(1, 0.0005), verdicts)
    assert "## 7. NMEA 0183 against pynmea2" in lines and "## 8. The examples against their peer libraries" in lines
    assert sum(line.startswith("| nmea0183 | pynmea2 |") for line in lines) == 2 * len(examples.NMEA_LINES)
    assert any(line.startswith("- mavlink2 decode: peer / codeword") for line in lines)
    assert len(verdicts) == len(examples.TARGETS) + 1
