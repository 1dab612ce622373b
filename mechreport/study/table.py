"""The study table: one row per variant, filled chunk by chunk as results arrive (arrays, not
per-variant objects, so 100 000 variants stay a few tens of MB), and what is read from it:
column names, the ranking of variants, the Pareto front.

Columns (study.parquet and study.csv):

- ``variant``: 1, 2, ... in plan order;
- one per varied key, named by the key as written (``links.coupler.points.C.0``), in the
  spec's own units;
- one per kept quantity, ``<quantity> [<SI unit>]`` (``cycle.torque.rms [N·m]``);
- ``design_pass``: every item of the spec's ``design`` passed (true when it has none; empty
  when the variant failed), ``design_failed``: the items that did not (``; ``-separated);
- ``status``: ``ok`` or ``failed``; ``reason``: why it failed, or why a kept quantity is
  undefined.

**Better.** Larger is better for ``cycle.transmission_angle.min`` and bearing lives
(``joint.J.life_h``); for every other quantity a smaller magnitude is better (peak and RMS
torque, bearing loads, flywheel inertia, shaking ...).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..quantities import unit_of
from ..units import with_unit
from .evaluate import Row
from .plan import Plan

#: quantities where more is better (see the module docstring)
LARGER_IS_BETTER = ("cycle.transmission_angle.min",)


def larger_is_better(quantity: str) -> bool:
    return quantity in LARGER_IS_BETTER or quantity.endswith(".life_h")


def quantity_unit(quantity: str) -> str:
    """The quantity's SI unit as every output spells it (``N·m``); "" when it has none."""
    return unit_of(quantity) or ""


def column_name(quantity: str) -> str:
    """``cycle.torque.rms [N·m]``: the quantity and its SI unit (as results.csv)."""
    return with_unit(quantity, quantity_unit(quantity))


def badness(quantity: str, values: np.ndarray) -> np.ndarray:
    """``values`` mapped so that smaller is better (NaN stays NaN)."""
    values = np.asarray(values, float)
    return -values if larger_is_better(quantity) else np.abs(values)


@dataclass
class Table:
    """Results of every variant of ``plan``: ``values`` (n, len(keep)) [SI], ``passed``
    (n,) 1 pass / 0 fail / -1 none (failed variant), ``failed`` and ``reason`` texts per
    variant, ``done`` (n,) whether the row has arrived."""

    plan: Plan
    keep: tuple[str, ...]
    method: str
    values: np.ndarray = field(init=False)
    passed: np.ndarray = field(init=False)
    failed: list[str] = field(init=False)
    reason: list[str] = field(init=False)
    done: np.ndarray = field(init=False)

    def __post_init__(self):
        n = self.plan.n
        self.values = np.full((n, len(self.keep)), math.nan)
        self.passed = np.full(n, -1, np.int8)
        self.failed = [""] * n
        self.reason = [""] * n
        self.done = np.zeros(n, bool)

    @property
    def n(self) -> int:
        return self.plan.n

    def put(self, start: int, rows: list[Row]) -> int:
        """Store ``rows`` as variants ``start``, ``start + 1`` ...; returns how many failed."""
        bad = 0
        for i, row in enumerate(rows, start):
            self.values[i] = row.values
            self.passed[i] = -1 if row.passed is None else int(bool(row.passed))
            self.failed[i] = "; ".join(row.failed)
            self.reason[i] = row.reason
            self.done[i] = True
            bad += bool(row.reason)
        return bad

    def row(self, i: int) -> Row:
        """Variant ``i``'s row back as a :class:`Row`."""
        p = int(self.passed[i])
        return Row(tuple(float(v) for v in self.values[i]), None if p < 0 else bool(p),
                   tuple(x for x in self.failed[i].split("; ") if x), self.reason[i])

    # ----------------------------------------------------------------------- reading

    @property
    def ok(self) -> np.ndarray:
        """(n,) the variant finished with every kept quantity defined."""
        return np.array([not r for r in self.reason], bool) & self.done

    @property
    def passing(self) -> np.ndarray:
        """(n,) complete rows whose design review passed."""
        return self.ok & (self.passed == 1)

    def ranked(self, among: np.ndarray | None = None) -> np.ndarray:
        """Indices of the rows ``among`` (default: passing), best first: by the first kept
        quantity, ties by the next ones (see "Better" in the module docstring)."""
        among = self.passing if among is None else among
        idx = np.flatnonzero(among)
        if not len(idx):
            return idx
        keys = [badness(q, self.values[idx, j]) for j, q in enumerate(self.keep)]
        order = np.lexsort(keys[::-1])                  # lexsort: last key is primary
        return idx[order]

    def pareto(self, among: np.ndarray | None = None) -> np.ndarray:
        """Indices of the Pareto front of the first two kept quantities among the rows
        ``among`` (default: passing), sorted by the first; empty with fewer than two kept."""
        if len(self.keep) < 2:
            return np.zeros(0, int)
        among = self.passing if among is None else among
        idx = np.flatnonzero(among)
        a = badness(self.keep[0], self.values[idx, 0])
        b = badness(self.keep[1], self.values[idx, 1])
        order = np.lexsort((b, a))
        front, best = [], math.inf
        for k in order:
            if b[k] < best:
                front.append(idx[k])
                best = b[k]
        return np.asarray(front, int)

    # ------------------------------------------------------------------------ columns

    def columns(self) -> dict[str, object]:
        """Column name -> values (numpy arrays or lists), in file order."""
        cols: dict[str, object] = {"variant": np.arange(1, self.n + 1)}
        for j, key in enumerate(self.plan.keys):
            cols[key] = self.plan.values[:, j]
        for j, q in enumerate(self.keep):
            cols[column_name(q)] = self.values[:, j]
        cols["design_pass"] = self.passed
        cols["design_failed"] = self.failed
        cols["status"] = ["ok" if not r else "failed" for r in self.reason]
        cols["reason"] = self.reason
        return cols
