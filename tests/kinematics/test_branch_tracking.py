"""Branch tracking through touch points, and the vectorised resolution of flip decisions."""
from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from mechreport.kinematics import solve_kinematics
from mechreport.kinematics.position import _resolve
from mechreport.model import build_mechanism
from mechreport.spec import Sweep, load_spec

ROOT = Path(__file__).resolve().parents[2]


def sequential(decide):
    out, f1, f2 = [], False, False
    for k in range(decide.shape[2]):
        f = bool(decide[int(f1), int(f2), k])
        out.append(f)
        f1, f2 = f, f1
    return out


def test_resolve_matches_sequential_rule():
    rng = np.random.default_rng(7)
    for _ in range(500):
        m = int(rng.integers(0, 40))
        decide = rng.random((2, 2, m)) < 0.5
        assert _resolve(decide).tolist() == sequential(decide)


@pytest.mark.parametrize("step", [1, 5, 7, 8, 10, 12, 13, 15, 16, 17, 20, 21, 23, 30])
def test_4_6_slider_crank_continues_through_its_touch_points_at_any_step(step):
    """AB = BC: the slider passes A at 90 and 270 deg (flagged, ERRATA); followed smoothly,
    x_C = 2 cos(phi) at every other angle, however coarse the sweep."""
    spec = dataclasses.replace(load_spec(ROOT / "specs" / "slider_crank.yaml"),
                               sweep=Sweep(0, 360, step), expect=())
    kin = solve_kinematics(build_mechanism(spec))
    x_c = kin.named_point("C").r[:, 0]
    np.testing.assert_allclose(x_c, 2 * np.cos(np.radians(kin.angles)), atol=1e-9)


def test_a_dyad_that_comes_back_on_its_other_branch_has_no_cycle_quantities():
    """A change-point four-bar (1 + 3 = 2 + 2) followed smoothly through its change point at
    0 deg is crossed from 1 to 89 deg and open from 90 deg: the motion repeats every two turns,
    so a 360-degree cycle would join two assemblies. The kinematics say so, and the cycle
    quantities are undefined with that reason; a parallelogram, whose change points come in a
    pair, comes back to its start."""
    from mechreport.pipeline.analysis import analyse
    edge = Path(__file__).resolve().parents[1] / "data" / "edge"
    a = analyse(edge / "change_point_four_bar.yaml")
    kin = a.kinematics
    c = kin.named_point("C", "rocker").r
    assert c[kin.at(359), 1] > 0 > c[kin.at(1), 1]          # the branch changed at 0 deg
    assert [b.closes for b in kin.branches] == [False]
    assert "is on its other branch" in " ".join(kin.notes())
    assert a.review is None and "repeats every two turns" in a.review_problem
    p = analyse(edge / "parallelogram_four_bar.yaml")
    assert [b.closes for b in p.kinematics.branches] == [True] and p.review is not None
