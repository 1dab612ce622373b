"""What one method's numbers can say about their own trust, where no second method is
there to compare with (a study's variants are solved by one method).

The solve's rounding error at an angle is bounded by about eps x cond x |x|max: the
product of its systems' condition numbers (``ForceResult.cond``) times the largest unknown
it solved there. A quantity is trustworthy to ``tol`` when that bound is within ``tol`` of
the largest magnitude of its kind over the sweep (forces against the largest force,
torques and couples against the largest moment), the scale the reports' round-off rule
uses. A driver torque that is the small difference of huge terms (a 1e17 kg crank under
1e-20 gravity: 5 N m out of 1e17 N m terms) fails it, as the methods' disagreement fails
`check`.
"""
from __future__ import annotations

import numpy as np

from ..forces import ForceResult
from ..kinematics import EPS


def untrusted(res: ForceResult, tol: float, axis_unit: str = "deg") -> str:
    """Why ``res``'s numbers cannot be trusted to ``tol`` ("" when they can): the kind of
    quantity whose error bound exceeds ``tol`` of its scale, by how much, and where (at an
    angle in ``axis_unit``: deg, or a stroke's length unit)."""
    values = res.values()
    if not values or not len(res.angles):
        return ""
    stacked = np.abs(np.array(list(values.values())))          # (q, n)
    cond = res.cond if res.cond is not None else np.ones(len(res.angles))
    with np.errstate(over="ignore", invalid="ignore"):
        bound = EPS * cond * stacked.max(axis=0)                # (n,)
    kinds = {"force": [q for q in values if _is_force(q, res)],
             "moment": [q for q in values if not _is_force(q, res)]}
    for kind, names in kinds.items():
        if not names:
            continue
        scale = max(float(np.max(np.abs(values[q]))) for q in names)
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            ratio = bound / scale if scale > 0 else np.where(bound > 0, np.inf, 0.0)
        k = int(np.argmax(ratio))
        if not ratio[k] <= tol:
            unit = "N" if kind == "force" else "N·m"
            return (f"the {kind}s cannot be trusted to {tol:g}: rounding in the {res.method} "
                    f"equations could reach {bound[k]:.1e} {unit} at {res.angles[k]:g} {axis_unit}, "
                    f"against {scale:.1e} {unit} at most over the sweep (terms far larger "
                    "than their sum)")
    return ""


def _is_force(quantity: str, res: ForceResult) -> bool:
    if quantity == res.driver_quantity:
        return quantity == "driver.force"
    return not quantity.endswith(".moment")
