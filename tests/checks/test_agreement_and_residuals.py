"""The checks' fast paths give the plain answers: the methods' spreads judged for many
quantities together equal one quantity at a time (a NaN the worst disagreement), residuals
taken as one matrix product equal the equations evaluated one by one (an unknown named
twice, constants only, and either path of the whole check), and a NaN in a method's values
makes its residual infinite, never a perfect 0."""
from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from mechreport.forces import ForceContext, solve_forces
from mechreport.kinematics import solve_kinematics
from mechreport.model import build_mechanism
from mechreport.spec import load_spec

ROOT = Path(__file__).resolve().parents[2]


def test_spreads_judged_together_equal_one_quantity_at_a_time(monkeypatch):
    """checks.agreement judges the quantities given by the same methods together, in slices
    of at most STACK_LIMIT values: one quantity per slice gives the same spreads, pairs and
    angles, a NaN (the worst disagreement) included."""
    import importlib      # mechreport.checks.agreement: in its package, a function's name too
    ag = importlib.import_module("mechreport.checks.agreement")
    spec = load_spec(ROOT / "specs" / "r_rtr_rtr.yaml")
    kin = solve_kinematics(build_mechanism(spec))
    forces = solve_forces(kin)
    nan = dataclasses.replace(forces["dyad"], driver_torque=forces["dyad"].driver_torque.copy())
    nan.driver_torque[5] = np.nan
    for results in (forces, {**forces, "dyad": nan}):
        together = ag.spreads(results)
        monkeypatch.setattr(ag, "STACK_LIMIT", 1)
        alone = ag.spreads(results)
        monkeypatch.undo()
        assert list(together) == list(alone)
        for q in together:
            a, b = together[q], alone[q]
            assert (a.methods, a.angle, a.n_methods) == (b.methods, b.angle, b.n_methods), q
            np.testing.assert_array_equal([a.spread, a.top], [b.spread, b.top], err_msg=q)
    assert np.isnan(ag.spreads({**forces, "dyad": nan})["driver.torque"].spread)


@pytest.mark.parametrize("path", sorted((ROOT / "specs").glob("*.yaml"))
                         + sorted((ROOT / "tests" / "data").rglob("*.yaml")),
                         ids=lambda p: p.stem)
def test_residuals_by_matrix_are_the_equations_evaluated(path):
    """A short sweep's residual check evaluates every link's Newton-Euler equations with
    every method's values as one matrix product per angle; each equation's largest
    residual is Equation.evaluate's up to the rounding of a sum taken in another order
    (below (terms) eps times the sum of the terms' magnitudes), on every spec."""
    import importlib
    from mechreport.forces.builders import newton_euler_equations
    module = importlib.import_module("mechreport.checks.residuals")
    spec = load_spec(path)
    spec = dataclasses.replace(spec, sweep=dataclasses.replace(
        spec.sweep, step=(spec.sweep.stop - spec.sweep.start) / 40))
    kin = solve_kinematics(build_mechanism(spec))
    ctx = ForceContext(kin)
    forces = solve_forces(kin, None, ctx)
    solved = {name: res.values() for name, res in forces.items() if res.reactions}
    names = list(solved)
    unknowns = list(solved[names[0]])
    values = np.array([[solved[name][u] for name in names] for u in unknowns])
    equations = [eq for link in spec.links for eq in newton_euler_equations(ctx, link.name)]
    got = module._largest_by_matrix(equations, unknowns, values)
    by_name = {u: values[i] for i, u in enumerate(unknowns)}
    eps = np.finfo(float).eps
    for e, eq in enumerate(equations):
        want = np.abs(eq.evaluate(by_name)).max(axis=-1)
        size = sum(np.abs(t.const) + sum(np.abs(t.coeffs[:, j] * by_name[u])
                                         for j, u in enumerate(t.action.unknowns))
                   for t in eq.terms)                                     # (methods, n)
        bound = 2 * len(eq.terms) * 3 * eps * size.max(axis=-1)
        assert (np.abs(got[e] - want) <= bound).all(), (eq.label, got[e], want, bound)
    # the whole check: the same method by method, through either path
    short = module.residuals(ctx, forces)
    old = module.DENSE_MAX
    try:
        module.DENSE_MAX = 0
        long = module.residuals(ctx, forces)
    finally:
        module.DENSE_MAX = old
    for a, b in zip(short, long):
        assert a.method == b.method
        assert a.force == pytest.approx(b.force, abs=1e-9) and \
            a.moment == pytest.approx(b.moment, abs=1e-9)


def test_residuals_by_matrix_take_an_unknown_named_twice():
    """An equation that names one unknown in two terms (the matrix has one place for it:
    the second is added apart) and one with constants only."""
    import importlib
    from mechreport.forces.equations import Action, Equation, Term
    module = importlib.import_module("mechreport.checks.residuals")
    n = 5
    rng = np.random.default_rng(3)
    a1 = Action("F1", "force", "reaction", "link", unknowns=("a", "b"))
    a2 = Action("F2", "force", "reaction", "link", unknowns=("a",))
    known = Action("G", "force", "gravity", "link")
    eqs = [Equation("twice", "force", ("link",),
                    [Term(a1, rng.standard_normal((n, 2)), rng.standard_normal(n)),
                     Term(a2, rng.standard_normal((n, 1)), rng.standard_normal(n), "lhs")]),
           Equation("known", "force", ("link",),
                    [Term(known, np.zeros((n, 0)), rng.standard_normal(n), "lhs")])]
    values = rng.standard_normal((2, 3, n))           # a, b for 3 methods
    got = module._largest_by_matrix(eqs, ["a", "b"], values)
    for e, eq in enumerate(eqs):
        want = np.broadcast_to(np.abs(eq.evaluate({"a": values[0], "b": values[1]}))
                               .max(axis=-1), (3,))
        np.testing.assert_allclose(got[e], want, rtol=1e-13, atol=1e-14)


def test_residual_of_a_value_that_is_not_a_number_is_infinitely_bad():
    """A NaN in a method's values makes its residuals inf, through either path (a NaN
    residual dropped by a max would read as a perfect 0); the other methods' stay finite."""
    import importlib
    module = importlib.import_module("mechreport.checks.residuals")
    spec = load_spec(ROOT / "specs" / "four_bar.yaml")
    for step, dense in ((10.0, 256), (10.0, 0), (1.0, 256)):
        spec_n = dataclasses.replace(spec, sweep=dataclasses.replace(spec.sweep, step=step))
        kin = solve_kinematics(build_mechanism(spec_n))
        ctx = ForceContext(kin)
        forces = solve_forces(kin, None, ctx)
        torque = forces["newton_euler"].driver_torque.copy()
        torque[3] = np.nan
        forces["newton_euler"] = dataclasses.replace(forces["newton_euler"],
                                                     driver_torque=torque)
        old = module.DENSE_MAX
        try:
            module.DENSE_MAX = dense
            found = {r.method: r for r in module.residuals(ctx, forces)}
        finally:
            module.DENSE_MAX = old
        assert found["newton_euler"].moment == np.inf, (step, dense)
        assert all(np.isfinite([r.force, r.moment]).all()
                   for name, r in found.items() if name != "newton_euler"), (step, dense)
