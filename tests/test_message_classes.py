"""Message and group classes are plain classes with slots (importing a module runs no
@dataclass decorator), yet behave as the dataclasses they replaced: keyword construction
with the schema's defaults (a group or a list built for each object), equality and repr
field by field, and dataclasses.fields, replace, asdict and is_dataclass."""
from __future__ import annotations

import dataclasses
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import load_generated

ROOT = Path(__file__).resolve().parent.parent
car = load_generated("car")
mtv4 = load_generated("mtv4")


def test_importing_a_module_runs_no_dataclass_decorator():
    code = "import sys, mtv4, car, tank, tr24, route; print(sorted(m for m in ('dataclasses', 'inspect') if m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT / "generated" / "python", capture_output=True,
                         text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_defaults_come_from_the_schema_and_each_object_gets_its_own_groups():
    a, b = car.SlaveControl(), car.SlaveControl()
    # car.yaml: accept_ir and forward_words default to 1, voice and body_sensor to 0
    assert (a.accept_ir, a.forward_words, a.voice, a.body_sensor) == (True, True, False, False)
    assert a.motor == car.ControlWordMotor() and a.motor is not b.motor
    a.motor.speed = 3
    assert b.motor.speed == 0


def test_a_required_field_left_out_or_an_unknown_one_is_a_type_error():
    with pytest.raises(TypeError):
        mtv4.SetWheelsVelocities(group=1)  # the other fields have no default
    with pytest.raises(TypeError):
        car.SlaveControl(speed=3)  # a field of a group, not of the word


def test_equality_and_repr_go_field_by_field_in_order():
    a = car.SlaveControl(voice=True)
    assert a == car.SlaveControl(voice=True) and a != car.SlaveControl() and a != car.MasterControl()
    assert repr(a).startswith("SlaveControl(accept_ir=True, forward_words=True, motor=ControlWordMotor(enable=False")
    assert repr(a).endswith("voice=True, body_sensor=False)")
    with pytest.raises(TypeError):
        hash(a)  # mutable and compared by value, as a dataclass with eq=True


def test_the_dataclasses_module_sees_a_dataclass():
    a = car.SlaveControl(voice=True)
    assert dataclasses.is_dataclass(car.SlaveControl) and dataclasses.is_dataclass(a)
    assert [f.name for f in dataclasses.fields(a)] == ["accept_ir", "forward_words", "motor", "led", "ultrasonic",
                                                         "voice", "body_sensor"]
    assert dataclasses.fields(car.SlaveControl)[0].default is True
    moved = dataclasses.replace(a, body_sensor=True)
    assert moved.body_sensor and moved.voice and moved.motor == a.motor and not a.body_sensor
    plain = dataclasses.asdict(a)
    assert plain["motor"] == {"enable": False, "direction": car.MotorDirection(0), "speed": 0, "duration": 0}
    assert car.SlaveControl(**{**plain, "motor": car.ControlWordMotor(**plain["motor"]),
                               "led": car.ControlWordLed(**plain["led"]),
                               "ultrasonic": car.ControlWordUltrasonic(**plain["ultrasonic"])}) == a


def test_a_decoded_object_is_the_same_class_and_compares_equal_to_a_built_one():
    sent = car.SlaveControl(voice=True, accept_ir=False)
    back = car.SlaveControl.decode(sent.encode())
    assert type(back) is car.SlaveControl and back == sent and dataclasses.replace(back) == sent
