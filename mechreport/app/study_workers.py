"""Run a study's variants in chunks: in this process, on a local process pool (the default:
one worker per core), or on an existing Dask distributed cluster (``--scheduler ADDRESS``).

The plan is cut into chunks of consecutive variants; each task evaluates one chunk with
:func:`~mechreport.study.evaluate.evaluate_chunk` and returns its rows, which are stored in
plan order whatever the order they finish in. Only a bounded number of chunks is in flight at
once, so memory does not grow with the number of variants. The base spec is sent to each
worker once (pool initializer; Dask ``scatter``), a task carries only its chunk's values.

**Local processes.** At most one per usable core and one per chunk, whatever ``--jobs`` asks
(:func:`local_jobs` says why it lowered it). Each process is a pool of its own holding one
chunk at a time, so a process that dies (killed, out of memory, a crash in native code) loses
exactly the chunk it was computing: that chunk is computed again in a fresh process, up to
``MAX_TRIES`` times in all, and the other chunks go on.

**Dask.** A chunk whose task is lost (its worker died, or it was cancelled or could not be
reached: ``CancelledError``, ``KilledWorker``, ``CommClosedError``, ``OSError``,
``TimeoutError``) is submitted again, up to ``MAX_TRIES`` times in all (a ``KilledWorker``
is final at once: the scheduler has already tried it on several workers). When the cluster
has no worker for ``NO_WORKERS_WAIT`` seconds, or the connection to the scheduler is lost
(the client gives up reconnecting after its connect timeout), the chunks not done are not
computed. While the study talks to the cluster, log records of the Dask libraries that carry
a traceback are not printed (their message reaches the user as the one line the study prints
about the lost chunk or scheduler; MECHREPORT_DEBUG=1 prints them). A scheduler address is
checked for its form (``tcp://HOST:PORT`` or ``HOST:PORT``) before any connection is tried,
and the client is always closed by the study, never left to the garbage collector.

**Lost chunks.** A chunk lost for good, by either runner, becomes failed rows whose reason
says why ("a worker process died while computing this variant (after 3 tries)"); after
``GIVE_UP_AFTER`` chunks in a row lost for good (and no chunk done in between) the study
stops starting chunks and the rest are rows "not computed: ...". The rows computed are kept
either way, and every loss is recorded in the ``lost`` list given to :func:`run_variants`
(the command then writes the study and exits with status 1). A task that raises (a bug, not a
variant's failure: those are rows already) makes its chunk's rows failed with that internal
error, without retries.

Ctrl-C (or SIGTERM) stops everything: pool workers are terminated, Dask tasks cancelled (the
cluster itself keeps running), and the KeyboardInterrupt goes on to the caller.
"""
from __future__ import annotations

import logging
import math
import multiprocessing
import os
import queue
import re
import time
from collections import deque
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from contextlib import contextmanager
from dataclasses import dataclass

import numpy as np

from ..errors import MechreportError, internal_error
from ..study.evaluate import Row, evaluate_chunk, failed_row
from ..study.plan import Plan
from ..study.table import Table
from ..study.variants import BaseSpec

#: chunks in flight per Dask worker thread
IN_FLIGHT = 3
#: most variants per chunk chosen automatically (a few tenths of a second of work each)
MAX_AUTO_CHUNK = 100
#: times a chunk is computed before its loss is final (the first try and two more)
MAX_TRIES = 3
#: chunks lost for good in a row (none done in between) after which the study stops
GIVE_UP_AFTER = 3
#: seconds a Dask cluster may have no worker (or no scheduler connection) before the study
#: stops waiting for one
NO_WORKERS_WAIT = 30.0
#: seconds between checks of the Dask cluster while no chunk finishes
POLL = 2.0
#: seconds to fetch a finished chunk's rows from a Dask worker
FETCH_TIMEOUT = 60.0
#: seconds to close a Dask client
CLOSE_TIMEOUT = 5.0

WORKER_DIED = "a worker process died while computing this variant"
DASK_LOST = "the Dask task computing this variant was lost"
SCHEDULER_LOST = "not computed: the connection to the Dask scheduler was lost"


class SchedulerError(MechreportError):
    """The Dask scheduler cannot be used (not installed, unreachable, no workers, versions)."""


@dataclass(frozen=True)
class Lost:
    """Variants ``start`` to ``stop - 1`` could not be computed (a worker or the scheduler
    was lost, or the task raised): their rows are failed with ``reason``."""

    start: int
    stop: int
    reason: str

    @property
    def count(self) -> int:
        return self.stop - self.start


def auto_chunk(n: int, workers: int) -> int:
    """Variants per chunk: about eight chunks per worker, at most ``MAX_AUTO_CHUNK``."""
    return max(1, min(MAX_AUTO_CHUNK, math.ceil(n / max(workers * 8, 1))))


def chunks(n: int, size: int) -> list[tuple[int, int]]:
    return [(a, min(a + size, n)) for a in range(0, n, size)]


def usable_cores() -> int:
    """The cores this process may run on (its CPU affinity where the system tells it)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):
        return max(1, os.cpu_count() or 1)


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


def _rows_of(base: BaseSpec, keys: tuple[str, ...], values: np.ndarray, method: str,
             keep: tuple[str, ...]) -> list[Row]:
    variants = [{k: float(v) for k, v in zip(keys, row)} for row in values]
    return evaluate_chunk(base, variants, method, keep)


class _Losses:
    """The retry book of one run: tries per chunk, chunks lost for good in a row."""

    def __init__(self, on_lost, notify):
        self.tries: dict[tuple[int, int], int] = {}
        self.in_a_row = 0
        self.on_lost = on_lost
        self.notify = notify

    def lost(self, chunk: tuple[int, int], reason: str, event: str) -> bool:
        """``chunk`` was lost (``event`` says how, for the user); True when it is to be
        computed again, else its rows are failed with ``reason (after N tries)``."""
        n = self.tries[chunk] = self.tries.get(chunk, 0) + 1
        if n < MAX_TRIES and not self.give_up:
            self.notify(f"warning: {event} while computing variant(s) {_span(chunk)}; "
                        f"computing them again (try {n + 1} of {MAX_TRIES})")
            return True
        self.fail(chunk, f"{reason} (after {n} tr{'y' if n == 1 else 'ies'})")
        return False

    def fail(self, chunk: tuple[int, int], reason: str) -> None:
        """``chunk`` is lost for good: failed rows with ``reason``."""
        self.on_lost(chunk[0], chunk[1], reason)
        self.in_a_row += 1
        if self.in_a_row == GIVE_UP_AFTER:
            self.notify(f"error: {GIVE_UP_AFTER} chunks in a row could not be computed; the "
                        "study stops here (the rows computed are kept)")

    def done(self) -> None:
        self.in_a_row = 0

    @property
    def give_up(self) -> bool:
        return self.in_a_row >= GIVE_UP_AFTER

    def abandon(self, todo, reason: str | None = None) -> None:
        """The chunks of ``todo`` will not be computed: failed rows (``reason``)."""
        reason = reason or (f"not computed: the study stopped after {GIVE_UP_AFTER} chunks in "
                            "a row could not be computed")
        for a, b in todo:
            self.on_lost(a, b, reason)
        todo.clear()


def _span(chunk: tuple[int, int]) -> str:
    a, b = chunk
    return f"{a + 1}" if b == a + 1 else f"{a + 1}-{b}"


# ------------------------------------------------------------------------- in process

def run_serial(base: BaseSpec, plan: Plan, method: str, keep, size: int, on_chunk) -> None:
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
    return _dask_task(_BASE, start, keys, values, method, keep)


def run_pool(base: BaseSpec, plan: Plan, method: str, keep, size: int, jobs: int,
             on_chunk, on_lost=None, notify=None) -> None:
    """The chunks on ``jobs`` worker processes, each a one-process pool computing one chunk
    at a time, so that a process that dies loses exactly its chunk (see the module
    docstring); ``on_lost(start, stop, reason)`` for the chunks lost for good."""
    from concurrent.futures.process import BrokenProcessPool

    from .workers import exit_codes, stop_pool
    # fresh interpreters, as `mechreport build` does: forking a process whose BLAS or Typst
    # threads are running can deadlock the child
    ctx = multiprocessing.get_context("spawn")
    keep = tuple(keep)
    todo = deque(chunks(plan.n, size))
    losses = _Losses(on_lost or _lost_raises, notify or (lambda message: None))
    pools: list[ProcessPoolExecutor | None] = [None] * jobs
    running: dict = {}                      # future -> (slot, chunk)

    def start(slot: int) -> None:
        a, b = chunk = todo.popleft()
        for fresh in (False, True):
            if pools[slot] is None:
                pools[slot] = ProcessPoolExecutor(max_workers=1, mp_context=ctx,
                                                  initializer=_pool_init,
                                                  initargs=(base, os.getpid()))
            try:
                fut = pools[slot].submit(_pool_task, a, plan.keys, plan.values[a:b], method,
                                         keep)
                break
            except BrokenProcessPool:      # its process died between two chunks
                stop_pool(pools[slot])
                pools[slot] = None
                if fresh:
                    raise
        running[fut] = (slot, chunk)

    try:
        while todo or running:
            if losses.give_up:
                losses.abandon(todo)
            busy = {slot for slot, _ in running.values()}
            for slot in range(jobs):
                if todo and slot not in busy:
                    start(slot)
            if not running:
                break
            finished, _ = wait(running, return_when=FIRST_COMPLETED)
            for fut in finished:
                slot, chunk = running.pop(fut)
                try:
                    first, rows = fut.result()
                except BrokenProcessPool:
                    how = exit_codes(pools[slot])
                    stop_pool(pools[slot])
                    pools[slot] = None
                    event = "a worker process died" + (f" ({how})" if how else "")
                    if losses.lost(chunk, WORKER_DIED, event):
                        todo.appendleft(chunk)
                    continue
                except Exception as exc:  # noqa: BLE001 - a bug: this chunk's rows say it
                    losses.fail(chunk, internal_error(exc, "the spec file"))
                    continue
                losses.done()
                on_chunk(first, rows)
    except BaseException:
        for pool in pools:
            if pool is not None:
                stop_pool(pool)
        raise
    for pool in pools:
        if pool is not None:
            pool.shutdown(wait=True)


def _lost_raises(start: int, stop: int, reason: str) -> None:
    """Without an ``on_lost``: a lost chunk fails the run (the old behaviour)."""
    raise MechreportError(f"variants {start + 1}-{stop}: {reason}")


# ------------------------------------------------------------------------------- Dask

def _dask_task(base: BaseSpec, start: int, keys, values: np.ndarray, method: str,
               keep) -> tuple[int, list]:
    """One chunk's rows, with where they start (a Dask task; the pool's, with its base)."""
    return start, _rows_of(base, keys, values, method, keep)


def _worker_version() -> str:
    import mechreport
    return mechreport.__version__


_ADDRESS = re.compile(r"(?:tcp://)?(\[[0-9A-Fa-f:.]+\]|[A-Za-z0-9_][A-Za-z0-9_.-]*):([0-9]+)\Z")
_SCHEME_HINTS = {
    "tls": "tls:// needs TLS certificates, which mechreport does not set up; use the "
           "scheduler's tcp:// address",
    "http": "http:// is a web address (the dashboard's), not the scheduler's",
    "https": "https:// is a web address (the dashboard's), not the scheduler's",
    "inproc": "inproc:// reaches only a scheduler inside this same process",
    "ws": "ws:// is not supported; use the scheduler's tcp:// address",
    "wss": "wss:// is not supported; use the scheduler's tcp:// address",
    "ucx": "ucx:// is not supported; use the scheduler's tcp:// address",
}


def check_address(address: str) -> str:
    """``address`` as ``tcp://HOST:PORT`` when it is of the form ``tcp://HOST:PORT`` or
    ``HOST:PORT`` (a port from 1 to 65535); else :class:`SchedulerError` saying what is
    expected."""
    text = address.strip()
    if not text:
        raise SchedulerError("the Dask scheduler address is empty; expected tcp://HOST:PORT "
                             "or HOST:PORT, e.g. tcp://127.0.0.1:8786")
    m = _ADDRESS.match(text)
    if m is not None and 1 <= int(m.group(2)) <= 65535:
        return f"tcp://{m.group(1)}:{int(m.group(2))}"
    scheme, sep, rest = text.partition("://")
    if sep and scheme.lower() != "tcp":
        hint = _SCHEME_HINTS.get(scheme.lower(), f"{scheme}:// is not supported")
    elif m is not None:
        hint = f"port {m.group(2)} is not from 1 to 65535"
    elif ":" not in (rest if sep else text):
        hint = "no port given (a scheduler listens on port 8786 unless told otherwise)"
    else:
        hint = "not a host name or IP address followed by ':' and a port number"
    raise SchedulerError(f"{address!r} is not a Dask scheduler address: {hint}; expected "
                         "tcp://HOST:PORT or HOST:PORT, e.g. tcp://127.0.0.1:8786")


def close_client(client, timeout: float = CLOSE_TIMEOUT) -> str:
    """Close ``client`` within ``timeout`` seconds; "" or what went wrong. A client that
    cannot close is marked closed, so that its ``__del__`` does not try again (and print an
    'Exception ignored' traceback) when the interpreter exits."""
    if client is None:
        return ""
    try:
        with quiet_library_tracebacks():
            client.close(timeout=timeout)
        return ""
    except Exception as exc:  # noqa: BLE001 - said by the caller
        try:
            client.status = "closed"
        except Exception:  # noqa: BLE001
            pass
        return (f"the Dask client did not close within {timeout:g} s "
                f"({type(exc).__name__}: {' '.join(str(exc).split())})")


def connect(address: str, timeout: float = 10.0, wait_workers: float = 30.0):
    """A Dask client of the scheduler at ``address`` (``tcp://HOST:PORT`` or ``HOST:PORT``,
    reached within ``timeout`` seconds) that has at least one worker (within
    ``wait_workers``) running this mechreport version; raises :class:`SchedulerError` saying
    what is wrong. The client is closed on every failure."""
    try:
        from distributed import Client
    except ImportError:
        raise SchedulerError("--scheduler needs Dask distributed: pip install "
                             "'mechreport[dask]' (here and on every worker)") from None
    address = check_address(address)
    # the client object first, so that it can be closed here if connecting fails (else its
    # __del__ would close it at exit, waiting 20 s and printing a traceback)
    client = Client.__new__(Client)
    try:
        with quiet_library_tracebacks():
            client.__init__(address, timeout=f"{timeout:g}s", set_as_default=False)
    except BaseException as exc:
        close_client(client, min(timeout, CLOSE_TIMEOUT))
        if not isinstance(exc, Exception):
            raise
        said = " ".join(str(exc).split()) or type(exc).__name__
        if said.startswith("Timed out") or isinstance(exc, TimeoutError):
            said = (f"no answer within {timeout:g} s (is a scheduler running there? `dask "
                    "scheduler` prints its address)")
        raise SchedulerError(f"cannot reach the Dask scheduler at {address}: {said}") from None
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
        close_client(client)
        raise
    return client


def dask_workers(client) -> int:
    """Threads over all workers of the cluster (how many tasks run at once)."""
    info = client.scheduler_info()
    workers = info.get("workers", {}) or {}
    return max(1, sum(int(w.get("nthreads", 1) or 1) for w in workers.values()))


class _NoTracebacks(logging.Filter):
    def filter(self, record: logging.LogRecord) -> bool:
        return not record.exc_info and not record.stack_info


@contextmanager
def quiet_library_tracebacks():
    """Within: log records of Dask's libraries (distributed, tornado, asyncio) that carry a
    traceback are not printed; the study reports what they are about in one line. Nothing
    is held back with MECHREPORT_DEBUG=1."""
    if os.environ.get("MECHREPORT_DEBUG", "") not in ("", "0"):
        yield
        return
    names = [n for n in list(logging.root.manager.loggerDict)
             if n.split(".")[0] in ("distributed", "tornado", "asyncio")]
    handlers = {id(h): h for n in names for h in logging.getLogger(n).handlers}
    handlers.update({id(h): h for h in logging.root.handlers})
    if logging.lastResort is not None:
        handlers[id(logging.lastResort)] = logging.lastResort
    quiet = _NoTracebacks()
    for h in handlers.values():
        h.addFilter(quiet)
    try:
        yield
    finally:
        for h in handlers.values():
            h.removeFilter(quiet)


def _dask_lost_errors() -> tuple[type[BaseException], ...]:
    import asyncio
    from concurrent.futures import CancelledError

    from distributed.client import FutureCancelledError
    from distributed.comm import CommClosedError
    return (CancelledError, FutureCancelledError, CommClosedError, OSError, TimeoutError,
            asyncio.CancelledError)


def run_dask(client, spec: BaseSpec, plan: Plan, method: str, keep, size: int,
             on_chunk, on_lost=None, notify=None) -> None:
    """The chunks on the Dask cluster of ``client``, a few per worker thread in flight;
    lost tasks are submitted again, a lost scheduler or a cluster without workers ends the
    run with the rest not computed (see the module docstring)."""
    from distributed import KilledWorker
    lost_errors = _dask_lost_errors()
    keep = tuple(keep)
    notify = notify or (lambda message: None)
    losses = _Losses(on_lost or _lost_raises, notify)
    slots = dask_workers(client) * IN_FLIGHT
    todo = deque(chunks(plan.n, size))
    running: dict = {}                       # future -> chunk
    scattered: dict = {}                     # future -> the spec's scatter it uses
    finished: queue.Queue = queue.Queue()    # futures, as their tasks end (any way)
    base = {"future": None, "n": 0}          # the scattered spec, how many scatters so far

    def scatter() -> None:
        _release(base["future"])
        base["future"] = None
        # a fresh key each time: the old one may be lost with the workers that held it
        [base["future"]] = client.scatter([spec], broadcast=True, hash=False,
                                          timeout=NO_WORKERS_WAIT)
        base["n"] += 1

    def submit(chunk) -> None:
        a, b = chunk
        fut = client.submit(_dask_task, base["future"], a, plan.keys, plan.values[a:b],
                            method, keep, pure=False)
        running[fut] = chunk
        scattered[fut] = base["n"]
        fut.add_done_callback(finished.put)

    def stop(reason: str, event: str) -> None:
        n = sum(b - a for a, b in list(running.values()) + list(todo))
        notify(f"error: {event}; the {n} variant(s) not computed yet are marked "
               "'not computed'")
        for fut in list(running):
            _release(fut)
        losses.abandon(deque(sorted(list(running.values()) + list(todo))), reason)
        running.clear()

    at = _at(client)

    def scheduler_lost() -> None:
        stop(SCHEDULER_LOST, f"lost the connection to the Dask scheduler{at} (it did not "
                             "come back)")

    def no_workers() -> None:
        stop(f"not computed: the Dask cluster had no workers for {NO_WORKERS_WAIT:g} s",
             f"the Dask cluster has had no workers for {NO_WORKERS_WAIT:g} s")

    def connected() -> bool:
        """Whether the scheduler is there; waits (bounded) while the client reconnects."""
        deadline = time.monotonic() + NO_WORKERS_WAIT
        while client.status == "connecting" and time.monotonic() < deadline:
            time.sleep(0.1)
        return client.status == "running"

    def lost(fut, chunk, exc) -> bool:
        """A lost task: submitted again (its spec scattered again if it may be gone with
        its workers) or failed; False when the run cannot go on."""
        if not connected():
            running[fut] = chunk                 # marked with the rest
            scheduler_lost()
            return False
        why = " ".join(str(getattr(exc, "reason", None) or exc).split())[:200]
        why = f"{type(exc).__name__}: {why}" if why else type(exc).__name__
        if not losses.lost(chunk, f"{DASK_LOST}: {type(exc).__name__}",
                           f"a Dask task was lost ({why})"):
            return True
        todo.appendleft(chunk)
        if scattered.get(fut) == base["n"]:      # not scattered again since it was sent
            try:
                scatter()
            except lost_errors:
                if not connected():
                    scheduler_lost()
                else:
                    no_workers()
                return False
        return True

    idle_since = None
    try:
        with quiet_library_tracebacks():
            try:
                scatter()
            except lost_errors:
                if not connected():
                    scheduler_lost()
                    return
                raise SchedulerError("cannot send the spec to the Dask workers (no worker "
                                     f"took it within {NO_WORKERS_WAIT:g} s)") from None
            while todo or running:
                if losses.give_up:
                    losses.abandon(todo)
                if todo and len(running) < slots and not connected():
                    scheduler_lost()
                    break
                while todo and len(running) < slots:
                    submit(todo.popleft())
                if not running:
                    break
                try:
                    fut = finished.get(timeout=POLL)
                except queue.Empty:
                    # nothing finished for a while: is there still a cluster to wait for?
                    if not connected():
                        scheduler_lost()
                        break
                    try:
                        n_workers = len(client.nthreads())
                    except lost_errors:
                        n_workers = 0
                    if n_workers:
                        idle_since = None
                    elif idle_since is None:
                        idle_since = time.monotonic()
                        notify(f"warning: the Dask cluster has no workers; waiting up to "
                               f"{NO_WORKERS_WAIT:g} s for one")
                    elif time.monotonic() - idle_since > NO_WORKERS_WAIT:
                        no_workers()
                        break
                    continue
                chunk = running.pop(fut, None)
                if chunk is None:                # released already (stopped)
                    continue
                idle_since = None
                try:
                    first, rows = fut.result(timeout=FETCH_TIMEOUT)
                except KilledWorker:
                    losses.fail(chunk, "the Dask workers computing this variant died "
                                       "(KilledWorker: the scheduler tried it on several)")
                    continue
                except lost_errors as exc:
                    if not lost(fut, chunk, exc):
                        break
                    continue
                except Exception as exc:  # noqa: BLE001 - a bug: this chunk's rows say it
                    losses.fail(chunk, internal_error(exc, "the spec file"))
                    continue
                finally:
                    _release(fut)
                    scattered.pop(fut, None)
                losses.done()
                on_chunk(first, rows)
    except BaseException:
        try:
            client.cancel(list(running))
        except Exception:  # noqa: BLE001 - interrupted anyway
            pass
        raise
    finally:
        _release(base["future"])


def _at(client) -> str:
    try:
        return f" at {client.scheduler.address}"
    except Exception:  # noqa: BLE001 - only for a message
        return ""


def _release(fut) -> None:
    if fut is not None:
        try:
            fut.release()
        except Exception:  # noqa: BLE001 - the cluster may be gone
            pass


# ----------------------------------------------------------------------------- entry

def run_variants(base: BaseSpec, plan: Plan, method: str, keep, *, jobs: int | None = None,
                 chunk: int | None = None, scheduler: str | None = None, client=None,
                 progress=None, lost: list | None = None, notify=None) -> Table:
    """Evaluate every variant of ``plan``; the filled :class:`Table`. ``jobs``: local
    processes (default: the cores; at most the usable cores and the chunks, see
    :func:`local_jobs`; 1 runs in this process); ``chunk``: variants per task (default
    :func:`auto_chunk`); ``scheduler`` (a Dask scheduler address) or ``client`` (a connected
    ``distributed.Client``) runs the chunks on that cluster instead. ``progress``: a
    :class:`~mechreport.study.progress.StudyProgress`.

    ``lost``: a list that receives a :class:`Lost` for each chunk that could not be computed
    (its rows are failed rows with the reason); without it such a chunk raises
    :class:`MechreportError`. ``notify(line)``: called with a line for the user when a chunk
    is lost and computed again, or the run stops early (see the module docstring)."""
    keep = tuple(keep)
    table = Table(plan, keep, method)
    count = {"done": 0, "failed": 0}

    def on_chunk(start: int, rows: list[Row]) -> None:
        count["failed"] += table.put(start, rows)
        count["done"] += len(rows)
        if progress is not None:
            progress.update(count["done"], count["failed"])

    def record_lost(start: int, stop: int, reason: str) -> None:
        lost.append(Lost(start, stop, reason))
        on_chunk(start, [failed_row(len(keep), reason)] * (stop - start))
    on_lost = record_lost if lost is not None else None

    own = None
    if scheduler is not None and client is None:
        client = own = connect(scheduler)
    try:
        if client is not None:
            size = chunk or auto_chunk(plan.n, dask_workers(client))
            run_dask(client, base, plan, method, keep, size, on_chunk, on_lost, notify)
        else:
            jobs, size, _why = local_jobs(plan.n, jobs, chunk)
            if jobs == 1:
                run_serial(base, plan, method, keep, size, on_chunk)
            else:
                run_pool(base, plan, method, keep, size, jobs, on_chunk, on_lost, notify)
    finally:
        if own is not None:
            close_client(own)
    if progress is not None:
        progress.close()
    return table
