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
    equations = [eq for link in ctx.spec.links for eq in newton_euler_equations(ctx, link.name)]
    out = []
    for name, res in results.items():
        if not res.reactions:
            continue
        values = res.values()
        force = moment = 0.0
        for eq in equations:
            r = float(np.max(np.abs(eq.evaluate(values)), initial=0.0))
            if eq.kind == "moment":
                moment = max(moment, r)
            else:
                force = max(force, r)
        out.append(Residual(name, force, moment))
    return out
