"""Planar vector helpers, vectorised over the angle axis (arrays shaped (n, 2) or (n,))."""
from __future__ import annotations

import numpy as np


def rotate(v, theta: np.ndarray) -> np.ndarray:
    """R(theta) v for a local vector ``v`` (2,) or (n, 2) and angles ``theta`` (n,) [rad]."""
    v = np.asarray(v, float)
    c, s = np.cos(theta), np.sin(theta)
    x, y = v[..., 0], v[..., 1]
    out = np.empty(np.broadcast_shapes(np.shape(c), np.shape(x)) + (2,))
    out[..., 0] = c * x - s * y
    out[..., 1] = s * x + c * y
    return out


def perp(v: np.ndarray) -> np.ndarray:
    """k x v: ``v`` turned +90 degrees."""
    v = np.asarray(v)
    out = np.empty(v.shape, np.result_type(v, float))
    out[..., 0] = -v[..., 1]
    out[..., 1] = v[..., 0]
    return out


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """z-component of a x b."""
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1]


def norm(a: np.ndarray) -> np.ndarray:
    return np.hypot(a[..., 0], a[..., 1])


def scaled(k, v: np.ndarray) -> np.ndarray:
    """``k`` times vectors ``v`` (n, 2): ``k`` a number, or one per row (n,) (a stacked
    variant's mass)."""
    k = np.asarray(k)
    return k[..., None] * v if k.ndim else k * v
