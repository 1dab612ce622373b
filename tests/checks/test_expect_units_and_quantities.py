"""More quantities at an angle, and expectations in any unit (format 1.1, "Problems as they
are stated"), against the textbook's 4.6 slider-crank at 45 deg worked by hand:
B = (sqrt2/2, sqrt2/2), C = (sqrt2, 0), v_C = -sqrt2 i, a_C = -sqrt2 i, the rod at -45 deg,
M = 3 + 105 sqrt2 N m."""
from __future__ import annotations

import math
from pathlib import Path

import pytest

import mechreport
from mechreport.errors import SpecError
from mechreport.report.check_text import problems

ROOT = Path(__file__).resolve().parents[2]
BASE = (ROOT / "specs" / "slider_crank.yaml").read_text(encoding="utf-8")
BASE = BASE[:BASE.index("expect:")]
S2 = math.sqrt(2)


def _with(*entries: str) -> str:
    return BASE + "expect:\n" + "".join(f"  - {e}\n" for e in entries)


def test_speed_and_acceleration_magnitudes_joint_angle_and_transmission_angle():
    a = mechreport.analyse(_with(
        f"{{angle: 45, quantity: point.C.v, value: {S2:.9f}, tol: 1e-9}}",
        f"{{angle: 45, quantity: point.C.a, value: {S2:.9f}, tol: 1e-9}}",
        "{angle: 45, quantity: joint.B.angle, value: -90, tol: 1e-9}",   # rod from the crank
        "{angle: 45, quantity: transmission_angle, value: 45, tol: 1e-9}"))
    assert a.passed, problems(a, a.tol)
    assert {e.source for e in a.expectations} == {"kinematics"}      # checked once


def test_a_wrong_new_quantity_fails():
    a = mechreport.analyse(_with("{angle: 45, quantity: joint.B.angle, value: 90}"))
    assert not a.passed


@pytest.mark.parametrize("entry, twin", [
    ("{angle: 45, quantity: point.C.x, value: 1414.2136, unit: mm}",
     "{angle: 45, quantity: point.C.x, value: 1.4142136}"),
    ("{angle: 45, quantity: driver.torque, value: 0.1514924, unit: kN*m, tol: 1e-7}",
     "{angle: 45, quantity: driver.torque, value: 151.4924, tol: 1e-4}"),
    ("{angle: 45, quantity: link.rod.omega, value: -9.549297, unit: rpm, tol: 1e-6}",
     "{angle: 45, quantity: link.rod.omega, value: -1, tol: 1.1e-7}"),
    ("{angle: 45, quantity: joint.B.angle, value: -1.5707963, unit: rad, tol: 1e-7}",
     "{angle: 45, quantity: joint.B.angle, value: -90, tol: 6e-6}"),
])
def test_an_expectation_with_a_unit_passes_and_fails_as_its_si_twin(entry, twin):
    assert mechreport.analyse(_with(entry)).passed and mechreport.analyse(_with(twin)).passed
    value = float(entry.split("value: ")[1].split(",")[0])
    wrong = entry.replace(f"value: {entry.split('value: ')[1].split(',')[0]}",
                          f"value: {value * 1.01 + 0.01:.10g}")
    a = mechreport.analyse(_with(wrong))
    assert not a.passed
    unit = entry.split("unit: ")[1].split(",")[0].rstrip("}")
    line = next(p for p in problems(a, a.tol) if p.startswith("expectation failed"))
    assert f" {unit}" in line, line                   # printed in the unit written


def test_a_unit_of_the_wrong_kind_is_an_error_naming_the_units_it_may_be():
    with pytest.raises(SpecError) as info:
        mechreport.analyse(_with("{angle: 45, quantity: point.C.x, value: 1, unit: N}"))
    (p,) = info.value.problems
    assert p.path == "expect[0].unit" and "mm" in p.message and "'N'" in p.message
