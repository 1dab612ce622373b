"""Properties of the force methods over whole sweeps of every spec in specs/ and tests/data/
(the latter cover dyad types the shipped specs do not, e.g. TRT).

- one contract every method must meet (same result type, square labelled systems, its own
  equations satisfied by its own answer);
- all methods agree to 1e-9 relative and the power balance gives the same torque;
- every method's reactions satisfy every link's Newton-Euler equations;
- the methods are genuinely different computations (different systems).
"""
from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from mechreport.pipeline.analysis import analyse
from mechreport.forces import METHODS, ForceResult
from mechreport.linalg import batched_solve

ROOT = Path(__file__).resolve().parents[2]
SPECS = sorted((ROOT / "specs").glob("*.yaml")) + sorted((ROOT / "tests" / "data").glob("*.yaml"))


@pytest.fixture(scope="module", params=SPECS, ids=lambda p: p.stem)
def analysis(request):
    return analyse(request.param)


@pytest.mark.parametrize("method", list(METHODS))
def test_contract_every_method(analysis, method):
    res = analysis.forces[method]
    assert isinstance(res, ForceResult) and res.method == method
    assert np.array_equal(res.angles, analysis.angles)
    assert not res.singular.any()
    values = res.values()
    for name, v in values.items():
        assert v.shape == analysis.angles.shape and np.all(np.isfinite(v)), name
    if method != "power":
        assert list(res.reactions) == list(analysis.spec.reported_reactions())
        assert {j.name for j in analysis.spec.joints} <= set(res.reactions)
    scale = max(float(np.max(np.abs(v))) for v in values.values())
    for step in analysis.worked_steps(method):
        assert len(step.equations) == len(step.unknowns), step.title
        for eq in step.equations:  # the labelled equations are what was solved
            assert np.max(np.abs(eq.evaluate(values))) <= 1e-9 * scale, (step.title, eq.label)


def test_methods_agree_over_sweep(analysis):
    for a in analysis.agreement:
        assert a.relative <= 1e-9, a


def test_power_balance_matches_torque(analysis):
    ne = analysis.forces["newton_euler"].driver_torque
    pw = analysis.forces["power"].driver_torque
    np.testing.assert_allclose(pw, ne, rtol=0, atol=1e-9 * np.max(np.abs(ne)))


def test_reactions_satisfy_newton_euler_of_every_link(analysis):
    forces = [np.max(np.abs(r.f)) for r in analysis.forces["dyad"].reactions.values()]
    for r in analysis.residuals:
        assert r.force <= 1e-10 * max(forces), r
        assert r.moment <= 1e-10 * max(forces), r


def test_expectations_pass(analysis):
    failed = [e.message for e in analysis.expectations if not e.ok]
    assert not failed


def test_methods_are_different_computations(analysis):
    """Same answers, different systems: step structure and moment centres differ."""
    worked = {name: analysis.worked_steps(name) for name in analysis.forces}
    n_links = len(analysis.spec.links)
    assert len(worked["newton_euler"]) == len(worked["dalembert"]) == 1
    groups = analysis.mechanism.groups          # dyads: outer and interior steps; others: one
    assert len(worked["dyad"]) == sum(2 if g.dyad is not None else 1 for g in groups)
    solved = [name for s in worked["contour"]        # each joint once, some several together
              for name in s.title.split(" (")[0].split(" ", 1)[1].split(", ")]
    assert sorted(solved) == sorted(j.name for j in analysis.spec.joints)
    ne_about = {eq.about for eq in worked["newton_euler"][0].equations if eq.kind == "moment"}
    da_about = {eq.about for eq in worked["dalembert"][0].equations if eq.kind == "moment"}
    assert ne_about == {f"C{k}" for k in range(1, n_links + 1)}   # centres of mass
    assert not ne_about & da_about                                 # joints, not centres


def test_no_nan_in_results(analysis):
    for res in analysis.forces.values():
        for r in res.reactions.values():
            for arr in (r.fx, r.fy, r.moment):
                assert arr is None or np.all(np.isfinite(arr))
            if r.px is not None:   # undefined only where the slider force vanishes
                undefined = ~np.isfinite(r.px)
                assert np.all(r.f[undefined] < 1e-9 * max(1.0, np.max(r.f)))


def test_singular_system_is_flagged_not_solved():
    A = np.array([np.eye(3), [[1.0, 2, 3], [2, 4, 6], [0, 0, 1]], [[1.0, 1, 0], [1, 1 + 1e-13, 0], [0, 0, 1]]])
    b = np.ones((3, 3))
    x, singular = batched_solve(A, b)
    assert singular.tolist() == [False, True, True]
    assert np.allclose(x[0], 1) and np.all(np.isnan(x[1:]))


def test_condition_check_ignores_units():
    """A well-posed system in mm and tonnes is as regular as in m and kg."""
    A = np.array([[[1e6, 0.0], [0.0, 1e-6]]])
    x, singular = batched_solve(A, np.array([[1e6, 1e-6]]))
    assert not singular[0] and np.allclose(x, 1)


def test_load_at_a_point_named_like_a_centre_of_mass(tmp_path):
    """A user point called C2 on link 2 is not link 2's centre of mass (textbook names C1,
    C2 ... are ours): a load there must work through that point's own velocity."""
    text = (ROOT / "specs" / "slider_crank.yaml").read_text()
    text = text.replace("points: {B: [0, 0], C: [1, 0]}", "points: {B: [0, 0], C: [1, 0], "
                                                          "C2: [0.8, 0.1]}")
    text = text.replace("loads:\n", "loads:\n  - {type: force, link: rod, point: C2, "
                                    "value: [30, -70]}\n")
    spec = tmp_path / "c2.yaml"
    spec.write_text(text.split("expect:")[0])
    a = analyse(spec)
    np.testing.assert_allclose(a.forces["power"].driver_torque,
                               a.forces["newton_euler"].driver_torque, rtol=0, atol=1e-9)


def test_angle_singular_for_one_method_is_flagged_and_left_out(monkeypatch):
    """A method whose system is singular at an angle (kinematics fine there): the angle is
    flagged with the method named, and left out of every result, which stay free of NaN."""
    from mechreport.forces import power
    from mechreport.forces.equations import Term
    real = power.build_steps

    def singular_at_60(ctx):            # the driver's power is 0 M there: no equation for M
        (step,) = real(ctx)
        (eq,) = step.equations
        driver = eq.terms[0]
        zero = np.where((ctx.kin.angles == 60.0)[:, None], 0.0, driver.coeffs)
        terms = [Term(driver.action, zero, driver.const, driver.side, rate=driver.rate,
                      kind=driver.kind), *eq.terms[1:]]
        return (dataclasses.replace(step, equations=[dataclasses.replace(eq, terms=terms)]),)

    monkeypatch.setattr(power, "build_steps", singular_at_60)
    a = analyse(ROOT / "specs" / "four_bar.yaml")
    assert [(f.angle, f.reason) for f in a.flags] == [(60.0, "force equations singular "
                                                             "(power)")]
    assert a.kinematics.index_of(60) is None and len(a.angles) == 359
    for res in a.forces.values():
        assert len(res.angles) == 359
        assert all(np.all(np.isfinite(v)) for v in res.values().values())
