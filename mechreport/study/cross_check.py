"""``--cross-check N``: re-run N variants of a study, drawn at random (seeded by the study's
seed), with every force method, and fail on any disagreement.

For each drawn variant:

- the methods must agree with each other over the sweep, as ``mechreport check`` requires
  (worst relative difference at most the tolerance, 1e-6);
- each kept quantity computed from each method that can give it must equal the study's value
  (computed with the study's one method) to the tolerance, relative to the larger of the two
  values and of the largest kept value with the same unit in that row (so a mean torque near
  zero is compared on the scale of the torques);
- a variant the study could not analyse must fail with every method too, and the other way
  round.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..pipeline import DEFAULT_TOL
from ..quantities import unit_of
from .evaluate import reason_of, row_of
from .methods import cannot_serve
from .table import Table
from .variants import BaseSpec, variant_spec


@dataclass(frozen=True)
class CrossRow:
    """One re-run variant (``index`` 0-based): ``ok`` when everything agreed; ``worst`` the
    largest relative difference found; ``where`` what it was (or why it disagreed)."""

    index: int
    ok: bool
    worst: float | None
    where: str


@dataclass(frozen=True)
class CrossCheck:
    rows: list[CrossRow]
    method: str
    tol: float = DEFAULT_TOL

    @property
    def ok(self) -> bool:
        return all(r.ok for r in self.rows)

    def summary(self) -> str:
        n = len(self.rows)
        bad = [r for r in self.rows if not r.ok]
        worst = max((r.worst for r in self.rows if r.worst is not None), default=None)
        head = (f"{n} variant(s) drawn at random re-run with every force method and compared "
                f"with the study's {self.method} values (tolerance {self.tol:g} relative): ")
        if bad:
            return head + (f"{len(bad)} DISAGREE (variant(s) "
                           f"{', '.join(str(r.index + 1) for r in bad[:10])}).")
        more = f"; worst relative difference {worst:.1e}" if worst is not None else ""
        return head + f"all agree{more}."


def pick(n_variants: int, count: int, seed: int) -> np.ndarray:
    """``count`` distinct variant indices drawn with the study's ``seed`` (sorted)."""
    rng = np.random.default_rng([int(seed), 0x63636B])      # its own stream: "cck"
    count = min(int(count), n_variants)
    return np.sort(rng.choice(n_variants, size=count, replace=False))


def cross_check(base: BaseSpec, table: Table, count: int, seed: int,
                tol: float = DEFAULT_TOL, progress=None, skip=()) -> CrossCheck:
    """Re-run ``count`` variants of ``table`` with every method (see the module docstring).
    ``progress(i, n)`` is called after each variant; ``skip``: indices of variants the study
    never computed (a lost worker): they are not drawn, having nothing to compare."""
    skip = set(int(i) for i in skip)
    keep = np.array([i for i in range(table.n) if i not in skip], int)
    picked = keep[pick(len(keep), count, seed)] if len(keep) else keep
    rows = []
    for k, i in enumerate(picked, 1):
        rows.append(check_one(base, table, int(i), tol))
        if progress is not None:
            progress(k, len(picked))
    return CrossCheck(rows, table.method, tol)


def check_one(base: BaseSpec, table: Table, i: int, tol: float = DEFAULT_TOL) -> CrossRow:
    from ..pipeline import analyse
    from ..post import design_review
    mine = table.row(i)
    try:
        spec = variant_spec(base, table.plan.variant(i))
        a = analyse(spec)
    except Exception as exc:  # noqa: BLE001 - compared with the study's outcome
        why = reason_of(exc, base.file)
        if mine.passed is None and not mine.ok:
            return CrossRow(i, True, None, f"fails with every method too: {why}")
        return CrossRow(i, False, None, f"the study analysed it, every method fails: {why}")
    if a.review is None:
        ok = mine.passed is None and not mine.ok
        return CrossRow(i, ok, None, ("no cycle quantities with every method too"
                                      if ok else "the study has cycle quantities, every "
                                      f"method has none: {a.review_problem}"))
    if mine.passed is None:
        if a.worst is not None and a.worst.relative > tol:    # the study's trust test held
            return CrossRow(i, True, a.worst.relative,
                            f"the study failed it ({mine.reason}); the methods disagree by "
                            f"{a.worst.relative:.1e} too")
        return CrossRow(i, False, None, f"the study failed it ({mine.reason}), every method "
                                        "analyses it")
    worst, where = 0.0, "methods agree"
    if a.worst is not None:
        worst = a.worst.relative
        where = (f"{a.worst.quantity}, {a.worst.methods[0]} vs {a.worst.methods[1]} at "
                 f"{a.worst.angle:g} deg")
    keep = table.keep
    mine_vals = np.asarray(mine.values, float)
    floors = {}
    for q, v in zip(keep, mine_vals):
        if math.isfinite(v):
            u = unit_of(q)
            floors[u] = max(floors.get(u, 0.0), abs(v))
    for method, res in a.forces.items():
        if cannot_serve(method, keep, spec.design) is not None:
            continue
        review, why = design_review(a.kinematics, {method: res}, a.loads)
        if review is None:
            return CrossRow(i, False, None, f"{method}: no cycle quantities ({why})")
        values = review.values
        for q, v in zip(keep, mine_vals):
            other = values.get(q)
            if other is None or not math.isfinite(v):
                if (other is None) != (not math.isfinite(v)):
                    return CrossRow(i, False, None, f"{q}: defined by only one of the study "
                                                    f"and {method}")
                continue
            scale = max(abs(v), abs(other), floors.get(unit_of(q), 0.0))
            rel = abs(other - v) / scale if scale > 0 else 0.0
            if rel > worst:
                worst, where = rel, f"{q}: study {v:.10g}, {method} {other:.10g}"
    row = row_of(a, keep)
    if row.passed != mine.passed:
        return CrossRow(i, False, worst, "design review: the study says "
                        f"{'pass' if mine.passed else 'fail'}, every method says "
                        f"{'pass' if row.passed else 'fail'}")
    return CrossRow(i, worst <= tol, worst, where)
