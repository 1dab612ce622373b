"""The one batched linear solver: every kinematic and force system, all angles at once.

Systems are stored angle-last, ``(m, m, n)``: builders write whole rows of coefficients over
the angle axis contiguously, and the equilibration's row and column maxima reduce over long
contiguous runs instead of short last axes (measured 6-10x faster for 6x6 and 17x17 than the
angle-first layout).

LAPACK's per-matrix cost is most of the time for the small systems here, so it solves only
what nothing cheaper can:

- rows that are the same at every angle (force balances, coefficients +-1) are eliminated once
  for all angles (:class:`ConstantRows`); what is left is most often 2x2 or smaller;
- 1x1 and 2x2 systems are solved in closed form over the angle axis (3-4x faster);
- systems up to ``SMALL_LU`` by Gaussian elimination with partial pivoting, one row
  operation at a time over the angle axis (LAPACK's algorithm; 2-5x faster at these sizes);
- LAPACK solves the rest, each angle's matrix from a view.

A chain of blocks (a method's systems, solved in turn) has many 1x1 and 2x2 systems whose
matrices do not depend on the earlier results: :func:`prepare_small` equilibrates and probes
them together, so that what is left per block is its own right-hand side;
:func:`prepare_large` does the same for larger systems of one size and the same constant rows.
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np


SINGULAR_COND = 1e10  # equilibrated condition number above which an angle is flagged singular
CONSTANT_PIVOT_COND = 100.0   # largest condition number of an eliminated constant block
CONSTANT_GROWTH = 4.0         # largest entry of K_P^-1 and K_P^-1 K_Q of an eliminated block
SMALL_LU = 6                  # largest system solved by row operations over the angle axis


class Equilibrated:
    """A batch of square systems ``At`` (m, m, n), rows and columns scaled once to a largest
    entry of 1 (which makes the condition number independent of units); solve any number of
    right-hand sides with it.

    ``solve_cond`` also estimates the condition number of the equilibrated matrix as
    ||A||_F * max_k ||A^-1 z_k|| / ||z_k|| with two fixed random probes z_k solved alongside
    b (a randomised estimate, within a small factor of ||A||_2 ||A^-1||_2, at the cost of one
    solve rather than an SVD): inf where exactly singular, NaN where A or b is not finite (an
    input that overflowed, or a pose that could not be solved). Singular angles get NaN."""

    def __init__(self, At: np.ndarray, members: int = 1):
        At = np.asarray(At, np.float64)
        m, _, n = At.shape
        self.m, self.n = m, n
        absA = np.abs(At)
        rs = absA.max(axis=1)                  # (m, n); NaN or inf where a row is not finite
        self.vanishing = vanishing_lines(rs, absA.max(axis=0), members)
        rs[rs == 0] = 1.0
        with np.errstate(invalid="ignore"):    # inf / inf: an overflow angle, replaced below
            absA /= rs[:, None, :]
        cs = absA.max(axis=0)                  # (m, n)
        cs[cs == 0] = 1.0
        absA /= cs[None, :, :]                 # |As|
        # non-finite input (a pose that could not be solved) is singular, never a LAPACK error
        self.overflow = ~np.isfinite(rs).all(axis=0)
        if self.overflow.any():
            absA[:, :, self.overflow] = np.eye(m)[:, :, None]
        self.fro = np.sqrt(np.einsum("ijn,ijn->n", absA, absA))   # ||As||_F (n,)
        del absA
        self.rs, self.cs = rs, cs              # all angle-last
        self.exact = np.zeros(n, bool)         # exactly singular (a zero pivot), found on solve
        self.schur = ConstantRows.of(At, rs, self.overflow) if m >= 3 else None
        self.As = None                         # the scaled matrices, for the solves that use them
        if self.schur is None:
            with np.errstate(invalid="ignore"):
                As = np.divide(At, rs[:, None, :])
            As /= cs[None, :, :]
            if self.overflow.any():
                As[:, :, self.overflow] = np.eye(m)[:, :, None]
            self.As = As

    def _part(self, here: slice) -> "Equilibrated":
        """The systems at angles ``here`` of this batch, sharing its arrays (views): what
        :func:`prepare_large` hands out for each of the systems it joined. What a solve
        writes into them (``exact``; ``As`` set to the identity at exactly singular angles)
        depends on the matrix alone, at those angles only: parts, and the methods sharing
        one prepared block, can solve in any order."""
        part = Equilibrated.__new__(Equilibrated)
        part.m, part.n = self.m, here.stop - here.start
        part.rs, part.cs = self.rs[:, here], self.cs[:, here]
        part.overflow, part.fro, part.exact = self.overflow[here], self.fro[here], self.exact[here]
        part.vanishing = self.vanishing[here]
        part.schur = None if self.schur is None else self.schur._part(here)
        part.As = None if self.As is None else self.As[:, :, here]
        return part

    def _solve(self, rhs: np.ndarray) -> np.ndarray:
        """Every angle's system for right-hand sides rhs (m, k, n) -> y (m, k, n), both
        angle-last; inf at bad angles. Systems with constant rows through
        :class:`ConstantRows`; 1x1 and 2x2 in closed form; up to ``SMALL_LU`` by row
        operations over the angle axis (LAPACK's per-matrix cost is most of theirs); larger
        ones by LAPACK."""
        if self.schur is not None:        # rows scaled, columns not: y = cs x
            with np.errstate(invalid="ignore", over="ignore"):   # overflow angles: inf
                y = self.schur.solve(rhs) * self.cs[:, None, :]
            self.exact |= self.schur.exact
        elif self.m <= 2:
            y, exact = _closed_form(self.As, rhs)
            self.exact |= exact
        elif self.m <= SMALL_LU:
            y, exact = _small_lu(self.As, rhs)
            self.exact |= exact
        else:
            lhs = self.As.transpose(2, 0, 1)
            try:
                y = np.linalg.solve(lhs, rhs.transpose(2, 0, 1))
            except np.linalg.LinAlgError:  # an exactly singular angle: LU finds a zero pivot
                self.exact |= np.linalg.det(lhs) == 0
                self.As[:, :, self.exact] = np.eye(self.m)[:, :, None]
                y = np.linalg.solve(self.As.transpose(2, 0, 1), rhs.transpose(2, 0, 1))
            y = y.transpose(1, 2, 0)
        y[:, :, self.overflow | self.exact] = np.inf
        return y

    def solve(self, b: np.ndarray) -> np.ndarray:
        """x (n, m) for b (n, m); NaN where the system is not finite or exactly singular.
        For angles already known to be regular (no condition estimate)."""
        if self.m == 0:
            return np.zeros((self.n, 0))
        y = self._solve((b.T / self.rs)[:, None, :])[:, 0, :]
        with np.errstate(over="ignore", invalid="ignore"):
            x = y / self.cs
        x[:, self.overflow | self.exact | ~np.isfinite(b).all(axis=1)] = np.nan
        return x.T

    def solve_cond(self, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """x (n, m) and the condition number estimate (n,) for b (n, m)."""
        n, m = self.n, self.m
        if m == 0:
            return np.zeros((n, 0)), np.ones(n)
        rhs = np.empty((m, 3, n))
        rhs[:, 0, :] = b.T / self.rs
        rhs[:, 1:, :] = PROBES[:m, :, None]
        overflow = self.overflow | ~np.isfinite(rhs[:, 0, :]).all(axis=0)
        rhs[:, 0, overflow] = 0.0
        y = self._solve(rhs)
        y[:, :, overflow] = np.inf
        cond = self._probed_cond(y[:, 1:])
        with np.errstate(over="ignore", invalid="ignore"):
            x = y[:, 0, :] / self.cs
        cond[overflow] = np.nan
        x[:, ~(cond < SINGULAR_COND)] = np.nan
        return x.T, cond

    def _probed_cond(self, y: np.ndarray) -> np.ndarray:
        """The condition number estimate (n,) from the solutions y (m, 2, n) for the probes:
        ||As||_F max_k ||y_k|| / ||z_k||, inf where not finite or a row or column vanishes
        (:func:`vanishing_lines`)."""
        with np.errstate(over="ignore", invalid="ignore"):
            probe = np.sqrt(np.einsum("ikn,ikn->kn", y, y)) / PROBE_NORMS[self.m][:, None]
            cond = self.fro * probe.max(axis=0)
        cond[~np.isfinite(cond)] = np.inf
        cond[self.vanishing] = np.inf
        return cond

    def solve_many(self, B: np.ndarray) -> np.ndarray:
        """X (m, k, n) for several right-hand sides B (m, k, n), both angle-last, for angles
        already known to be regular (a superposition of loads over a solved system; a
        Schur complement's solve); inf where not finite or exactly singular."""
        if self.m == 0:
            return np.zeros(B.shape)
        with np.errstate(invalid="ignore", over="ignore"):
            return self._solve(B / self.rs[:, None, :]) / self.cs[:, None, :]


class ConstantRows:
    """A system ``At`` (m, m, n) whose rows ``R`` are the same at every angle and made of
    +-1 and 0 only (a force balance in x or y: the reactions' components with coefficient
    +-1; a slider's couple alone in its link's moment equation), solved by eliminating those
    rows once for all angles.

    The system is taken with its rows scaled to a largest entry of 1 (the unit rows are
    unchanged), so nothing overflows whatever the scale of the others. With ``P`` the
    unknowns the constant rows are pivoted on (complete pivoting over the constant block
    K = [K_P K_Q]), ``N`` the other rows and ``Q`` the other unknowns:
    x_P = K_P^-1 b_R - M x_Q with M = K_P^-1 K_Q, and the Schur complement
    (A_NQ - A_NP M) x_Q = b_N - A_NP K_P^-1 b_R, of size m - |R| (most often 2x2 or
    smaller), is solved equilibrated (:class:`Equilibrated`: no overflow of its
    determinant, whatever the scale).

    Why it is as accurate as partial pivoting: with rows of +-1 and 0, a row's scale is 1, so
    the multipliers of the equilibrated system are those of A_NP K_P^-1 relative to each
    varying row's own largest entry, bounded by |K_P^-1|. The block is accepted only when
    K_P^-1 and M are small (at most ``CONSTANT_GROWTH``) and K_P well conditioned; rows with
    other constant numbers (a fixed lever arm) are left with the varying rows. Otherwise
    :meth:`of` returns None and the whole system goes to the general solve."""

    def __init__(self, At, rs, rows, others, pivots, rest, Kinv, M, at_np, at_nq):
        self.rows, self.others, self.pivots, self.rest = rows, others, pivots, rest
        self.Kinv, self.M = Kinv, M
        q, n = len(others), At.shape[2]
        flat = At.reshape(-1, n)
        scale = rs[others][:, None, :]
        self.A_NP = flat[at_np].reshape(q, len(pivots), n) / scale   # (q, p, n), rows scaled
        S = flat[at_nq].reshape(q, len(rest), n) / scale
        S -= np.einsum("ipn,pq->iqn", self.A_NP, M)
        self.S = Equilibrated(S) if len(rest) else None
        self.exact = np.zeros(At.shape[2], bool)

    @staticmethod
    def of(At: np.ndarray, rs: np.ndarray, bad: np.ndarray) -> "ConstantRows | None":
        """The elimination for ``At`` with row scales ``rs`` (m, n) if it has usable constant
        rows, else None. ``bad`` (n,) marks angles whose coefficients are not finite (left
        out of the comparison; their results are discarded by the caller)."""
        m, _, n = At.shape
        good = np.flatnonzero(~bad)
        if good.size == 0:
            return None
        first = At[:, :, good[0]]
        if good.size < n:                  # the bad angles take a good angle's numbers
            At = At.copy()
            At[:, :, bad] = first[:, :, None]
            rs = rs.copy()
            rs[:, bad] = rs[:, good[:1]]
        rows = _unit_rows(At)
        if rows.size == 0:
            return None
        K = first[rows]
        plan = _constant_plan(m, tuple(rows.tolist()), K.shape, K.tobytes())
        return None if plan is None else ConstantRows(At, rs, rows, *plan)

    def _part(self, here: slice) -> "ConstantRows":
        """The elimination at angles ``here`` (see :meth:`Equilibrated._part`)."""
        part = ConstantRows.__new__(ConstantRows)
        part.__dict__.update(self.__dict__)         # the plan: the same for every angle
        part.A_NP, part.exact = self.A_NP[..., here], self.exact[here]
        part.S = None if self.S is None else self.S._part(here)
        return part

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        """x (m, k, n) with A x = rs rhs for right-hand sides rhs (m, k, n) already divided
        by the row scales; ``exact`` marks the angles where the Schur complement is exactly
        singular."""
        _, k, n = rhs.shape
        c = (self.Kinv @ rhs[self.rows].reshape(len(self.rows), -1)).reshape(-1, k, n)
        x = np.empty(rhs.shape)
        if self.S is not None:
            xq = self.S.solve_many(rhs[self.others] - np.einsum("ipn,pkn->ikn", self.A_NP, c))
            self.exact |= self.S.exact | self.S.overflow
            x[self.rest] = xq
            c -= (self.M @ xq.reshape(len(self.rest), -1)).reshape(c.shape)
        x[self.pivots] = c
        return x


def _unit_rows(At: np.ndarray) -> np.ndarray:
    """The rows of ``At`` (m, m, n) made of +-1 and 0 (not all 0), the same at every angle
    (NaN never is): :func:`_rows_of` its entries' largest and smallest values."""
    return np.array(_rows_of(At.max(axis=2).tolist(), At.min(axis=2).tolist()), dtype=np.intp)


def _rows_of(top: list, low: list) -> list[int]:
    """The rows whose largest values ``top`` and smallest ``low`` over the angles (m lists
    of m numbers) are equal, made of +-1 and 0, not all 0: read as Python numbers, which
    costs less for an m x m matrix than a dozen numpy calls."""
    return [r for r, (hi, lo) in enumerate(zip(top, low))
            if hi == lo and any(hi) and all(x in (0.0, 1.0, -1.0) for x in hi)]


@lru_cache(maxsize=1024)
def _constant_plan(m: int, rows: tuple[int, ...], shape: tuple[int, int], data: bytes):
    """(others, pivots, rest, K_P^-1, M, and where A_NP and A_NQ are in A flattened to
    (m * m, n)) for the constant rows ``rows`` of an m x m system, whose coefficients K
    (``shape``, float64 +-1 and 0) are ``data``; None if they are not to be eliminated. The
    same few constant blocks come back every analysis: planned once each (read-only)."""
    K = np.frombuffer(data, np.float64).reshape(shape)
    pivots = _complete_pivots(K)
    if pivots is None:
        return None
    rest = np.array([j for j in range(m) if j not in set(pivots)], int)
    pivots = np.array(pivots, int)
    K_P = K[:, pivots]
    if not np.linalg.cond(K_P) <= CONSTANT_PIVOT_COND:
        return None
    Kinv = np.linalg.inv(K_P)
    M = Kinv @ K[:, rest]
    if not (np.max(np.abs(Kinv)) <= CONSTANT_GROWTH
            and np.max(np.abs(M), initial=0.0) <= CONSTANT_GROWTH):
        return None
    others = np.array([i for i in range(m) if i not in set(rows)], int)
    at_np = np.add.outer(others * m, pivots).ravel()   # A[others][:, pivots] in A (m * m, n)
    at_nq = np.add.outer(others * m, rest).ravel()
    for a in (rest, pivots, Kinv, M, others, at_np, at_nq):
        a.setflags(write=False)
    return others, pivots, rest, Kinv, M, at_np, at_nq


def _complete_pivots(K: np.ndarray) -> list[int] | None:
    """The column each row of the constant block K (p, m) is pivoted on, by Gaussian
    elimination with complete pivoting; None if K has not full row rank."""
    W = K.astype(float)
    p, m = W.shape
    top = np.max(np.abs(W), initial=0.0)
    free_rows, free_cols = list(range(p)), list(range(m))
    out = []
    for _ in range(p):
        sub = np.abs(W[np.ix_(free_rows, free_cols)])
        i, j = np.unravel_index(np.argmax(sub), sub.shape)
        if not sub[i, j] > 1e-12 * top:
            return None
        r, c = free_rows.pop(i), free_cols.pop(j)
        for k in free_rows:
            W[k] -= W[k, c] / W[r, c] * W[r]
        out.append(c)
    return out


def _small_lu(At: np.ndarray, rhs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Solve systems At (m, m, n) for rhs (m, k, n) by Gaussian elimination with partial
    pivoting (LAPACK's getrf/getrs algorithm: the largest entry of the column, the first on a
    tie), one row operation at a time over the angle axis: y (m, k, n), and where a pivot is
    exactly zero (exactly singular) (n,) bool. For m up to ``SMALL_LU``, where LAPACK's
    per-matrix cost is most of its time (measured 0.09 against 0.43 us per angle for a
    contour 3x3 block)."""
    m = At.shape[0]
    rows = [np.concatenate([At[i], rhs[i]]) for i in range(m)]   # [A_i | b_i], (m + k, n)
    exact = np.zeros(At.shape[2], bool)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for j in range(m):
            if j < m - 1:
                p = np.argmax(np.abs(np.stack([r[j] for r in rows[j:]])), axis=0)
                if p.any():                 # swap row j with row j + p where p > 0
                    top = rows[j]
                    for i in range(j + 1, m):
                        here = p == i - j
                        if here.any():
                            rows[j] = np.where(here, rows[i], rows[j])
                            rows[i] = np.where(here, top, rows[i])
            pivot = rows[j][j]
            exact |= pivot == 0
            for i in range(j + 1, m):
                rows[i][j + 1:] -= (rows[i][j] / pivot) * rows[j][j + 1:]
        y = np.empty(rhs.shape)
        for j in range(m - 1, -1, -1):
            s = rows[j][m:].copy()
            for i in range(j + 1, m):
                s -= rows[j][i] * y[i]
            y[j] = s / rows[j][j]
    return y, exact


def _closed_form(At: np.ndarray, rhs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Solve 1x1 or 2x2 systems At (m, m, n) for rhs (m, k, n) by Cramer's rule (forward
    stable for 2x2): y (m, k, n), and where they are exactly singular (n,) bool."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        if At.shape[0] == 1:
            a = At[0, 0]
            return rhs / a, a == 0
        det = _determinant(At)
        return _cramer(At, det, rhs), det == 0


def _determinant(At: np.ndarray) -> np.ndarray:
    """Determinants (n,) of 2x2 systems At (2, 2, n)."""
    return At[0, 0] * At[1, 1] - At[0, 1] * At[1, 0]


def _cramer(At: np.ndarray, det: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """Cramer's rule for 2x2 systems At (2, 2, n) of determinants ``det`` (n,): y shaped as
    the right-hand sides ``rhs`` (2, ..., n) (call it where errors are ignored)."""
    y = np.empty(rhs.shape)
    y[0] = (At[1, 1] * rhs[0] - At[0, 1] * rhs[1]) / det
    y[1] = (At[0, 0] * rhs[1] - At[1, 0] * rhs[0]) / det
    return y


def solve_cond(At: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """x (n, m) and the condition number estimate (n,) for systems At (m, m, n) angle-last
    and b (n, m): :meth:`Equilibrated.solve_cond`, with a 1x1 system answered directly
    (:class:`SmallSystem`: its equilibrated matrix is +-1, its condition number exactly 1;
    the same bits as the general path at a fraction of its numpy calls)."""
    if At.shape[0] != 1:
        return Equilibrated(At).solve_cond(b)
    return prepare_small([At])[0].solve_cond(b)


class SmallSystem:
    """A 1x1 or 2x2 system prepared with others (:func:`prepare_small`): slice ``part`` of
    their group. What is left per right-hand side is its own solve: a 2x2 by the operations
    :meth:`Equilibrated.solve_cond` does on it alone, a 1x1 answered directly (its
    equilibrated matrix is +-1)."""

    def __init__(self, group: "_SmallGroup", part: slice):
        self.group, self.part = group, part

    def solve_cond(self, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        x, cond = self.group.solve_at(self.part, b.T)
        return x.T, cond


class _SmallGroup:
    """Systems of one size m <= 2 concatenated along the angle axis (m, m, N), equilibrated
    and solved for :class:`Equilibrated`'s probes at once: per angle the very operations of
    :func:`solve_cond`, so each slice's condition number is the one it would get alone."""

    def __init__(self, At: np.ndarray, members: int = 1):
        self.m = m = At.shape[0]
        if m == 1:              # the equilibrated matrix is +-1: no probe to solve
            a = At[0, 0]
            rs = np.abs(a)
            vanishing = vanishing_lines(rs[None, :], rs[None, :], members)
            rs[rs == 0] = 1.0
            with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
                self.unit = a / rs
            self.rs = rs[None, :]
            self.cond = np.where(np.isfinite(rs), np.where((a == 0) | vanishing, np.inf, 1.0),
                                 np.nan)
            return
        eq = Equilibrated(At, members)
        cond = eq._probed_cond(eq._solve(np.broadcast_to(PROBES[:m, :, None],
                                                          (m, 2, At.shape[2]))))
        cond[eq.overflow] = np.nan
        self.cond, self.rs, self.cs, self.As = cond, eq.rs, eq.cs, eq.As
        with np.errstate(over="ignore", invalid="ignore"):
            self.det = _determinant(eq.As)

    def solve_at(self, at, bt: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """x (m, k) and the condition numbers (k,) of the systems at ``at`` (a slice or an
        index array of the joined angle axis, k angles) for the right-hand sides bt (m, k),
        angle-last: a 2x2 by the operations :meth:`Equilibrated.solve_cond` does on it
        alone, a 1x1 answered directly (its equilibrated matrix is +-1). Every step is per
        angle, so any of the group's systems can be solved together."""
        rs = self.rs[:, at]
        cond = self.cond[at]
        if isinstance(at, slice):
            cond = cond.copy()
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            q = bt / rs                               # (m, k)
            finite = np.isfinite(q)
            everywhere = finite.all()                 # (as a rule: nothing to mark)
            if self.m == 1:                           # a / rs is +-1 (0 where singular)
                x = q / self.unit[at]
                if not everywhere:
                    cond[~finite[0]] = np.nan
            else:
                if not everywhere:
                    overflow = ~finite.all(axis=0)
                    q[:, overflow] = 0.0
                    cond[overflow] = np.nan
                x = _cramer(self.As[:, :, at], self.det[at], q) / self.cs[:, at]
        regular = cond < SINGULAR_COND
        if not regular.all():
            x[:, ~regular] = np.nan
        return x, cond


def prepare_small(systems: list[np.ndarray]) -> list[SmallSystem]:
    """1x1 and 2x2 systems At (m, m, n), all over the same n angles, each ready to be solved
    for one right-hand side: ``prepare_small(systems)[k].solve_cond(b)`` equals
    ``solve_cond(systems[k], b)`` bit for bit.

    A method's chain of blocks has many such systems; their matrices do not depend on the
    earlier blocks' results (only their right-hand sides do), so those of one size are
    equilibrated, solved for the probes and judged together, concatenated along the angle
    axis: one pass of numpy calls for all of them instead of one each (the calls' own cost
    is most of the time of short sweeps)."""
    out: list[SmallSystem | None] = [None] * len(systems)
    for m in (1, 2):
        ks = [k for k, A in enumerate(systems) if A.shape[0] == m]
        if not ks:
            continue
        joined = np.concatenate([systems[k] for k in ks], axis=2, dtype=np.float64)
        for k, system in zip(ks, prepare_joined(joined, len(ks))):
            out[k] = system
    if any(s is None for s in out):
        raise ValueError("prepare_small takes 1x1 and 2x2 systems only")
    return out


def prepare_joined(At: np.ndarray, count: int) -> list[SmallSystem]:
    """:func:`prepare_small` for ``count`` 1x1 or 2x2 systems already joined along the angle
    axis, At (m, m, count n), the k-th over angles [k n, (k + 1) n). Systems of one angle
    are prepared each alone: einsum sums ||As||_F's squares in another order for one angle
    than for several (the condition number's last bit)."""
    n = At.shape[2] // count
    if n > 1:
        group = _SmallGroup(At, count)
        return [SmallSystem(group, slice(i * n, (i + 1) * n)) for i in range(count)]
    return [SmallSystem(_SmallGroup(At[:, :, i * n:(i + 1) * n]), slice(0, n))
            for i in range(count)]


def prepare_large(systems: list[np.ndarray]) -> list[Equilibrated]:
    """``Equilibrated(At)`` for each of ``systems`` (m, m, n), m >= 3: those of one size and
    the same constant rows (:class:`ConstantRows`: which rows, and their numbers), all
    finite, over n > 1 angles, joined along the angle axis and equilibrated and planned
    together (the second of two Newton-Euler dyad blocks costs a few views, not a few
    dozen numpy calls). Each is solved as it would be alone: every step is per angle, and
    the constant rows and their plan are those each has alone. A system whose constant
    rows leave a Schur complement of three rows or more is prepared alone: the complement
    is searched for constant rows in turn, and over joined angles it could find fewer."""
    out: list[Equilibrated | None] = [None] * len(systems)
    sizes: dict[tuple, list[int]] = {}
    for k, At in enumerate(systems):
        sizes.setdefault(At.shape, []).append(k)
    for (m, _, n), ks in sizes.items():
        if n < 2 or len(ks) < 2:
            continue
        joined = np.concatenate([systems[k] for k in ks], axis=2)
        each = joined.reshape(m, m, len(ks), n)
        top, low = each.max(axis=3), each.min(axis=3)           # (m, m, k): per system
        finite = (np.isfinite(top) & np.isfinite(low)).all(axis=(0, 1)).tolist()
        groups: dict[tuple, list[int]] = {}
        for i in (i for i in range(len(ks)) if finite[i]):
            hi = top[:, :, i].tolist()
            rows = _rows_of(hi, low[:, :, i].tolist())
            # with a Schur complement of 3 rows or more, searched in turn: alone
            if not rows or m - len(rows) <= 2:
                groups.setdefault(tuple((r, tuple(hi[r])) for r in rows), []).append(i)
        for members in (g for g in groups.values() if len(g) > 1):
            whole = Equilibrated(joined if len(members) == len(ks) else np.concatenate(
                [systems[ks[i]] for i in members], axis=2), len(members))
            for j, i in enumerate(members):
                out[ks[i]] = whole._part(slice(j * n, (j + 1) * n))
    return [Equilibrated(At) if system is None else system
            for system, At in zip(out, systems)]


def vanishing_lines(row_max: np.ndarray, col_max: np.ndarray, members: int = 1) -> np.ndarray:
    """Angles (N,) bool at which a row or a column of a system nearly vanishes: its largest
    coefficient |A| there (``row_max``, ``col_max``: (m, N), before any scaling) below
    1 / ``SINGULAR_COND`` of its largest over the system's angles. ``members`` systems of
    N / members angles each may be joined along the angle axis; each is judged on its own.

    Why: the equilibration scales every row and column at each angle to a largest entry of
    1, so a column that is only rounding at one angle (an unknown that drops out of every
    equation there: a lever arm of cos 90 deg = 6e-17) is scaled up to look like any other,
    and the condition number misses the singularity; the unknown is then rounding divided by
    rounding. Judged against the same line at the other angles (the same quantity, the same
    unit), such a line is as singular as a condition number of ``SINGULAR_COND``. A line
    that is zero at every angle is left to the exact test (a zero pivot)."""
    m, total = row_max.shape
    n = total // members
    lines = np.concatenate([row_max, col_max]).reshape(2 * m, members, n)
    finite = np.isfinite(lines)
    top = (lines if finite.all() else np.where(finite, lines, 0.0)).max(axis=2, keepdims=True)
    with np.errstate(invalid="ignore"):         # NaN lines: never "small" (judged elsewhere)
        small = (lines < top / SINGULAR_COND) & (top > 0)
    return small.any(axis=0).reshape(total)


def angle_last(A: np.ndarray) -> np.ndarray:
    """(n, m, m) -> (m, m, n), contiguous."""
    return np.ascontiguousarray(A.transpose(1, 2, 0))


def batched_solve(A: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Solve A x = b for A (n, m, m) and b (n, m); returns x (n, m) and singular (n,) bool.
    See :class:`Equilibrated`; singular angles get NaN."""
    x, cond = batched_solve_cond(A, b)
    return x, ~(cond < SINGULAR_COND)


def batched_solve_cond(A: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Solve A x = b for A (n, m, m) and b (n, m); x (n, m) and the condition number
    estimate (n,) of the equilibrated matrix (see :class:`Equilibrated`)."""
    return solve_cond(angle_last(A), b)


PROBES = np.random.default_rng(20261121).standard_normal((64, 2))
PROBE_NORMS = {m: np.sqrt(np.sum(PROBES[:m] ** 2, axis=0)) for m in range(1, 65)}
