"""THE SEAM between a study and the solver: one chunk of variants in, one row per variant out.

    rows = evaluate_chunk(base, variants, method, keep)

- ``base``: the :class:`~mechreport.study.variants.BaseSpec` (the validated spec, its data
  tree in the spec's own units, and each varied key's path in it);
- ``variants``: a sequence of ``{varied key: value}`` dicts (the keys of ``study.vary`` as
  written, values in the spec's own units);
- ``method``: one force method name (``mechreport.forces.METHODS``), able to give the kept
  quantities (:func:`mechreport.study.methods.cannot_serve`);
- ``keep``: the kept cycle quantity names (``cycle.torque.rms``, ``joint.B.f_max`` ...).

It returns a list of :class:`Row`, one per variant, in order. It never raises for a variant's
sake: a variant that cannot be built, assembled or analysed is a row with its ``reason``.
Only ``KeyboardInterrupt`` and the like get through.

The variants are analysed as one batch (:mod:`mechreport.batch`: their numbers stacked with
the angles), and each row equals the single analysis of its variant (tests/test_study.py
checks each row against ``analyse`` to 1e-12).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping, Sequence

from .variants import BaseSpec, variant_spec


@dataclass(frozen=True)
class Row:
    """One variant's result. ``values``: the kept quantities in ``keep`` order [SI; units in
    ``mechreport.quantities``], NaN where undefined or when the variant failed. ``passed``:
    every verdict of the spec's ``design`` passed (True when it has none); None when the
    variant failed before any verdict. ``failed``: the design items that did not pass.
    ``reason``: why the variant failed, or why a kept quantity is undefined ("" when the row
    is complete)."""

    values: tuple[float, ...]
    passed: bool | None
    failed: tuple[str, ...] = ()
    reason: str = ""

    @property
    def ok(self) -> bool:
        return not self.reason


def evaluate_chunk(base: BaseSpec, variants: Sequence[Mapping[str, float]], method: str,
                   keep: Sequence[str]) -> list[Row]:
    """One :class:`Row` per variant of ``variants`` (see the module docstring): the variants
    that build are analysed together by :func:`mechreport.batch.analyse_variants`."""
    return batch_results(base, variants, method, lambda outcome: row_of(outcome, keep),
                         lambda exc, _: failed_row(len(keep), reason_of(exc, base.file)))


def batch_results(base: BaseSpec, variants: Sequence[Mapping[str, float]], method: str,
                  result, failed) -> list:
    """One result per variant of ``variants`` ({varied key: value}), never raising for a
    variant's sake (a study's rows, a tolerance analysis's samples, the optimiser's
    candidates): the variants whose spec builds are analysed together
    (:func:`mechreport.pipeline.batch.analyse_variants`, ``method``) and each gives
    ``result(outcome)``; ``failed(exc, analysed)`` stands for one whose spec cannot be built
    (``analysed`` False) or whose analysis or result raised (True)."""
    from ..pipeline.batch import analyse_variants
    out: list = [None] * len(variants)
    specs, where = [], []
    for i, values in enumerate(variants):
        try:
            specs.append(variant_spec(base, values))
            where.append(i)
        except Exception as exc:  # noqa: BLE001 - a failing variant is a row, never a crash
            out[i] = failed(exc, False)
    for i, outcome in zip(where, analyse_variants(specs, method)):
        try:
            if outcome.exception is not None:
                raise outcome.exception
            out[i] = result(outcome)
        except Exception as exc:  # noqa: BLE001
            out[i] = failed(exc, True)
    return out


def row_of(analysis, keep: Sequence[str]) -> Row:
    """The row of a finished analysis (an :class:`~mechreport.pipeline.Analysis`, or a
    batch's :class:`~mechreport.pipeline.batch.Outcome`): kept values resolved as
    ``expect:`` resolves cycle quantities, and the design verdicts."""
    from ..checks.expectations import cycle_value
    if getattr(analysis, "untrusted", ""):    # the one method cannot vouch for its numbers
        return failed_row(len(keep), analysis.untrusted)
    from ..quantities import is_member
    cycle = (analysis.cycle_values if hasattr(analysis, "cycle_values") else
             analysis.review.values if analysis.review is not None else None)
    strength = getattr(analysis, "members", None)
    if strength is None and getattr(analysis, "strength", None) is not None:
        strength = analysis.strength.values           # an Analysis
    if cycle is None and not all(is_member(q) for q in keep):   # one reason, not one per
        return failed_row(len(keep), f"no cycle quantities: {analysis.review_problem}")
    got, why = [], []
    for q in keep:
        value, undefined = (cycle_value(strength or {}, q) if is_member(q) else
                            cycle_value(cycle, q, analysis.review_problem))
        got.append(math.nan if value is None else float(value))
        if undefined:
            why.append(undefined)
    failed = tuple(v.item for v in analysis.verdicts if not v.passed)
    return Row(tuple(got), not failed, failed, "; ".join(why))


def failed_row(n_keep: int, reason: str) -> Row:
    return Row((math.nan,) * n_keep, None, (), reason or "failed (no message)")


def reason_of(exc: BaseException, file: str) -> str:
    """The user-facing message of a variant's failure on one line, without the spec's file
    name in front (every row is about the same file): ``line 30: links.coupler.mass: must be
    a positive number, got -5``."""
    from ..errors import describe_failure
    lines = []
    for line in describe_failure(exc).splitlines():
        line = line.strip()
        if line.startswith(file + ":"):
            line = line[len(file) + 1:].lstrip()
            head, sep, rest = line.partition(":")
            if sep and head.isdigit():
                line = f"line {head}:{rest}"
        if line:
            lines.append(line)
    return "; ".join(lines)
