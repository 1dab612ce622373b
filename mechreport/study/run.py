"""Running a study: its variants cut into chunks and computed by the executor, in this
process, on a local process pool (the default: one worker per core) or on an existing Dask
distributed cluster; and :func:`run_study`, the Python entry point.

    from mechreport import run_study
    table = run_study("specs/four_bar.yaml", jobs=2)
    table.columns()["cycle.torque.rms [N·m]"]          # one value per variant

The plan is cut into chunks of consecutive variants; each task evaluates one chunk with
:func:`~mechreport.study.evaluate.evaluate_chunk` and returns its rows, which are stored in
plan order whatever the order they finish in. Only a bounded number of chunks is in flight at
once, so memory does not grow with the number of variants. Local processes: at most one per
usable core and one per chunk, whatever ``jobs`` asks (:func:`local_jobs` says why it lowered
it). Lost chunks are computed again, and lost for good they become failed rows saying why
(:mod:`.executor`, :mod:`.cluster`).
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .evaluate import Row, evaluate_chunk, failed_row
from .executor import STUDY_WORDS, Lost, chunks, run_pool, run_serial, usable_cores
from .plan import Plan
from .table import Table
from .variants import BaseSpec

#: most variants per chunk chosen automatically (a few tenths of a second of work each)
MAX_AUTO_CHUNK = 100

__all__ = ["run_study", "run_variants", "run_chunks", "auto_chunk", "local_jobs", "Lost"]


def auto_chunk(n: int, workers: int) -> int:
    """Variants per chunk: about eight chunks per worker, at most ``MAX_AUTO_CHUNK``."""
    return max(1, min(MAX_AUTO_CHUNK, math.ceil(n / max(workers * 8, 1))))


def local_jobs(n: int, jobs: int | None, chunk: int | None) -> tuple[int, int, str]:
    """(processes, variants per chunk, why) for ``n`` variants on this machine: ``jobs``
    (default: the cores) but at most one process per usable core and one per chunk; ``why``
    says why fewer processes than ``jobs`` asked for are used ("" when not lowered or
    ``jobs`` is None)."""
    cores = usable_cores()
    workers = max(1, min(jobs or cores, cores))
    size = chunk or auto_chunk(n, workers)
    n_chunks = max(1, math.ceil(n / size))
    why = ""
    if jobs is not None and jobs > cores:
        why = (f"this machine has {cores} usable core(s), and more processes than cores only "
               "cost memory and time")
    if n_chunks < workers:
        workers = n_chunks
        if jobs is not None:
            why = (f"the study has {n_chunks} chunk(s) of up to {size} variant(s), one process "
                   "each at most" + (f"; this machine has {cores} usable core(s)"
                                     if jobs > cores else ""))
    return workers, size, why


def chunk_task(base: BaseSpec, start: int, keys, values: np.ndarray, method: str,
               keep) -> tuple[int, list[Row]]:
    """One chunk's rows, with where they start (the task a worker runs)."""
    variants = [{k: float(v) for k, v in zip(keys, row)} for row in values]
    return start, evaluate_chunk(base, variants, method, tuple(keep))


def run_chunks(task, shared, n: int, size: int, args_of, on_done, *, jobs: int = 1,
               client=None, on_lost=None, notify=None, stop_check=None, setup=None,
               words=STUDY_WORDS, kept: list | None = None) -> None:
    """The executor: items ``0 .. n-1`` in chunks of ``size``, ``task(shared,
    *args_of(chunk))`` each, on the Dask cluster of ``client``, else on ``jobs`` local
    processes (1: in this process); ``on_done(chunk, result)`` as each finishes. Retries,
    lost chunks (``on_lost(start, stop, reason)``), ``notify``, ``stop_check`` and
    ``setup``: :mod:`.executor`; ``kept``: local pools kept between runs
    (:func:`~.executor.run_pool`)."""
    todo = chunks(n, size)
    if client is not None:
        from .cluster import run_dask
        run_dask(client, task, shared, todo, args_of, on_done, on_lost, notify, stop_check,
                 words)
    elif jobs <= 1:
        run_serial(task, shared, todo, args_of, on_done, stop_check)
    else:
        run_pool(task, shared, todo, args_of, jobs, on_done, on_lost, notify, stop_check,
                 setup, words, kept)


def run_variants(base: BaseSpec, plan: Plan, method: str, keep, *, jobs: int | None = None,
                 chunk: int | None = None, scheduler: str | None = None, client=None,
                 progress=None, lost: list | None = None, notify=None, stop_check=None,
                 setup=None) -> Table:
    """Evaluate every variant of ``plan``; the filled :class:`Table`. ``jobs``: local
    processes (default: the cores; at most the usable cores and the chunks, see
    :func:`local_jobs`; 1 runs in this process); ``chunk``: variants per task (default
    :func:`auto_chunk`); ``scheduler`` (a Dask scheduler address) or ``client`` (a connected
    ``distributed.Client``) runs the chunks on that cluster instead. ``progress(done,
    failed)``: called with running totals as chunks finish.

    ``lost``: a list that receives a :class:`Lost` for each chunk that could not be computed
    (its rows are failed rows with the reason); without it such a chunk raises
    :class:`~mechreport.errors.MechreportError`. ``notify(line)``: called with a line for the
    user when a chunk is lost and computed again, or the run stops early. ``stop_check()``:
    called while waiting, raises to stop the run; ``setup()``: run first in each local worker
    process (see :mod:`.executor`)."""
    from .cluster import close_client, connect, dask_workers
    keep = tuple(keep)
    table = Table(plan, keep, method)
    count = {"done": 0, "failed": 0}

    def on_done(chunk, result) -> None:
        start, rows = result
        count["failed"] += table.put(start, rows)
        count["done"] += len(rows)
        if progress is not None:
            progress(count["done"], count["failed"])

    def record_lost(start: int, stop: int, reason: str) -> None:
        lost.append(Lost(start, stop, reason))
        on_done(None, (start, [failed_row(len(keep), reason)] * (stop - start)))
    on_lost = record_lost if lost is not None else None

    def args_of(chunk) -> tuple:
        a, b = chunk
        return a, plan.keys, plan.values[a:b], method, keep

    own = None
    if scheduler is not None and client is None:
        client = own = connect(scheduler)
    try:
        if client is not None:
            size, jobs = chunk or auto_chunk(plan.n, dask_workers(client)), 0
        else:
            jobs, size, _why = local_jobs(plan.n, jobs, chunk)
        run_chunks(chunk_task, base, plan.n, size, args_of, on_done, jobs=jobs,
                   client=client, on_lost=on_lost, notify=notify, stop_check=stop_check,
                   setup=setup)
    finally:
        if own is not None:
            close_client(own)
    return table


def run_study(spec, *, jobs: int | None = None, scheduler: str | None = None,
              method: str | None = None, chunk: int | None = None, progress=None) -> Table:
    """Run the study of ``spec`` (a spec file's path, its YAML text, or a
    :class:`~mechreport.study.variants.BaseSpec`; it needs a ``study:`` section) as
    ``mechreport study`` does, and return its :class:`~mechreport.study.table.Table`: the
    rows, columns and values that command writes to study.csv and study.parquet
    (``table.columns()``: column name -> one value per variant; ``mechreport.study.outputs``
    writes the files). ``jobs``, ``scheduler`` (a Dask scheduler address), ``method`` (default:
    the fastest that gives every kept quantity and design verdict) and ``chunk``: as the
    command's options. ``progress(done, failed)``: called with running totals.

    Variants that cannot be analysed, or whose chunk was lost (a worker process or the
    cluster died), are failed rows saying why; nothing is printed. Raises ``SpecError`` for a
    spec that is not valid or has no study, ``MechreportError`` for a method that cannot give
    the kept quantities or a scheduler that cannot be used, and KeyboardInterrupt when
    interrupted (the local workers are stopped)."""
    from .methods import choose_method
    from .plan import plan_of
    base = _base(spec)
    study = base.spec.study
    method, _why = choose_method(method, study.keep, base.spec.design, named="method")
    return run_variants(base, plan_of(study), method, study.keep, jobs=jobs, chunk=chunk,
                        scheduler=scheduler, progress=progress, lost=[])


def _base(spec) -> BaseSpec:
    """The :class:`BaseSpec` of a path, YAML text (more than one line) or a BaseSpec."""
    from .variants import load_base, study_base
    if isinstance(spec, BaseSpec):
        return spec
    if isinstance(spec, str) and "\n" in spec:
        from ..spec.loader import parse_source
        return study_base(parse_source(spec, "<text>"))
    return load_base(Path(spec))
