"""The public pipeline: spec -> model -> kinematics -> forces -> checks, in one call.

    from mechreport.analysis import analyse
    result = analyse("specs/slider_crank.yaml")
    result.forces["dyad"].reactions["B"].fx        # (n,) [N] over result.angles

Angles where the kinematics or any method's equations are singular are flagged and left out
of every result, so all arrays share one angle axis.
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .checks import (Agreement, ExpectationResult, Residual, agreement, check_expectations,
                     residuals)
from .forces import METHODS, ForceContext, ForceResult, solve_forces
from .kinematics import Flag, Kinematics, solve_kinematics
from .model import Mechanism, build_mechanism
from .spec import Spec, load_spec

DEFAULT_TOL = 1e-6


@dataclass(frozen=True)
class Analysis:
    """Everything known about one spec. ``forces`` by method name; ``flags`` the angles left
    out (kinematic or force singularities) with reasons."""

    spec: Spec
    mechanism: Mechanism
    kinematics: Kinematics
    context: ForceContext
    forces: dict[str, ForceResult]
    flags: tuple[Flag, ...]
    agreement: list[Agreement]
    residuals: list[Residual]
    expectations: list[ExpectationResult]
    tol: float = DEFAULT_TOL

    @property
    def angles(self) -> np.ndarray:
        return self.kinematics.angles

    @property
    def worst(self) -> Agreement | None:
        return self.agreement[0] if self.agreement else None

    @property
    def passed(self) -> bool:
        worst = self.worst
        return (all(e.ok for e in self.expectations)
                and (worst is None or worst.relative <= self.tol)
                and self.kinematics.n > 0)


def analyse(spec: Spec | str | Path, methods=None, tol: float = DEFAULT_TOL) -> Analysis:
    """Load (if given a path), solve every method and run the checks."""
    if not isinstance(spec, Spec):
        spec = load_spec(spec)
    mech = build_mechanism(spec)
    kin = solve_kinematics(mech)
    forces = solve_forces(kin, methods)
    singular = np.zeros(kin.n, bool)
    for res in forces.values():
        singular |= res.singular
    if singular.any():
        extra = []
        for k in np.flatnonzero(singular):
            which = [m for m, r in forces.items() if r.singular[k]]
            extra.append(Flag(float(kin.angles[k]),
                              f"force equations singular ({', '.join(which)})"))
        kin = kin.take(~singular, tuple(sorted(kin.flags + tuple(extra),
                                                key=lambda f: f.angle)))
        forces = solve_forces(kin, methods)
    ctx = ForceContext(kin)
    return Analysis(spec, mech, kin, ctx, forces, kin.flags, agreement(forces),
                    residuals(ctx, forces), check_expectations(kin, forces, kin.flags), tol)


__all__ = ["Analysis", "analyse", "METHODS", "DEFAULT_TOL"]
