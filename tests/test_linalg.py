"""The batched linear algebra (mechreport.linalg) and the block solving built on it
(forces.equations, forces.chains) give the numbers of the plain path: steps split into
triangular blocks, structurally singular steps left whole, blockwise solves equal to whole
ones; 1x1 and 2x2 systems in closed form, small ones by row operations and constant rows
eliminated all equal to LAPACK (singular, non-finite, single-precision and extreme-scale
systems included); systems, blocks and methods prepared together equal to one by one; chains
solved level by level equal to each chain in turn."""
from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from mechreport import linalg
from mechreport.forces import METHODS, ForceContext, solve_forces
from mechreport.kinematics import solve_kinematics
from mechreport.model import build_mechanism
from mechreport.spec import load_spec

ROOT = Path(__file__).resolve().parents[1]


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


def test_a_column_that_is_only_rounding_at_one_angle_is_flagged_singular():
    """An unknown that drops out of every equation at one angle (its lever arm cos 90 deg =
    6e-17) is undetermined there: the per-angle equilibration must not scale the rounding up
    into a well-conditioned matrix (the contour method's B1 of an in-line engine at 90 deg
    gave rounding / rounding as a reaction before)."""
    phi = np.radians(np.arange(0.0, 181.0, 15.0))            # 90 deg among them
    n = phi.size
    for m in (1, 2, 3):
        At = np.zeros((m, m, n))
        for i in range(m):
            At[i, i] = 1.0 + i
        At[m - 1, m - 1] = np.cos(phi)                          # column m-1 vanishes at 90
        x, cond = linalg.solve_cond(At, np.ones((n, m)))
        at90 = int(np.argmin(np.abs(phi - np.pi / 2)))
        assert not cond[at90] < linalg.SINGULAR_COND, m
        assert np.isnan(x[at90]).all(), m
        assert (cond[np.arange(n) != at90] < linalg.SINGULAR_COND).all(), m


def test_rows_that_only_shrink_are_not_flagged():
    """A system whose every coefficient scales down together (units) is as regular as
    before: the test compares each line with itself at the other angles."""
    n = 5
    At = np.zeros((2, 2, n))
    At[0, 0], At[1, 1], At[0, 1] = 1e-12, 2e-12, 0.5e-12
    x, cond = linalg.solve_cond(At, np.ones((n, 2)))
    assert (cond < linalg.SINGULAR_COND).all() and np.isfinite(x).all()
