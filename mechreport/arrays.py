"""Small array helpers for the short sweeps where numpy's per-call cost is most of the time."""
from __future__ import annotations

from contextlib import contextmanager, nullcontext
from contextvars import ContextVar

import numpy as np


def stack(arrays, axis: int = 0) -> np.ndarray:
    """``np.stack(arrays, axis)`` for a non-empty sequence of arrays of one shape: the same
    values in the same C-contiguous layout, without np.stack's per-array checks and
    reshapes (half its cost for a handful of (n,) or (n, 2) arrays: 2-3 us a call instead of
    5-6 here). Unequal shapes raise ValueError, as np.stack does."""
    if not len(arrays):
        raise ValueError("need at least one array to stack")
    out = np.array(arrays)              # (k, *shape)
    axis %= out.ndim
    if axis == 0:
        return out
    order = list(range(1, out.ndim))
    order.insert(axis, 0)
    return np.ascontiguousarray(out.transpose(order))


_QUIET: ContextVar[bool] = ContextVar("mechreport_fp_quiet", default=False)
_NOTHING = nullcontext()


def fp_ignore(**categories):
    """``np.errstate(**categories)`` (those floating-point errors ignored), or nothing to do
    inside :func:`fp_quiet`, which already ignores every one: entering and leaving an
    errstate took 2.4 us here, this null context 0.8, and a short sweep's analysis enters
    about 80."""
    return _NOTHING if _QUIET.get() else np.errstate(**categories)


@contextmanager
def fp_quiet():
    """Every floating-point error ignored for the block, as ``np.errstate(all="ignore")``,
    and every :func:`fp_ignore` inside it free. For a whole analysis: what is not finite
    there is found and reported by its own checks (flags, finite checks), never by a
    warning. Per thread (a context variable, as numpy's own state)."""
    token = _QUIET.set(True)
    try:
        with np.errstate(all="ignore"):
            yield
    finally:
        _QUIET.reset(token)


def average(values: np.ndarray) -> float:
    """``float(np.mean(values))`` of a float array, bit for bit (the same pairwise sum of
    every element, divided by their count), without np.mean's Python-level dispatch."""
    return float(np.add.reduce(values, axis=None) / values.size)


def largest(values: np.ndarray) -> float:
    """``float(np.max(values))`` (NaN if any is NaN), without its Python-level dispatch."""
    return float(np.maximum.reduce(values, axis=None))


def smallest(values: np.ndarray) -> float:
    """``float(np.min(values))`` (NaN if any is NaN), without its Python-level dispatch."""
    return float(np.minimum.reduce(values, axis=None))
