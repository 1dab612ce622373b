"""The speed and memory machinery changes no number: chunked force solves, results sliced
instead of solved twice, equation objects rebuilt on demand instead of kept."""
from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from mechreport import forces as forces_pkg
from mechreport import linalg
from mechreport.pipeline.analysis import analyse
from mechreport.forces import METHODS, ForceContext, solve_forces, worked_steps
from mechreport.kinematics import solve_kinematics
from mechreport.model import build_mechanism
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


# ------------------------------------------------------------ block triangular solves

def _step(structure: dict[str, list[str]], unknowns: list[str]):
    """A Step whose equations name the given unknowns (coefficients are irrelevant here)."""
    from mechreport.forces.equations import Action, Equation, Step, Term
    eqs = []
    for label, names in structure.items():
        act = Action(label, "force", "reaction", "1", unknowns=tuple(names))
        eqs.append(Equation(label, "force", ("1",),
                            [Term(act, np.ones((1, len(names))), np.zeros(1))]))
    return Step("test", unknowns, eqs)


def test_triangular_blocks_order_dependencies_first():
    from mechreport.forces.equations import triangular_blocks
    # c from e3 alone; a and b together from e1, e2 (which also need c); d from e4 (needs a)
    step = _step({"e1": ["a", "b", "c"], "e2": ["a", "b"], "e3": ["c"], "e4": ["d", "a"]},
                 ["a", "b", "c", "d"])
    blocks = [(sorted(b.unknowns), sorted(e.label for e in b.equations))
              for b in triangular_blocks(step)]
    assert blocks == [(["c"], ["e3"]), (["a", "b"], ["e1", "e2"]), (["d"], ["e4"])]


def test_structurally_singular_step_is_left_whole():
    from mechreport.forces.equations import triangular_blocks
    step = _step({"e1": ["a"], "e2": ["a"], "e3": ["b", "c"]}, ["a", "b", "c"])
    assert triangular_blocks(step) == [step]


@pytest.mark.parametrize("name", ["r_rtr_rtr", "stephenson3_six_bar", "offset_slider_crank",
                                  "hydraulic_boom", "scotch_yoke"])
@pytest.mark.parametrize("method", ["newton_euler", "dalembert", "contour"])
def test_blockwise_solve_equals_the_whole_system(name, method):
    """Each method's systems solved whole (one LAPACK solve) and block by block agree."""
    from mechreport.forces.equations import solve_step, triangular_blocks
    kin = solve_kinematics(build_mechanism(load_spec(ROOT / "specs" / f"{name}.yaml")))
    steps = METHODS[method].build_steps(ForceContext(kin))
    whole: dict[str, np.ndarray] = {}
    parts: dict[str, np.ndarray] = {}
    for step in steps:
        whole.update(solve_step(step, whole, kin.n).values)
        for block in triangular_blocks(step):
            parts.update(solve_step(block, parts, kin.n).values)
    assert whole.keys() == parts.keys()
    for k in whole:
        np.testing.assert_allclose(parts[k], whole[k], rtol=1e-11,
                                   atol=1e-12 * max(np.max(np.abs(whole[k])), 1.0))


@pytest.mark.parametrize("m", [1, 2])
def test_closed_form_small_solves_equal_lapack(m, monkeypatch):
    """1x1 and 2x2 systems are solved by Cramer's rule: same answer and condition estimate
    as the LAPACK path (3x3 systems padded with an identity row and column), exactly singular
    ones NaN with an infinite condition number."""
    from mechreport.linalg import batched_solve_cond
    _lapack_only(monkeypatch)        # the padding rows are constant: keep them for LAPACK
    rng = np.random.default_rng(7)
    n = 500
    A = rng.standard_normal((n, m, m)) * 10.0 ** rng.uniform(-3, 3, (n, m, 1))
    A[0] = 0.0                                    # exactly singular
    A[1, :, 0] = 0.0
    b = rng.standard_normal((n, m))
    x, cond = batched_solve_cond(A, b)
    big = np.zeros((n, 3, 3))
    big[:, :m, :m] = A
    big[:, m:, m:] = np.eye(3 - m)
    ref, _ = batched_solve_cond(big, np.concatenate([b, np.zeros((n, 3 - m))], axis=1))
    ok = np.arange(n) > 1
    np.testing.assert_allclose(x[ok], ref[ok, :m], rtol=1e-10)
    assert np.all(np.isinf(cond[:2])) and np.all(np.isnan(x[:2]))
    assert np.all(np.isfinite(cond[ok]))


def _lapack_only(monkeypatch):
    """Every system of size 3 and more through LAPACK (no constant rows eliminated, no row
    operations over the angle axis)."""
    from mechreport import linalg
    monkeypatch.setattr(linalg.ConstantRows, "of", staticmethod(lambda At, rs, bad: None))
    monkeypatch.setattr(linalg, "SMALL_LU", 2)


@pytest.mark.parametrize("m", [3, 4, 5, 6])
def test_small_systems_by_row_operations_equal_lapack(m, monkeypatch):
    """Systems up to SMALL_LU solved by Gaussian elimination with partial pivoting over the
    angle axis: LAPACK's solution and condition estimate to rounding; an exactly singular
    angle (a zero column) NaN with an infinite condition number, as LAPACK has it."""
    from mechreport.linalg import SMALL_LU, Equilibrated
    assert m <= SMALL_LU
    rng = np.random.default_rng(20 + m)
    n = 600
    A = rng.standard_normal((m, m, n)) * 10.0 ** rng.uniform(-3, 3, (m, 1, n))
    A[:, 1, 0] = 0.0                      # exactly singular
    A[0, :, 1] = A[1, :, 1]               # two equal rows: singular in exact arithmetic
    b = rng.standard_normal((n, m))
    fast = Equilibrated(A)
    assert fast.schur is None             # no constant rows: the row-operation path
    x, cond = fast.solve_cond(b)
    _lapack_only(monkeypatch)
    ref, ref_cond = Equilibrated(A).solve_cond(b)
    assert np.isinf(cond[0]) and np.isinf(ref_cond[0]) and np.all(np.isnan(x[0]))
    assert not cond[1] < 1e10 and not ref_cond[1] < 1e10
    ok = ref_cond < 1e8
    assert ok.mean() > 0.9
    err = np.abs(x - ref)[ok] / np.max(np.abs(ref[ok]), axis=1, keepdims=True)
    assert np.all(err <= 1e-14 * ref_cond[ok, None])
    np.testing.assert_allclose(cond[ok], ref_cond[ok], rtol=1e-6)


def _with_constant_rows(rng, n: int, p: int, q: int) -> np.ndarray:
    """Systems (m, m, n), angle-last: ``p`` rows of +-1 and 0, the same at every angle (force
    balances), over ``q`` rows that vary (moment equations, lever arms over six decades)."""
    m = p + q
    while True:
        K = rng.choice([-1.0, 0.0, 1.0], size=(p, m), p=[0.3, 0.4, 0.3])
        if p == 0 or np.linalg.matrix_rank(K[:, :p]) == p:
            break
    A = np.empty((m, m, n))
    A[:p] = K[:, :, None]
    A[p:] = rng.standard_normal((q, m, n)) * 10.0 ** rng.uniform(-3, 3, (q, 1, n))
    perm = rng.permutation(m)                  # constant rows anywhere, not first
    return A[perm]


@pytest.mark.parametrize("p,q", [(4, 0), (5, 1), (5, 2), (4, 3), (2, 5)])
def test_constant_rows_eliminated_equal_lapack(p, q, monkeypatch):
    """Systems whose constant rows are eliminated once for all angles (``ConstantRows``)
    give LAPACK's solution and condition estimate, to rounding."""
    from mechreport.linalg import Equilibrated
    rng = np.random.default_rng(11 + p + 10 * q)
    n = 400
    A = _with_constant_rows(rng, n, p, q)
    b = rng.standard_normal((n, p + q))
    fast = Equilibrated(A)
    assert fast.schur is not None and len(fast.schur.rest) == q
    x, cond = fast.solve_cond(b)
    _lapack_only(monkeypatch)
    ref, ref_cond = Equilibrated(A).solve_cond(b)
    ok = ref_cond < 1e8
    assert ok.mean() > 0.9
    err = np.abs(x - ref)[ok] / np.max(np.abs(ref[ok]), axis=1, keepdims=True)
    assert np.all(err <= 1e-14 * ref_cond[ok, None])
    np.testing.assert_allclose(cond[ok], ref_cond[ok], rtol=1e-6)


def test_constant_rows_singular_and_non_finite_angles(monkeypatch):
    """An angle where the Schur complement is exactly singular, and one whose coefficients
    are not finite, come out as the LAPACK path has them: NaN values, an infinite or NaN
    condition number; the other angles are untouched."""
    from mechreport.linalg import Equilibrated
    rng = np.random.default_rng(5)
    n, p, q = 50, 4, 2
    A = _with_constant_rows(rng, n, p, q)
    fast = Equilibrated(A)
    rows = fast.schur.rows
    others = fast.schur.others
    A[others[0], :, 7] = A[rows[0], :, 7]       # a varying row equal to a constant one
    A[others[1], 0, 9] = np.inf
    b = rng.standard_normal((n, p + q))
    fast = Equilibrated(A)
    assert fast.schur is not None
    x, cond = fast.solve_cond(b)
    _lapack_only(monkeypatch)
    ref, ref_cond = Equilibrated(A).solve_cond(b)
    assert np.isinf(cond[7]) and np.isinf(ref_cond[7])
    assert np.isnan(cond[9]) and np.isnan(ref_cond[9])
    assert np.all(np.isnan(x[[7, 9]])) and np.all(np.isnan(ref[[7, 9]]))
    ok = np.ones(n, bool)
    ok[[7, 9]] = False
    np.testing.assert_allclose(x[ok], ref[ok], rtol=1e-9, atol=1e-12)


def test_only_unit_constant_rows_are_eliminated():
    """Constant rows of +-1 and 0 are eliminated; a constant row with other numbers (a fixed
    lever arm) stays with the varying rows; dependent unit rows are not eliminated (the whole
    system goes to the general solve, which reports it singular)."""
    from mechreport.linalg import Equilibrated
    rng = np.random.default_rng(3)
    n = 20
    A = rng.standard_normal((3, 3, n))
    A[0] = np.array([1.0, 1.0, 0.0])[:, None]
    A[1] = np.array([1e-3, 0.0, 1.0])[:, None]
    plan = Equilibrated(A).schur
    assert plan is not None and list(plan.rows) == [0] and list(plan.others) == [1, 2]
    A[1] = np.array([-1.0, -1.0, 0.0])[:, None]           # the first row again, negated
    assert Equilibrated(A).schur is None


def test_constant_rows_with_other_numbers_keep_full_accuracy():
    """Constant rows of small lever arms with a nearly dependent pair (review finding: their
    elimination lost three digits on a system of condition number 4). Left with the varying
    rows, the solution is exact to rounding."""
    from fractions import Fraction
    from mechreport.linalg import Equilibrated
    A = np.array([[0.001, -1.0, 0.001, 0.1],
                  [-0.003, 1.0, 0.004, -0.121],
                  [-0.003, 0.0, -0.004, 1.0],
                  [0.002, 0.001, -0.003, -1.0]])
    At = np.stack([A, A], 2)
    At[2:, :, 1] *= 1.25
    b = np.array([[3.0, 4.0, 0.0, -3.0]] * 2)
    x, cond = Equilibrated(At).solve_cond(b)
    assert np.all(cond < 10)
    for k in range(2):                          # exact rational solution by elimination
        M = [[Fraction(v) for v in row] + [Fraction(r)] for row, r in zip(At[:, :, k], b[k])]
        for j in range(4):
            p = next(i for i in range(j, 4) if M[i][j] != 0)
            M[j], M[p] = M[p], M[j]
            for i in range(4):
                if i != j:
                    f = M[i][j] / M[j][j]
                    M[i] = [a - f * c for a, c in zip(M[i], M[j])]
        exact = np.array([float(M[i][4] / M[i][i]) for i in range(4)])
        np.testing.assert_allclose(x[k], exact, rtol=1e-14, atol=1e-15 * np.max(np.abs(exact)))


@pytest.mark.parametrize("scale", [1e160, 1e-170, 1e-160])
def test_constant_rows_schur_complement_at_extreme_scales(scale, monkeypatch):
    """Varying rows at the ends of double precision's range (review finding: the 2x2 Schur
    complement solved unscaled overflowed to an infinite determinant, every angle reported
    exactly singular): the complement is equilibrated, so the answer is LAPACK's."""
    from mechreport.linalg import Equilibrated
    rng = np.random.default_rng(8)
    n = 40
    A = rng.standard_normal((3, 3, n)) * scale
    A[0] = 1.0
    b = rng.standard_normal((n, 3)) * scale
    fast = Equilibrated(A)
    assert fast.schur is not None
    x, cond = fast.solve_cond(b)
    _lapack_only(monkeypatch)
    ref, ref_cond = Equilibrated(A).solve_cond(b)
    assert np.all(np.isfinite(cond)) and np.all(np.isfinite(x))
    np.testing.assert_allclose(cond, ref_cond, rtol=1e-6)
    err = np.abs(x - ref) / np.max(np.abs(ref), axis=1, keepdims=True)
    assert np.all(err <= 1e-14 * ref_cond[:, None])


def test_single_precision_systems_are_solved_in_double():
    """float32 coefficients with a constant row (review finding: the cached plan read the
    block's bytes as float64 and raised)."""
    from mechreport.linalg import batched_solve_cond
    rng = np.random.default_rng(9)
    A = rng.standard_normal((30, 3, 3))
    A[:, 0] = [1.0, -1.0, 0.0]
    b = rng.standard_normal((30, 3))
    x, cond = batched_solve_cond(A.astype(np.float32), b)
    ref, _ = batched_solve_cond(A.astype(np.float32).astype(float), b)
    np.testing.assert_allclose(x, ref, rtol=1e-12)


@pytest.mark.parametrize("name", ["r_rtr_rtr", "four_bar", "slider_crank"])
def test_force_blocks_of_three_and_more_eliminate_constant_rows(name):
    """Newton-Euler's and the dyad method's blocks (force balances with +-1 coefficients)
    reach LAPACK only through their Schur complements, 2x2 or smaller: the path that removed
    LAPACK's per-matrix cost stays taken."""
    from mechreport.forces.equations import step_system, triangular_blocks
    from mechreport.linalg import Equilibrated
    kin = solve_kinematics(build_mechanism(load_spec(ROOT / "specs" / f"{name}.yaml")))
    ctx = ForceContext(kin)
    for method in ("newton_euler", "dyad"):
        res = METHODS[method].solve(ctx)
        for block in (b for s in METHODS[method].build_steps(ctx)
                      for b in triangular_blocks(s)):
            if len(block.unknowns) >= 3:
                A, _ = step_system(block, res.values(), kin.n)
                schur = Equilibrated(A).schur
                assert schur is not None and len(schur.rest) <= 2, (method, block.unknowns)


def test_allocator_setting_respects_the_environment(monkeypatch):
    """The glibc setting the command line makes (keep freed memory for reuse) is skipped when
    the user set glibc's own variables or MECHREPORT_MALLOC=default."""
    from mechreport.app import process
    for name, value in (("MECHREPORT_MALLOC", "default"), ("MALLOC_TRIM_THRESHOLD_", "0"),
                        ("MALLOC_MMAP_THRESHOLD_", "131072")):
        with monkeypatch.context() as m:
            m.setenv(name, value)
            assert process.keep_freed_memory() is False
    import platform
    if platform.libc_ver()[0] == "glibc":        # applied where it can be
        assert process.keep_freed_memory() is True


def test_one_by_one_systems_answered_directly_equal_the_general_path():
    """linalg.solve_cond answers a 1x1 system without the general machinery: the same bits
    for solutions and condition numbers over six hundred decades, zeros, -0, subnormals,
    NaN and infinities in the coefficient and the right-hand side."""
    from mechreport import linalg
    rng = np.random.default_rng(1)
    n = 2000
    a = rng.standard_normal(n) * 10.0 ** rng.uniform(-300, 300, n)
    a[:20], a[20:30], a[30:40], a[40:45], a[45:50] = 0.0, np.nan, np.inf, -0.0, 5e-324
    b = rng.standard_normal(n) * 10.0 ** rng.uniform(-300, 300, n)
    b[50:60], b[60:70], b[70:80] = np.nan, np.inf, 0.0
    x, cond = linalg.solve_cond(a[None, None, :], b[:, None])
    with np.errstate(all="ignore"):
        ref, ref_cond = linalg.Equilibrated(a[None, None, :]).solve_cond(b[:, None])
    np.testing.assert_array_equal(cond, ref_cond)
    np.testing.assert_array_equal(x, ref)
    assert np.array_equal(np.signbit(x), np.signbit(ref))


@pytest.mark.parametrize("n", [300, 1])
@pytest.mark.parametrize("m", [1, 2])
def test_small_systems_prepared_together_equal_one_by_one(m, n):
    """linalg.prepare_small equilibrates and probes a chain's 1x1 and 2x2 systems together:
    each still gets the bits linalg.solve_cond gives it alone (solutions, their signs, and
    condition numbers), over extreme scales, singular and non-finite angles in the matrices
    and in the right-hand sides."""
    from mechreport import linalg
    rng = np.random.default_rng(7 + m)
    k = 5

    def system():
        A = rng.standard_normal((m, m, 300)) * 10.0 ** rng.uniform(-150, 150, (m, 1, 300))
        A[:, :, :10] = 0.0                               # zero matrices: singular
        A[:, :, 10:15] = np.nan
        A[0, 0, 15:20] = np.inf
        A[:, :, 20:25] = 5e-324
        if m == 2:
            A[1, :, 25:30] = A[0, :, 25:30] * 3.0        # dependent rows: exactly singular
            A[1, :, 30:35] = A[0, :, 30:35] * (1 + 1e-12)   # near-singular
        return A

    def rhs():
        b = rng.standard_normal((300, m)) * 10.0 ** rng.uniform(-150, 150, (300, 1))
        b[40:45] = np.nan
        b[45:50, 0] = np.inf
        b[50:55] = 0.0
        return b
    systems, rhss = [system() for _ in range(k)], [rhs() for _ in range(k)]
    if n == 1:      # every angle a system of its own (einsum sums one angle in another order)
        systems = [A[:, :, j:j + 1] for A in systems for j in range(300)]
        rhss = [b[j:j + 1] for b in rhss for j in range(300)]
    prepared = linalg.prepare_small(systems)
    for A, b, p in zip(systems, rhss, prepared):
        x, cond = p.solve_cond(b)
        with np.errstate(all="ignore"):
            ref, ref_cond = linalg.solve_cond(A, b)
        np.testing.assert_array_equal(cond, ref_cond)
        np.testing.assert_array_equal(x, ref)
        assert np.array_equal(np.signbit(x), np.signbit(ref))
    with pytest.raises(ValueError):
        linalg.prepare_small([np.ones((3, 3, n))])


def test_chain_of_blocks_equals_block_by_block():
    """equations.solve_chain (the blocks prepared together) gives every method's
    unknowns and condition numbers bit for bit as solving its blocks one by one."""
    from mechreport.forces.equations import solve_chain, solve_step, triangular_blocks
    for name in ("r_rtr_rtr", "stephenson3_six_bar", "scotch_yoke"):
        spec = load_spec(ROOT / "specs" / f"{name}.yaml")
        kin = solve_kinematics(build_mechanism(spec))
        ctx = ForceContext(kin)
        for method, module in METHODS.items():
            blocks = [b for s in module.build_steps(ctx) for b in triangular_blocks(s)]
            values, solutions = solve_chain(blocks, kin.n)
            known = {}
            for block, sol in zip(blocks, solutions):
                ref = solve_step(block, known, kin.n)
                known.update(ref.values)
                np.testing.assert_array_equal(sol.cond, ref.cond, err_msg=f"{name} {method}")
            assert values.keys() == known.keys()
            for u in known:
                np.testing.assert_array_equal(values[u], known[u], err_msg=f"{name} {method} {u}")


def _summed_matrix(step, n):
    """A step's matrix as the plain rule writes it: from 0, each coefficient of a step's
    unknown added in term order (a lhs term's subtracted)."""
    col = {u: j for j, u in enumerate(step.unknowns)}
    A = np.zeros((len(col), len(col), n))
    for row, eq in enumerate(step.equations):
        for t in eq.terms:
            for k, u in enumerate(t.action.unknowns):
                if u in col:
                    A[row, col[u]] = (A[row, col[u]] + t.coeffs[:, k] if t.side == "rhs"
                                      else A[row, col[u]] - t.coeffs[:, k])
    return A


def test_matrices_written_together_equal_the_sum_of_their_terms():
    """equations.joined_matrices writes the matrices of many blocks in one gather: each is
    bit for bit (zero signs included) the sum of its terms' coefficients in term order, for
    every block of every method of the specs, and where one equation names an unknown in
    two terms, on either side, with -0 among the coefficients."""
    from mechreport.forces.equations import (Action, Equation, Step, Term, joined_matrices,
                                             triangular_blocks)
    for name in ("r_rtr_rtr", "stephenson3_six_bar", "hydraulic_boom"):
        ctx = ForceContext(solve_kinematics(build_mechanism(load_spec(
            ROOT / "specs" / f"{name}.yaml"))))
        blocks = [b for module in METHODS.values() for s in module.build_steps(ctx)
                  for b in triangular_blocks(s)]
        for m in {len(b.unknowns) for b in blocks}:
            same = [b for b in blocks if len(b.unknowns) == m]
            joined = joined_matrices(same, ctx.n)
            for i, b in enumerate(same):
                part = joined[:, :, i * ctx.n:(i + 1) * ctx.n]
                ref = _summed_matrix(b, ctx.n)
                assert np.array_equal(part, ref) and np.array_equal(np.signbit(part),
                                                                    np.signbit(ref)), name
    n = 4
    c = np.array([[1.0, -0.0], [-0.0, 2.0], [3.0, 0.0], [-1e-300, 5.0]])
    a = Action("F", "force", "reaction", "2", unknowns=("u", "v"))
    eqs = [Equation("e1", "force", ("2",), [Term(a, c, np.zeros(n)),
                                            Term(a, c[::-1].copy(), np.zeros(n), "lhs"),
                                            Term(a, -c, np.zeros(n))]),
           Equation("e2", "force", ("2",), [Term(a, -c, np.zeros(n), "lhs")])]
    step = Step("test", ["u", "v"], eqs)
    for A in (joined_matrices([step], n), joined_matrices([step, step], n)[:, :, :n]):
        ref = _summed_matrix(step, n)
        assert np.array_equal(A, ref) and np.array_equal(np.signbit(A), np.signbit(ref))


@pytest.mark.parametrize("n", [36, 1])
def test_methods_prepared_together_equal_each_method_alone(n):
    """solve_forces prepares every method's blocks together, and the blocks the
    methods share once: each method's numbers and condition numbers are bit for bit those
    of the method solved alone on a fresh context, and nothing of the pass is kept."""
    from mechreport.forces.equations import prepare_blocks
    from mechreport.forces.result import chain
    for name in ("r_rtr_rtr", "stephenson3_six_bar", "hydraulic_boom"):
        spec = load_spec(ROOT / "specs" / f"{name}.yaml")
        w = spec.sweep
        step = (w.stop - w.start) / n if n > 1 else 1.0
        sweep = dataclasses.replace(w, step=step, stop=w.stop if n > 1 else w.start)
        kin = solve_kinematics(build_mechanism(dataclasses.replace(
            spec, sweep=sweep, at=(w.start,), expect=())))
        ctx = ForceContext(kin)
        together = solve_forces(kin, ctx=ctx)
        assert not any(isinstance(v, dict) and any(
            isinstance(x, (linalg.SmallSystem, linalg.Equilibrated)) for x in v.values())
            for v in ctx.cache.values())       # the prepared blocks: as large as the sweep
        for method, module in METHODS.items():
            alone = module.solve(ForceContext(kin))
            va, vt = alone.values(), together[method].values()
            assert va.keys() == vt.keys()
            for q in va:
                np.testing.assert_array_equal(vt[q], va[q], err_msg=f"{name} {method} {q}")
            np.testing.assert_array_equal(together[method].cond, alone.cond)
    # R-RTR-RTR: the sliders' couples and the crank's blocks, shared, are prepared once;
    # Newton-Euler's two 7x7 dyad blocks together
    ctx = ForceContext(solve_kinematics(build_mechanism(load_spec(
        ROOT / "specs" / "r_rtr_rtr.yaml"))))
    chains = [chain(ctx, module.build_steps(ctx)) for module in METHODS.values()]
    prepared = prepare_blocks(chains, ctx.n)
    every = [b for c in chains for b in c]
    assert set(prepared) == {id(b) for b in every}
    assert len({id(s) for s in prepared.values()}) < len(every)
    seven = [prepared[id(b)] for b in every if len(b.unknowns) == 7]
    assert len(seven) == 2 and seven[0].fro.base is seven[1].fro.base is not None


@pytest.mark.parametrize("n", [40, 1])
def test_large_systems_prepared_together_equal_one_by_one(n):
    """linalg.prepare_large joins systems of one size and the same constant rows along the
    angle axis: each still gets the bits Equilibrated gives it alone (solutions with their
    signs, condition numbers), whether it has constant rows or not, is solved by row
    operations or by LAPACK, or has singular and near-singular angles; systems with other
    constant rows, non-finite numbers or a single angle are prepared alone."""
    from mechreport import linalg
    rng = np.random.default_rng(5)

    def system(m, unit_rows):
        A = rng.standard_normal((m, m, n)) * 10.0 ** rng.uniform(-5, 5, (m, 1, n))
        for r, row in unit_rows.items():
            A[r] = np.asarray(row, float)[:, None]
        if n > 1:
            A[-1, :, 1] = A[-2, :, 1] * 2.0                 # exactly singular at angle 1
            A[-1, :, 2] = A[-2, :, 2] * (1 + 1e-13)         # near-singular at angle 2
        return A
    K = {0: [1, 0, -1, 0], 1: [0, 1, 0, 1]}
    systems = [system(4, K), system(4, K), system(4, {0: [0, 1, 1, 0]}), system(4, {}),
               system(4, {}), system(3, {}), system(3, {}), system(8, {}), system(8, {})]
    bad = system(4, K)
    bad[0, 1, 0] = np.nan
    systems.append(bad)
    prepared = linalg.prepare_large(systems)
    for A, p in zip(systems, prepared):
        b = rng.standard_normal((n, A.shape[0]))
        with np.errstate(all="ignore"):
            got, want = p.solve_cond(b), linalg.Equilibrated(A).solve_cond(b)
        for g, w in zip(got, want):
            assert np.array_equal(g.view(np.uint64), w.view(np.uint64)), A.shape
    shared = [p.fro.base is not None for p in prepared]
    assert shared == ([True, True, False, True, True, True, True, True, True, False] if n > 1
                      else [False] * len(systems))


def test_large_system_whose_complement_has_constant_rows_is_prepared_alone():
    """A review's case: two 4x4 systems with the same unit row; in the first, another row is
    constant but not +-1 (2, 2), and its Schur complement, scaled, has a unit row of its own
    that the second's does not. Joined, the complement's search over both would miss it:
    each is prepared alone, and solved with the bits Equilibrated gives it."""
    from mechreport import linalg
    rng = np.random.default_rng(1)
    n = 50

    def system(constant_second_row):
        A = rng.standard_normal((4, 4, n))
        A[0] = np.array([1.0, 0.0, 0.0, 0.0])[:, None]
        if constant_second_row:
            A[1] = np.array([0.0, 2.0, 2.0, 0.0])[:, None]
        return A
    systems = [system(True), system(False)]
    b = rng.standard_normal((n, 4))
    assert linalg.Equilibrated(systems[0]).schur.S.schur is not None
    for A, p in zip(systems, linalg.prepare_large(systems)):
        assert p.fro.base is None
        for g, w in zip(p.solve_cond(b), linalg.Equilibrated(A).solve_cond(b)):
            assert np.array_equal(g.view(np.uint64), w.view(np.uint64))


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


def test_contour_rank_of_one_row_equals_the_svd():
    """The contour search's rank of a single row (a zero test, where no entry is near the
    SVD's floor or overflow) is the SVD's count: zero rows, -0 and large entries; with
    subnormal rows, or a row whose length overflows, the SVD itself decides."""
    from mechreport.forces import contour

    def svd_rank(rows):
        s = np.linalg.svd(rows, compute_uv=False)
        return np.sum(s > contour.RANK_RTOL * np.maximum(s[:, :1], 1e-300), axis=1)
    rng = np.random.default_rng(3)
    rows = rng.standard_normal((400, 1, 3)) * 10.0 ** rng.uniform(-280, 300, (400, 1, 1))
    rows[:50] = 0.0
    rows[50:60, 0, 1:] = 0.0
    rows[70:80, 0, 0] = -0.0
    tiny = rows.copy()
    tiny[60:70] = 5e-324
    tiny[80:90] = 1e-305
    huge = rows.copy()
    huge[90:95] = 1.5e308                 # the row's length overflows: the SVD counts none
    for case in (rows, tiny, huge):
        np.testing.assert_array_equal(contour._rank(case), svd_rank(case))
    assert contour._rank(tiny)[60:70].sum() == 0      # below the floor: no rank


def test_contour_independence_by_determinant_implies_the_svd_rank():
    """The contour search's check of a chosen set by its determinants: wherever it says the
    square matrices are independent with the margin, the SVD says so too (random matrices
    of 1 to 8 unknowns over many scales and conditions, near-singular and singular ones and
    out-of-range scales among them; NaN is never independent); and it does say so for
    well-conditioned sets, which is what makes it worth having."""
    from mechreport.forces import contour
    rng = np.random.default_rng(11)
    rtol = 2 * contour.RANK_RTOL
    certified = 0
    for trial in range(600):
        k = int(rng.integers(1, 9))
        U = np.linalg.qr(rng.standard_normal((16, k, k)))[0]
        V = np.linalg.qr(rng.standard_normal((16, k, k)))[0]
        s = 10.0 ** rng.uniform(-12 if trial % 3 else -1, 0, (16, k))
        s[:, 0] = 1.0
        rows = (U * s[:, None, :]) @ V * 10.0 ** rng.uniform(-40, 40)
        if trial % 40 == 1 and k > 1:
            rows[5, -1] = rows[5, 0]                  # two equal rows: singular
        surely = contour._surely_independent(rows, rtol)
        assert bool((contour._rank(rows, rtol) == k).all()) or not surely, (trial, k)
        certified += surely
        if trial % 50 == 0:                           # (the SVD itself fails on NaN)
            rows[3, 0, 0] = np.nan
            assert not contour._surely_independent(rows, rtol)
    assert certified > 100
    assert not contour._surely_independent(np.ones((4, 2, 3)), rtol)    # not square
    # numbers whose k-th power of the norm could underflow or overflow: left to the SVD
    for scale in (1e-40, 1e40):
        assert not contour._surely_independent(np.eye(8)[None] * scale, rtol)
    assert contour._surely_independent(np.eye(8)[None], rtol)


def _both_selections(monkeypatch):
    """Make the contour search run the structural and the numerical selection side by side
    and record whether they chose the same equation objects."""
    from mechreport.forces import contour
    numeric = contour._select_numeric
    compared = []

    def select(unknowns, chosen, candidates, build, probes, needs, record=None):
        by_structure = contour_select(unknowns, chosen, candidates, build, probes, needs,
                                      record)
        by_numbers = numeric(unknowns, chosen, candidates, build, probes)
        compared.append((by_structure is None and by_numbers is None)
                        or (by_structure is not None and by_numbers is not None
                            and list(map(id, by_structure)) == list(map(id, by_numbers))))
        return by_structure
    contour_select = contour._select
    monkeypatch.setattr(contour, "_select", select)     # (no ContourPlans: none replayed)
    return compared


@pytest.mark.parametrize("path", sorted((ROOT / "specs").glob("*.yaml"))
                         + sorted((ROOT / "tests" / "data").rglob("*.yaml")),
                         ids=lambda p: p.stem)
def test_contour_structural_selection_equals_the_numerical_one(path, monkeypatch):
    """The contour search picks its equations by structural rank and checks them with one
    rank test: on every spec (short sweeps searched in place, and the probe context of a
    long one), every selection, failed ones included, is the one the candidate-by-candidate
    numerical selection makes."""
    from mechreport.forces import contour
    compared = _both_selections(monkeypatch)
    spec = load_spec(path)
    for step in (spec.sweep.step, (spec.sweep.stop - spec.sweep.start) / 30):
        kin = solve_kinematics(build_mechanism(dataclasses.replace(
            spec, sweep=dataclasses.replace(spec.sweep, step=step))))
        if kin.n == 0:
            continue
        contour.plan(ForceContext(kin))
    assert compared and all(compared)
    # the unknowns the structure reads from the actions are those of the equation built
    ctx = ForceContext(kin)
    cuts = [r for p in contour.plan(ctx) for r in p.recipes if r[0] == "cut"]
    assert cuts
    for _, w, body in cuts:
        joint = spec.joint(w)
        eq = contour._equation(ctx, joint, list(body))
        assert contour._needs(ctx, joint, list(body)) == set(eq.unknown_names()), (w, body)


def _fake_equation(label, row):
    """An equation over unknowns a, b, c whose coefficients are ``row`` (P, 3) at P probes."""
    from mechreport.forces.equations import Action, Equation, Term
    act = Action(label, "force", "reaction", "link", unknowns=("a", "b", "c"))
    return Equation(label, "force", ("link",), [Term(act, np.asarray(row, float),
                                                     np.zeros(len(row)))])


def test_contour_selection_falls_back_to_the_numbers_where_structure_misleads():
    """Where the structure promises rank the numbers do not have (a multiple of a row taken;
    a row that vanishes at one probe angle), the numerical selection decides: the result is
    the candidate-by-candidate one."""
    from mechreport.forces import contour
    P = 4
    probes = np.arange(P)
    one = np.ones(P)
    rows = {
        "e1": np.stack([one, one, 0 * one], axis=1),
        "twice": np.stack([2 * one, 2 * one, 0 * one], axis=1),    # 2 e1: dependent
        "gap": np.stack([one, -one, 0 * one], axis=1) * np.array([1, 1, 0, 1])[:, None],
        "b": np.stack([0 * one, one, 0 * one], axis=1),
        "c": np.stack([0 * one, 0 * one, one], axis=1),
    }
    eqs = {k: _fake_equation(k, v) for k, v in rows.items()}
    needs = {k: frozenset({"a", "b", "c"}) for k in rows}
    needs["b"], needs["c"] = frozenset({"b"}), frozenset({"c"})
    for order in (["e1", "twice", "b", "c"], ["e1", "gap", "c", "b"], ["gap", "c", "e1"],
                  ["c", "twice"], ["e1", "twice"]):
        got = contour._select(["a", "b", "c"], [], order, eqs.__getitem__, probes, needs)
        want = contour._select_numeric(["a", "b", "c"], [], order, eqs.__getitem__, probes)
        assert (got is None) == (want is None), order
        if got is not None:
            assert [e.label for e in got] == [e.label for e in want], order
    assert [e.label for e in contour._select(["a", "b", "c"], [], ["e1", "twice", "b", "c"],
                                             eqs.__getitem__, probes, needs)] == ["e1", "b", "c"]


def test_contour_selection_where_structure_falls_short_or_is_near_rank():
    """Two cases an adversarial review found. Too few equations by structure: the numerical
    selection's second pass still takes two rows of one unknown that add rank at different
    angles, a set singular at every angle (no row names b); the selection refuses it, as
    it refuses any set the structure cannot make independent. And a set whose smallest
    singular value is within rounding of the rank threshold, where a subset falls below
    it: the numerical selection decides, and says so."""
    from mechreport.forces import contour
    from mechreport.forces.equations import Action, Equation, Term

    def eq(label, row, unknowns):
        act = Action(label, "force", "reaction", "link", unknowns=unknowns)
        return Equation(label, "force", ("link",), [Term(act, np.asarray(row, float),
                                                         np.zeros(len(row)))])
    eqs = {"r1": eq("r1", [[1.0, 0.0], [0.0, 0.0]], ("a", "b")),
           "r2": eq("r2", [[0.0, 0.0], [1.0, 0.0]], ("a", "b"))}
    needs = {"r1": frozenset({"a"}), "r2": frozenset({"a"})}
    by_numbers = contour._select_numeric(["a", "b"], [], ["r1", "r2"], eqs.__getitem__,
                                         np.arange(2))
    assert [e.label for e in by_numbers] == ["r1", "r2"]
    both = np.stack([eqs["r1"].terms[0].coeffs, eqs["r2"].terms[0].coeffs], axis=1)
    assert (np.linalg.det(both) == 0).all()                # singular at every angle
    record: list = []
    assert contour._select(["a", "b"], [], ["r1", "r2"], eqs.__getitem__, np.arange(2),
                           needs, record) is None
    assert not record                   # decided by the structure alone
    M = np.array([[2.136261400290193e-10, -9.127772506153829e-10, 3.481401140932097e-10],
                  [-0.8337553361356009, -0.35607590279527473, -0.4219739220780606],
                  [-0.5091325079640706, 0.20011902008450655, 0.8371000341265268]])
    assert contour._rank(M[None]) == 3 and contour._rank(M[None, :2]) == 1
    u = ("a", "b", "c")
    eqs = {f"k{i}": eq(f"k{i}", M[i][None, :], u) for i in range(3)}
    needs = {k: frozenset(u) for k in eqs}
    # the numbers drop k1 (the first two rows are below the threshold): too few, None
    assert contour._select_numeric(list(u), [], list(eqs), eqs.__getitem__, np.arange(1)) \
        is None
    assert contour._select(list(u), [], list(eqs), eqs.__getitem__, np.arange(1), needs,
                           record) is None
    assert record == [True]             # not independent enough: the numbers decided


def test_terms_shared_between_equations_are_those_built_for_each():
    """An action's projection on a direction, and its moment about a point, are built once
    per context and shared by every equation that holds them: each equation's terms, in
    every method of three specs, are bit for bit those built afresh for it (its direction;
    its centre, a joint's point, a centre of mass or a ground point, named as the equation
    says), and some are shared."""
    from mechreport.forces.builders import force_term, moment_term
    for name in ("r_rtr_rtr", "hydraulic_boom", "stephenson3_six_bar"):
        ctx = ForceContext(solve_kinematics(build_mechanism(load_spec(
            ROOT / "specs" / f"{name}.yaml"))))
        seen: dict[int, int] = {}
        centre_arrays = ([s.r for s in ctx.links.values()] + list(ctx.joint_points.values())
                         + [ctx.point_of(p) for p in ctx.spec.ground])
        for module in METHODS.values():
            for step in module.build_steps(ctx):
                for eq in step.equations:
                    for t in eq.terms:
                        seen[id(t)] = seen.get(id(t), 0) + 1
                        if t.kind == "projection" and t.side == "rhs" and eq.kind != "constraint":
                            d = ctx.axis(eq.axis) if eq.axis in ("x", "y") else \
                                ctx.line_direction(ctx.spec.joint(eq.axis[len("Delta_"):]))
                            fresh = force_term(t.action, d)
                        elif t.kind == "moment":
                            assert t.factor("about") == eq.about, (name, eq.label)
                            centres = [c for c in centre_arrays
                                       if np.array_equal(t.action.at - c, t.lever)]
                            assert centres, (name, eq.label)
                            fresh = moment_term(t.action, centres[0], ctx.n,
                                                about_name=t.factor("about"))
                        else:
                            continue
                        for a, b in ((t.coeffs, fresh.coeffs), (t.const, fresh.const)):
                            assert np.array_equal(np.asarray(a).view(np.uint64),
                                                  np.asarray(b).view(np.uint64)), eq.label
        assert max(seen.values()) > 1, name


def test_forces_at_the_moment_centre_are_those_at_it_at_every_angle():
    """builders.with_moment leaves out the forces applied at the moment centre: a force
    apart from it at the first angle is kept without a look at the others; otherwise the
    whole sweep decides, as the plain rule does (within 1e-12 of 1 m + the centre's largest
    coordinate at every angle; NaN is never at the centre)."""
    from mechreport.forces.builders import with_moment
    from mechreport.forces.equations import Action
    ctx = ForceContext(solve_kinematics(build_mechanism(load_spec(
        ROOT / "specs" / "four_bar.yaml"))))
    n = ctx.n
    rng = np.random.default_rng(7)
    p = rng.normal(size=(n, 2)) * 1e3
    tol = 1e-12 * (1.0 + np.abs(p).max())

    def near(offset):
        return p + offset

    late = np.zeros((n, 2))
    late[-1, 1] = 10 * tol                              # apart at the last angle only
    first = np.zeros((n, 2))
    first[0, 0] = 10 * tol                              # apart at the first angle only
    nan = np.zeros((n, 2))
    nan[n // 2, 0] = np.nan
    cases = {"same": near(0.0), "within": near(0.5 * tol), "late": near(late),
             "first": near(first), "nan": near(nan), "far": near(1.0),
             "nan first": near(np.where(np.arange(n)[:, None] == 0, np.nan, 0.0))}
    acts = [Action(name, "force", "load", "x", at, value=np.zeros((n, 2)))
            for name, at in cases.items()]
    acts.append(Action("M", "couple", "load", "x", value=np.zeros(n)))
    kept = [a.symbol for a in with_moment(ctx, acts, p)]
    plain = [a.symbol for a in acts
             if a.kind != "force" or not (np.abs(a.at - p) <= tol).all()]
    assert kept == plain == ["late", "first", "nan", "far", "nan first", "M"]
    assert [a.symbol for a in with_moment(ctx, acts, p)] == kept     # from the memo


def _shape(mech):
    """A mechanism's structure by name, every joint checked to be its own spec's."""
    own = {j.name: j for j in mech.spec.joints}

    def names(joints):
        assert all(j is own[j.name] for j in joints)
        return tuple(j.name for j in joints)
    groups = [(g.links, names(g.joints), g.driver, g.dyad and (g.dyad.links,
               names(g.dyad.outer), names([g.dyad.inner]))) for g in mech.groups]
    loops = [[(l.links, names(l.joints)) for l in ls] for ls in (mech.loops, mech.cycles)]
    return groups, loops


def test_structure_found_once_per_topology_equals_a_fresh_one(monkeypatch):
    """build_mechanism keeps each topology's structure: another spec of the same topology
    (other numbers) gets it bound to its own joints, equal to one found afresh; another
    order of the joints is another topology."""
    import mechreport.model as model
    from mechreport.spec.loader import parse_spec
    text = (ROOT / "specs" / "r_rtr_rtr.yaml").read_text()
    moved = text.replace("C: [0, 0.06]", "C: [0, 0.07]")
    joints = text.index("  A:   {type: R"), text.index("\ndriver:")
    lines = text[joints[0]:joints[1]].splitlines(keepends=True)
    reordered = text[:joints[0]] + "".join(lines[::-1]) + text[joints[1]:]
    assert moved != text and reordered != text
    specs = [parse_spec(t, "r_rtr_rtr.yaml") for t in (text, text, moved, reordered)]
    monkeypatch.setattr(model, "_STRUCTURES", {})
    kept = [build_mechanism(s) for s in specs]
    assert len(model._STRUCTURES) == 2                  # the reordered joints: another key
    for spec, mech in zip(specs, kept):
        assert mech.spec is spec
        monkeypatch.setattr(model, "_STRUCTURES", {})
        assert _shape(mech) == _shape(build_mechanism(spec))
    assert [g.links for g in kept[0].groups] == [g.links for g in kept[3].groups]


def _every_spec():
    return sorted([*(ROOT / "specs").glob("*.yaml"), *(ROOT / "tests" / "data").glob("*.yaml")])


@pytest.mark.parametrize("n", [36, 1])
@pytest.mark.parametrize("path", _every_spec(), ids=lambda p: p.stem)
def test_chains_solved_level_by_level_equal_each_chain_in_turn(path, n):
    """chains.solve_chains (every method's chain at once, the 1x1 and 2x2 blocks of a level
    solved together, a block as soon as the blocks it needs are) gives each chain's
    unknowns, condition numbers and singular angles bit for bit as equations.solve_chain
    solving its blocks in turn, and the product of the condition numbers run_steps formed
    block by block."""
    from mechreport.forces.chains import solve_chains
    from mechreport.forces.equations import prepare_blocks, solve_chain
    from mechreport.forces.result import chain, method_steps
    spec = load_spec(path)
    w = spec.sweep
    step = (w.stop - w.start) / n if n > 1 else 1.0
    kin = solve_kinematics(build_mechanism(dataclasses.replace(
        spec, sweep=dataclasses.replace(w, step=step, stop=w.stop if n > 1 else w.start),
        at=(w.start,), expect=())))
    ctx = ForceContext(kin)
    chains = [chain(ctx, method_steps(ctx, m, module.build_steps))
              for m, module in METHODS.items()]
    together = solve_chains(chains, kin.n, prepare_blocks(chains, kin.n))
    levels = 0
    for blocks, got in zip(chains, together):
        values, solutions = solve_chain(blocks, kin.n)
        assert list(got.values) and got.values.keys() == values.keys()
        for u in values:
            assert np.array_equal(got.values[u], values[u], equal_nan=True), (path.stem, u)
            assert np.array_equal(np.signbit(got.values[u]), np.signbit(values[u]))
        cond = np.ones(kin.n)
        singular = np.zeros(kin.n, bool)
        for sol in solutions:
            cond = cond * sol.cond
            singular |= sol.singular
        assert np.array_equal(got.cond, cond, equal_nan=True), path.stem
        np.testing.assert_array_equal(got.singular, singular)
        levels = max(levels, max(_levels_of(blocks), default=0))
    assert levels < max(map(len, chains))     # some blocks were taken before their turn


def _levels_of(blocks):
    from mechreport.forces.chains import _levels
    return _levels(blocks)


def test_chain_levels_follow_what_each_block_needs():
    """A block is solved one level after the latest block that found what it needs; a
    chain that does not say what its blocks need, or needs what no block before found,
    goes block by block, and then fails as solve_chain does."""
    from mechreport.forces.chains import solve_chains
    from mechreport.forces.equations import Action, Equation, Step, Term, solve_chain
    n = 3

    def block(unknown, uses=(), needs=()):
        acts = [Action(u, "force", "reaction", "2", unknowns=(u,)) for u in (unknown, *uses)]
        eq = Equation(f"e {unknown}", "force", ("2",),
                      [Term(a, np.full((n, 1), 2.0 if a.unknowns[0] == unknown else 1.0),
                            np.full(n, 3.0)) for a in acts])
        return Step(unknown, [unknown], [eq], needs=needs)

    blocks = [block("a"), block("b"), block("c", ("a",), ("a",)), block("d", ("c", "b"),
                                                                          ("c", "b"))]
    assert _levels_of(blocks) == [0, 0, 1, 2]
    assert _levels_of([block("a"), block("b", needs=None)]) == [0, 1]
    assert _levels_of([block("c", ("a",), ("a",)), block("a")]) == [0, 1]
    values, _ = solve_chain(blocks, n)
    got = solve_chains([blocks], n)[0].values
    assert all(np.array_equal(got[u], values[u]) for u in values)
    with pytest.raises(ValueError, match="needs a, which is neither solved here nor known"):
        solve_chains([[block("c", ("a",), ("a",)), block("a")]], n)


def _contour_context(spec, step=None, plans=None):
    if step is not None:
        spec = dataclasses.replace(spec, sweep=dataclasses.replace(spec.sweep, step=step))
    ctx = ForceContext(solve_kinematics(build_mechanism(spec)))
    ctx.plans = plans
    return ctx


def _steps_as_numbers(steps):
    """Each step's title, unknowns and equations (labels, and every term's numbers)."""
    return [(s.title, list(s.unknowns), [(e.label, [(t.action.symbol, t.coeffs.tobytes(),
                                                      t.const.tobytes()) for t in e.terms])
                                         for e in s.equations]) for s in steps]


def test_contour_plan_replayed_for_a_structure_is_the_search_s_own(monkeypatch):
    """The contour method's plan is kept per structure and replayed for the next spec of
    it (issue 14, the fixed cost): for every spec, replayed from a spec of the same topology
    (itself over another sweep, and the other specs of its topology in the repository), the
    plan and every equation of its steps are bit for bit those a fresh search gives."""
    from mechreport.forces import contour
    from mechreport.model import topology
    paths = sorted((ROOT / "specs").glob("*.yaml")) + sorted((ROOT / "tests" / "data").rglob("*.yaml"))
    specs = [load_spec(p) for p in paths]
    by_topology: dict = {}
    for spec in specs:
        by_topology.setdefault(topology(spec), []).append(spec)
    assert any(len(v) > 1 for v in by_topology.values())   # replays across specs are tried
    replayed = []
    real_replay = contour._replay

    def replay(ctx, plans):
        out = real_replay(ctx, plans)
        replayed.append(out is not None)
        return out
    monkeypatch.setattr(contour, "_replay", replay)
    for spec in specs:
        for step in (spec.sweep.step, (spec.sweep.stop - spec.sweep.start) / 30):
            fresh = _contour_context(spec, step)
            want = contour.plan(fresh), _steps_as_numbers(contour.build_steps(fresh))
            for source in by_topology[topology(spec)]:
                book = contour.ContourPlans()
                contour.plan(_contour_context(source, source.sweep.step / 2, book))   # kept
                if not len(book):
                    continue
                replayed.clear()
                ctx = _contour_context(spec, step, book)
                got = contour.plan(ctx), _steps_as_numbers(contour.build_steps(ctx))
                assert got == want, (spec.file, source.file)
                assert replayed in ([True], [False]), replayed
                if source is spec:
                    assert replayed == [True]
    # a plan that fails its test at the replay falls back to the search
    spec = load_spec(ROOT / "specs" / "r_rtr_rtr.yaml")
    book = contour.ContourPlans()
    good = contour.plan(_contour_context(spec, plans=book))
    [structure] = book.structures()
    twice = dataclasses.replace(good[0], recipes=(good[0].recipes[0],) * 2)   # dependent
    book.keep(structure, (twice,) + good[1:])
    replayed.clear()
    assert contour.plan(_contour_context(spec, plans=book)) == good and replayed == [False]
    assert book.get(structure) == good


def test_contour_plan_is_kept_only_when_the_structure_decided(monkeypatch):
    """A search in which the numerical selection decided anything is not kept: its choice
    hangs on the numbers of its spec. The structure key tells apart two specs of one
    topology whose reactions act at different pins (which changes what a cut names)."""
    from mechreport.forces import contour
    from mechreport.spec.loader import parse_spec
    text = (ROOT / "specs" / "r_rtr_rtr.yaml").read_text()
    spec = parse_spec(text, "r_rtr_rtr.yaml")
    real = contour._verified
    calls = []

    def once_not(unknowns, equations, probes):
        calls.append(1)
        return len(calls) > 1 and real(unknowns, equations, probes)
    book = contour.ContourPlans()
    monkeypatch.setattr(contour, "_verified", once_not)
    contour.plan(_contour_context(spec, plans=book))
    assert calls and not len(book)
    monkeypatch.setattr(contour, "_verified", real)
    contour.plan(_contour_context(spec, plans=book))
    assert len(book) == 1
    # B_T's slider point moved off the pin B: B_T's reaction has a moment about B
    moved = parse_spec(text.replace("points: {B: [0, 0]}", "points: {B: [0, 0], S: [0.02, 0]}")
                       .replace("point: B, line", "point: S, line"), "moved.yaml")
    book = contour.ContourPlans()
    ctx, ctx_moved = _contour_context(spec, plans=book), _contour_context(moved, plans=book)
    assert contour._structure(ctx)[0] == contour._structure(ctx_moved)[0]
    assert contour._structure(ctx) != contour._structure(ctx_moved)
    want = _steps_as_numbers(contour.build_steps(_contour_context(moved)))
    contour.plan(ctx)                                       # r_rtr_rtr's plan kept
    assert _steps_as_numbers(contour.build_steps(ctx_moved)) == want


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


LONE_CRANK = """
mechreport: 1
name: lone crank
units: {length: m, mass: kg}
gravity: [0, -9.807]
ground: {A: [0, 0]}
links:
  crank: {points: {A: [0, 0], B: [0.1, 0]}, mass: 1.0, inertia: 0.001, com: [0.05, 0]}
joints:
  A: {type: R, links: [ground, crank]}
driver: {joint: A, rpm: 100}
sweep: {start: 0, stop: 360, step: 10}
"""


def test_contour_plan_with_a_bridge_is_replayed_as_searched(monkeypatch):
    """A joint on no loop (a lone crank) is solved as a bridge: the whole part beyond it as
    one free body. Its plan is kept and replayed like any other, bit for bit the search's."""
    from mechreport.forces import contour
    from mechreport.spec.loader import parse_spec
    spec = parse_spec(LONE_CRANK, "lone_crank.yaml")
    book = contour.ContourPlans()
    fresh = _contour_context(spec, plans=book)
    plans = contour.plan(fresh)
    assert [p.recipes[0][0] for p in plans] == ["bridge"] and len(book) == 1
    search = contour._search

    def no_search(ctx):
        raise AssertionError("searched, not replayed")
    monkeypatch.setattr(contour, "_search", no_search)
    got = _steps_as_numbers(contour.build_steps(_contour_context(spec, 5.0, book)))
    monkeypatch.setattr(contour, "_search", search)
    assert got == _steps_as_numbers(contour.build_steps(_contour_context(spec, 5.0)))
    result = analyse(spec)
    assert result.agreement[0].relative < 1e-12


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
