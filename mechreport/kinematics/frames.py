"""Planar vector helpers, vectorised over the angle axis (arrays shaped (n, 2) or (n,))."""
from __future__ import annotations

import numpy as np

from ..spec.types import GROUND


def rotate(v, theta: np.ndarray) -> np.ndarray:
    """R(theta) v for a local vector ``v`` (2,) or (n, 2) and angles ``theta`` (n,) [rad]."""
    return rotate_cs(v, np.cos(theta), np.sin(theta))


def rotate_cs(v, c: np.ndarray, s: np.ndarray) -> np.ndarray:
    """R(theta) v as :func:`rotate`, from the angles' cosines ``c`` and sines ``s`` (n,)
    computed once for several vectors."""
    v = np.asarray(v, float)
    x, y = v[..., 0], v[..., 1]
    shape = np.shape(c) if v.ndim == 1 else np.broadcast_shapes(np.shape(c), np.shape(x))
    out = np.empty(shape + (2,))
    out[..., 0] = c * x - s * y
    out[..., 1] = s * x + c * y
    return out


def perp(v: np.ndarray) -> np.ndarray:
    """k x v: ``v`` turned +90 degrees."""
    v = np.asarray(v, float)
    out = np.empty(v.shape)
    np.negative(v[..., 1], out=out[..., 0])     # (no temporary: a third less time at (36, 2))
    out[..., 1] = v[..., 0]
    return out


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """z-component of a x b."""
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1]


def project(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a . b (n,) for vectors (n, 2), summed as ``np.einsum("ni,ni->n")`` sums them (from +0,
    so never -0), bit for bit, without einsum's per-call cost (5x for these shapes)."""
    out = a[..., 0] * b[..., 0]
    out += a[..., 1] * b[..., 1]
    out += 0.0
    return out


def norm(a: np.ndarray) -> np.ndarray:
    return np.hypot(a[..., 0], a[..., 1])


def scaled(k, v: np.ndarray) -> np.ndarray:
    """``k`` times vectors ``v`` (n, 2): ``k`` a number, or one per row (n,) (a stacked
    variant's mass)."""
    k = np.asarray(k)
    return k[..., None] * v if k.ndim else k * v


class Trig:
    """cos and sin of angle arrays [rad], each computed once however often it is asked for:
    remembered by the array object (kept, so that no other array can take its id)."""

    def __init__(self):
        self._seen: dict[int, tuple] = {}

    def __call__(self, th: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        hit = self._seen.get(id(th))
        if hit is None or hit[0] is not th:
            hit = self._seen[id(th)] = (th, np.cos(th), np.sin(th))
        return hit[1], hit[2]

    def rotate(self, v, th: np.ndarray) -> np.ndarray:
        """:func:`rotate` with the remembered cos and sin of ``th``."""
        return rotate_cs(v, *self(th))


class LinkFrames:
    """Every link's frame over the angles: origin ``r[link]`` (n, 2) [m] and angle
    ``th[link]`` (n,) [rad], both in the global frame. Each link's cos and sin are computed
    once, on first use, and reused for every vector of that link turned into the global
    frame (a solve rotates the same link's points in many joints)."""

    def __init__(self, r: dict, th: dict):
        self.r, self.th = r, th
        self._trig: dict[str, tuple[np.ndarray, np.ndarray]] = {}
        self.n = next(iter(th.values())).shape[0]

    def trig(self, link: str) -> tuple[np.ndarray, np.ndarray]:
        """cos and sin of the link's angle (n,) (the frame's, "ground", never turns)."""
        cs = self._trig.get(link)
        if cs is None:
            th = self.th[link]
            if link == GROUND:
                cs = (np.ones(self.n), np.zeros(self.n))
            else:
                cs = (np.cos(th), np.sin(th))
            self._trig[link] = cs
        return cs

    def rotate(self, link: str, v) -> np.ndarray:
        """R(theta_link) v (n, 2) [m] for a vector ``v`` (2,) or (n, 2) in the link's frame:
        the same numbers as :func:`rotate` (``v`` (n, 2): stacked variants)."""
        return rotate_cs(v, *self.trig(link))
