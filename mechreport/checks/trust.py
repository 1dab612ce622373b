"""What one method's numbers can say about their own trust, where no second method is
there to compare with (a study's variants are solved by one method).

A solve's rounding error at an angle is bounded by about eps x cond x the largest term of
its equations: the product of its systems' condition numbers (``ForceResult.cond``) times
the largest of the unknowns it solved and of the inputs it was given (each load, m a_C,
m g, I alpha), forces and moments each with their own size, a moment's lever arm being at
most the mechanism's size. A kind of quantity (forces, moments) is trustworthy to ``tol``
when that bound is within ``tol`` of its largest magnitude over the sweep, the scale the
reports' round-off rule uses. A driver torque that is the small difference of huge terms
(a 1e17 kg crank under 1e-20 gravity: 24 N·m out of 1e17 N·m terms; two 1e16 N loads that
cancel) fails it, as the methods' disagreement fails `check`.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..forces import ForceResult
from ..kinematics import EPS


@dataclass(frozen=True)
class Inputs:
    """The largest input of each kind at each angle (n,): ``force`` [N] (a load, m a_C,
    m g), ``moment`` [N m] (a moment load, I alpha), and the mechanism's ``length`` [m]
    (the span of its joints: a moment's lever arm is at most about this)."""

    force: np.ndarray
    moment: np.ndarray
    length: np.ndarray

    def take(self, rows) -> "Inputs":
        return Inputs(self.force[rows], self.moment[rows], self.length[rows])


def inputs_of(ctx) -> Inputs:
    """The :class:`Inputs` of a ForceContext (a stacked batch's included: its masses and
    inertias may be arrays over the rows)."""
    n = ctx.n
    force, moment = np.zeros(n), np.zeros(n)
    g = float(np.hypot(*ctx.gravity))
    for s in ctx.links.values():
        mass = np.abs(np.broadcast_to(np.asarray(s.mass, float), (n,)))
        inertia = np.abs(np.broadcast_to(np.asarray(s.inertia, float), (n,)))
        force = np.maximum(force, mass * np.maximum(np.hypot(s.a[:, 0], s.a[:, 1]), g))
        moment = np.maximum(moment, inertia * np.abs(s.alpha))
    for ld in ctx.loads:
        if ld.force is not None:
            force = np.maximum(force, np.hypot(ld.force[:, 0], ld.force[:, 1]))
        else:
            moment = np.maximum(moment, np.abs(ld.moment))
    points = np.stack(list(ctx.joint_points.values()))              # (J, n, 2)
    span = points.max(axis=0) - points.min(axis=0)                  # (n, 2)
    return Inputs(force, moment, np.maximum(np.hypot(span[:, 0], span[:, 1]), 1e-300))


@dataclass(frozen=True)
class Bound:
    """For one kind of quantity: the largest rounding bound over the angles, where it is
    (``angle``), and the kind's largest magnitude (``scale``): mergeable over the chunks of
    a long sweep."""

    bound: float
    angle: float
    scale: float

    def merged(self, other: "Bound") -> "Bound":
        top = self if self.bound >= other.bound else other
        return Bound(top.bound, top.angle, max(self.scale, other.scale))


def bounds(res: ForceResult, inputs: Inputs | None = None) -> dict[str, Bound]:
    """The :class:`Bound` of each kind (``force``, ``moment``) in ``res``."""
    values = res.values()
    n = len(res.angles)
    if not values or not n:
        return {}
    kinds = {"force": [q for q in values if _is_force(q, res)],
             "moment": [q for q in values if not _is_force(q, res)]}
    zero = np.zeros(n)

    def largest(names):
        return np.max(np.abs(np.array([values[q] for q in names])), axis=0) if names else zero
    xf, xm = largest(kinds["force"]), largest(kinds["moment"])
    if inputs is not None:
        fin, min_, length = inputs.force, inputs.moment, inputs.length
    else:
        fin, min_, length = zero, zero, np.ones(n)
    cond = res.cond if res.cond is not None else np.ones(n)
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        terms = {"force": np.maximum.reduce([xf, fin, (xm + min_) / length]),
                 "moment": np.maximum.reduce([xm, min_, length * np.maximum(xf, fin)])}
        largest_of = {"force": xf, "moment": xm}
        out = {}
        for kind, names in kinds.items():
            if not names:
                continue
            bound = EPS * cond * terms[kind]
            k = int(np.argmax(np.where(np.isnan(bound), np.inf, bound)))
            out[kind] = Bound(float(bound[k]), float(res.angles[k]),
                              float(np.max(largest_of[kind])))
    return out


def judged(found: dict[str, Bound], tol: float, method: str, axis_unit: str = "deg") -> str:
    """Why the ``found`` bounds of ``method`` fail ``tol`` ("" when they do not)."""
    for kind, b in found.items():
        if not (b.bound <= tol * b.scale):
            unit = "N" if kind == "force" else "N·m"
            return (f"the {kind}s cannot be trusted to {tol:g}: rounding in the {method} "
                    f"equations could reach {b.bound:.1e} {unit} at {b.angle:g} {axis_unit}, "
                    f"against {b.scale:.1e} {unit} at most over the sweep (terms far larger "
                    "than their sum)")
    return ""


def untrusted(res: ForceResult, tol: float, axis_unit: str = "deg",
              inputs: Inputs | None = None) -> str:
    """Why ``res``'s numbers cannot be trusted to ``tol`` ("" when they can): the kind of
    quantity whose error bound exceeds ``tol`` of its scale, by how much, and where (at an
    angle in ``axis_unit``: deg, or a stroke's length unit). ``inputs``: the loads and
    inertia terms its equations were given (:func:`inputs_of`); without them only the
    unknowns bound the terms."""
    return judged(bounds(res, inputs), tol, res.method, axis_unit)


def _is_force(quantity: str, res: ForceResult) -> bool:
    if quantity == res.driver_quantity:
        return quantity == "driver.force"
    return not quantity.endswith(".moment")
