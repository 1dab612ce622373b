"""Textbook validation: Marghitu, *Dynamic Force Analysis*, sections 4.6 and
4.7, joint reactions and driver torque, checked for EVERY method (the text works each example
by some of them; all four must give its final results).

Conventions: a joint's reaction is the force of its first link on its second. The text's F23
at the slider joint B_T is our joint B_T reaction F32 = -F23; its F45 at D_T is our F54 = -F45.
Tolerances: 4.6 is exact (closed forms with sqrt 2): 1e-9 relative. 4.7 prints 6 significant
digits; we allow half a unit in the last printed digit.
"""
from __future__ import annotations

import math
from pathlib import Path

import pytest

from mechreport.pipeline.analysis import analyse
from mechreport.forces import METHODS

ROOT = Path(__file__).resolve().parents[2]
R2 = math.sqrt(2.0)
REACTION_METHODS = [m for m in METHODS if m != "power"]


@pytest.fixture(scope="module")
def slider_crank():
    return analyse(ROOT / "specs" / "slider_crank.yaml")


@pytest.fixture(scope="module")
def r_rtr_rtr():
    return analyse(ROOT / "specs" / "r_rtr_rtr.yaml")


# Section 4.6.1-4.6.4 final results at phi = 45 deg. (Intermediate eqs. 4.57, 4.72, 4.73 and
# 4.75 of the text have typos, see ERRATA.md; these final values are right.)
SLIDER_CRANK_45 = {
    "joint.C_T.fy": -85 - 3 * R2 / 2,            # F03y
    "joint.C_T.fx": 0.0,                          # F03 is normal to the x guide
    "joint.C_T.moment": 0.0,                      # F03 acts at C (P = C in 4.6.1)
    "joint.C.fx": -100 - R2,                      # F23x
    "joint.C.fy": 95 + 3 * R2 / 2,                # F23y
    "joint.B.fx": -(400 + 7 * R2) / 4,            # F12x
    "joint.B.fy": 5 * (84 + R2) / 4,              # F12y
    "joint.A.fx": -2 * (50 + R2),                 # F01x
    "joint.A.fy": 115 + R2,                       # F01y
    "driver.torque": 3 + 105 * R2,                # M
}


@pytest.mark.parametrize("method", REACTION_METHODS)
def test_4_6_slider_crank_reactions_at_45deg(slider_crank, method):
    k = slider_crank.kinematics.at(45)
    res = slider_crank.forces[method]
    for quantity, expected in SLIDER_CRANK_45.items():
        got = float(res.quantity(quantity)[k])
        assert got == pytest.approx(expected, rel=1e-9, abs=1e-9), quantity


def test_4_6_magnitudes_at_45deg(slider_crank):
    """|F23| = sqrt(38063/2 + 485 sqrt2), |F12| = sqrt(84137 + 2450 sqrt2)/2,
    |F01| = sqrt(23235 + 630 sqrt2) (4.6.1)."""
    k = slider_crank.kinematics.at(45)
    r = slider_crank.forces["newton_euler"].reactions
    assert r["C"].f[k] == pytest.approx(math.sqrt(38063 / 2 + 485 * R2), rel=1e-12)
    assert r["B"].f[k] == pytest.approx(math.sqrt(84137 + 2450 * R2) / 2, rel=1e-12)
    assert r["A"].f[k] == pytest.approx(math.sqrt(23235 + 630 * R2), rel=1e-12)


def test_4_6_power_balance_torque_at_45deg(slider_crank):
    k = slider_crank.kinematics.at(45)
    assert slider_crank.forces["power"].driver_torque[k] == pytest.approx(3 + 105 * R2,
                                                                         rel=1e-12)


def test_4_6_3_dyad_printed_decimals(slider_crank):
    """4.6.3 prints F12 = (-102.475, 106.768) N and F03y = -87.1213 N."""
    k = slider_crank.kinematics.at(45)
    r = slider_crank.forces["dyad"].reactions
    assert r["B"].fx[k] == pytest.approx(-102.475, abs=5e-4)
    assert r["B"].fy[k] == pytest.approx(106.768, abs=5e-4)
    assert r["C_T"].fy[k] == pytest.approx(-87.1213, abs=5e-5)


def test_4_6_singular_positions_flagged(slider_crank):
    """ERRATA: with AB = BC the mechanism is singular at 90 and 270 deg (slider at A)."""
    assert [f.angle for f in slider_crank.flags] == [90.0, 270.0]
    assert slider_crank.kinematics.index_of(90) is None


# Section 4.7.1-4.7.3 results at phi = 30 deg, printed to 6 significant digits.
R_RTR_RTR_30 = {
    "joint.E.fx": (268.165, 5e-4), "joint.E.fy": (135.057, 5e-4),             # F05
    # F45 = -268.109 i - 134.647 j: 4.7.3 prints -134.646 (truncated; ERRATA)
    "joint.D_T.fx": (268.109, 5e-4), "joint.D_T.fy": (134.647, 5e-4),         # F54 = -F45
    "joint.D.fx": (-268.072, 5e-4), "joint.D.fy": (-134.583, 5e-4),           # F34
    "joint.D_T.px": (-0.149492, 5e-7), "joint.D_T.py": (0.0476701, 5e-8),     # r_P
    "joint.C.fx": (-256.745, 5e-4), "joint.C.fy": (-272.179, 5e-4),           # F03
    "joint.B_T.fx": (11.3762, 5e-5), "joint.B_T.fy": (-137.93, 5e-3),         # F32 = -F23
    "joint.B_T.px": (0.121243, 5e-7), "joint.B_T.py": (0.07, 5e-3),           # r_Q
    "joint.B.fx": (-11.4028, 5e-5), "joint.B.fy": (137.993, 5e-4),            # F12
    "joint.A.fx": (-11.4214, 5e-5), "joint.A.fy": (138.092, 5e-4),            # F01
    "driver.torque": (17.5356, 5e-5),                                         # M_m
}


@pytest.mark.parametrize("method", REACTION_METHODS)
def test_4_7_r_rtr_rtr_reactions_at_30deg(r_rtr_rtr, method):
    k = r_rtr_rtr.kinematics.at(30)
    res = r_rtr_rtr.forces[method]
    for quantity, (expected, tol) in R_RTR_RTR_30.items():
        got = float(res.quantity(quantity)[k])
        assert got == pytest.approx(expected, abs=tol), quantity


def test_4_7_power_balance_torque_at_30deg(r_rtr_rtr):
    k = r_rtr_rtr.kinematics.at(30)
    assert r_rtr_rtr.forces["power"].driver_torque[k] == pytest.approx(17.5356, abs=5e-5)


def test_4_7_external_moment_opposes_rotation(r_rtr_rtr):
    """M_5ext = -sign(omega5) 100 k: -100 N m at 30 deg, where omega5 = 0.917 rad/s."""
    k = r_rtr_rtr.kinematics.at(30)
    (load,) = r_rtr_rtr.loads
    assert load.moment[k] == -100.0


def test_4_7_3_contour_walks_loops_as_the_text(r_rtr_rtr):
    """4.7.3 does loop 0-3-4-5-0 first (E, D_T, D), then 0-1-2-3-0 (C, B_T, B, A)."""
    titles = [s.title.split()[1] for s in r_rtr_rtr.worked_steps("contour")]
    assert titles == ["E", "D_T", "D", "C", "B_T", "B", "A"]


def test_4_7_2_dyad_order_last_group_first(r_rtr_rtr):
    titles = [s.title for s in r_rtr_rtr.worked_steps("dyad")]
    assert titles[0].startswith("Dyad D D_T E") and titles[2].startswith("Dyad B B_T C")
    assert titles[-1] == "Driver link link1"
