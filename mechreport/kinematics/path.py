"""The path the driver takes through the analysed crank angles, from the assembled position.

Branches are tracked, and reachability judged, along *runs*: sequences of tracking-grid angles
that start at the first reference angle and move away from it, one forward (the sense of
rotation) and one backward. A run stops where the mechanism cannot close: the driver locks
there, and nothing beyond is reachable without taking the mechanism apart.

The tracking grid is the sweep (uniform) plus the first reference angle, plus fill points at
the sweep step (at most 1 deg) wherever analysed angles lie outside a sweep that is not a
whole turn, so the path from the assembly to every analysed angle is sampled. Other analysed
angles (further ``at`` and ``expect`` angles) are *off the grid*: they never steer the
tracking (a sample 1e-7 deg from a touch point would), and take the candidate nearest the
tracked branch interpolated from their grid neighbours (``off_grid_neighbours``).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..spec import Spec

FILL_MAX = 20000   # fill points at most; their spacing grows beyond that


@dataclass(frozen=True)
class SweepPath:
    """``angles`` (N,) every angle solved [deg]; ``analysed`` (n,) indices of the analysed
    angles into ``angles``; ``on_grid`` (N,) bool; ``runs`` forward and backward sequences of
    grid indices starting at ``ref`` (index of the first reference angle); ``travel`` the angle
    travelled along each run [deg], from 0, increasing; ``periodic`` for whole-turn sweeps."""

    angles: np.ndarray
    analysed: np.ndarray
    on_grid: np.ndarray
    runs: tuple[np.ndarray, np.ndarray]
    travel: tuple[np.ndarray, np.ndarray]
    ref: int
    periodic: bool

    def wrapped(self, a: np.ndarray) -> np.ndarray:
        """Angles [deg] mapped into the grid's turn (periodic) or left as they are."""
        if not self.periodic:
            return np.asarray(a, float)
        start = float(np.min(self.angles[self.on_grid]))
        return start + np.mod(np.asarray(a, float) - start, 360.0)

    def off_grid_neighbours(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """For every off-grid angle: its index, the grid indices just below and above it (by
        angle, wrapping for whole turns) and the interpolation weight of the upper one."""
        off = np.flatnonzero(~self.on_grid)
        if not off.size:
            return off, off, off, np.zeros(0)
        grid = np.flatnonzero(self.on_grid)
        ga = self.wrapped(self.angles[grid])
        order = np.argsort(ga)
        grid, ga = grid[order], ga[order]
        x = self.wrapped(self.angles[off])
        if self.periodic:   # the interval from the last grid angle to the first one + 360
            grid = np.concatenate([grid, grid[:1]])
            ga = np.concatenate([ga, ga[:1] + 360.0])
        hi = np.clip(np.searchsorted(ga, x), 1, len(ga) - 1)
        lo = hi - 1
        span = ga[hi] - ga[lo]
        w = np.clip((x - ga[lo]) / np.where(span > 0, span, 1.0), 0.0, 1.0)
        return off, grid[lo], grid[hi], w


def sweep_path(spec: Spec, analysed: np.ndarray, ref_angle: float) -> SweepPath:
    """The tracking grid and runs for the ``analysed`` angles [deg] (sorted, unique)."""
    analysed = np.asarray(analysed, float)
    grid = np.round(spec.sweep.angles(), 9)
    periodic = spec.sweep.whole_turn
    ref_angle = round(float(ref_angle), 9)
    if periodic:   # the reference angle's place in the grid's turn
        start = float(grid[0])
        ref_angle = round(start + (ref_angle - start) % 360.0, 9)
    else:
        lo = min(float(analysed.min()), float(grid[0]))
        hi = max(float(analysed.max()), float(grid[-1]))
        step = max(min(spec.sweep.step, 1.0), (hi - lo) / FILL_MAX)
        below = grid[0] - step * np.arange(1, int(np.ceil((grid[0] - lo) / step - 1e-9)) + 1)
        above = grid[-1] + step * np.arange(1, int(np.ceil((hi - grid[-1]) / step - 1e-9)) + 1)
        grid = np.union1d(grid, np.round(np.concatenate([below, above]), 9))
    grid = np.union1d(grid, [ref_angle])
    angles = np.union1d(np.round(analysed, 9), grid)
    on_grid = np.isin(angles, grid)
    ref = int(np.searchsorted(angles, ref_angle))
    analysed_idx = np.searchsorted(angles, np.round(analysed, 9))
    g = np.flatnonzero(on_grid)
    if periodic:
        a = angles[g]
        fwd_key = np.mod(a - angles[ref], 360.0)
        fwd = g[np.argsort(fwd_key, kind="stable")]
        back = np.concatenate([fwd[:1], fwd[1:][::-1]])
        fwd_t = np.mod(angles[fwd] - angles[ref], 360.0)
        back_t = np.mod(angles[ref] - angles[back], 360.0)
    else:
        pos = int(np.searchsorted(g, ref))
        fwd, back = g[pos:], g[:pos + 1][::-1]
        fwd_t, back_t = angles[fwd] - angles[ref], angles[ref] - angles[back]
    if spec.driver.omega < 0:   # the driver turns clockwise: "forward" is decreasing angle
        fwd, back, fwd_t, back_t = back, fwd, back_t, fwd_t
    return SweepPath(angles, analysed_idx, on_grid, (fwd, back), (fwd_t, back_t), ref, periodic)
