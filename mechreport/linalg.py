"""The one batched linear solver: every kinematic and force system, all angles at once."""
from __future__ import annotations

import numpy as np

SINGULAR_COND = 1e10  # equilibrated condition number above which an angle is flagged singular


def batched_solve(A: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Solve A x = b for A (n, m, m) and b (n, m); returns x (n, m) and singular (n,) bool.

    Rows and columns are first equilibrated (each scaled to a largest entry of 1), which makes
    the test independent of units. An angle is singular when the condition number of the
    equilibrated matrix exceeds ``SINGULAR_COND``; the condition number is estimated as
    ||A||_F * max_k ||A^-1 z_k|| / ||z_k|| with two fixed random probes z_k solved alongside b
    (a randomised estimate, within a small factor of ||A||_2 ||A^-1||_2, at the cost of one
    solve rather than an SVD). Singular angles get NaN.
    """
    n, m, _ = A.shape
    if m == 0:
        return np.zeros((n, 0)), np.zeros(n, bool)
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
    try:
        y = np.linalg.solve(As, rhs)
    except np.linalg.LinAlgError:  # an exactly singular angle: find it the slow way
        exact = ~(np.linalg.cond(As) < SINGULAR_COND)
        As = np.where(exact[:, None, None], np.eye(m), As)
        y = np.linalg.solve(As, rhs)
        y[exact] = np.inf
    with np.errstate(over="ignore", invalid="ignore"):
        probe = np.sqrt(np.einsum("nik,nik->nk", y[:, :, 1:], y[:, :, 1:])) / _PROBE_NORMS[m]
        cond = np.sqrt(np.einsum("nij,nij->n", As, As)) * np.max(probe, axis=1)
    singular = ~(cond < SINGULAR_COND)
    x = y[:, :, 0] / cs
    x[singular] = np.nan
    return x, singular


_PROBES = np.random.default_rng(20261121).standard_normal((64, 2))
_PROBE_NORMS = {m: np.sqrt(np.sum(_PROBES[:m] ** 2, axis=0)) for m in range(1, 65)}
