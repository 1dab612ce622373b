"""One cycle of the crank on the sweep's grid, with left-out angles filled in.

A cycle is one turn, or the spec's ``cycle`` when it is longer (a four-stroke engine's 720
crank degrees: its loads repeat every two turns, and every cycle quantity is taken over the
whole cycle). Cycle quantities (integrals, means, extremes over a cycle) need every angle of
the cycle. They
use the sweep's own grid (``at`` angles off it are not part of the cycle); angles left out of
the results (singular, near-singular) are filled by periodic linear interpolation of their
neighbours, and ``interpolated`` says which. Means and integrals are periodic trapezoids (the
closing interval included); on a uniform grid the mean is the plain average.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import MechreportError
from ..spec import Spec


class CycleUndefined(MechreportError):
    """A cycle quantity was asked for where there is no whole turn of an R driver."""


@dataclass(frozen=True)
class Cycle:
    """``angles`` (N,) the sweep grid over one cycle [deg]; ``rows`` (N,) the row of each in
    the analysed results (-1 where left out); ``interpolated`` (K,) the grid angles filled in
    [deg]; ``omega`` the driver speed [rad/s]; ``period`` the cycle [deg] (360: one turn)."""

    angles: np.ndarray
    rows: np.ndarray
    interpolated: np.ndarray
    omega: float
    period: float = 360.0

    @property
    def step(self) -> float:
        """Grid spacing [rad]."""
        return float(np.radians(self.period / len(self.angles)))

    @property
    def turns(self) -> float:
        """Crank turns per cycle (2 for a four-stroke engine's 720 degrees)."""
        return self.period / 360.0

    def sample(self, values: np.ndarray, analysed: np.ndarray) -> np.ndarray:
        """``values`` (n, ...) over the analysed angles -> (N, ...) over the cycle grid, left-out
        angles interpolated periodically from their analysed neighbours."""
        values = np.asarray(values, float)
        if not len(self.interpolated) and len(values) == len(self.rows):
            return values        # the analysed angles are the grid's (rows 0, 1, ...)
        out = np.empty((len(self.angles),) + values.shape[1:])
        have = self.rows >= 0
        out[have] = values[self.rows[have]]
        if (~have).any():
            x = self.angles[have]
            flat = out[have].reshape(have.sum(), -1)
            filled = np.stack([np.interp(self.angles[~have], x, flat[:, c],
                                         period=self.period)
                               for c in range(flat.shape[1])], axis=1)
            out[~have] = filled.reshape((-1,) + values.shape[1:])
        return out

    def mean(self, values: np.ndarray) -> float:
        return float(np.mean(np.asarray(values, float)))

    def rms(self, values: np.ndarray) -> float:
        return math.sqrt(float(np.mean(np.asarray(values, float) ** 2)))

    def integral(self, values: np.ndarray) -> np.ndarray:
        """Running integral over the crank angle [value x rad] at each grid angle, from 0 at
        the first (trapezoids; the closing interval back to the start is not included)."""
        v = np.asarray(values, float)
        out = np.empty(len(v))
        out[0] = 0.0
        np.cumsum(np.add(v[1:], v[:-1]), out=out[1:])
        out *= 0.5             # halving is exact: the trapezoids' sum as (a + b) / 2 each
        out *= self.step
        return out


def cycle_of(spec: Spec, analysed_angles: np.ndarray, reachable: bool = True,
             turn_problem: str = "", jam: str = "") -> Cycle:
    """The cycle grid of ``spec`` and where each of its angles sits among ``analysed_angles``.
    Raises ``CycleUndefined`` when the sweep is not one whole turn of a crank, when the
    crank cannot make a full turn (``reachable`` False), when the motion does not repeat
    every turn (``turn_problem`` says why), or when friction jams the mechanism over part of
    the turn (``jam`` says where: a cycle it cannot complete has no cycle quantities, and
    values interpolated across the jam would be invented)."""
    why = spec.cycle_problem()
    if why is None and not reachable:
        why = "cycle quantities need a crank that makes a full turn; this one locks"
    if why is None and turn_problem:
        why = f"cycle quantities need a motion that repeats every turn; {turn_problem}"
    if why is None and jam:
        why = f"cycle quantities need a mechanism that can be driven through its cycle; {jam}"
    if why is not None:
        raise CycleUndefined(f"{spec.file}: {why}")
    grid = np.round(spec.sweep.angles(), 9)
    have = np.round(np.asarray(analysed_angles, float), 9)
    pos = np.clip(np.searchsorted(have, grid), 0, max(len(have) - 1, 0))
    hit = np.abs(have[pos] - grid) < 1e-9 if len(have) else np.zeros(len(grid), bool)
    if not hit.any():
        raise CycleUndefined(f"{spec.file}: no angle of the cycle could be analysed")
    rows = np.where(hit, pos, -1)
    return Cycle(grid, rows, grid[~hit], spec.driver.omega, spec.sweep.cycle)
