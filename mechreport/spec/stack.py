"""Variants of one mechanism stacked into one spec, for analysing them as one batch.

Variants that differ only in their numbers (points, centres of mass, masses, inertias, T-joint
lines, the driver's speed and acceleration, gravity, load values, spring and damper constants)
stack into a single :class:`Spec` whose differing numbers are arrays over *rows*: ``rows``
consecutive rows per variant (one per angle), ``(V * rows,)`` for a scalar and
``(V * rows, 2)`` for a vector. Numbers equal in every variant stay as they are. The solvers
broadcast these arrays along their angle axis, so a batch of variants is solved like one
long sweep.
"""
from __future__ import annotations

from dataclasses import fields, replace

import numpy as np

from .types import Driver, Joint, Line, Link, Load, Spec

# the numbers of each record that may differ between stacked variants
_NUMBERS = {
    Link: ("mass", "com", "inertia"),
    Line: ("through", "direction"),
    Driver: ("omega", "alpha"),
    Load: ("value", "direction", "stiffness", "free_length", "damping", "free_angle"),
}
_IGNORED = {Driver: ("rpm_given",), Link: ("shape",)}


def _leaf(values: list, rows: int):
    """The common value, or the values repeated ``rows`` times each (an array)."""
    first = values[0]
    if any((v is None) != (first is None) for v in values):
        raise _Unstackable
    if first is None or all(_same(v, first) for v in values[1:]):
        return first
    return np.repeat(np.asarray(values, float), rows, axis=0)


def _same(a, b) -> bool:
    return a == b if not isinstance(a, (tuple, list)) else tuple(a) == tuple(b)


class _Unstackable(Exception):
    pass


def _skeleton(record) -> tuple:
    """The record's fields other than its stackable numbers (what must be equal to stack)."""
    skip = _NUMBERS.get(type(record), ()) + _IGNORED.get(type(record), ())
    out = []
    for f in fields(record):
        if f.name in skip:
            continue
        value = getattr(record, f.name)
        if f.name == "points":
            value = tuple(value)
        elif f.name == "line" and value is not None:
            value = _skeleton(value)
        out.append(value)
    return tuple(out)


def _record(records: list, rows: int):
    """Stack equal-shaped records (Link, Joint, Line, Driver, Load)."""
    first = records[0]
    if any(r is not first for r in records[1:]):
        shape = _skeleton(first)
        if any(_skeleton(r) != shape for r in records[1:] if r is not first):
            raise _Unstackable
    changes = {f: _leaf([getattr(r, f) for r in records], rows)
               for f in _NUMBERS.get(type(first), ())}
    if isinstance(first, Link):
        changes["points"] = {p: _leaf([r.points[p] for r in records], rows)
                             for p in first.points}
    if isinstance(first, Joint) and first.line is not None:
        changes["line"] = _record([r.line for r in records], rows)
    return replace(first, **changes) if changes else first


def stack_specs(specs: list[Spec], rows: int) -> Spec | None:
    """One spec for all ``specs`` with ``rows`` rows per variant, or None when they differ in
    more than their numbers (structure, names, sweep, reference or expectation angles,
    load profiles)."""
    first = specs[0]
    if len(specs) == 1:
        return first
    try:
        for s in specs[1:]:
            if (set(s.ground) != set(first.ground) or s.at[:1] != first.at[:1]
                    or s.sweep != first.sweep or len(s.links) != len(first.links)
                    or len(s.joints) != len(first.joints) or len(s.loads) != len(first.loads)
                    or not np.array_equal(s.analysed_angles(), first.analysed_angles())):
                raise _Unstackable
        return replace(
            first,
            gravity=_leaf([s.gravity for s in specs], rows),
            ground={p: _leaf([s.ground[p] for s in specs], rows) for p in first.ground},
            links=tuple(_record([s.links[i] for s in specs], rows)
                        for i in range(len(first.links))),
            joints=tuple(_record([s.joints[i] for s in specs], rows)
                         for i in range(len(first.joints))),
            driver=_record([s.driver for s in specs], rows),
            loads=tuple(_record([s.loads[i] for s in specs], rows)
                        for i in range(len(first.loads))))
    except _Unstackable:
        return None


__all__ = ["stack_specs"]
