"""A four-bar holding a load torque at rest (tests/data/four_bar_load_torque_at_rest.yaml,
points partly in polar form): the crank's holding torque against the closed form of virtual
work, M = -T omega4/omega2, with the velocity ratio of the four-bar
omega4/omega2 = a sin(theta3 - theta2) / (c sin(theta3 - theta4)) (the derivative of the
four-bar's loop-closure equation) from positions found by circle intersection."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

import mechreport

ROOT = Path(__file__).resolve().parents[2]
SPEC = ROOT / "tests" / "data" / "four_bar_load_torque_at_rest.yaml"
A_, B_, C_ = 0.060, 0.200, 0.140                 # crank, coupler, rocker [m]
D = 0.220 * np.array([math.cos(math.radians(10)), math.sin(math.radians(10))])
T = -25.0                                        # load torque on the rocker [N m]


def _angles(phi: np.ndarray):
    """theta3 (coupler), theta4 (rocker) [rad] at crank angles ``phi`` [rad], the branch with
    C to the left of B->D (the spec's assembly hint)."""
    B = np.stack([A_ * np.cos(phi), A_ * np.sin(phi)], axis=1)
    BD = D - B
    L = np.hypot(BD[:, 0], BD[:, 1])
    along = (B_**2 - C_**2 + L**2) / (2 * L)
    h = np.sqrt(B_**2 - along**2)
    u = BD / L[:, None]
    C = B + along[:, None] * u + h[:, None] * np.stack([-u[:, 1], u[:, 0]], axis=1)
    return (np.arctan2(C[:, 1] - B[:, 1], C[:, 0] - B[:, 0]),
            np.arctan2(C[:, 1] - D[1], C[:, 0] - D[0]))


def test_closed_form_four_bar_holding_a_load_torque_by_virtual_work():
    a = mechreport.analyse(SPEC)
    assert a.passed
    phi = np.radians(a.angles)
    th3, th4 = _angles(phi)
    ratio = A_ * np.sin(th3 - phi) / (C_ * np.sin(th3 - th4))
    holding = -T * ratio
    for name, res in a.forces.items():
        np.testing.assert_allclose(res.driver_torque, holding, rtol=1e-10,
                                   atol=1e-12 * abs(T), err_msg=name)
    # the massless coupler is a two-force member: its pins carry one force along B->C
    theta = np.radians(a.kinematics.angle_deg("coupler"))
    b = a.forces["dyad"].reactions["B"]
    np.testing.assert_allclose(b.fx * np.sin(theta) - b.fy * np.cos(theta), 0,
                               atol=1e-9 * np.max(b.f))
