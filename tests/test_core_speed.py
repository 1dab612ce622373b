"""The speed and memory machinery changes no number: chunked force solves, results sliced
instead of solved twice, equation objects rebuilt on demand instead of kept."""
from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from mechreport import forces as forces_pkg
from mechreport.analysis import analyse
from mechreport.forces import METHODS, ForceContext, solve_forces
from mechreport.kinematics import solve_kinematics
from mechreport.model import build_mechanism
from mechreport.spec import load_spec

ROOT = Path(__file__).resolve().parents[1]


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
        assert res._steps == []
        eager = METHODS[name].build_steps(ctx)
        assert [s.title for s in res.steps] == [s.title for s in eager]
        values = res.values()
        for step in res.steps:
            for eq in step.equations:
                scale = max(1.0, max(float(np.max(np.abs(v))) for v in values.values()))
                assert np.max(np.abs(eq.evaluate(values))) < 1e-9 * scale, (name, eq.label)


def test_flagged_angles_are_sliced_not_solved_again(monkeypatch):
    """An angle one method flags is cut from every result; what is left equals a fresh solve
    on the kept kinematics."""
    from mechreport.forces import power
    real = power.solve
    calls = []

    def singular_at_90(ctx):
        calls.append(ctx.n)
        res = real(ctx)
        bad = ctx.kin.angles == 90.0
        return dataclasses.replace(res, driver_torque=np.where(bad, np.nan, res.driver_torque),
                                   singular=res.singular | bad)

    monkeypatch.setattr(power, "solve", singular_at_90)
    a = analyse(ROOT / "specs" / "r_rtr_rtr.yaml")
    assert calls == [a.kinematics.n + 1]          # one solve, not two
    fresh = solve_forces(a.kinematics)
    for method, res in a.forces.items():
        _same(res, fresh[method])


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
