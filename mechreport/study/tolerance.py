"""Tolerance analysis: the spec's manufacturing and parameter uncertainty (``tolerances:``)
sampled and carried through the whole analysis, on the study engine.

    from mechreport import tolerance
    result = tolerance("spec.yaml", jobs=2)       # a spec with a tolerances: section
    result.quantities[0].p95          # the 95th percentile of the first kept quantity [SI]
    result.verdicts[0].p, result.verdicts[0].low, result.verdicts[0].high

One module per step: this one (the samples, the runner, :func:`run_tolerance`), the
statistics :mod:`.tolerance_stats`, the files :mod:`.tolerance_outputs`, the report
:mod:`.tolerance_report`. The command's messages, progress and output folder are
:mod:`mechreport.app.tolerance`'s.

**Samples.** ``count`` points of the unit hypercube, a Latin hypercube (``sample: lhs``, the
default: ``scipy.stats.qmc.LatinHypercube``) or independent uniform draws (``random``), from
``numpy.random.default_rng(seed)``, each mapped to its leaf's distribution by the inverse of
its distribution function: uniform over [low, high], normal by ``scipy.stats.norm.ppf``. A
Latin hypercube stratifies every leaf: each of the ``count`` equal-probability slices of each
distribution is used exactly once. The same spec and seed give the same samples whatever the
chunks, the processes or the scheduler.

**Each sample** is the spec with those leaves replaced (:mod:`.variants`), analysed as a
study's variant is (the batch, one force method, the trust test). Its ``status``:

- ``ok``: analysed, trusted, every kept quantity defined;
- ``invalid``: the spec refuses the sampled value (a normal mass drawn negative);
- ``no assembly``: the mechanism cannot be assembled at its reference angle, or locks before
  the crank makes its turn (the loop does not close over the whole sweep);
- ``untrusted``: the one method's numbers fail the trust test (a near-singular position);
- ``failed``: anything else, with its reason (a kept quantity undefined, a lost worker).

Only ``ok`` samples enter the statistics of the kept quantities; every sample is in the
files, and the report counts each status with its reasons.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Sequence

import numpy as np

from .evaluate import batch_results, reason_of, row_of
from .executor import Lost, Words
from .plan import Plan, unit_samples
from .tolerance_stats import STATUSES, analyse_samples
from .variants import BaseSpec, section_base, variant_spec

TOLERANCE_WORDS = Words(item="sample", run="tolerance analysis",
                        kept="the samples computed are kept")

__all__ = ["run_tolerance", "tolerance_base", "load_tolerance_base", "tolerance_plan",
           "Sample", "SampleTable", "STATUSES", "run_samples", "nominal_sample"]


# ---------------------------------------------------------------------------- samples

def tolerance_plan(tol) -> Plan:
    """The samples of a ``tolerances`` section (see the module docstring): a :class:`Plan`
    whose ``values`` (count, len(vary)) are in the spec's own units."""
    from scipy.stats import norm
    n, d = int(tol.count), len(tol.vary)
    # inside (0, 1): a normal's inverse is finite there
    unit = np.clip(unit_samples(tol.sample, n, d, tol.seed), 1e-12, 1.0 - 1e-12)
    values = np.empty((n, d))
    for j, v in enumerate(tol.vary):
        if v.dist == "normal":
            values[:, j] = v.mean + v.sigma * norm.ppf(unit[:, j])
        else:
            values[:, j] = v.low + unit[:, j] * (v.high - v.low)
    return Plan(tuple(v.key for v in tol.vary), values, tol.sample, tol.seed)


def load_tolerance_base(path) -> BaseSpec:
    """Read and validate the spec at ``path`` (raises ``SpecError``); it must have a
    ``tolerances`` section."""
    from ..spec.loader import load_source
    return tolerance_base(load_source(path))


def tolerance_base(src) -> BaseSpec:
    """The :class:`BaseSpec` whose varied keys are the ``tolerances.vary`` leaves of the spec
    read into ``src`` (validated; raises ``SpecError``, also when it has no ``tolerances``)."""
    from ..errors import Problem, SpecError
    from ..spec.loader import spec_from_data
    spec = spec_from_data(src.data, src)
    if spec.tolerances is None:
        raise SpecError([Problem(src.filename, None, "", "this spec has no 'tolerances:' "
                                 "section; `mechreport tolerance` needs one saying what is "
                                 "uncertain and what to keep (docs/spec.md, section 21)")])
    return section_base(spec, src, spec.tolerances.vary, ("tolerances",))


# ------------------------------------------------------------------------- one sample

@dataclass(frozen=True)
class Sample:
    """One sample's result: the kept ``values`` [SI] (NaN where undefined), ``status`` (one
    of :data:`STATUSES`), ``reason`` ("" when ok), per design verdict (in the spec's order)
    ``passes`` (1 pass, 0 fail, -1 not judged) and ``margins`` (the fraction of the limit
    left over; NaN where undefined); ``assembled``: the analysis got far enough to know that
    the mechanism assembles over its sweep (False for ``no assembly`` and ``invalid``, and
    for a failure before that was known: an error of the analysis, a lost worker)."""

    values: tuple[float, ...]
    status: str
    reason: str = ""
    passes: tuple[int, ...] = ()
    margins: tuple[float, ...] = ()
    assembled: bool = True


def _failed(status: str, reason: str, n_keep: int, n_items: int) -> Sample:
    """A sample without a result: not known to assemble."""
    return Sample((math.nan,) * n_keep, status, reason or "failed (no message)",
                  (-1,) * n_items, (math.nan,) * n_items, assembled=False)


def evaluate_samples(base: BaseSpec, samples: Sequence[dict], method: str,
                     keep: Sequence[str], items: Sequence[str]) -> list[Sample]:
    """One :class:`Sample` per ``{key: value}`` of ``samples``, analysed together as a
    study's variants are (:func:`mechreport.pipeline.batch.analyse_variants`); never raises
    for a sample's sake."""
    from ..errors import AssemblyError, SpecError

    def failed(exc: Exception, analysed: bool) -> Sample:
        status = ("no assembly" if analysed and isinstance(exc, AssemblyError) else
                  "invalid" if not analysed and isinstance(exc, SpecError) else "failed")
        return _failed(status, reason_of(exc, base.file), len(keep), len(items))
    return batch_results(base, samples, method,
                         lambda outcome: _sample_of(outcome, keep, items, base.file), failed)


def _sample_of(outcome, keep, items, file: str) -> Sample:
    if getattr(outcome, "locked", ""):    # a machine that cannot turn does not pass,
        # whatever its member quantities (defined over the angles it reaches) say
        return _failed("no assembly", outcome.locked, len(keep), len(items))
    row = row_of(outcome, keep)
    by_item = {v.item: v for v in outcome.verdicts}
    passes = tuple(-1 if it not in by_item else int(by_item[it].passed) for it in items)
    margins = tuple(math.nan if it not in by_item or by_item[it].margin is None
                    else float(by_item[it].margin) for it in items)
    if outcome.untrusted:
        return Sample(row.values, "untrusted", outcome.untrusted, (-1,) * len(items),
                      (math.nan,) * len(items))
    if row.reason:
        locked = _locked(outcome.spec)
        if locked:
            return _failed("no assembly", locked, len(keep), len(items))
        # not ok: not judged (its verdicts are not counted, so the files do not show them)
        return Sample(row.values, "failed", row.reason, (-1,) * len(items),
                      (math.nan,) * len(items))
    return Sample(row.values, "ok", "", passes, margins)


def _locked(spec) -> str:
    """Why the mechanism of ``spec`` cannot be assembled over its whole sweep ("" when it
    can): it locks before the driver has covered the sweep."""
    from ..errors import AssemblyError
    from ..kinematics import solve_kinematics
    from ..model import build_mechanism
    try:
        kin = solve_kinematics(build_mechanism(spec))
    except AssemblyError as exc:
        return str(exc)
    except Exception:  # noqa: BLE001 - not an assembly problem: the row's reason stands
        return ""
    motion = kin.motion
    return "" if motion is None or motion.full else (motion.describe() or "")


def sample_task(base: BaseSpec, start: int, keys, values: np.ndarray, method: str, keep,
                items) -> tuple[int, list[Sample]]:
    """One chunk's samples, with where they start (the task a worker runs)."""
    samples = [{k: float(v) for k, v in zip(keys, row)} for row in values]
    return start, evaluate_samples(base, samples, method, tuple(keep), tuple(items))


def nominal_sample(base: BaseSpec, method: str, keep, items=None) -> tuple[Sample, list]:
    """The spec as written, analysed as a sample is: (its Sample, its verdicts). ``items``
    None: the spec's verdict items are read from this analysis."""
    from ..pipeline.batch import analyse_variants
    spec = variant_spec(base, {})
    outcome = analyse_variants([spec], method)[0]
    if outcome.exception is not None:
        return _failed("failed", reason_of(outcome.exception, base.file), len(keep), 0), []
    verdicts = list(outcome.verdicts)
    items = tuple(v.item for v in verdicts) if items is None else tuple(items)
    return _sample_of(outcome, tuple(keep), items, base.file), verdicts


# ----------------------------------------------------------------------------- table

@dataclass
class SampleTable:
    """Every sample of ``plan``: ``values`` (n, len(keep)) [SI], ``status`` and ``reason``
    per sample, ``passes`` (n, len(items)) int8 (1 pass, 0 fail, -1 not judged) and
    ``margins`` (n, len(items)), ``done`` (n,) whether the row has arrived, ``assembled``
    (n,) whether the sample is known to assemble (see :class:`Sample`)."""

    plan: Plan
    keep: tuple[str, ...]
    items: tuple[str, ...]
    values: np.ndarray = field(init=False)
    status: list[str] = field(init=False)
    reason: list[str] = field(init=False)
    passes: np.ndarray = field(init=False)
    margins: np.ndarray = field(init=False)
    done: np.ndarray = field(init=False)
    assembled: np.ndarray = field(init=False)

    def __post_init__(self):
        n = self.plan.n
        self.values = np.full((n, len(self.keep)), math.nan)
        self.status = ["failed"] * n
        self.reason = ["not computed"] * n
        self.passes = np.full((n, len(self.items)), -1, np.int8)
        self.margins = np.full((n, len(self.items)), math.nan)
        self.done = np.zeros(n, bool)
        self.assembled = np.zeros(n, bool)

    @property
    def n(self) -> int:
        return self.plan.n

    def put(self, start: int, rows: list[Sample]) -> int:
        """Store ``rows`` as samples ``start``, ``start + 1`` ...; returns how many are not
        ok."""
        bad = 0
        for i, row in enumerate(rows, start):
            self.values[i] = row.values
            self.status[i], self.reason[i] = row.status, row.reason
            if self.items:
                self.passes[i] = row.passes
                self.margins[i] = row.margins
            self.done[i] = True
            self.assembled[i] = row.assembled
            bad += row.status != "ok"
        return bad

    @property
    def ok(self) -> np.ndarray:
        """(n,) the sample was analysed, trusted, with every kept quantity."""
        return np.array([s == "ok" for s in self.status], bool)

    def has(self, status: str) -> np.ndarray:
        return np.array([s == status for s in self.status], bool)

    @property
    def design_pass(self) -> np.ndarray:
        """(n,) int8: 1 every verdict passes (an ok sample), 0 one fails, -1 not judged."""
        out = np.full(self.n, -1, np.int8)
        ok = self.ok
        if not self.items:
            out[ok] = 1
            return out
        judged = ok & (self.passes >= 0).all(axis=1)
        out[judged] = (self.passes[judged] == 1).all(axis=1)
        out[ok & (self.passes == 0).any(axis=1)] = 0
        return out


# ---------------------------------------------------------------------------- running

def run_samples(base: BaseSpec, plan: Plan, method: str, keep, items, *,
                jobs: int | None = None, chunk: int | None = None, client=None,
                progress=None, lost: list | None = None, notify=None, stop_check=None,
                setup=None) -> SampleTable:
    """Every sample of ``plan`` on the executor (this process, local processes or the Dask
    cluster of ``client``), as :func:`mechreport.study.run.run_variants` runs a study's
    variants: ``progress(done, not_ok)``, ``lost`` (receives a :class:`Lost` per chunk lost
    for good: its samples are ``failed`` with the reason), ``notify``, ``stop_check``,
    ``setup`` as there."""
    from .cluster import dask_workers
    from .run import auto_chunk, local_jobs, run_chunks
    keep, items = tuple(keep), tuple(items)
    table = SampleTable(plan, keep, items)
    count = {"done": 0, "bad": 0}

    def on_done(_chunk, result) -> None:
        start, rows = result
        count["bad"] += table.put(start, rows)
        count["done"] += len(rows)
        if progress is not None:
            progress(count["done"], count["bad"])

    def record_lost(start: int, stop: int, reason: str) -> None:
        if lost is not None:
            lost.append(Lost(start, stop, reason))
        on_done(None, (start, [_failed("failed", reason, len(keep), len(items))]
                       * (stop - start)))

    def args_of(c) -> tuple:
        a, b = c
        return a, plan.keys, plan.values[a:b], method, keep, items

    if client is not None:
        size, jobs = chunk or auto_chunk(plan.n, dask_workers(client)), 0
    else:
        jobs, size, _why = local_jobs(plan.n, jobs, chunk)
    run_chunks(sample_task, base, plan.n, size, args_of, on_done, jobs=jobs, client=client,
               on_lost=record_lost, notify=notify, stop_check=stop_check, setup=setup,
               words=TOLERANCE_WORDS)
    return table


def run_tolerance(spec, *, jobs: int | None = None, scheduler: str | None = None,
                  method: str | None = None, chunk: int | None = None, progress=None):
    """The tolerance analysis of ``spec`` (a spec file's path, its YAML text, or a
    :class:`BaseSpec` from :func:`tolerance_base`; it needs a ``tolerances:`` section), as
    ``mechreport tolerance`` computes it: a
    :class:`~mechreport.study.tolerance_stats.ToleranceResult` (``.table`` every sample,
    ``.quantities``, ``.verdicts``, ``.assembly``, ``.ranking``, ``.summary()``). ``jobs``,
    ``scheduler`` (a Dask scheduler address), ``method`` (default: the fastest that gives
    every kept quantity and verdict) and ``chunk``: as the command's options;
    ``progress(done, not_ok)``: running totals. Nothing is printed. Raises ``SpecError`` for a
    spec that is not valid or has no tolerances, ``MechreportError`` when the spec as written
    cannot be analysed, the method cannot serve or the scheduler cannot be used."""
    import time

    from .cluster import close_client, connect
    from .methods import choose_method
    base = _base(spec)
    tol = base.spec.tolerances
    method, why = choose_method(method, tol.keep, base.spec.design, named="method")
    nominal, verdicts = checked_nominal(base, method, tol.keep)
    plan = tolerance_plan(tol)
    lost: list = []
    client = connect(scheduler) if scheduler is not None else None
    start = time.perf_counter()
    try:
        table = run_samples(base, plan, method, tol.keep, [v.item for v in verdicts],
                            jobs=jobs, chunk=chunk, client=client, progress=progress,
                            lost=lost)
    finally:
        if client is not None:
            close_client(client)
    return analyse_samples(base, table, nominal, verdicts, method, why,
                           time.perf_counter() - start, lost)


def checked_nominal(base: BaseSpec, method: str, keep) -> tuple[Sample, list]:
    """The nominal sample and verdicts; ``MechreportError`` when the spec as written cannot
    be analysed (its tolerances would have nothing to be measured against), or when its
    force methods disagree as ``mechreport check`` judges them (every method solves the
    nominal design once: the samples' one method is vouched for there)."""
    from ..errors import MechreportError
    from ..pipeline import analyse
    nominal, verdicts = nominal_sample(base, method, keep)
    if nominal.status != "ok":
        raise MechreportError(f"{base.file}: the spec as written cannot be analysed "
                              f"({nominal.status}: {nominal.reason}); a tolerance analysis "
                              "needs the nominal design to work")
    full = analyse(variant_spec(base, {}))
    worst = full.worst
    if worst is not None and worst.relative > full.tol:
        raise MechreportError(f"{base.file}: the force methods disagree on the spec as "
                              f"written ({worst.quantity}: {worst.relative:.1e} relative, "
                              f"{worst.methods[0]} against {worst.methods[1]}, more than "
                              f"{full.tol:g}); see mechreport check before sampling it")
    return nominal, verdicts


def _base(spec) -> BaseSpec:
    """The tolerance :class:`BaseSpec` of a path, YAML text (more than one line) or a
    BaseSpec."""
    if isinstance(spec, BaseSpec):
        return spec
    if isinstance(spec, str) and "\n" in spec:
        from ..spec.loader import parse_source
        return tolerance_base(parse_source(spec, "<text>"))
    return load_tolerance_base(Path(spec))
