"""Run a study's variants in chunks: in this process, on a local process pool (the default:
one worker per core), or on an existing Dask distributed cluster (``--scheduler ADDRESS``).

The plan is cut into chunks of consecutive variants; each task evaluates one chunk with
:func:`~mechreport.study.evaluate.evaluate_chunk` and returns its rows, which are stored in
plan order whatever the order they finish in. Only a bounded number of chunks is in flight at
once (a few per worker), so memory does not grow with the number of variants. The base spec
is sent to each worker once (pool initializer; Dask ``scatter``), a task carries only its
chunk's values.

Ctrl-C (or SIGTERM) stops everything: pool workers are terminated, Dask tasks cancelled (the
cluster itself keeps running), and the KeyboardInterrupt goes on to the caller.
"""
from __future__ import annotations

import math
import multiprocessing
import os
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait

import numpy as np

from ..errors import MechreportError
from ..study.evaluate import Row, evaluate_chunk
from ..study.plan import Plan
from ..study.table import Table
from ..study.variants import BaseSpec

#: chunks in flight per worker
IN_FLIGHT = 3
#: most variants per chunk chosen automatically (a few tenths of a second of work each)
MAX_AUTO_CHUNK = 100


class SchedulerError(MechreportError):
    """The Dask scheduler cannot be used (not installed, unreachable, no workers, versions)."""


def auto_chunk(n: int, workers: int) -> int:
    """Variants per chunk: about eight chunks per worker, at most ``MAX_AUTO_CHUNK``."""
    return max(1, min(MAX_AUTO_CHUNK, math.ceil(n / max(workers * 8, 1))))


def chunks(n: int, size: int) -> list[tuple[int, int]]:
    return [(a, min(a + size, n)) for a in range(0, n, size)]


def _rows_of(base: BaseSpec, keys: tuple[str, ...], values: np.ndarray, method: str,
             keep: tuple[str, ...]) -> list[Row]:
    variants = [{k: float(v) for k, v in zip(keys, row)} for row in values]
    return evaluate_chunk(base, variants, method, keep)


# ------------------------------------------------------------------------- in process

def run_serial(base: BaseSpec, plan: Plan, method: str, keep, size: int, table: Table,
               on_chunk) -> None:
    for a, b in chunks(plan.n, size):
        on_chunk(a, _rows_of(base, plan.keys, plan.values[a:b], method, tuple(keep)))


# ----------------------------------------------------------------------- process pool

_BASE: BaseSpec | None = None


def _pool_init(base: BaseSpec, parent: int) -> None:
    from .workers import worker_init
    global _BASE
    worker_init(parent)                 # Ctrl-C is the parent's; exit if the parent dies
    _BASE = base


def _pool_task(start: int, keys, values: np.ndarray, method: str, keep) -> tuple[int, list]:
    return start, _rows_of(_BASE, keys, values, method, keep)


def run_pool(base: BaseSpec, plan: Plan, method: str, keep, size: int, jobs: int,
             on_chunk) -> None:
    from .workers import stop_pool
    # fresh interpreters, as `mechreport build` does: forking a process whose BLAS or Typst
    # threads are running can deadlock the child
    ctx = multiprocessing.get_context("spawn")
    pool = ProcessPoolExecutor(max_workers=jobs, mp_context=ctx, initializer=_pool_init,
                               initargs=(base, os.getpid()))
    todo = iter(chunks(plan.n, size))
    keep = tuple(keep)
    try:
        running = set()

        def submit() -> bool:
            nxt = next(todo, None)
            if nxt is None:
                return False
            a, b = nxt
            running.add(pool.submit(_pool_task, a, plan.keys, plan.values[a:b], method, keep))
            return True

        for _ in range(jobs * IN_FLIGHT):
            if not submit():
                break
        while running:
            finished, _ = wait(running, return_when=FIRST_COMPLETED)
            for fut in finished:
                running.discard(fut)
                start, rows = fut.result()          # a dead worker raises: the study fails
                on_chunk(start, rows)
                submit()
    except BaseException:
        stop_pool(pool)
        raise
    pool.shutdown(wait=True)


# ------------------------------------------------------------------------------- Dask

def _dask_task(base: BaseSpec, start: int, keys, values: np.ndarray, method: str,
               keep) -> tuple[int, list]:
    return start, _rows_of(base, keys, values, method, keep)


def _worker_version() -> str:
    import mechreport
    return mechreport.__version__


def connect(address: str, timeout: float = 10.0, wait_workers: float = 30.0):
    """A Dask client of the scheduler at ``address`` (reached within ``timeout`` seconds)
    that has at least one worker (within ``wait_workers``) running this mechreport version;
    raises :class:`SchedulerError` saying what is wrong."""
    try:
        from distributed import Client
    except ImportError:
        raise SchedulerError("--scheduler needs Dask distributed: pip install "
                             "'mechreport[dask]' (here and on every worker)") from None
    try:
        client = Client(address, timeout=f"{timeout:g}s", set_as_default=False)
    except (OSError, TimeoutError, ValueError) as exc:
        raise SchedulerError(f"cannot reach the Dask scheduler at {address}: "
                             f"{' '.join(str(exc).split()) or type(exc).__name__}") from None
    try:
        try:
            client.wait_for_workers(1, timeout=wait_workers)
        except (TimeoutError, OSError):
            raise SchedulerError(f"the Dask scheduler at {address} has no workers (waited "
                                 f"{wait_workers:g} s); start some with `dask worker "
                                 f"{address}`") from None
        from ..version import __version__
        try:
            versions = client.run(_worker_version)
        except Exception as exc:  # noqa: BLE001 - e.g. mechreport not importable there
            raise SchedulerError(f"the Dask workers at {address} cannot run mechreport "
                                 f"({type(exc).__name__}: {exc}); install mechreport "
                                 f"{__version__} on every worker") from None
        wrong = {w: v for w, v in versions.items() if v != __version__}
        if wrong:
            listed = ", ".join(f"{w} has {v}" for w, v in sorted(wrong.items())[:3])
            raise SchedulerError(f"Dask workers run another mechreport version than this "
                                 f"one ({__version__}): {listed}; install the same version "
                                 "on every worker")
    except BaseException:
        client.close()
        raise
    return client


def dask_workers(client) -> int:
    """Threads over all workers of the cluster (how many tasks run at once)."""
    info = client.scheduler_info()
    workers = info.get("workers", {}) or {}
    return max(1, sum(int(w.get("nthreads", 1) or 1) for w in workers.values()))


def run_dask(client, base: BaseSpec, plan: Plan, method: str, keep, size: int,
             on_chunk) -> None:
    from distributed import as_completed
    keep = tuple(keep)
    slots = dask_workers(client) * IN_FLIGHT
    [base_future] = client.scatter([base], broadcast=True)
    todo = iter(chunks(plan.n, size))
    futures = []

    def submit(ac=None):
        nxt = next(todo, None)
        if nxt is None:
            return None
        a, b = nxt
        fut = client.submit(_dask_task, base_future, a, plan.keys, plan.values[a:b], method,
                            keep, pure=False, retries=1)
        futures.append(fut)
        if ac is not None:
            ac.add(fut)
        return fut

    try:
        first = [f for f in (submit() for _ in range(slots)) if f is not None]
        ac = as_completed(first, loop=client.loop)
        for fut in ac:
            start, rows = fut.result()
            on_chunk(start, rows)
            futures.remove(fut)
            fut.release()
            submit(ac)
    except BaseException:
        try:
            client.cancel(futures)
        except Exception:  # noqa: BLE001 - interrupted anyway
            pass
        raise
    finally:
        try:
            base_future.release()
        except Exception:  # noqa: BLE001
            pass


# ----------------------------------------------------------------------------- entry

def run_variants(base: BaseSpec, plan: Plan, method: str, keep, *, jobs: int | None = None,
                 chunk: int | None = None, scheduler: str | None = None, client=None,
                 progress=None) -> Table:
    """Evaluate every variant of ``plan``; the filled :class:`Table`. ``jobs``: local
    processes (default: the cores; 1 runs in this process); ``chunk``: variants per task
    (default :func:`auto_chunk`); ``scheduler`` (a Dask scheduler address) or ``client`` (a
    connected ``distributed.Client``) runs the chunks on that cluster instead. ``progress``:
    a :class:`~mechreport.study.progress.StudyProgress`."""
    keep = tuple(keep)
    table = Table(plan, keep, method)
    count = {"done": 0, "failed": 0}

    def on_chunk(start: int, rows: list[Row]) -> None:
        count["failed"] += table.put(start, rows)
        count["done"] += len(rows)
        if progress is not None:
            progress.update(count["done"], count["failed"])

    own = None
    if scheduler is not None and client is None:
        client = own = connect(scheduler)
    try:
        if client is not None:
            size = chunk or auto_chunk(plan.n, dask_workers(client))
            run_dask(client, base, plan, method, keep, size, on_chunk)
        else:
            jobs = max(1, jobs or os.cpu_count() or 1)
            size = chunk or auto_chunk(plan.n, jobs)
            n_chunks = math.ceil(plan.n / size)
            if jobs == 1 or n_chunks == 1:
                run_serial(base, plan, method, keep, size, table, on_chunk)
            else:
                run_pool(base, plan, method, keep, size, min(jobs, n_chunks), on_chunk)
    finally:
        if own is not None:
            own.close()
    if progress is not None:
        progress.close()
    return table
