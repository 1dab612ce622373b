"""Periodic splines over one cycle of the crank (a turn, or the loads' longer cycle), as polynomial pieces per grid interval: how
the equation of motion keeps what it found on its grid of crank angles."""
from __future__ import annotations

import math

import numpy as np

#: crank angles of the grid the equation's coefficients are found on [deg]
GRID_STEP_DEG = 0.5
#: the degree of the splines between them (the scalar right-hand side is written for 5)
DEGREE = 5


def periodic_pieces(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The pieces (N, F, DEGREE + 1) of periodic splines of degree DEGREE through ``y``
    (N, F) at the equally spaced ``x`` (N,) [rad] over one cycle (N steps, the period), by
    interval, function and power of the angle from the interval's start (highest first):
    each piece the spline's Taylor polynomial at its interval's start (exact: one polynomial
    over the interval)."""
    from scipy.interpolate import make_interp_spline
    xx = np.append(x, x[0] + len(x) * (x[1] - x[0]))
    yy = np.vstack([y, y[:1]])
    spline = make_interp_spline(xx, yy, k=DEGREE, bc_type="periodic", axis=0)
    taylor = np.stack([spline(x, nu=k) / math.factorial(k) for k in range(DEGREE + 1)],
                      axis=-1)
    return taylor[..., ::-1].copy()


def values_at(pieces: np.ndarray, phi) -> np.ndarray:
    """Every function of ``pieces`` (:func:`periodic_pieces` on the GRID_STEP_DEG grid over
    a cycle, its period len(pieces) steps) at crank angles ``phi`` (n,) [rad], (n, F)."""
    h = math.radians(GRID_STEP_DEG)
    x = np.mod(np.atleast_1d(np.asarray(phi, float)), len(pieces) * h) / h
    i = np.minimum(x.astype(int), len(pieces) - 1)
    t = (x - i) * h
    powers = t[:, None] ** np.arange(DEGREE, -1, -1)[None, :]           # (n, DEGREE + 1)
    return np.einsum("nfd,nd->nf", pieces[i], powers)


__all__ = ["DEGREE", "GRID_STEP_DEG", "periodic_pieces", "values_at"]
