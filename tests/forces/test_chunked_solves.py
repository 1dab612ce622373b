"""Force solves cut up to save time and memory change no number: a sweep solved in chunks
equals one batch, the equation objects a result does not keep are rebuilt on demand and still
balance, angles one method flags are sliced from the results rather than solved again, and a
slider's application point is judged against the whole sweep, not each chunk."""
from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from mechreport import forces as forces_pkg
from mechreport.forces import METHODS, ForceContext, solve_forces, worked_steps
from mechreport.kinematics import solve_kinematics
from mechreport.model import build_mechanism
from mechreport.pipeline.analysis import analyse
from mechreport.spec import load_spec

ROOT = Path(__file__).resolve().parents[2]


def _same(a, b):
    va, vb = a.values(), b.values()
    assert va.keys() == vb.keys()
    for k in va:
        np.testing.assert_allclose(va[k], vb[k], rtol=1e-12, atol=1e-12 * np.max(np.abs(vb[k])))
    np.testing.assert_array_equal(a.singular, b.singular)


@pytest.mark.parametrize("name", ["r_rtr_rtr", "stephenson3_six_bar", "hydraulic_boom"])
def test_chunked_force_solve_equals_one_batch(name, monkeypatch):
    kin = solve_kinematics(build_mechanism(load_spec(ROOT / "specs" / f"{name}.yaml")))
    whole = solve_forces(kin)
    monkeypatch.setattr(forces_pkg, "CHUNK", 37)     # chunks of uneven length, one short
    chunked = solve_forces(kin)
    assert kin.n > 2 * 37
    for method in whole:
        _same(chunked[method], whole[method])
        np.testing.assert_array_equal(chunked[method].angles, kin.angles)


def test_equation_objects_are_rebuilt_on_demand_and_balance():
    """Results keep no equation objects; asked for, they are the method's own, and every
    equation vanishes with the solved values."""
    kin = solve_kinematics(build_mechanism(load_spec(ROOT / "specs" / "slider_crank.yaml")))
    ctx = ForceContext(kin)
    for name, res in solve_forces(kin, ctx=ctx).items():
        assert not any(isinstance(v, (list, tuple)) for v in vars(res).values())
        eager = METHODS[name].build_steps(ctx)
        again = worked_steps(ctx, name)
        assert [s.title for s in again] == [s.title for s in eager]
        values = res.values()
        for step in again:
            for eq in step.equations:
                scale = max(1.0, max(float(np.max(np.abs(v))) for v in values.values()))
                assert np.max(np.abs(eq.evaluate(values))) < 1e-9 * scale, (name, eq.label)


def test_flagged_angles_are_sliced_not_solved_again(monkeypatch):
    """An angle one method flags is cut from every result; what is left equals a fresh solve
    on the kept kinematics."""
    real = forces_pkg.run_methods
    calls = []

    def singular_at_90(steps, ctx, prepared=None):
        calls.append(ctx.n)
        out = real(steps, ctx, prepared)
        res = out["power"]
        bad = ctx.kin.angles == 90.0
        out["power"] = dataclasses.replace(
            res, driver_torque=np.where(bad, np.nan, res.driver_torque),
            singular=res.singular | bad)
        return out

    monkeypatch.setattr(forces_pkg, "run_methods", singular_at_90)
    a = analyse(ROOT / "specs" / "r_rtr_rtr.yaml")
    assert calls == [a.kinematics.n + 1]          # one solve, not two
    fresh = solve_forces(a.kinematics)
    for method, res in a.forces.items():
        _same(res, fresh[method])


def test_slider_points_are_defined_against_the_whole_sweep():
    """A T joint's application point is undefined where its force is below 1e-12 of the
    largest over the sweep: joining chunks judges against the whole sweep, not each chunk
    (a chunk of tiny forces has points of its own that the whole sweep leaves undefined)."""
    from mechreport.forces import ForceResult, dyad
    from mechreport.forces.result import slider_point
    kin = solve_kinematics(build_mechanism(load_spec(ROOT / "specs" / "slider_crank.yaml")))
    ctx = ForceContext(kin)
    res = dyad.solve(ctx)
    one, two = slice(0, 100), slice(100, kin.n)
    first = res.take(one, ForceContext(kin.take(one, ())))
    c2 = ForceContext(kin.take(two, ()))
    second = res.take(two, c2)
    r = second.reactions["C_T"]
    tiny = dataclasses.replace(r, fx=r.fx * 1e-14, fy=r.fy * 1e-14, moment=r.moment * 1e-14)
    tiny = dataclasses.replace(tiny, **dict(zip(("px", "py"), slider_point(
        c2, c2.spec.joint("C_T"), tiny.fx, tiny.fy, tiny.moment))))
    assert np.isfinite(tiny.px).all()                   # defined against its own chunk
    second = dataclasses.replace(second, reactions={**second.reactions, "C_T": tiny})
    joined = ForceResult.join([first, second], ctx).reactions["C_T"]
    assert np.isfinite(joined.px[:100]).all() and np.isnan(joined.px[100:]).all()
    # the largest force is over both components (either may hold it); a NaN leaves every
    # point undefined: as the plain formula over the stacked force does
    u, at = ctx.line_direction(ctx.spec.joint("C_T")), ctx.joint_points["C_T"]
    rng = np.random.default_rng(2)
    for case in range(4):
        fx, fy, m = rng.normal(size=(3, kin.n)) * 10.0 ** rng.uniform(-3, 3, (3, 1))
        fx[:5] *= 1e-13
        fy[:5] *= 1e-13
        if case == 3:
            fy[7] = np.nan
        f = np.stack([fx, fy], axis=1)
        s = u[:, 0] * f[:, 1] - u[:, 1] * f[:, 0]
        with np.errstate(divide="ignore", invalid="ignore"):
            t = np.where(np.abs(s) > 1e-12 * np.maximum(np.max(np.abs(f), initial=0.0),
                                                         1e-300), m / s, np.nan)
        ref = at + t[:, None] * u
        got = slider_point(ctx, ctx.spec.joint("C_T"), fx, fy, m)
        np.testing.assert_array_equal(got, (ref[:, 0], ref[:, 1]))
