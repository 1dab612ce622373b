"""A problem's variants for a class (``sheet.variants``): one set of data per student, each
drawn from the seed, printed rounded to ``digits`` and analysed from exactly those printed
data, so that a student who solves what is printed gets the key's answer.

A candidate is kept when its mechanism assembles at every sheet angle on the spec's branch,
no angle there is flagged (singular, near-singular, jammed by friction), ``require`` holds
there, and its data and answers differ from every variant kept before; otherwise it is
redrawn. Candidates come from one random stream in order and are kept in that order, so the
seed alone decides the set. The redraws are bounded (:data:`MAX_DRAWS_PER_VARIANT`): a
``require`` that no variant meets is an error naming it, never an endless loop.

A variant's spec is the spec's data tree with the varied leaves replaced
(:func:`.variants.variant_spec`: validated like any spec) and its name numbered; it is
analysed by :func:`mechreport.pipeline.analyse` through the executor's serial runner.
"""
from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from ..errors import MechreportError, Problem, SpecError
from ..spec import Spec
from .variants import BaseSpec, section_base, variant_spec

#: draws allowed per variant asked for (and at least MIN_DRAWS): redraws are bounded
MAX_DRAWS_PER_VARIANT = 10
MIN_DRAWS = 40
#: significant digits of a printed answer; its tolerance is ANSWER_RTOL of its magnitude
ANSWER_DIGITS = 4
ANSWER_RTOL = 0.01


@dataclass(frozen=True)
class Answer:
    """One asked quantity of a variant: ``quantity`` (its result name, ``joint.B.f``,
    ``driver.torque``), ``label`` (the sheet's symbol and where: ``|F12| at φ = 30°``),
    ``angle`` (the sheet angle), ``value`` (printed to :data:`ANSWER_DIGITS`), ``unit`` (SI)
    and ``tolerance`` (absolute, same unit)."""

    quantity: str
    label: str
    angle: float
    value: float
    unit: str
    tolerance: float


@dataclass
class SheetVariant:
    """Variant ``number`` (1, 2, ...): the varied data as printed (``values``: key -> value,
    spec units), its spec and analysis, and its answers."""

    number: int
    values: dict
    spec: Spec
    analysis: object = field(repr=False)
    answers: list


def round_sig(x: float, digits: int) -> float:
    """``x`` rounded to ``digits`` significant digits (the value the sheet prints)."""
    if x == 0 or not math.isfinite(x):
        return float(x)
    return float(f"{x:.{digits - 1}e}")


def grid(v) -> list[float] | None:
    """The values a varied datum takes: ``values``, or its range by ``step`` (both ends
    included when the step reaches them); None for a continuous range."""
    if v.values is not None:
        return list(v.values)
    if v.step is None:
        return None
    lo, hi = sorted((v.start, v.stop))
    n = int(math.floor((hi - lo) / v.step + 1e-9))
    return [lo + i * v.step for i in range(n + 1)]


def draw(settings, rng: np.random.Generator) -> dict:
    """One candidate's varied data (key -> value, spec units), rounded to ``digits``."""
    out = {}
    for v in settings.vary:
        values = grid(v)
        if values is not None:
            x = values[int(rng.integers(len(values)))]
        else:
            lo, hi = sorted((v.start, v.stop))
            x = float(rng.uniform(lo, hi))
        out[v.key] = round_sig(x, settings.digits)
    return out


def sheet_angles(spec: Spec, angles) -> list[float]:
    """The sheet's angles: ``angles`` (``--sheet-angles``) or the spec's ``at``."""
    return [float(a) for a in (angles if angles is not None else spec.at)]


def infeasible(analysis, angles: list[float], require) -> str | None:
    """Why a candidate cannot be a variant (None when it can): an angle left out or flagged,
    or a ``require`` that fails there."""
    from ..post.transmission import smallest_transmission_angle
    from ..report.sheet.model import coordinate
    spec, kin = analysis.spec, analysis.kinematics
    for a in angles:
        where = coordinate(spec, a)[1]
        if kin.index_of(a) is None or any(abs(f.angle - a) < 1e-9 for f in analysis.flags):
            return f"the mechanism is left out or flagged at {where}"
    bounds = dict(require)
    if "transmission_angle_min" in bounds:
        mu = smallest_transmission_angle(kin)
        for a in angles:
            x = float(mu[kin.index_of(a)])
            if math.isfinite(x) and x < bounds["transmission_angle_min"]:
                return (f"require transmission_angle_min: {bounds['transmission_angle_min']:g} "
                        f"fails at {where_of(spec, a)} (transmission angle {x:.3g}°)")
    return None


def where_of(spec, a: float) -> str:
    from ..report.sheet.model import coordinate
    return coordinate(spec, a)[1]


def answers_of(analysis, angles: list[float]) -> list[Answer]:
    """The asked quantities at each sheet angle: the driver's effort and the magnitude of
    every joint's reaction (the reference method's, as the sheet's answers table)."""
    from ..post import reference_method
    from ..quantities import unit_of
    from ..report.sheet.symbols import Names
    spec, kin = analysis.spec, analysis.kinematics
    res = analysis.forces[reference_method(analysis.forces)]
    names = Names(spec)
    out = []
    for a in angles:
        k = kin.index_of(a)
        where = where_of(spec, a)
        asked = [(spec.driver.quantity, "M" if spec.driver.kind == "R" else "F_d")]
        asked += [(f"joint.{j.name}.f", f"|{names.vec[j.name]}|") for j in spec.joints]
        rows = []
        for q, sym in asked:
            values = res.quantity(q, spec)
            if values is None:
                continue
            rows.append((q, f"{sym} at {where}", float(values[k])))
        scale = max((abs(x) for _, _, x in rows), default=0.0)
        for q, label, x in rows:
            value = round_sig(x, ANSWER_DIGITS)
            if abs(value) < 1e-9 * scale:
                value = 0.0
            tol = round_sig(max(ANSWER_RTOL * abs(value), 1e-3 * ANSWER_RTOL * scale, 1e-12),
                            2)
            out.append(Answer(q, label, a, value, unit_of(q) or "", tol))
    return out


def sheet_base(src) -> tuple[Spec, BaseSpec]:
    """The spec read into ``src`` (validated) and its :class:`~.variants.BaseSpec` for the
    sheet's varied keys; a ``SpecError`` when the spec has no ``sheet.variants``."""
    from ..spec.loader import spec_from_data
    spec = spec_from_data(src.data, src)
    settings = spec.sheet_settings.variants
    if settings is None:
        raise SpecError([Problem(src.filename, None, "sheet", "this spec has no "
                                 "'sheet: {variants: ...}' section")])
    return spec, section_base(spec, src, settings.vary)


def make_variants(path: str | Path, count: int | None = None, seed: int | None = None,
                  angles=None, stop_check=None) -> list[SheetVariant]:
    """The variants of the spec at ``path`` (``count`` and ``seed`` override the spec's;
    ``angles`` the sheet's angles, default ``at``). Raises ``SpecError`` naming the failing
    condition when fewer than ``count`` feasible, distinct variants are found within the
    bounded draws."""
    return _make(path, count, seed, angles, stop_check)[1]


def write_class(path: str | Path, folder: Path, options=None, stop_check=None,
                jobs: int | None = None) -> list[Path]:
    """Make the variants of the spec at ``path`` (``options``: a
    :class:`~mechreport.report.sheet.SheetOptions`, its ``variants``, ``seed`` and ``angles``
    override the spec's) and write them into ``folder/variants/``: each variant's sheets
    (on ``jobs`` local processes through the executor; default: every usable core when this
    is the main process, else 1: a build of several specs is parallel already), then the
    class's answers and question bank. Returns the class files' paths."""
    import multiprocessing

    from ..report.sheet.variants_out import write_class_files
    from .executor import usable_cores
    from .run import run_chunks
    base, variants = _make(path, getattr(options, "variants", None),
                           getattr(options, "seed", None), getattr(options, "angles", None),
                           stop_check)
    root = Path(folder) / "variants"
    if jobs is None:
        jobs = usable_cores() if multiprocessing.parent_process() is None else 1
    jobs = max(1, min(jobs, len(variants)))
    shared = (base, sheet_angles(base.spec, getattr(options, "angles", None)), options, root)
    problems: dict[int, dict] = {}
    size = max(1, math.ceil(len(variants) / jobs))

    def args_of(chunk) -> tuple:
        return ([(v.number, v.values) for v in variants[chunk[0]:chunk[1]]],)

    def on_done(chunk, result) -> None:
        problems.update(result)

    run_chunks(_write_task, shared, len(variants), size, args_of, on_done, jobs=jobs,
               stop_check=stop_check)
    return write_class_files(variants, [problems[v.number] for v in variants], root,
                             base.spec.name)


def _write_task(shared, items) -> dict:
    """In a worker: analyse each (number, values) again (the same data give the same
    analysis) and write its sheets into ``root/NN``; its problem as question text."""
    from ..pipeline import analyse
    from ..report.sheet.variants_out import folder_of, write_variant
    base, angles, options, root = shared
    out = {}
    for number, values in items:
        spec = _variant(base, values, angles, number)
        out[number] = write_variant(analyse(spec), root / folder_of(number), options)
    return out


def _make(path, count, seed, angles, stop_check) -> tuple[BaseSpec, list[SheetVariant]]:
    from ..spec.loader import load_source
    src = load_source(path)
    spec, base = sheet_base(src)
    settings = spec.sheet_settings.variants
    count = settings.count if count is None else int(count)
    seed = settings.seed if seed is None else int(seed)
    angles = sheet_angles(spec, angles)
    rng = np.random.default_rng(seed)
    budget = max(MAX_DRAWS_PER_VARIANT * count, MIN_DRAWS)
    kept: list[SheetVariant] = []
    seen_data, seen_answers = set(), set()
    reasons: Counter[str] = Counter()
    draws = 0
    while len(kept) < count and draws < budget:
        values = draw(settings, rng)
        draws += 1
        key = tuple(sorted(values.items()))
        if key in seen_data:
            reasons["the same data as another variant"] += 1
            continue
        seen_data.add(key)
        if stop_check is not None:
            stop_check()
        variant, why = _candidate(base, values, angles, settings, len(kept) + 1)
        if variant is not None:
            answers = tuple((a.quantity, a.angle, a.value) for a in variant.answers)
            if answers in seen_answers:
                variant, why = None, "the same answers as another variant"
            else:
                seen_answers.add(answers)
        if variant is None:
            reasons[why] += 1
            continue
        kept.append(variant)
    if len(kept) < count:
        worst = reasons.most_common(3)
        why = "; ".join(f"{n} draw{'s' if n > 1 else ''}: {r}" for r, n in worst)
        raise SpecError([Problem(spec.file, settings.line, "sheet.variants",
                                 f"only {len(kept)} of {count} variants found in {draws} "
                                 f"draws (seed {seed}); the others failed: {why}. Widen "
                                 "'vary', relax 'require' or ask for fewer")])
    return base, kept


def _variant(base: BaseSpec, values: dict, angles, number: int) -> Spec:
    """Variant ``number``'s spec: the varied data in, the sheet's angles analysed, its name
    numbered and without the description (written for the spec's own data, it would
    describe other numbers); raises ``SpecError`` for data not valid there."""
    from ..report.sheet.model import SheetOptions, sheet_spec
    spec = variant_spec(base, values)
    return replace(sheet_spec(spec, SheetOptions(angles=tuple(angles))), name=f"{spec.name}, variant {number:02d}",
                   description="")


def _candidate(base: BaseSpec, values: dict, angles, settings, number: int):
    """(SheetVariant, None) for a feasible candidate, else (None, why)."""
    from ..pipeline import analyse
    try:
        spec = _variant(base, values, angles, number)
    except SpecError as exc:
        return None, exc.problems[0].message if exc.problems else str(exc)
    try:
        analysis = analyse(spec)
    except MechreportError as exc:
        return None, str(exc).splitlines()[0]
    why = infeasible(analysis, angles, settings.require)
    if why is not None:
        return None, why
    return SheetVariant(number, dict(values), spec, analysis, answers_of(analysis, angles)), None
