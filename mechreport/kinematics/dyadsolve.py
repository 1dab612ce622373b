"""A dyad's 6x6 rate systems solved through their block structure, all angles at once.

The columns are the dyad's two links' rates (x, y, theta each). The two rows of each outer
joint involve one link only, P_k q_k = b_k with P_k 2x3 (rank 2 at every pose: an R joint's
rows hold the identity, a T joint's the line's unit normal and the unit relative-angle row);
the inner joint's two rows involve both, C_0 q_0 + C_1 q_1 = b_c. With u, v the rows of P_k
and N_k = u x v (its null vector), every solution of the outer pair is

    q_k = P_k^+ b_k + t_k N_k,   P_k^+ = [v x N_k, N_k x u] / |N_k|^2

(the pseudo-inverse of a 2x3 matrix of rank 2), and the inner rows leave the 2x2 system
M t = b_c - S_0 b_0 - S_1 b_1 with M = [C_0 N_0, C_1 N_1] and S_k = C_k P_k^+, solved by
Cramer's rule (forward stable for 2x2). A singular pose of the dyad is a singular M.

This replaces one LAPACK call per angle and right-hand side by a few dozen array operations
over the angle axis, on the 24 entries that are not structurally zero, with few large
temporaries (touching fresh memory costs more than this arithmetic). The system is
equilibrated and its condition number estimated as :class:`mechreport.linalg.Equilibrated`
does (the same row and column scales, the same random probes: the same number to round-off
times the condition number), so the singular and near-singular flags calibrated on that
number do not change.
"""
from __future__ import annotations

import numpy as np

from ..linalg import PROBE_NORMS, PROBES, SINGULAR_COND   # Equilibrated's probes


def _cross(a: np.ndarray, b: np.ndarray, out: np.ndarray) -> np.ndarray:
    """a x b over axis 1 (3 components) of arrays (k, 3, n), into ``out``."""
    for i, j, k in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
        np.subtract(a[:, j] * b[:, k], a[:, k] * b[:, j], out=out[:, i])
    return out


def _absmax(x: np.ndarray, axis) -> np.ndarray:
    """max |x| over ``axis`` (NaN where any is NaN), without a temporary |x|."""
    top, low = x.max(axis=axis), x.min(axis=axis)
    return np.maximum(top, np.negative(low, out=low), out=top)


class DyadSystem:
    """A dyad's batch of velocity (and acceleration) systems from its rate equations ``eqs``
    (a :class:`~mechreport.kinematics.groups.RateEquations`), with the interface and the
    numbers of :class:`mechreport.linalg.Equilibrated` on the full 6x6 matrices (right-hand
    sides b (n, 6) in the group's row order, solutions x (n, 6)): equilibrated once, then
    solved in closed form (see the module's docstring) for any number of right-hand sides.

    Internally rows go in the dyad's order: link 0's outer joint, link 1's, the inner joint
    (``order``: the group's row slices in that order)."""

    def __init__(self, eqs):
        self.order = self._prepare([eqs])[0]

    @classmethod
    def joined(cls, eqs_list: list) -> list["DyadSystem"]:
        """One system per dyad of ``eqs_list`` (each a RateEquations over the same angles),
        prepared together: their matrices joined along the angle axis and equilibrated,
        factored and probed in one pass (each dyad's numbers are those it gets alone: every
        step is per angle, and einsum sums each angle in the same order for any number of
        angles above one; over a single angle each is prepared alone). What is left per
        dyad is its own solves."""
        n = eqs_list[0].frames.n if eqs_list else 0
        if len(eqs_list) < 2 or n < 2:
            return [cls(eqs) for eqs in eqs_list]
        whole = cls.__new__(cls)
        orders = whole._prepare(eqs_list)
        return [whole._part(i, n, order) for i, order in enumerate(orders)]

    def _prepare(self, eqs_list: list) -> list:
        """Equilibrate and factor the dyads' systems joined along the angle axis; each
        dyad's row order (see the class docstring)."""
        step = eqs_list[0].frames.n                      # each dyad's angles
        self.n = n = step * len(eqs_list)
        # D[outer or inner, link, row, column, angle]: P_k, then the inner rows' C_k
        D = np.empty((2, 2, 2, 3, n))
        D.fill(0.0)   # (np.zeros' lazily zeroed pages would be touched twice: read, write)
        orders = []
        for i, eqs in enumerate(eqs_list):
            links, here = eqs.group.links, slice(i * step, (i + 1) * step)
            order: list = [None, None, None]
            for rows, joint, geo in zip(eqs.rows, eqs.group.joints, eqs.geometry):
                mine = [k for k, l in enumerate(links) if l in joint.links]
                kind = 1 if len(mine) == 2 else 0
                geo.write_blocks({links[k]: D[kind, k, ..., here] for k in mine})
                order[2 if kind else mine[0]] = rows
            orders.append(order)
        self._equilibrate(D)
        P, C = D[0], D[1]
        u, v = P[:, 0], P[:, 1]                          # (link, 3, n)
        N = _cross(u, v, np.empty((2, 3, n)))
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            inv = 1.0 / np.einsum("kjn,kjn->kn", N, N)
        pinv = np.empty((2, 3, 2, n))                    # (link, column, row, n)
        _cross(v, N, pinv[:, :, 0])
        _cross(N, u, pinv[:, :, 1])
        pinv *= inv[:, None, None]
        M = np.einsum("krjn,kjn->rkn", C, N)             # (row, link, n)
        self.S = np.einsum("krjn,kjsn->krsn", C, pinv)   # C_k P_k^+ (link, row, row, n)
        self.N, self.pinv, self.M = N, pinv, M
        self._scratch = D.reshape(-1)    # D is no longer needed: room for right-hand sides
        self.det = M[0, 0] * M[1, 1] - M[0, 1] * M[1, 0]
        self.exact = (self.det == 0) | ~np.isfinite(inv).all(axis=0)   # exactly singular
        return orders

    def _part(self, i: int, n: int, order: list) -> "DyadSystem":
        """Dyad ``i`` of a joined system, rows in ``order``: every array's angles [i n,
        (i + 1) n), and its own stretch of the scratch memory (24 n numbers, of which a
        solve uses 18 n)."""
        part = DyadSystem.__new__(DyadSystem)
        here = slice(i * n, (i + 1) * n)
        part.n, part.order = n, order
        part.rs = tuple(r[..., here] for r in self.rs)
        part.cs, part.overflow, part.fro = self.cs[:, here], self.overflow[here], self.fro[here]
        part.N, part.pinv, part.M = self.N[..., here], self.pinv[..., here], self.M[..., here]
        part.S, part.det, part.exact = self.S[..., here], self.det[here], self.exact[here]
        part._scratch = self._scratch[24 * n * i:24 * n * (i + 1)]
        return part

    def _equilibrate(self, D: np.ndarray) -> None:
        """Rows, then columns of the 6x6 matrices scaled to a largest entry of 1, in place
        (the zero blocks change no maximum): ``rs`` the row scales (2, n) of the dyad's three
        row pairs, ``cs`` (6, n) in column order, ``fro`` (n,) the Frobenius norm after
        scaling."""
        rs_out = _absmax(D[0], axis=2)                   # (link, row, n)
        rs_in = _absmax(D[1], axis=(0, 2))               # (row, n)
        for rs in (rs_out, rs_in):
            rs[rs == 0] = 1.0
        D[0] /= rs_out[:, :, None]
        D[1] /= rs_in[None, :, None]
        cs = _absmax(D, axis=(0, 2))                     # (link, column, n)
        cs[cs == 0] = 1.0
        D /= cs[None, :, None]
        self.rs = (rs_out[0], rs_out[1], rs_in)           # (2, n) each, in the dyad's order
        self.cs = cs.reshape(6, -1)
        self.overflow = ~(np.isfinite(rs_out).all(axis=(0, 1)) & np.isfinite(rs_in).all(axis=0))
        self.fro = np.sqrt(np.einsum("abcdn,abcdn->n", D, D))

    def _scaled_rhs(self, b: np.ndarray, out: np.ndarray) -> np.ndarray:
        """b (n, 6) in the group's row order, in the dyad's and row-scaled, into ``out``
        (6, n)."""
        bt = b.T
        for i, (rows, rs) in enumerate(zip(self.order, self.rs)):
            np.divide(bt[rows], rs, out=out[2 * i:2 * i + 2])
        return out

    def _solve(self, Y: np.ndarray) -> np.ndarray:
        """y (6, k, n) with As y = Y for Y (6, k, n) (rows in the dyad's order); inf where
        not finite or exactly singular."""
        y = np.empty(Y.shape)
        q = y.reshape(2, 3, *Y.shape[1:])                         # (link, 3, k, n)
        b = Y[:4].reshape(2, 2, *Y.shape[1:])                     # (link, row, k, n)
        M, det, N = self.M, self.det, self.N
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            res = Y[4:] - np.einsum("krsn,ksmn->rmn", self.S, b)
            t0 = (M[1, 1] * res[0] - M[0, 1] * res[1]) / det
            t1 = (M[0, 0] * res[1] - M[1, 0] * res[0]) / det
            np.einsum("kjrn,krmn->kjmn", self.pinv, b, out=q)
            for j in range(3):
                q[0, j] += N[0, j] * t0
                q[1, j] += N[1, j] * t1
        y[:, :, self.overflow | self.exact] = np.inf
        return y

    def solve(self, b: np.ndarray) -> np.ndarray:
        """x (n, 6) for b (n, 6); NaN where the system is not finite or exactly singular.
        For angles already known to be regular (no condition estimate)."""
        rhs = self._scaled_rhs(b, self._scratch[:6 * self.n].reshape(6, self.n))
        y = self._solve(rhs[:, None])[:, 0]
        with np.errstate(over="ignore", invalid="ignore"):
            y /= self.cs
        y[:, self.overflow | self.exact | ~np.isfinite(b).all(axis=1)] = np.nan
        return y.T

    def solve_cond(self, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """x (n, 6) and the condition number estimate (n,) for b (n, 6): ||As||_F times the
        larger of ||As^-1 z|| / ||z|| over Equilibrated's two probes z (one per row of the
        full system, in the group's order)."""
        rhs = self._scratch[:18 * self.n].reshape(6, 3, self.n)
        self._scaled_rhs(b, rhs[:, 0])
        rows = np.concatenate([np.arange(6)[r] for r in self.order])
        rhs[:, 1:] = PROBES[rows, :, None]
        overflow = self.overflow | ~np.isfinite(rhs[:, 0]).all(axis=0)
        rhs[:, 0, overflow] = 0.0
        y = self._solve(rhs)
        y[:, :, overflow] = np.inf
        with np.errstate(over="ignore", invalid="ignore"):
            probe = np.sqrt(np.einsum("ikn,ikn->kn", y[:, 1:], y[:, 1:]))
            probe /= PROBE_NORMS[6][:, None]
            cond = self.fro * probe.max(axis=0)
        cond = np.where(np.isfinite(cond), cond, np.inf)
        cond[overflow] = np.nan
        with np.errstate(over="ignore", invalid="ignore"):
            x = y[:, 0] / self.cs      # (not a view: y's probe solutions are let go)
        x[:, ~(cond < SINGULAR_COND)] = np.nan
        return x.T, cond
