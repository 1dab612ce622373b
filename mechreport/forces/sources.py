"""Every joint reaction and the driver effort split by source: inertia, gravity, each load.

The equations of every method are linear in the loads, so a method's result is the sum of its
results for each source taken alone. The same step matrices are solved once with one
right-hand side per source (no second analysis); the parts add up to the method's total.
"""
from __future__ import annotations

import numpy as np

from ..linalg import batched_solve_many
from .context import ForceContext
from .equations import Action
from .result import ForceResult

INERTIA, GRAVITY = "inertia", "gravity"


def source_of(action: Action, names: dict[str, str]) -> str | None:
    """The source an action's known part belongs to (None for unknown reactions/torque)."""
    if action.category == "inertia":
        return INERTIA
    if action.category == "gravity":
        return GRAVITY
    if action.category == "load":
        return names[action.symbol]
    return None


def load_names(ctx: ForceContext) -> dict[str, str]:
    """Load symbol (F3ext) -> the load's name (its ``name``, or ``load i`` in list order)."""
    return {ld.symbol: ld.name for ld in ctx.loads}


def split_by_source(ctx: ForceContext, res: ForceResult) -> dict[str, dict[str, np.ndarray]]:
    """``{source: {unknown: (n,)}}`` for every unknown ``res`` solved (``driver.torque``,
    ``joint.J.fx`` ...): inertia first, then gravity, then each load in spec order. The sum
    over sources equals ``res.values()``."""
    names = load_names(ctx)
    sources = list(dict.fromkeys([INERTIA, GRAVITY] + [ld.name for ld in ctx.loads]))
    col = {s: k for k, s in enumerate(sources)}
    n, S = ctx.n, len(sources)
    known: dict[str, np.ndarray] = {}            # unknown -> (n, S) parts
    for step in res.steps:
        m = len(step.unknowns)
        idx = {u: i for i, u in enumerate(step.unknowns)}
        A = np.zeros((n, m, m))
        B = np.zeros((n, m, S))
        for row, eq in enumerate(step.equations):
            for t in eq.terms:
                sign = 1.0 if t.side == "rhs" else -1.0
                src = source_of(t.action, names)
                if src is not None:
                    B[:, row, col[src]] -= sign * t.const
                for k, u in enumerate(t.action.unknowns):
                    if u in idx:
                        A[:, row, idx[u]] += sign * t.coeffs[:, k]
                    else:
                        B[:, row, :] -= sign * t.coeffs[:, k, None] * known[u]
        X = batched_solve_many(A, B)
        for u, i in idx.items():
            known[u] = X[:, i, :]
    return {s: {u: parts[:, k] for u, parts in known.items()} for s, k in col.items()}
