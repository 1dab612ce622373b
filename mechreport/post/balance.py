"""Balancing the crank: the point counterweight that minimises the RMS inertial shaking force.

A mass m at radius r on the crank, at angle beta from the crank's x-axis, adds m a to the sum
of m a_C. In complex notation (z = x + i y) with the crank angle theta and constant driver
alpha, omega: a = r e^{i(theta + beta)} (i alpha - omega^2), so the added force is c u(theta)
with c = m r e^{i beta} and u = e^{i theta} (i alpha - omega^2). Minimising sum |S + c u|^2
over the cycle is linear least squares in c: c = -sum(conj(u) S) / sum(|u|^2).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


#: the least reduction of the RMS inertial shaking force for which a counterweight is worth
#: recommending (a relative 1 %); below it the crank is best left as it is
NOTICEABLE = 0.01


@dataclass(frozen=True)
class Counterweight:
    """``mr`` [kg m] and ``angle`` [deg, in (-180, 180], from the crank's x-axis] of the best
    point counterweight; ``rms_before`` and ``rms_after`` the RMS inertial shaking force
    [N] over the cycle without and with it."""

    mr: float
    angle: float
    rms_before: float
    rms_after: float
    balanced: np.ndarray | None = field(default=None, repr=False)   # (N, 2) [N], with it

    @property
    def reduction(self) -> float:
        """How much it reduces the RMS inertial shaking force, relative (0 to 1)."""
        return 1.0 - self.rms_after / self.rms_before if self.rms_before > 0 else 0.0

    @property
    def worthwhile(self) -> bool:
        """Whether it reduces the RMS noticeably (by at least ``NOTICEABLE``)."""
        return self.mr > 0 and self.reduction >= NOTICEABLE


def counterweight(inertia_force: np.ndarray, crank_theta: np.ndarray, omega: float,
                  alpha: float = 0.0) -> Counterweight:
    """``inertia_force`` (N, 2) [N] = sum of m a_C over the cycle grid; ``crank_theta`` (N,)
    [rad] the crank's x-axis angle there."""
    # real and imaginary parts kept apart: half the memory of complex temporaries
    sx, sy = inertia_force[:, 0], inertia_force[:, 1]
    theta = np.asarray(crank_theta, float)
    w2 = omega ** 2
    ux, uy = np.cos(theta), np.sin(theta)        # u = e^{i theta} (i alpha - omega^2)
    if alpha:
        ux, uy = -w2 * ux - alpha * uy, alpha * ux - w2 * uy
    else:
        ux *= -w2
        uy *= -w2
    uu = w2 ** 2 + alpha ** 2                    # |u|^2, the same at every angle
    before = float(np.sqrt((np.dot(sx, sx) + np.dot(sy, sy)) / len(theta)))
    # a crank at rest (omega and alpha 0) has no inertia force to balance: u = 0
    c = 0j if uu == 0 else -complex(np.dot(ux, sx) + np.dot(uy, sy),
                                    np.dot(ux, sy) - np.dot(uy, sx)) / (uu * len(theta))
    if abs(c) * np.sqrt(uu) <= 1e-12 * max(before, 1e-300):
        c = 0j                     # nothing to balance: no counterweight, angle 0 (not -0)
    balanced = np.empty((len(theta), 2))
    bx, by = balanced[:, 0], balanced[:, 1]
    np.multiply(ux, c.real, out=bx)              # S + c u, component by component
    bx += sx
    bx -= c.imag * uy
    np.multiply(uy, c.real, out=by)
    by += sy
    by += c.imag * ux
    after = float(np.sqrt((np.dot(bx, bx) + np.dot(by, by)) / len(theta)))
    angle = float(np.degrees(np.angle(c))) + 0.0
    if angle <= -180.0:
        angle += 360.0
    return Counterweight(float(abs(c)), angle, before, after, balanced)
