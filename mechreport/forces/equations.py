"""Labelled linear equations over named unknowns, and the one batched solver all methods share.

An ``Equation`` is a list of ``Term``s; each term is one action (a force or a couple) as it
enters that equation: its coefficients on the unknowns it carries (joint reaction components,
T-joint couples, the driver torque) and its known constant part. The equation reads
``sum(rhs terms) - sum(lhs terms) = 0`` (Newton-Euler writes ``m a_C`` on the left; every other
method has only right-hand terms, ``... = 0``). Arrays carry the angle axis first: coefficients
(n, k), constants (n,).

A ``Step`` is one square system solved at once (a method may chain several, e.g. dyad by
dyad). Unknowns solved by earlier steps are substituted as known values. The same objects feed
the worked solution sheets, so each term keeps its symbol, application point and lever arm.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

SINGULAR_COND = 1e10  # equilibrated condition number above which an angle is flagged singular


@dataclass(frozen=True)
class Action:
    """A force or couple acting on a link.

    ``symbol`` follows the textbook (F12 = force of link 1 on link 2, Fin2, G2, Min2, M).
    Forces: ``at`` (n, 2) is the application point [m], named ``at_name``. Unknown actions carry
    ``unknowns`` (joint.B.fx, joint.B.fy / joint.C_T.moment / driver.torque) times ``sign``;
    known ones carry ``value``: (n, 2) [N] for forces, (n,) [N m] for couples.
    """

    symbol: str
    kind: str                       # "force" | "couple"
    category: str                   # "reaction" | "driver" | "gravity" | "inertia" | "load"
    link: str
    at: np.ndarray | None = None
    at_name: str | None = None
    unknowns: tuple[str, ...] = ()
    sign: float = 1.0
    value: np.ndarray | None = None


@dataclass(frozen=True)
class Term:
    """One action's contribution to one equation: ``coeffs @ x[unknowns] + const``.

    ``lever`` (n, 2) is r_PQ for moment equations (Q the action's point, P the moment centre);
    ``direction`` (n, 2) the projection direction for force equations."""

    action: Action
    coeffs: np.ndarray              # (n, len(action.unknowns))
    const: np.ndarray               # (n,)
    side: str = "rhs"
    lever: np.ndarray | None = None
    direction: np.ndarray | None = None
    rate: np.ndarray | None = None   # power terms: the velocity (n, 2) or omega (n,) it works on


@dataclass
class Equation:
    """A scalar equation. ``kind``: force | moment | constraint | power.

    ``label`` is how a reader names it (sum F^(2&3) . i); ``bodies`` the links of the free body;
    ``axis`` the projection (x, y, or a named sliding direction); ``about`` the moment centre."""

    label: str
    kind: str
    bodies: tuple[str, ...]
    terms: list[Term] = field(default_factory=list)
    axis: str | None = None
    about: str | None = None
    note: str = ""

    def unknown_names(self) -> list[str]:
        names: list[str] = []
        for t in self.terms:
            for u in t.action.unknowns:
                if u not in names:
                    names.append(u)
        return names

    def evaluate(self, values: dict[str, np.ndarray]) -> np.ndarray:
        """Residual sum(rhs) - sum(lhs) (n,) with every unknown taken from ``values``."""
        total = 0.0
        for t in self.terms:
            s = 1.0 if t.side == "rhs" else -1.0
            part = t.const.copy()
            for k, u in enumerate(t.action.unknowns):
                part = part + t.coeffs[:, k] * values[u]
            total = total + s * part
        return total


@dataclass
class Step:
    """A square system: ``equations`` determine ``unknowns`` (given earlier steps' results)."""

    title: str
    unknowns: list[str]
    equations: list[Equation]
    bodies: tuple[str, ...] = ()


@dataclass(frozen=True)
class Solution:
    """Values (n,) per unknown, and where the system was singular (n,) bool."""

    values: dict[str, np.ndarray]
    singular: np.ndarray


def solve_step(step: Step, known: dict[str, np.ndarray], n: int) -> Solution:
    """Solve one step for all angles at once: A (n, m, m) x = b (n, m)."""
    m = len(step.unknowns)
    if len(step.equations) != m:
        raise ValueError(f"{step.title}: {len(step.equations)} equations for {m} unknowns")
    col = {u: i for i, u in enumerate(step.unknowns)}
    A = np.zeros((n, m, m))
    b = np.zeros((n, m))
    for row, eq in enumerate(step.equations):
        for t in eq.terms:
            s = 1.0 if t.side == "rhs" else -1.0
            b[:, row] -= s * t.const
            for k, u in enumerate(t.action.unknowns):
                if u in col:
                    A[:, row, col[u]] += s * t.coeffs[:, k]
                elif u in known:
                    b[:, row] -= s * t.coeffs[:, k] * known[u]
                else:
                    raise ValueError(f"{step.title}: equation '{eq.label}' needs {u}, "
                                     "which is neither solved here nor known")
    x, singular = batched_solve(A, b)
    return Solution({u: x[:, i] for u, i in col.items()}, singular)


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
    rs = np.max(absA, axis=2, keepdims=True)
    rs[rs == 0] = 1.0
    absA /= rs
    cs = np.max(absA, axis=1, keepdims=True)
    cs[cs == 0] = 1.0
    As = A / (rs * cs)
    rhs = np.concatenate([(b / rs[..., 0])[..., None],
                          np.broadcast_to(_PROBES[:m], (n, m, 2))], axis=2)
    try:
        y = np.linalg.solve(As, rhs)
    except np.linalg.LinAlgError:  # an exactly singular angle: find it the slow way
        exact = ~(np.linalg.cond(As) < SINGULAR_COND)
        As = np.where(exact[:, None, None], np.eye(m), As)
        y = np.linalg.solve(As, rhs)
        y[exact] = np.inf
    with np.errstate(over="ignore", invalid="ignore"):
        probe = np.sqrt(np.sum(y[:, :, 1:] ** 2, axis=1)) / _PROBE_NORMS[m]
        cond = np.sqrt(np.sum(As**2, axis=(1, 2))) * np.max(probe, axis=1)
    singular = ~(cond < SINGULAR_COND)
    x = y[:, :, 0] / cs[:, 0, :]
    x[singular] = np.nan
    return x, singular


_PROBES = np.random.default_rng(20261121).standard_normal((64, 2))
_PROBE_NORMS = {m: np.sqrt(np.sum(_PROBES[:m] ** 2, axis=0)) for m in range(1, 65)}
