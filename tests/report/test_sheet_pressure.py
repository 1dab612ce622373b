"""A solution sheet works a gas force out of the printed indicator diagram: the pressure
read at the crank angle (phased by the load's shift), less the ambient, times the piston's
area, along the load's direction; never "as given" (the problem gives a pressure, not a
force). Numbers worked here from the data."""
from __future__ import annotations

import math

import pytest

import mechreport
from mechreport.report.sheet.model import build_sheet

ENGINE = """\
mechreport: 1.2
name: sheet gas force
cycle: 720
ground: {O: [0, 0]}
units: {length: mm, mass: kg}
links:
  crank: {points: {O: [0, 0], B: [43, 0]}, mass: 3, com: [0, 0], inertia: 0.012}
  rod: {points: {B: [0, 0], C: [145, 0]}, mass: 0.55, com: [40, 0], inertia: 1.7e-3}
  piston: {points: {C: [0, 0]}, mass: 0.45, com: [0, 0], inertia: 0}
joints:
  O: {type: R, links: [ground, crank]}
  B: {type: R, links: [crank, rod]}
  C: {type: R, links: [rod, piston]}
  bore: {type: T, links: [ground, piston], point: C, line: {through: O, direction: 0}}
driver: {joint: O, rpm: 3000}
sweep: {start: 0, stop: 720, step: 5}
at: [400]
assembly: {C: [188, 0]}
loads:
  - {type: pressure, name: gas, link: piston, point: C, bore: 80, direction: [-1, 0],
     unit: bar, ambient: 1, profile: [[0, 1], [360, 50], [540, 3], [720, 1]], shift: SHIFT}
"""


@pytest.mark.parametrize("shift, read", [(0, 400), (-20, 420), (740, 380)])
def test_the_gas_force_is_worked_from_the_diagram(shift, read):
    a = mechreport.analyse(ENGINE.replace("SHIFT", str(shift)))
    (at,) = build_sheet(a).angles                       # the sheet at 400 deg
    (row,) = at.loads
    rule = row[-1]
    p = 50 + (3 - 50) * (read - 360) / 180                  # the diagram at the read angle
    force = (p - 1) * 1e5 * math.pi * 0.080 ** 2 / 4
    assert f"{read}°" in rule and "as given" not in rule
    assert f"p = {p:.6g} bar" in rule and "p_a = 1 bar" in rule and "d = 0.08 m" in rule
    assert f"(p − p_a) A = {force:.6g} N along (-1, 0)" in rule
    assert row[3] == f"({-force:.6g}, 0) N"
