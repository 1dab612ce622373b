"""A driver at rest (format 1.1): a static analysis (`rpm: 0`, or `speed: 0`) gives the holding
effort and the reactions; with `alpha` it is the instant of starting from rest. Checked against
the potential energy and the kinetic energy of the mechanism differentiated numerically from
closed-form positions, not against the methods' own equations."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import mechreport
from mechreport.errors import SpecError
from mechreport.kinematics import solve_kinematics
from mechreport.model import build_mechanism
from mechreport.spec import parse_spec

ROOT = Path(__file__).resolve().parents[2]
G = 9.80665

# A four-bar whose links are uniform bars (centres of mass at mid-length), held by its crank
# against gravity: AB = 50, BC = 180, DC = 120, AD = 200 mm.
FOUR_BAR = """\
mechreport: 1.1
name: four-bar held at rest
units: {length: mm, mass: kg}
ground: {A: [0, 0], D: [200, 0]}
links:
  crank:   {points: {A: [0, 0], B: [50, 0]}, mass: 0.4, com: [25, 0], inertia: 1.0e-4}
  coupler: {points: {B: [0, 0], C: [180, 0]}, mass: 1.2, com: [90, 0], inertia: 3.0e-3}
  rocker:  {points: {D: [0, 0], C: [120, 0]}, mass: 0.8, com: [60, 0], inertia: 1.0e-3}
joints:
  A: {type: R, links: [ground, crank]}
  B: {type: R, links: [crank, coupler]}
  C: {type: R, links: [coupler, rocker]}
  D: {type: R, links: [ground, rocker]}
driver: {joint: A, DRIVER}
sweep: {start: 0, stop: 360, step: 15}
at: [30]
assembly: {C: [196, 120]}
"""
MASS = {"crank": 0.4, "coupler": 1.2, "rocker": 0.8}
INERTIA = {"crank": 1.0e-4, "coupler": 3.0e-3, "rocker": 1.0e-3}


def _four_bar(driver: str) -> str:
    return FOUR_BAR.replace("DRIVER", driver)


def _poses(phi: np.ndarray) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """(centre of mass [m] (n, 2), angle [rad] (n,)) of each link at crank angles ``phi``
    [rad], by circle intersection (the open branch: C above the line BD's left normal)."""
    a, b, c, d = 0.05, 0.18, 0.12, 0.2
    B = np.stack([a * np.cos(phi), a * np.sin(phi)], axis=1)
    D = np.array([d, 0.0])
    BD = D - B
    L = np.hypot(BD[:, 0], BD[:, 1])
    along = (b**2 - c**2 + L**2) / (2 * L)
    h = np.sqrt(b**2 - along**2)
    u = BD / L[:, None]
    C = B + along[:, None] * u + h[:, None] * np.stack([-u[:, 1], u[:, 0]], axis=1)
    th_b = np.arctan2(C[:, 1] - B[:, 1], C[:, 0] - B[:, 0])
    th_c = np.arctan2(C[:, 1] - D[1], C[:, 0] - D[0])
    return {"crank": (B / 2, phi), "coupler": ((B + C) / 2, th_b),
            "rocker": ((C + D) / 2, th_c)}


def _potential(phi: np.ndarray) -> np.ndarray:
    """Potential energy of the weights [J] at crank angles ``phi`` [rad]."""
    return sum(MASS[k] * G * r[:, 1] for k, (r, _) in _poses(phi).items())


def _generalized_inertia(phi: np.ndarray, h: float = 1e-5) -> np.ndarray:
    """J(phi) = sum m |dr_C/dphi|^2 + I (dtheta/dphi)^2 [kg m^2], central differences."""
    up, down = _poses(phi + h), _poses(phi - h)
    out = np.zeros(len(phi))
    for k in MASS:
        dr = (up[k][0] - down[k][0]) / (2 * h)
        dth = np.unwrap(np.stack([down[k][1], up[k][1]]), axis=0)
        out += MASS[k] * np.sum(dr**2, axis=1) + INERTIA[k] * ((dth[1] - dth[0]) / (2 * h))**2
    return out


def test_a_crank_at_rest_holds_the_weights_by_every_method_and_by_virtual_work():
    a = mechreport.analyse(_four_bar("rpm: 0"))
    assert a.passed
    phi = np.radians(a.angles)
    h = 1e-4
    holding = (_potential(phi + h) - _potential(phi - h)) / (2 * h)     # M = dV/dphi
    scale = np.max(np.abs(holding))
    assert "power" in a.forces
    for name, res in a.forces.items():
        np.testing.assert_allclose(res.driver_torque, holding, rtol=0, atol=1e-7 * scale,
                                   err_msg=name)


def test_at_rest_the_frame_carries_exactly_the_weights():
    a = mechreport.analyse(_four_bar("rpm: 0"))
    weight = G * sum(MASS.values())
    for name, res in a.forces.items():
        if not res.reactions:
            continue
        up = res.reactions["A"].fy + res.reactions["D"].fy    # the frame on the links
        np.testing.assert_allclose(up, weight, rtol=1e-12, err_msg=name)
        np.testing.assert_allclose(res.reactions["A"].fx + res.reactions["D"].fx, 0,
                                   atol=1e-12 * weight, err_msg=name)


def test_starting_from_rest_adds_the_generalized_inertia_times_alpha():
    """At rest, M(phi) = dV/dphi + J(phi) alpha (no velocity terms)."""
    alpha = 40.0
    still = mechreport.analyse(_four_bar("rpm: 0"))
    start = mechreport.analyse(_four_bar(f"omega: 0, alpha: {alpha}"))
    phi = np.radians(start.angles)
    expected = still.forces["newton_euler"].driver_torque + _generalized_inertia(phi) * alpha
    scale = np.max(np.abs(expected))
    for name, res in start.forces.items():
        np.testing.assert_allclose(res.driver_torque, expected, rtol=0, atol=1e-7 * scale,
                                   err_msg=name)


def test_a_cylinder_at_rest_holds_the_boom_by_virtual_work():
    """A T driver at `speed: 0`: its force is dV/ds (V: the weights' and the payload's
    potential energy) from positions at neighbouring strokes."""
    text = (ROOT / "specs" / "hydraulic_boom.yaml").read_text(encoding="utf-8")
    text = text.replace("driver: {joint: cyl, speed: 50}", "driver: {joint: cyl, speed: 0}")
    text = text[:text.index("\nexpect:")] + "\n" if "\nexpect:" in text else text
    spec = parse_spec(text, "boom.yaml")
    a = mechreport.analyse(spec)
    mech = build_mechanism(spec)
    g = np.asarray(spec.gravity)
    payload = next(ld for ld in spec.loads if ld.name == "payload")

    def potential(s_mm: np.ndarray) -> np.ndarray:
        kin = solve_kinematics(mech, s_mm)
        v = -sum(link.mass * kin.com(link.name).r @ g for link in spec.links)
        return v - kin.named_point("T", "boom").r @ np.asarray(payload.value)

    s = a.angles[(a.angles > 110) & (a.angles < 490)]
    h = 1e-3                                             # mm
    force = (potential(s + h) - potential(s - h)) / (2 * h * 1e-3)   # N: dV/ds, s in m
    for name, res in a.forces.items():
        got = res.driver_torque[np.isin(a.angles, s)]
        np.testing.assert_allclose(got, force, rtol=1e-6, err_msg=name)


def test_a_static_sweep_has_zero_power_and_no_counterweight_and_stays_finite():
    a = mechreport.analyse(_four_bar("rpm: 0"))
    values = a.review.values
    assert values["cycle.power.max"] == 0.0 and values["cycle.power.mean"] == 0.0
    assert values["balance.counterweight.mr"] == 0.0
    assert all(math.isfinite(v) for v in values.values())


@pytest.mark.parametrize("extra, path, words", [
    ("design: {speed_fluctuation: 0.05}\n", "design.speed_fluctuation", "at rest"),
    ("design: {bearings: {A: {rating: 4000}}}\n", "design.bearings", "at rest"),
    ("expect:\n  - {quantity: cycle.flywheel_inertia, value: 1}\n", "expect[0]", "at rest"),
])
def test_what_divides_by_the_speed_is_an_error_at_rest(extra, path, words):
    with pytest.raises(SpecError) as info:
        parse_spec(_four_bar("rpm: 0") + extra, "x.yaml")
    found = [p for p in info.value.problems if p.path == path]
    assert found and words in found[0].message and "driver.rpm: 0" in found[0].message, \
        info.value.problems
