"""How well the methods agree: for every quantity, the largest difference between any two
methods over the sweep, relative to that quantity's largest magnitude.

A component that is zero by construction (a slider's reaction along a fixed x guide, the couple
of a block whose centre of mass is its slider point) would otherwise compare rounding noise
with rounding noise; so the scale is never below ``SCALE_FLOOR`` times the largest quantity of
the same kind in the result (forces [N] or moments [N m]).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..forces import ForceResult
from ..quantities import unit_kind

SCALE_FLOOR = 1e-3


def _kind(quantity: str) -> str:
    return unit_kind(quantity)


@dataclass(frozen=True)
class Agreement:
    """Worst disagreement of one quantity: ``relative`` = max |a - b| / max |q|; ``absolute``
    in the quantity's unit; between ``methods`` at crank ``angle`` [deg]."""

    quantity: str
    relative: float
    absolute: float
    methods: tuple[str, str]
    angle: float
    n_methods: int


def agreement(results: dict[str, ForceResult]) -> list[Agreement]:
    """One entry per quantity computed by at least two methods, worst first."""
    by_q: dict[str, dict[str, np.ndarray]] = {}
    for name, res in results.items():
        for q, values in res.values().items():
            by_q.setdefault(q, {})[name] = values
    kind_scale: dict[str, float] = {}
    for q, per in by_q.items():
        top = max(float(np.max(np.abs(v), initial=0.0)) for v in per.values())
        kind_scale[_kind(q)] = max(kind_scale.get(_kind(q), 0.0), top)
    out = []
    for q, per in by_q.items():
        if len(per) < 2:
            continue
        names = list(per)
        stack = np.stack([per[m] for m in names])          # (methods, n)
        if stack.shape[1] == 0:
            continue
        hi, lo = np.argmax(stack, axis=0), np.argmin(stack, axis=0)
        spread = np.max(stack, axis=0) - np.min(stack, axis=0)
        finite = np.isfinite(spread)
        # a NaN never agrees: it is the worst disagreement there is, not none
        k = int(np.argmax(spread)) if finite.all() else int(np.flatnonzero(~finite)[0])
        scale = max(float(np.max(np.abs(stack))), SCALE_FLOOR * kind_scale[_kind(q)])
        if not (finite[k] and np.isfinite(scale)):
            rel = float("inf")
        else:
            rel = float(spread[k] / scale) if scale > 0 else 0.0
        angle = float(next(iter(results.values())).angles[k])
        pair = (names[hi[k]], names[lo[k]]) if spread[k] > 0 else (names[0], names[1])
        out.append(Agreement(q, rel, float(spread[k]), pair, angle, len(names)))
    return sorted(out, key=lambda a: -a.relative)
