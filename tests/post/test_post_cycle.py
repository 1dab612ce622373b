"""Cycle quantities against closed forms and independent computations (design review).

- a crank loaded only by a sinusoidal moment: energy fluctuation 2 M0 (integral of M0 sin);
- a crank whose centre of mass is on its pivot: no inertial shaking force, no counterweight;
- the textbook 4.6 slider-crank: mean torque 400/pi and the energy fluctuation integrated
  here from its closed-form torque, independently of the solver;
- the basic rating life worked by hand; the counterweight against a brute-force scan;
- every method's reactions and torque split by source add up to the total, every spec.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mechreport.pipeline.analysis import analyse
from mechreport.post import CycleUndefined, counterweight, rating_life_h, review
from mechreport.spec import parse_spec

ROOT = Path(__file__).resolve().parents[2]

LONE_CRANK = """
mechreport: 1
name: crank with a sinusoidal moment load
gravity: [0, -9.81]
ground: {A: [0, 0]}
links:
  crank: {points: {A: [0, 0], B: [0.2, 0]}, mass: 3, com: [0, 0], inertia: 0.05}
joints:
  A: {type: R, links: [ground, crank]}
driver: {joint: A, rpm: 60}
loads:
  - {type: moment, link: crank, profile: PROFILE}
"""
M0 = 40.0


def lone_crank():
    profile = [[a, round(M0 * float(np.sin(np.radians(a))), 12)] for a in range(360)]
    return analyse(parse_spec(LONE_CRANK.replace("PROFILE", str(profile)), "crank.yaml"))


def test_sinusoidal_moment_energy_fluctuation_is_2_M0():
    """Torque T = -M0 sin(phi); E(phi) = M0 (cos(phi) - 1) swings by 2 M0 (trapezoids on a
    1-degree grid are low by h^2/12 relative: 2.5e-5)."""
    r = review(lone_crank(), speed_fluctuation=0.05)
    assert r.values["cycle.torque.mean"] == pytest.approx(0, abs=1e-9)
    assert r.values["cycle.torque.rms"] == pytest.approx(M0 / np.sqrt(2), rel=1e-9)
    assert r.values["cycle.energy_fluctuation"] == pytest.approx(2 * M0, rel=1e-4)
    omega = 2 * np.pi
    assert r.values["cycle.flywheel_inertia"] == pytest.approx(2 * M0 / (0.05 * omega ** 2),
                                                               rel=1e-4)


def test_crank_balanced_about_its_pivot_has_no_inertial_shaking_force():
    r = review(lone_crank())
    assert r.values["cycle.inertia_shaking.force_rms"] == pytest.approx(0, abs=1e-12)
    assert r.values["balance.counterweight.mr"] == 0
    assert r.values["balance.counterweight.angle"] == 0
    # its weight still reaches the frame: shaking force = m g through the pivot
    assert r.values["cycle.shaking.force_max"] == pytest.approx(3 * 9.81, rel=1e-12)


def test_4_6_mean_torque_and_energy_fluctuation_from_the_closed_form():
    a = analyse(ROOT / "specs" / "slider_crank.yaml")
    r = review(a)
    assert list(r.cycle.interpolated) == [90.0, 270.0]      # left out, filled in
    phi = np.radians(np.arange(360.0))
    torque = 6 * np.sin(phi) * np.cos(phi) + 10 * np.cos(phi) + 200 * np.abs(np.sin(phi))
    assert np.mean(torque) == pytest.approx(400 / np.pi, rel=1e-4)
    for left_out in (90, 270):   # the convention: filled in from the neighbouring samples
        torque[left_out] = (torque[left_out - 1] + torque[left_out + 1]) / 2
    mean = float(np.mean(torque))
    assert r.values["cycle.torque.mean"] == pytest.approx(mean, rel=1e-12)
    energy = np.concatenate([[0], np.cumsum((torque[1:] + torque[:-1]) / 2 - mean)])
    energy *= np.radians(1.0)
    assert r.values["cycle.energy_fluctuation"] == pytest.approx(np.ptp(energy), rel=1e-12)
    assert r.values["cycle.torque.max"] == pytest.approx(np.max(torque), rel=1e-9)


def test_rating_life_worked_by_hand():
    # C = 10 kN, P = 1 kN, 1000 rpm: 10^6 x 10^3 / (60 x 1000) = 16 666.7 h
    assert rating_life_h(10_000, 1_000, 1000) == pytest.approx(50000 / 3, rel=1e-12)
    assert rating_life_h(10_000, 1_000, -1000) == pytest.approx(50000 / 3, rel=1e-12)


def test_counterweight_beats_every_point_of_a_brute_force_scan():
    a = analyse(ROOT / "specs" / "four_bar.yaml")
    r = review(a)
    cw = r.counterweight
    k = a.kinematics
    theta = r.cycle.sample(k.theta[:, k.index(a.spec.driver.link)][:, None], k.angles)[:, 0]
    s = r.shaking_balanced  # not used for the scan: rebuild from the unbalanced force
    inertial = r.shaking_balanced - _added(cw.mr, cw.angle, theta, a.spec.driver.omega)
    best = np.inf
    for mr in np.linspace(0, 2 * cw.mr, 81):
        for ang in np.linspace(-180, 180, 145):
            best = min(best, _rms(inertial + _added(mr, ang, theta, a.spec.driver.omega)))
    assert cw.rms_after <= best + 1e-12
    assert cw.rms_after == pytest.approx(_rms(s), rel=1e-12)
    assert cw.rms_after < cw.rms_before


def _added(mr, angle_deg, theta, omega):
    z = -omega ** 2 * mr * np.exp(1j * (theta + np.radians(angle_deg)))
    return np.stack([z.real, z.imag], axis=1)


def _rms(v):
    return float(np.sqrt(np.mean(np.sum(v ** 2, axis=1))))


def test_counterweight_of_a_pure_rotating_imbalance_cancels_it():
    theta = np.radians(np.arange(0, 360, 5.0))
    unbalance = 0.3 * np.exp(1j * (theta + 0.7)) * (-(4.0 ** 2))
    cw = counterweight(np.stack([unbalance.real, unbalance.imag], axis=1), theta, 4.0)
    assert cw.mr == pytest.approx(0.3) and cw.rms_after == pytest.approx(0, abs=1e-12)
    assert cw.angle == pytest.approx(np.degrees(0.7) - 180)


def test_cycle_quantities_undefined_without_a_whole_turn():
    a = analyse(ROOT / "tests" / "data" / "slotted_crank_slider.yaml")
    with pytest.raises(CycleUndefined, match="one whole turn of the crank; this one runs "
                                             "from 30 to 150 deg"):
        review(a)


def test_sources_add_up_to_the_total_for_every_method(spec_path):
    a = analyse(spec_path)
    for name, res in a.forces.items():
        parts = a.by_source(name)
        assert list(parts)[:2] == ["inertia", "gravity"]
        for q, total in res.values().items():
            summed = sum(p[q] for p in parts.values())
            scale = max(1.0, float(np.max(np.abs(total))))
            np.testing.assert_allclose(summed, total, rtol=0, atol=1e-12 * scale,
                                       err_msg=f"{name} {q}")


def test_4_6_torque_by_source_at_45_deg():
    """M = 6 sin cos + 10 cos + 200 |sin|: inertia 3, gravity 5 sqrt2, load 100 sqrt2 N m."""
    a = analyse(ROOT / "specs" / "slider_crank.yaml")
    k = a.kinematics.at(45)
    parts = a.by_source("dyad")
    assert parts["inertia"]["driver.torque"][k] == pytest.approx(3, abs=1e-12)
    assert parts["gravity"]["driver.torque"][k] == pytest.approx(5 * np.sqrt(2), abs=1e-12)
    assert parts["load 1"]["driver.torque"][k] == pytest.approx(100 * np.sqrt(2), abs=1e-12)


def test_equal_peaks_are_reported_at_the_first_angle():
    """Two peaks equal to rounding (a symmetric mechanism's shaking force peaks at 74 and
    106 deg) are reported at the first, whichever is larger by the last bit: a report does
    not change between runs whose numbers differ by rounding only. A peak larger by more
    than rounding is still the one reported."""
    from mechreport.post.torque import peak
    angles = np.array([0.0, 74.0, 90.0, 106.0])
    top = 1.445
    for later in (top * (1 + 4e-16), top, top * (1 - 4e-16)):
        values = np.array([0.2, top, 1.0, later])
        assert peak(angles, values).angle == 74.0
        assert peak(angles, -values).angle == 74.0
    assert peak(angles, np.array([0.2, top, 1.0, top * (1 + 1e-9)])).angle == 106.0
    assert np.isnan(peak(angles, np.array([0.2, np.nan, 1.0, 2.0])).value)
