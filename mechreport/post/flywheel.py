"""The flywheel problem as the textbooks work it: the turning-moment diagram's areas between
its crossings with the mean torque, the energy level after each, and the largest energy
fluctuation between the highest and the lowest level (the kinetic energy the flywheel must
take up), from which I = dE / (Cs omega^2)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class EnergyArea:
    """One area of the turning-moment diagram between two crossings with the mean: from
    ``start`` to ``end`` [deg] (``end`` beyond the cycle for the area that spans its end),
    its ``energy`` the integral of (torque - mean) over it [J] (positive: the machine takes
    more than the mean torque gives), ``level`` the energy taken in excess after it, from
    the first crossing [J]."""

    start: float
    end: float
    energy: float
    level: float


def energy_areas(angles: np.ndarray, torque: np.ndarray, mean: float, period: float
                 ) -> list[EnergyArea]:
    """The areas of the diagram of ``torque`` [N m] at the equally spaced crank ``angles``
    [deg] of one cycle (``period`` [deg], the closing interval included) against ``mean``
    [N m], in crank order from the first crossing: trapezoids on the grid, the crossings
    interpolated linearly between grid angles; their energies sum to zero (over a cycle) to
    round-off. One area (the whole cycle) without a crossing."""
    a = np.append(np.asarray(angles, float), float(angles[0]) + period)
    y = np.append(np.asarray(torque, float), float(torque[0])) - mean
    n = len(a) - 1
    ks = np.flatnonzero((y[:-1] == 0) | (y[:-1] * y[1:] < 0))     # the grid steps crossed
    with np.errstate(divide="ignore", invalid="ignore"):          # y == 0 there: exact
        at = np.where(y[ks] == 0, a[ks],
                      a[ks] - y[ks] * (a[ks + 1] - a[ks]) / (y[ks + 1] - y[ks]))
    cuts = [(int(k), float(x)) for k, x in zip(ks, at)]
    if not cuts:
        energy = float(np.sum(0.5 * (y[1:] + y[:-1]) * np.radians(np.diff(a))))
        return [EnergyArea(float(a[0]), float(a[-1]), energy, energy)]
    out, level = [], 0.0
    for (k0, x0), (k1, x1) in zip(cuts, cuts[1:] + [(cuts[0][0] + n, cuts[0][1] + period)]):
        idx = np.arange(k0 + 1, k1 + 1)
        xs = np.concatenate([[x0], a[idx % n] + period * (idx // n), [x1]])
        ys = np.concatenate([[0.0], y[idx % n], [0.0]])
        energy = float(np.sum(0.5 * (ys[1:] + ys[:-1]) * np.radians(np.diff(xs))))
        level += energy
        out.append(EnergyArea(x0, x1, energy, level))
    return out


def largest_fluctuation(areas: list[EnergyArea]) -> tuple[float, EnergyArea | None,
                                                           EnergyArea | None]:
    """(the largest energy fluctuation [J]: the highest level minus the lowest, the first
    crossing's level 0 among them; the areas after which the level is highest and lowest,
    None for the first crossing)."""
    levels = [(0.0, None)] + [(x.level, x) for x in areas]
    top = max(levels, key=lambda t: t[0])
    low = min(levels, key=lambda t: t[0])
    return top[0] - low[0], top[1], low[1]


__all__ = ["EnergyArea", "energy_areas", "largest_fluctuation"]
