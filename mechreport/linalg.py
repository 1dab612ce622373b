"""The one batched linear solver: every kinematic and force system, all angles at once."""
from __future__ import annotations

import numpy as np

SINGULAR_COND = 1e10  # equilibrated condition number above which an angle is flagged singular


def batched_solve(A: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Solve A x = b for A (n, m, m) and b (n, m); returns x (n, m) and singular (n,) bool.
    See :func:`batched_solve_cond`; singular angles get NaN."""
    x, cond = batched_solve_cond(A, b)
    return x, ~(cond < SINGULAR_COND)


def batched_solve_cond(A: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Solve A x = b for A (n, m, m) and b (n, m); returns x (n, m) and the estimated
    condition number (n,) of the equilibrated matrix: inf where exactly singular, NaN where A
    or b is not finite (an input that overflowed, or a pose that could not be solved).

    Rows and columns are first equilibrated (each scaled to a largest entry of 1), which makes
    the test independent of units. An angle is singular when the condition number of the
    equilibrated matrix exceeds ``SINGULAR_COND``; the condition number is estimated as
    ||A||_F * max_k ||A^-1 z_k|| / ||z_k|| with two fixed random probes z_k solved alongside b
    (a randomised estimate, within a small factor of ||A||_2 ||A^-1||_2, at the cost of one
    solve rather than an SVD). Singular angles get NaN.
    """
    n, m, _ = A.shape
    if m == 0:
        return np.zeros((n, 0)), np.ones(n)
    absA = np.abs(A)
    rs = absA.max(axis=2)
    rs[rs == 0] = 1.0
    absA /= rs[:, :, None]
    cs = absA.max(axis=1)
    cs[cs == 0] = 1.0
    As = A / rs[:, :, None]
    As /= cs[:, None, :]
    rhs = np.empty((n, m, 3))
    rhs[:, :, 0] = b / rs
    rhs[:, :, 1:] = _PROBES[:m]
    # non-finite input (a pose that could not be solved) is singular, never a LAPACK error
    bad = ~(np.isfinite(As).all(axis=(1, 2)) & np.isfinite(rhs[:, :, 0]).all(axis=1))
    overflow = bad.copy()
    if bad.any():
        As[bad] = np.eye(m)
        rhs[bad, :, 0] = 0.0
    try:
        y = np.linalg.solve(As, rhs)
    except np.linalg.LinAlgError:  # an exactly singular angle: LU finds a zero pivot
        exact = np.linalg.det(As) == 0
        As[exact] = np.eye(m)
        y = np.linalg.solve(As, rhs)
        bad |= exact
    y[bad] = np.inf
    with np.errstate(over="ignore", invalid="ignore"):
        probe = np.sqrt(np.einsum("nik,nik->nk", y[:, :, 1:], y[:, :, 1:])) / _PROBE_NORMS[m]
        cond = np.sqrt(np.einsum("nij,nij->n", As, As)) * np.max(probe, axis=1)
    cond = np.where(np.isfinite(cond), cond, np.inf)
    cond[overflow] = np.nan
    with np.errstate(over="ignore", invalid="ignore"):
        x = y[:, :, 0] / cs
    x[~(cond < SINGULAR_COND)] = np.nan
    return x, cond


def batched_solve_many(A: np.ndarray, B: np.ndarray) -> np.ndarray:
    """Solve A X = B for A (n, m, m) and several right-hand sides B (n, m, k), rows and
    columns equilibrated as in :func:`batched_solve_cond`; X (n, m, k). For angles already
    known to be regular (a superposition of loads over a solved system)."""
    n, m, _ = A.shape
    if m == 0:
        return np.zeros((n, 0, B.shape[2]))
    rs = np.abs(A).max(axis=2)
    rs[rs == 0] = 1.0
    As = A / rs[:, :, None]
    cs = np.abs(As).max(axis=1)
    cs[cs == 0] = 1.0
    As /= cs[:, None, :]
    return np.linalg.solve(As, B / rs[:, :, None]) / cs[:, :, None]


_PROBES = np.random.default_rng(20261121).standard_normal((64, 2))
_PROBE_NORMS = {m: np.sqrt(np.sum(_PROBES[:m] ** 2, axis=0)) for m in range(1, 65)}
