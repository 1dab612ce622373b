"""An optimisation's candidates judged as a design reviewer would: feasible only when every
``design:`` verdict passes, every ``subject_to`` bound holds, the mechanism assembles on the
spec's own branch over the whole sweep, it leaves out no angle that the original analysis did
not, and its one method's numbers pass the study's trust test.

    problem = problem_of(base, original)        # the original's branches and left-out angles
    judged = judge_chunk(problem, start, values)  # (start, [Judged ...]) on a worker

An infeasible candidate is never dropped: it is scored by how far it violates (its
``violation``), so that the search can move toward the feasible region. The violation is the
sum of the relative shortfalls of the verdicts and bounds (``margin`` below zero), plus a
fixed amount per structural fault, larger for worse faults so that a candidate that at least
assembles beats one that does not:

=====================================================  =========================
fault                                                  violation added
=====================================================  =========================
cannot be built, assembled or analysed                 ``FAILED`` = 10 000
its one method cannot vouch for its numbers (trust)    ``UNTRUSTED`` = 1 000
a constraint's quantity is undefined                   ``UNTRUSTED`` = 1 000
the driver cannot make the whole sweep (it locks)      ``UNTRUSTED`` = 1 000
a dyad assembles on its other branch (or none chosen)  ``OTHER_BRANCH`` = 100
angles left out that the original analyses             1 + 10 x (their share of the sweep)
=====================================================  =========================

Values are in SI (quantities) and in the spec's own units (the varied keys).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np

from ..quantities import unit_of
from .evaluate import batch_results, reason_of, row_of
from .variants import BaseSpec

FAILED = 1e4
UNTRUSTED = 1e3
OTHER_BRANCH = 1e2


@dataclass(frozen=True)
class Constraint:
    """One constraint of the optimisation: a ``design:`` verdict (``kind`` "design",
    ``item`` its design key, ``limits.transmission_angle``) or a ``subject_to`` bound
    (``kind`` "bound", ``item`` its quantity, ``low``/``high`` [SI], ``scale`` [SI] the size
    its margin is relative to)."""

    kind: str
    item: str
    quantity: str
    low: float | None = None
    high: float | None = None
    scale: float = 1.0
    unit: str | None = None

    @property
    def written_unit(self) -> tuple[str, float]:
        """The unit the bound was written in (the quantity's SI unit if none) and its size
        [SI]."""
        from ..units import EXPECT_UNITS
        si = unit_of(self.quantity) or ""
        unit = self.unit or si
        return unit, EXPECT_UNITS.get(si, {}).get(unit, 1.0) if self.unit else 1.0

    def show(self, value: float) -> str:
        """``value`` [SI] in the bound's unit: ``59.07 deg``."""
        unit, f = self.written_unit
        return f"{value / f:.6g}{' ' + unit if unit else ''}"

    @property
    def name(self) -> str:
        """``design limits.transmission_angle`` or ``cycle.transmission_angle.min >= 40 deg``."""
        if self.kind == "design":
            return f"design {self.item}"
        unit, f = self.written_unit
        parts = []
        if self.low is not None:
            parts.append(f">= {self.low / f:.6g}")
        if self.high is not None:
            parts.append(f"<= {self.high / f:.6g}")
        return f"{self.quantity} {' and '.join(parts)}{' ' + unit if unit else ''}"

    def margin(self, value: float | None) -> float:
        """The bound's relative margin at ``value`` [SI] (>= 0: it holds); NaN when undefined."""
        if value is None or not math.isfinite(value):
            return math.nan
        m = math.inf
        if self.low is not None:
            m = min(m, (value - self.low) / self.scale)
        if self.high is not None:
            m = min(m, (self.high - value) / self.scale)
        return m


@dataclass(frozen=True)
class Problem:
    """What a worker needs to judge candidates: the ``base`` spec (its varied paths those of
    ``optimize.vary``), the ``method``, the ``objective`` and its sense, the quantities read
    (objective first, then the bounds'), the ``constraints`` (verdicts, then bounds), and the
    original's assembly ``branches`` ((dyad, sign) each), its ``left_out`` angles (rounded to
    1e-9) and its number of sweep angles ``n_angles``."""

    base: BaseSpec
    method: str
    objective: str
    maximize: bool
    quantities: tuple[str, ...]
    constraints: tuple[Constraint, ...]
    branches: tuple[tuple[str, int], ...]
    left_out: frozenset
    n_angles: int
    scale: float = 1.0

    @property
    def keys(self) -> tuple[str, ...]:
        return tuple(v.key for v in self.base.spec.optimize.vary)


@dataclass(frozen=True)
class Judged:
    """One candidate judged: ``objective`` [SI] (NaN when undefined), ``values`` the
    quantities read [SI], ``margins`` one per constraint (relative, >= 0 holds; NaN
    undefined), ``faults`` the structural reasons it is infeasible (text), ``violation``
    (0: feasible; see the module docstring)."""

    objective: float
    values: tuple[float, ...]
    margins: tuple[float, ...]
    faults: tuple[str, ...]
    violation: float

    @property
    def feasible(self) -> bool:
        return self.violation == 0.0 and not self.faults

    def missed(self, problem: Problem) -> list[str]:
        """What it misses, one line each: the faults, then each constraint not met."""
        out = list(self.faults)
        values = dict(zip(problem.quantities, self.values))
        for c, m in zip(problem.constraints, self.margins):
            if m >= 0:
                continue
            if math.isnan(m):
                out.append(f"{c.name}: undefined")
                continue
            got = ""
            if c.kind == "bound" and math.isfinite(values.get(c.quantity, math.nan)):
                got = f"{c.show(values[c.quantity])}, "
            out.append(f"{c.name}: {got}missed by {100 * -m:.3g} % of the "
                       + ("limit" if c.kind == "design" else "bound"))
        return out


def failed(problem: Problem, reason: str) -> Judged:
    n = len(problem.quantities)
    return Judged(math.nan, (math.nan,) * n, (math.nan,) * len(problem.constraints),
                  (reason,), FAILED)


def judge_chunk(problem: Problem, start: int, values: np.ndarray) -> tuple[int, list[Judged]]:
    """Candidates ``values`` (m, d) [spec units] analysed as one batch (the study's
    :func:`~mechreport.pipeline.batch.analyse_variants`, one method, the trust test on
    each); (start, one :class:`Judged` each). Never raises for a candidate's sake."""
    candidates = [{k: float(v) for k, v in zip(problem.keys, row)} for row in values]
    return start, batch_results(
        problem.base, candidates, problem.method,
        lambda outcome: judge_outcome(problem, outcome),
        lambda exc, _: failed(problem, reason_of(exc, problem.base.file)))


def judge_outcome(problem: Problem, outcome) -> Judged:
    """A batch :class:`~mechreport.pipeline.batch.Outcome` (or a full
    :class:`~mechreport.pipeline.Analysis`) judged (see the module docstring)."""
    if getattr(outcome, "exception", None) is not None:
        raise outcome.exception
    row = row_of(outcome, problem.quantities)
    if row.passed is None:                          # untrusted, or no cycle quantities
        n = len(problem.quantities)
        return Judged(math.nan, (math.nan,) * n, (math.nan,) * len(problem.constraints),
                      (row.reason,), UNTRUSTED)
    values = dict(zip(problem.quantities, row.values))
    verdicts = {v.item: v for v in outcome.verdicts}
    faults: list[str] = []
    violation = 0.0
    margins = []
    for c in problem.constraints:
        if c.kind == "design":
            v = verdicts.get(c.item)
            if v is None or v.margin is None:       # undefined (or vacuous: it passes)
                m = 0.0 if v is not None and v.passed else math.nan
            else:
                m = max(v.margin, 0.0) if v.passed else min(v.margin, -1e-15)
        else:
            m = c.margin(values.get(c.quantity))
        margins.append(m)
        if math.isnan(m):
            violation += UNTRUSTED
        elif m < 0:
            violation += min(-m, UNTRUSTED)
    kin = getattr(outcome, "kinematics", None)
    branches = kin.branches if kin is not None else getattr(outcome, "branches", ())
    if getattr(outcome, "streamed", None) is None or branches:
        mine = {b.dyad: b for b in branches}
        for dyad, sign in problem.branches:
            b = mine.get(dyad)
            if b is None or b.sign != sign or not b.closes or b.rule.startswith("undecided"):
                faults.append(f"dyad {dyad} does not stay on the spec's assembly branch "
                              "over the whole sweep")
                violation += OTHER_BRANCH
    if kin is not None:
        from ..pipeline.batch import locked_text
        locked = locked_text(kin)
    else:
        locked = getattr(outcome, "locked", "")
    if locked:                  # infeasible however the original fares: it must turn
        faults.append(locked)
        violation += UNTRUSTED
    left = (tuple(f.angle for f in kin.flags) if kin is not None
            else getattr(outcome, "left_out", ()))
    extra = sorted(a for a in left if round(float(a), 9) not in problem.left_out)
    if extra:
        shown = ", ".join(f"{a:g}" for a in extra[:4]) + (" ..." if len(extra) > 4 else "")
        faults.append(f"leaves out {len(extra)} angle(s) that the original analyses "
                      f"({shown})")
        violation += 1.0 + 10.0 * len(extra) / max(problem.n_angles, 1)
    objective = values[problem.objective]
    if not math.isfinite(objective):
        violation += UNTRUSTED
        faults.append(f"{problem.objective} is undefined")
    return Judged(objective, tuple(row.values), tuple(margins), tuple(faults), violation)


def score(problem: Problem, judged: Judged) -> float:
    """The number the search minimises: in (-1, 1) for a feasible candidate, increasing with
    the objective (decreasing for ``maximize``) scaled by the original's; 1 + violation for
    an infeasible one (always worse than any feasible candidate)."""
    if not judged.feasible:
        return 1.0 + judged.violation
    t = (-1.0 if problem.maximize else 1.0) * judged.objective / problem.scale
    return t / (1.0 + abs(t))
