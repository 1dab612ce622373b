"""How well the methods agree: for every quantity, the largest difference between any two
methods over the sweep, relative to that quantity's largest magnitude.

A component that is zero by construction (a slider's reaction along a fixed x guide, the couple
of a block whose centre of mass is its slider point, the torque that keeps a balanced rotor
turning at constant speed) would otherwise compare rounding noise with rounding noise; so the
scale is never below ``SCALE_FLOOR`` times the analysis's load scale in that quantity's unit.
The load scale is dimensionally consistent: for a moment [N m] the largest moment or the
largest force times the mechanism's size (:attr:`Spec.size`), whichever is larger; for a
force [N] the largest force or the largest moment over the size. A quantity that is round-off
next to the real loads (every moment of a mechanism whose forces all pass through its pins)
is then judged as zero, never as a disagreement.

The driver's effort is the exception where its value is not zero by construction: where any
known action requires a resolvable share of it (``resolvable`` [N m or N], from
:func:`mechreport.forces.power.resolvable_effort`), its floor is taken from that share and the
largest quantity of its own unit, not from the load scale. A
torque of 13 N m from a piston's load, lost in the rounding of a 1e20 kg crank's 1e19 N
inertia forces, is then a disagreement (its value cannot be trusted), not round-off.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..forces import ForceResult
from ..quantities import load_scales, unit_kind

SCALE_FLOOR = 1e-3
#: the largest relative disagreement between methods a spec passes with (``check --tol``'s
#: default; every analysis, its machine-dynamics turn and a study's cross-check use it)
DEFAULT_TOL = 1e-6
STACK_LIMIT = 1 << 21   # most values (16 MB) judged at once


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


def agreement(results: dict[str, ForceResult], size: float = 0.0,
              resolvable: float = 0.0) -> list[Agreement]:
    """One entry per quantity computed by at least two methods, worst first; ``size`` [m]
    the mechanism's characteristic length (0: forces and moments are scaled apart);
    ``resolvable`` the driver effort's resolvable scale (see the module docstring)."""
    return finish(spreads(results), size, resolvable)


@dataclass(frozen=True)
class Spread:
    """One quantity over some angles: its largest spread between methods ``spread`` (inf or
    NaN where a method's value is not finite) at ``angle`` between ``methods``, and its
    largest magnitude ``top``; what a long sweep keeps of each chunk (see :func:`merge`)."""

    spread: float
    methods: tuple[str, str]
    angle: float
    top: float
    n_methods: int


Spreads = dict   # quantity -> Spread (n_methods 1: only its magnitude counts)


def spreads(results: dict[str, ForceResult]) -> Spreads:
    """Each quantity's :class:`Spread` over the results' angles (the quantities given by the
    same methods, as a rule every reaction component, judged together)."""
    by_q: dict[str, dict[str, np.ndarray]] = {}
    for name, res in results.items():
        for q, values in res.values().items():
            by_q.setdefault(q, {})[name] = values
        for r in res.reactions.values():    # each method's friction, from its reactions
            if r.friction is not None:
                by_q.setdefault(f"joint.{r.joint}.friction", {})[name] = r.friction
    angles = next(iter(results.values())).angles if results else np.zeros(0)
    groups: dict[tuple[str, ...], list[str]] = {}
    for q, per in by_q.items():
        groups.setdefault(tuple(per), []).append(q)
    found: Spreads = {}
    n = len(angles)
    for names, every in groups.items():
        step = max(1, STACK_LIMIT // max(len(names) * n, 1))
        for qs in (every[i:i + step] for i in range(0, len(every), step)):
            found.update(_spreads(by_q, names, qs, angles))
    return {q: found[q] for q in by_q if q in found}


def _spreads(by_q: dict, names: tuple[str, ...], qs: list[str], angles) -> Spreads:
    """The spreads of quantities ``qs``, each given by the methods ``names``, judged at once."""
    stack = np.array([[by_q[q][m] for m in names] for q in qs], float)  # (Q, methods, n)
    if len(names) < 2:              # its magnitude still sets its kind's scale
        tops = np.abs(stack).max(axis=(1, 2), initial=0.0).tolist()
        return {q: Spread(0.0, (names[0], names[0]), 0.0, top, 1)
                for q, top in zip(qs, tops)}
    if stack.shape[2] == 0:
        return {}
    hi, lo = stack.max(axis=1), stack.min(axis=1)                      # (Q, n)
    top = np.maximum(hi.max(axis=1), -lo.min(axis=1))   # max |stack|; NaN if any is NaN
    spread = hi - lo
    bad = ~np.isfinite(spread)
    # a NaN never agrees: it is the worst disagreement there is, not none
    k = np.where(bad.any(axis=1), bad.argmax(axis=1), spread.argmax(axis=1))
    rows = np.arange(len(qs))
    at = stack[rows, :, k]                                              # (Q, methods)
    worst = spread[rows, k].tolist()
    first, last = at.argmax(axis=1).tolist(), at.argmin(axis=1).tolist()
    found: Spreads = {}
    for q, w, i, j, kk, t in zip(qs, worst, first, last, k.tolist(), top.tolist()):
        pair = (names[i], names[j]) if w > 0 else (names[0], names[1])
        found[q] = Spread(w, pair, float(angles[kk]), t, len(names))
    return found


def merge(a: Spreads, b: Spreads) -> Spreads:
    """The spreads of two sets of angles together (``a``'s angles first: on a tie, and for
    the first value that is not finite, ``a``'s entry is kept)."""
    out = dict(a)
    for q, s in b.items():
        if q not in out:
            out[q] = s
            continue
        r = out[q]
        bad_s, bad_r = not np.isfinite(s.spread), not np.isfinite(r.spread)
        worse = (bad_s and not bad_r) or (not bad_s and not bad_r and s.spread > r.spread)
        keep = s if worse else r
        out[q] = Spread(keep.spread, keep.methods, keep.angle, max(r.top, s.top),
                        max(r.n_methods, s.n_methods))
    return out


DRIVER_QUANTITIES = ("driver.torque", "driver.force")


def finish(parts: Spreads, size: float = 0.0, resolvable: float = 0.0) -> list[Agreement]:
    """The agreement table from the spreads over the whole sweep, worst first; ``size`` [m]
    and ``resolvable`` as for :func:`agreement`."""
    kinds = {q: _kind(q) for q in parts}
    tops: dict[str, float] = {}
    for q, s in parts.items():
        tops[kinds[q]] = max(tops.get(kinds[q], 0.0), s.top)
    kind_scale = load_scales(tops, size)
    out = []
    for q, s in parts.items():
        if s.n_methods < 2:
            continue
        if q in DRIVER_QUANTITIES and resolvable > 0:   # a real effort: no load-scale floor
            load = max(tops[kinds[q]], resolvable)
        else:
            load = kind_scale[kinds[q]]
        scale = max(s.top, SCALE_FLOOR * load)
        if not (math.isfinite(s.spread) and math.isfinite(scale)):   # Python floats
            rel = float("inf")
        else:
            rel = float(s.spread / scale) if scale > 0 else 0.0
        out.append(Agreement(q, rel, s.spread, s.methods, s.angle, s.n_methods))
    return sorted(out, key=lambda a: -a.relative)
