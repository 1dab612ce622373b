"""A spec written in inches and pounds (format 1.2 ``units``) gives the same SI numbers as its
metric translation: the loaded spec and the analysed forces agree to ~1e-12 relative.

The imperial spec is made here from the metric one with the exact definitions (1 in = 0.0254
m, 1 ft = 12 in, 1 lb = 0.45359237 kg, 1 lbf = 4.4482216152605 N: the international yard and
pound of 1959, the pound-force at standard gravity), written out in this test, independently
of mechreport.units.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from mechreport.pipeline.analysis import analyse
from mechreport.spec import parse_spec

INCH, POUND, LBF = 0.0254, 0.45359237, 4.4482216152605
FOOT = 12 * INCH
#: each unit system: the ``units:`` it writes and the SI size of each kind of number
SYSTEMS = {
    "SI": ("{length: m, mass: kg}", {"L": 1.0, "M": 1.0, "F": 1.0, "T": 1.0, "J": 1.0,
                                     "K": 1.0}),
    "in-lb": ("{length: in, mass: lb, force: lbf, moment: lbf*in, inertia: lb*in^2}",
              {"L": INCH, "M": POUND, "F": LBF, "T": LBF * INCH, "J": POUND * INCH ** 2,
               "K": LBF / INCH}),
    "ft-kip": ("{length: ft, mass: lb, force: kip, moment: lbf*ft, inertia: lb*ft^2}",
               {"L": FOOT, "M": POUND, "F": 1000 * LBF, "T": LBF * FOOT,
                "J": POUND * FOOT ** 2, "K": 1000 * LBF / FOOT}),
}

#: a slider-crank with every kind of number a spec writes: {L:0.04} is 0.04 m written in the
#: system's length unit, F a force, T a moment or torque, J an inertia, K a spring or damper
#: rate (force per length)
TEMPLATE = """\
mechreport: 1.2
name: units check
units: UNITS
gravity: [0, -9.81]
ground:
  A: [0, 0]
  O: [0, {L:0.01}]
  S: [{L:0.3}, {L:0.01}]
links:
  crank:
    points: {A: [0, 0], B: [{L:0.04}, 0]}
    mass: {M:0.3}
    com: [{L:0.02}, 0]
    inertia: {J:0.0002}
  rod:
    points: {B: [0, 0], C: [{L:0.12}, 0]}
    mass: {M:0.25}
    shape: {bar: {length: {L:0.12}, height: {L:0.012}, depth: {L:0.008}}}
  slider:
    points: {C: [0, 0]}
    mass: {M:0.6}
    com: [0, 0]
    inertia: {J:0.0001}
joints:
  A: {type: R, links: [ground, crank]}
  B: {type: R, links: [crank, rod]}
  C: {type: R, links: [rod, slider]}
  C_T: {type: T, links: [ground, slider], point: C, line: {through: O, direction: 0}}
driver: {joint: A, rpm: 600}
sweep: {start: 0, stop: 360, step: 10}
assembly: {C: [{L:0.155}, {L:0.01}]}
loads:
  - {type: force, link: slider, point: C, value: [{F:-40}, {F:5}]}
  - {type: force, link: rod, point: C, direction: [1, 1], profile: [[0, {F:10}], [180, {F:-20}]]}
  - {type: moment, link: rod, value: {T:0.7}}
  - {type: moment, link: crank, profile: [[0, {T:0.1}], [90, {T:-0.3}]]}
  - {type: spring, between: [[ground, S], [slider, C]], stiffness: {K:4000}, free_length: {L:0.2}}
  - {type: damper, between: [[ground, S], [slider, C]], damping: {K:30}}
  - {type: torsion_spring, joint: C, stiffness: {T:20}, free_angle: 0}
design:
  bearings: {A: {rating: {F:5000}}}
  motor: {rated_torque: {T:3}, peak_torque: {T:9}}
  limits: {joint_force: {F:900}, shaking_force: {F:600}}
dynamics:
  motor: {linear: {stall_torque: {T:15}, no_load_rpm: 700}}
  flywheel: {J:0.05}
"""


def written(system: str) -> str:
    """The spec in ``system``'s units: each ``{K:x}`` (x in SI) as x / size of K."""
    units, size = SYSTEMS[system]
    text = TEMPLATE.replace("UNITS", units)
    out, i = [], 0
    while (j := text.find("{", i)) >= 0:
        out.append(text[i:j])
        end = text.find("}", j)
        body = text[j + 1:end]
        if len(body) > 2 and body[0] in size and body[1] == ":":
            out.append(repr(float(body[2:]) / size[body[0]]))
            i = end + 1
        else:
            out.append("{")
            i = j + 1
    return "".join(out) + text[i:]


def numbers(node, path="spec"):
    """Every float of a loaded spec (dataclasses, tuples, dicts), by where it is."""
    if dataclasses.is_dataclass(node):
        for f in dataclasses.fields(node):
            if f.name not in ("file", "units", "line", "length_scale"):
                yield from numbers(getattr(node, f.name), f"{path}.{f.name}")
    elif isinstance(node, dict):
        for k, v in node.items():
            yield from numbers(v, f"{path}[{k}]")
    elif isinstance(node, (tuple, list)):
        for k, v in enumerate(node):
            yield from numbers(v, f"{path}[{k}]")
    elif isinstance(node, float) and not isinstance(node, bool):
        yield path, node


@pytest.mark.parametrize("system", ["in-lb", "ft-kip"])
def test_a_spec_in_inches_and_pounds_loads_to_the_same_si_numbers(system):
    metric = dict(numbers(parse_spec(written("SI"), "si.yaml")))
    other = dict(numbers(parse_spec(written(system), f"{system}.yaml")))
    assert metric.keys() == other.keys()
    assert len(metric) > 60
    for where, x in metric.items():
        assert other[where] == pytest.approx(x, rel=1e-12, abs=1e-15), where


def test_the_unit_names_are_kept_for_the_reports():
    spec = parse_spec(written("in-lb"), "in.yaml")
    assert spec.units == {"length": "in", "mass": "lb", "force": "lbf", "moment": "lbf*in",
                          "inertia": "lb*in^2"}
    assert parse_spec(written("SI"), "si.yaml").units == {"length": "m", "mass": "kg"}


@pytest.mark.slow
def test_a_spec_in_inches_and_pounds_gives_the_same_forces():
    """Driver torque and every joint reaction over the sweep, by every force method."""
    a, b = (analyse(parse_spec(written(s), f"{s}.yaml")) for s in ("SI", "in-lb"))
    for method, res in a.forces.items():
        other = b.forces[method]
        scale = max(np.abs(res.driver_torque).max(), 1.0)
        np.testing.assert_allclose(other.driver_torque, res.driver_torque, rtol=1e-12,
                                   atol=1e-12 * scale)
        for joint, r in res.reactions.items():
            top = max(np.abs(r.fx).max(), np.abs(r.fy).max(), 1.0)
            for x, y in ((r.fx, other.reactions[joint].fx), (r.fy, other.reactions[joint].fy)):
                np.testing.assert_allclose(y, x, rtol=1e-12, atol=1e-12 * top)
    assert math.isclose(a.review.values["cycle.torque.rms"] if a.review else 0.0,
                        b.review.values["cycle.torque.rms"] if b.review else 0.0,
                        rel_tol=1e-12)


def test_report_and_expect_units_of_format_1_2():
    """report.units in, ft, lbf, kip, lbf*in, lbf*ft, psi, ksi; expect in in/s, ft/s^2."""
    text = written("in-lb") + (
        "report: {units: {length: ft, force: kip, moment: lbf*ft, stress: ksi, "
        "pressure: psi}}\n"
        "expect:\n"
        "  - {angle: 0, quantity: point.C.vx, value: 0, unit: in/s, tol: 1}\n"
        "  - {angle: 0, quantity: point.C.ax, value: -1, unit: ft/s^2, tol: 1}\n")
    spec = parse_spec(text, "in.yaml")
    assert spec.report.units == {"length": "ft", "force": "kip", "moment": "lbf*ft",
                                 "mass": "kg", "stress": "ksi", "pressure": "psi"}
    assert [e.scale for e in spec.expect] == [INCH, FOOT]
    assert spec.expect[1].value == -FOOT and spec.expect[1].tol == FOOT
    # without report.units, forces and moments are shown in the spec's own units
    assert parse_spec(written("in-lb"), "in.yaml").report.units == {}


def test_an_acceleration_may_be_expected_in_mm_per_s2_as_the_reports_show_it():
    """A mm spec's report shows accelerations in mm/s²; expect takes that unit too (mm/s was
    accepted, mm/s^2 refused)."""
    text = written("SI") + (
        "expect:\n"
        "  - {angle: 0, quantity: point.C.ax, value: -1500, unit: mm/s^2, tol: 2}\n")
    (entry,) = parse_spec(text, "si.yaml").expect
    assert entry.scale == 0.001 and entry.value == -1.5 and entry.tol == 0.002
