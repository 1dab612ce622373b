"""Stage 4: joint reactions and driver torque by the textbook's four methods plus a power
balance. Every method module has ``NAME``, ``TITLE``, ``SECTION`` and
``solve(ctx: ForceContext) -> ForceResult``; they are registered here by name."""
from __future__ import annotations

from types import ModuleType

from ..kinematics import Kinematics
from . import contour, dalembert, dyad, newton_euler, power
from .context import ForceContext
from .equations import Equation, Step, Term
from .result import ForceResult, JointReaction

METHODS: dict[str, ModuleType] = {m.NAME: m for m in (newton_euler, dalembert, dyad, contour,
                                                      power)}


def solve_forces(kin: Kinematics, methods=None,
                 ctx: ForceContext | None = None) -> dict[str, ForceResult]:
    """Run the named methods (default: all) on one kinematics; results by method name.
    ``ctx``: the kinematics' ForceContext, if the caller has built it already."""
    names = list(METHODS) if methods is None else list(methods)
    unknown = [m for m in names if m not in METHODS]
    if unknown:
        raise ValueError(f"unknown method(s) {', '.join(unknown)}; valid: {', '.join(METHODS)}")
    ctx = ForceContext(kin) if ctx is None else ctx
    return {name: METHODS[name].solve(ctx) for name in names}


__all__ = ["METHODS", "solve_forces", "ForceContext", "ForceResult", "JointReaction",
           "Equation", "Step", "Term"]
