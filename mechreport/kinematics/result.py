"""The kinematics result: link-frame states over the analysed crank angles."""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..model import Mechanism
from ..spec import GROUND
from .frames import perp, rotate
from .position import BranchChoice


@dataclass(frozen=True)
class Flag:
    """A crank angle left out of the results, and why."""

    angle: float   # [deg]
    reason: str


@dataclass(frozen=True)
class PointState:
    """Global position [m], velocity [m/s], acceleration [m/s^2] of a point, each (n, 2)."""

    r: np.ndarray
    v: np.ndarray
    a: np.ndarray


@dataclass(frozen=True)
class Kinematics:
    """Positions, velocities and accelerations over the analysed angles that could be solved.

    Arrays are indexed ``[angle, link]`` with the link axis in link-number order (0 = ground):
    ``r`` (n, L+1, 2) origin of each link frame [m], ``theta`` (n, L+1) [rad], ``v`` [m/s],
    ``omega`` [rad/s], ``a`` [m/s^2], ``alpha`` [rad/s^2]. ``angles`` (n,) are crank angles
    [deg]; ``flags`` lists the angles left out (cannot close, or singular).
    """

    mechanism: Mechanism
    angles: np.ndarray
    r: np.ndarray
    theta: np.ndarray
    v: np.ndarray
    omega: np.ndarray
    a: np.ndarray
    alpha: np.ndarray
    flags: tuple[Flag, ...]
    branches: tuple[BranchChoice, ...]

    @property
    def n(self) -> int:
        return len(self.angles)

    def index(self, link: str) -> int:
        return self.mechanism.spec.number(link)

    def point(self, link: str, local) -> PointState:
        """State of the point at ``local`` [m] in ``link``'s frame."""
        k = self.index(link)
        s = rotate(local, self.theta[:, k])
        w, al = self.omega[:, k][:, None], self.alpha[:, k][:, None]
        return PointState(self.r[:, k] + s,
                          self.v[:, k] + w * perp(s),
                          self.a[:, k] + al * perp(s) - w**2 * s)

    def named_point(self, name: str, link: str | None = None) -> PointState:
        """A named point of ``link`` (default: the first link in spec order that has it)."""
        spec = self.mechanism.spec
        link = link or spec.point_owner(name)
        pts = spec.ground if link == GROUND else spec.link(link).points
        return self.point(link, pts[name])

    def com(self, link: str) -> PointState:
        return self.point(link, self.mechanism.spec.link(link).com)

    def take(self, rows: np.ndarray, flags: tuple[Flag, ...]) -> "Kinematics":
        """The same kinematics at angle indices ``rows`` (index array or bool mask)."""
        return replace(self, angles=self.angles[rows], r=self.r[rows], theta=self.theta[rows],
                       v=self.v[rows], omega=self.omega[rows], a=self.a[rows],
                       alpha=self.alpha[rows], flags=flags)

    def angle_deg(self, link: str) -> np.ndarray:
        """Orientation of ``link``'s x-axis [deg] in (-180, 180], (n,)."""
        deg = (np.degrees(self.theta[:, self.index(link)]) + 180.0) % 360.0 - 180.0
        return np.where(deg == -180.0, 180.0, deg)

    def at(self, angle: float) -> int | None:
        """Index of a crank angle among the analysed ones, None if left out."""
        hit = np.flatnonzero(np.abs(self.angles - angle) < 1e-9)
        return int(hit[0]) if hit.size else None
