"""Every joint reaction and the driver effort split by source: inertia, gravity, each load,
and friction (the effort with friction minus the effort without it).

The equations of every method are linear in the loads, so a method's result is the sum of its
results for each source taken alone. The same step matrices are solved once with one
right-hand side per source (no second analysis); the parts add up to the method's total.
"""
from __future__ import annotations

import numpy as np

from ..linalg import Equilibrated
from .context import ForceContext
from .equations import Action, step_system, triangular_blocks

INERTIA, GRAVITY, FRICTION = "inertia", "gravity", "friction"


def source_of(action: Action, names: dict[str, str]) -> str | None:
    """The source an action's known part belongs to (None for unknown reactions/torque)."""
    if action.category == "inertia":
        return INERTIA
    if action.category == "gravity":
        return GRAVITY
    if action.category in ("load", "friction"):
        return names[action.symbol]
    return None


def friction_names(ctx: ForceContext, apart: bool = False) -> dict[str, str]:
    """Friction symbol (Mf12, Ff23, either way round) -> its source: ``friction``, or
    ``friction J`` for each joint with ``apart``."""
    out = {}
    for fr in ctx.spec.friction:
        a, b = ctx.spec.joint(fr.joint).links
        kind = "Mf" if ctx.spec.joint(fr.joint).type == "R" else "Ff"
        for src, dst in ((a, b), (b, a)):
            out[ctx.spec.symbol(src, dst, kind)] = f"{FRICTION} {fr.joint}" if apart else FRICTION
    return out


def load_names(ctx: ForceContext) -> dict[str, str]:
    """Load symbol (F3ext) -> the load's name (its ``name``, or ``load i`` in list order)."""
    return {ld.symbol: ld.name for ld in ctx.loads}


def split_by_source(ctx: ForceContext, steps, friction_apart: bool = False
                    ) -> dict[str, dict[str, np.ndarray]]:
    """``{source: {unknown: (n,)}}`` for every unknown a method's ``steps`` (its labelled
    systems over ``ctx``) solve (``driver.torque``, ``joint.J.fx`` ...): inertia first,
    then gravity, then each load in spec order, then friction (with ``friction_apart``,
    each joint's: ``friction J``) when the kinematics carry it. The sum over sources equals
    the method's ``values()``."""
    rubs = friction_names(ctx, friction_apart) if ctx.kin.friction is not None else {}
    names = {**load_names(ctx), **rubs}
    sources = list(dict.fromkeys([INERTIA, GRAVITY] + [ld.name for ld in ctx.loads]
                                 + list(rubs.values())))
    col = {s: k for k, s in enumerate(sources)}
    known: dict[str, np.ndarray] = {}            # unknown -> (S, n) parts

    def column(t) -> int | None:
        src = source_of(t.action, names)
        return None if src is None else col[src]
    for step in (b for s in steps for b in triangular_blocks(s)):
        A, b = step_system(step, known, ctx.n, len(sources), column)
        X = Equilibrated(A).solve_many(b)                        # (m, S, n)
        for i, u in enumerate(step.unknowns):
            known[u] = X[i]
    return {s: {u: parts[k] for u, parts in known.items()} for s, k in col.items()}
