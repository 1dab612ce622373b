"""Substitute a method's reactions into every link's Newton-Euler equations (m a_C = sum F,
I_C alpha = sum M_C): what is left over shows the method's equilibrium is genuine."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..forces import ForceContext, ForceResult
from ..forces.builders import newton_euler_equations
from ..forces.equations import Equation, no_constant

# chunks of at most this many angles are evaluated as one matrix product per angle (a few
# numpy calls for every equation); longer ones term by term (fewer operations per angle)
DENSE_MAX = 256


@dataclass(frozen=True)
class Residual:
    """Largest |residual| over links and angles: ``force`` [N], ``moment`` [N m]."""

    method: str
    force: float
    moment: float


def residuals(ctx: ForceContext, results: dict[str, ForceResult]) -> list[Residual]:
    """The largest residuals of each method with joint reactions, over every link and angle
    (long sweeps chunk by chunk: the equations hold coefficients at every angle); inf where
    a value is not finite (an analysis refuses those before: this is for other callers)."""
    from ..forces import CHUNK
    worst: dict[str, list[float]] = {name: [0.0, 0.0] for name, res in results.items()
                                     if res.reactions}
    solved = {name: results[name].values() for name in worst}   # unknown -> values (n,)
    for a in range(0, ctx.n, CHUNK):
        cut = slice(a, a + CHUNK)
        part = ctx if ctx.n <= CHUNK else ForceContext(ctx.kin.take(cut, ctx.kin.flags))
        equations = [eq for link in ctx.spec.links
                     for eq in newton_euler_equations(part, link.name)]
        moment = np.array([eq.kind == "moment" for eq in equations], bool)
        for names in _same_unknowns(solved):    # every method's at once
            unknowns = list(solved[names[0]])
            if part.n <= DENSE_MAX:
                values = np.array([[solved[name][u][cut] for name in names]
                                   for u in unknowns])                   # (U, methods, n)
                largest = _largest_by_matrix(equations, unknowns, values)
            else:
                values = {u: np.array([solved[name][u][cut] for name in names])
                          for u in unknowns}
                largest = np.array([np.broadcast_to(
                    np.abs(eq.evaluate(values)).max(axis=-1, initial=0.0), (len(names),))
                    for eq in equations]).reshape(len(equations), len(names))
            # a residual that is not a number is the worst there is, never none
            largest[np.isnan(largest)] = np.inf
            for k, rows in ((0, ~moment), (1, moment)):
                found = largest[rows].max(axis=0, initial=0.0).tolist()
                for name, value in zip(names, found):
                    worst[name][k] = max(worst[name][k], value)
    return [Residual(name, force, moment) for name, (force, moment) in worst.items()]


def _largest_by_matrix(equations: list[Equation], unknowns: list[str],
                       values: np.ndarray) -> np.ndarray:
    """max over the angles of |sum(rhs) - sum(lhs)| (E, k) of each equation, with the
    ``unknowns`` taken from ``values`` (U, k, n): k solutions at once. ``Equation.evaluate``
    up to rounding (the sums are taken in another order), as one product per angle of the
    equations' coefficient matrix (E, U + c: each equation's constants in columns of their
    own, against ones) and the unknowns: a few numpy calls for all the equations, where
    evaluating them costs several per term (most of a short sweep's time is the calls' own).
    The matrix is mostly zeros: over long sweeps, term by term is less work."""
    U, k, n = values.shape
    zero = no_constant(n)
    column = {u: j for j, u in enumerate(unknowns)}
    rows: list[np.ndarray] = []     # coefficients and constants (n,)
    signs: list[float] = []
    places: list[tuple[int, int]] = []      # (equation, column) of each; -1: named twice
    twice: list[tuple[int, int, int]] = []  # (equation, row, unknown) named twice in one
    width = U
    for e, eq in enumerate(equations):
        taken: set[int] = set()
        constants = 0
        for t in eq.terms:
            sign = 1.0 if t.side == "rhs" else -1.0
            if t.const is not zero:
                places.append((e, U + constants))
                constants += 1
                rows.append(t.const)
                signs.append(sign)
            for j, u in enumerate(t.action.unknowns):
                c = column[u]
                if c in taken:
                    twice.append((e, len(rows), c))
                    places.append((e, -1))
                else:
                    taken.add(c)
                    places.append((e, c))
                rows.append(t.coeffs[:, j])
                signs.append(sign)
        width = max(width, U + constants)
    largest = np.zeros((len(equations), k))
    if n == 0 or not rows:
        return largest
    keep = [i for i, (_, c) in enumerate(places) if c >= 0]
    at = [places[i][0] * width + places[i][1] for i in keep]
    coeffs = np.array(rows) * np.array(signs)[:, None]                       # (K, n)
    matrix = np.zeros((n, len(equations) * width))                            # angle first
    matrix[:, at] = coeffs[keep].T
    x = np.empty((n, width, k))
    x[:, :U, :] = values.transpose(2, 0, 1)
    x[:, U:, :] = 1.0
    total = np.matmul(matrix.reshape(n, len(equations), width), x)           # (n, E, k)
    for e, r, c in twice:
        total[:, e, :] += coeffs[r][:, None] * x[:, c, :]
    return np.abs(total).max(axis=0)


def _same_unknowns(solved: dict[str, dict]) -> list[list[str]]:
    """The methods of ``solved`` (method -> its values by unknown) grouped by the unknowns
    they name (all of them, as a rule: every method with reactions solves the same ones)."""
    groups: dict[tuple, list[str]] = {}
    for name, values in solved.items():
        groups.setdefault(tuple(values), []).append(name)
    return list(groups.values())
