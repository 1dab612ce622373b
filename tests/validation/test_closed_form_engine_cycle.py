"""Engines over their 720-degree cycle against the closed forms of the dynamic-force-analysis
chapter (format 1.2: ``cycle``, ``type: pressure``, ``shift``):

- the mean torque of a four-stroke cycle is the cycle's indicated work over 4 pi, the work
  being the integral of p dV round the indicator diagram, computed here independently from
  the slider-crank's piston position x = r cos(phi) + sqrt(l^2 - r^2 sin^2(phi)) and the
  swept volume V = A (r + l - x), at a hundredth of a degree;
- an in-line four with equal cranks (pins 1 and 4 at 0, 2 and 3 at 180 degrees) and
  point-mass pistons on massless rods has no primary shaking force, and its shaking force is
  exactly minus the sum of the pistons' inertia forces m x'' (x'' = omega^2 d^2x/dphi^2 from
  the same closed form, differentiated by hand): the secondary force of the four, with its
  higher harmonics; the gas forces, reacting on the cylinder head, add nothing to it.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import mechreport

R, L, BORE = 0.043, 0.145, 0.086            # crank radius, rod, bore [m]
AREA = math.pi * BORE ** 2 / 4
RPM = 3000.0
OMEGA = RPM * math.pi / 30
M_PISTON = 0.45                              # [kg]
#: an indicator diagram (absolute bar) over the cycle: firing at the top dead centre 360
DIAGRAM = [[0, 1.05], [20, 0.92], [200, 0.92], [260, 1.45], [300, 3.22], [340, 12.0],
           [360, 20.7], [370, 35.6], [380, 48.5], [390, 44.6], [420, 18.1], [450, 9.56],
           [500, 5.7], [520, 2.33], [560, 1.12], [700, 1.12], [720, 1.05]]


def _x(phi):
    """Piston position from the crank pivot [m] at crank angles ``phi`` [rad]."""
    return R * np.cos(phi) + np.sqrt(L ** 2 - (R * np.sin(phi)) ** 2)


def _x_dd(phi):
    """d^2x/dphi^2 [m/rad^2], by hand from x = r cos + D, D = sqrt(l^2 - r^2 sin^2)."""
    s, c = np.sin(phi), np.cos(phi)
    d = np.sqrt(L ** 2 - (R * s) ** 2)
    return -R * c - R ** 2 * (c ** 2 - s ** 2) / d - R ** 4 * s ** 2 * c ** 2 / d ** 3


def _cylinder(n: int, shift: float) -> tuple[str, str, str]:
    """The links, joints and pressure load (YAML lines) of cylinder ``n``."""
    links = (f"  rod{n}: {{points: {{B{n}: [0, 0], C{n}: [{L}, 0]}}, mass: 0}}\n"
             f"  piston{n}: {{points: {{C{n}: [0, 0]}}, mass: {M_PISTON}, com: [0, 0], "
             f"inertia: 0}}\n")
    joints = (f"  B{n}: {{type: R, links: [crank, rod{n}]}}\n"
              f"  C{n}: {{type: R, links: [rod{n}, piston{n}]}}\n"
              f"  bore{n}: {{type: T, links: [ground, piston{n}], point: C{n}, "
              f"line: {{through: O, direction: 0}}}}\n")
    load = (f"  - {{type: pressure, link: piston{n}, point: C{n}, bore: {BORE}, "
            f"direction: [-1, 0], unit: bar, ambient: 1.013, profile: {DIAGRAM}, "
            f"shift: {shift}}}\n")
    return links, joints, load


def _engine(cylinders: list[tuple[int, float, float]], sweep: str) -> str:
    """A spec of ``cylinders`` (number, pin angle [deg], shift [deg]) on one crank."""
    pins = ", ".join(f"B{n}: [{R * math.cos(math.radians(a)):.17g}, "
                     f"{R * math.sin(math.radians(a)):.17g}]" for n, a, _ in cylinders)
    links, joints, loads = ("".join(part) for part in
                            zip(*(_cylinder(n, shift) for n, _, shift in cylinders)))
    hints = ", ".join(f"C{n}: [{_x(math.radians(a)):.6g}, 0]" for n, a, _ in cylinders)
    return (f"mechreport: 1.2\nname: engine\ngravity: [0, 0]\ncycle: 720\n"
            f"ground: {{O: [0, 0]}}\nlinks:\n"
            f"  crank: {{points: {{O: [0, 0], {pins}}}, mass: 5, com: [0, 0], inertia: 0.02}}\n"
            f"{links}joints:\n  O: {{type: R, links: [ground, crank]}}\n{joints}"
            f"driver: {{joint: O, rpm: {RPM}}}\nsweep: {sweep}\nassembly: {{{hints}}}\n"
            f"loads:\n{loads}")


def _indicated_work() -> float:
    """The integral of p dV round the diagram [J] (gauge: the ambient's integral is 0)."""
    deg = np.linspace(0.0, 720.0, 72001)
    xp, fp = np.array(DIAGRAM, float).T
    p = (np.interp(deg, xp, fp) - 1.013) * 1e5
    volume = AREA * (R + L - _x(np.radians(deg)))
    return float(np.sum(0.5 * (p[1:] + p[:-1]) * np.diff(volume)))


def test_four_stroke_mean_torque_is_the_indicated_work_over_4_pi():
    work = _indicated_work()
    assert work > 100.0                       # a firing cycle gives work, not absorbs it
    a = mechreport.analyse(_engine([(1, 0.0, 0.0)], "{start: 0, stop: 720, step: 1}"))
    assert a.passed
    mean = a.review.values["cycle.torque.mean"]
    # the engine drives: the driver (the load on the shaft) takes minus the work's share
    assert mean == pytest.approx(-work / (4 * math.pi), rel=2e-4)
    # the cycle is two turns: the mean over the first turn alone is far from it
    first = a.angles < 360
    assert abs(np.mean(a.forces[a.review.method].driver_torque[first]) - mean) > 0.2 * abs(mean)


def test_inline_four_has_no_primary_and_exactly_the_pistons_secondary_shaking_force():
    # firing order 1-3-4-2: shifts 0, 540, 180, 360; a half-degree grid (see the example)
    cylinders = [(1, 0.0, 0.0), (2, 180.0, 540.0), (3, 180.0, 180.0), (4, 0.0, 360.0)]
    a = mechreport.analyse(_engine(cylinders, "{start: 0.5, stop: 720.5, step: 1}"))
    rv = a.review
    phi = np.radians(rv.cycle.angles)
    inertia = sum(M_PISTON * OMEGA ** 2 * _x_dd(phi + math.radians(pin))
                  for _, pin, _ in cylinders)
    fx, fy = rv.shaking[:, 0], rv.shaking[:, 1]
    scale = float(np.max(np.abs(inertia)))
    np.testing.assert_allclose(fx, -inertia, rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(fy, 0.0, rtol=0, atol=1e-9 * scale)
    primary = abs(np.mean(fx * np.exp(-1j * phi))) * 2        # the first harmonic's amplitude
    secondary = abs(np.mean(fx * np.exp(-2j * phi))) * 2
    assert primary < 1e-9 * scale
    # one cylinder's primary force m r omega^2 is there, and cancels among the four
    one = M_PISTON * R * OMEGA ** 2
    assert secondary == pytest.approx(4 * one * R / L, rel=0.05)  # 4 m r w^2 (r/l), about
