"""Substitute a method's reactions into every link's Newton-Euler equations (m a_C = sum F,
I_C alpha = sum M_C): what is left over shows the method's equilibrium is genuine."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..forces import ForceContext, ForceResult
from ..forces.builders import newton_euler_equations


@dataclass(frozen=True)
class Residual:
    """Largest |residual| over links and angles: ``force`` [N], ``moment`` [N m]."""

    method: str
    force: float
    moment: float


def residuals(ctx: ForceContext, results: dict[str, ForceResult]) -> list[Residual]:
    """The largest residuals of each method with joint reactions, over every link and angle
    (long sweeps chunk by chunk: the equations hold coefficients at every angle)."""
    from ..forces import CHUNK
    worst: dict[str, list[float]] = {name: [0.0, 0.0] for name, res in results.items()
                                     if res.reactions}
    solved = {name: results[name].values() for name in worst}   # unknown -> values (n,)
    for a in range(0, ctx.n, CHUNK):
        cut = slice(a, a + CHUNK)
        part = ctx if ctx.n <= CHUNK else ForceContext(ctx.kin.take(cut, ctx.kin.flags))
        equations = [eq for link in ctx.spec.links
                     for eq in newton_euler_equations(part, link.name)]
        for names in _same_unknowns(solved):    # every method's at once
            values = {k: np.array([solved[name][k][cut] for name in names])
                      for k in solved[names[0]]}
            for eq in equations:
                r = np.abs(eq.evaluate(values)).max(axis=-1, initial=0.0)
                k = 1 if eq.kind == "moment" else 0
                largest = r.tolist() if r.ndim else [float(r)] * len(names)
                for name, value in zip(names, largest):
                    worst[name][k] = max(worst[name][k], value)
    return [Residual(name, force, moment) for name, (force, moment) in worst.items()]


def _same_unknowns(solved: dict[str, dict]) -> list[list[str]]:
    """The methods of ``solved`` (method -> its values by unknown) grouped by the unknowns
    they name (all of them, as a rule: every method with reactions solves the same ones)."""
    groups: dict[tuple, list[str]] = {}
    for name, values in solved.items():
        groups.setdefault(tuple(values), []).append(name)
    return list(groups.values())
