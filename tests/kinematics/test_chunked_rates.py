"""Kinematics solved in chunks (to bound memory) equal one batch: the same flags, and the
same positions, rates, accelerations and closure errors to the bit."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mechreport.kinematics import solve_kinematics
from mechreport.model import build_mechanism
from mechreport.spec import load_spec

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("name", ["r_rtr_rtr", "stephenson3_six_bar"])
def test_chunked_kinematic_rates_equal_one_batch(name, monkeypatch):
    import mechreport.kinematics as kinematics
    mech = build_mechanism(load_spec(ROOT / "specs" / f"{name}.yaml"))
    whole = solve_kinematics(mech)
    monkeypatch.setattr(kinematics, "CHUNK", 41)
    chunked = solve_kinematics(mech)
    assert whole.n > 2 * 41
    assert [(f.angle, f.reason) for f in chunked.flags] == [(f.angle, f.reason)
                                                            for f in whole.flags]
    for what in ("r", "theta", "v", "omega", "a", "alpha", "error"):
        np.testing.assert_array_equal(getattr(chunked, what), getattr(whole, what))
