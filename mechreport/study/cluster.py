"""The chunks of a run on an existing Dask distributed cluster (``--scheduler ADDRESS``):
connecting to it, and running chunks there with the retries and partial results of
:mod:`.executor`.

A chunk whose task is lost (its worker died, or it was cancelled or could not be reached:
``CancelledError``, ``KilledWorker``, ``CommClosedError``, ``OSError``, ``TimeoutError``) is
submitted again, up to ``MAX_TRIES`` times in all (a ``KilledWorker`` is final at once: the
scheduler has already tried it on several workers). When the cluster has no worker for
``NO_WORKERS_WAIT`` seconds, or the connection to the scheduler is lost (the client gives up
reconnecting after its connect timeout), the chunks not done are not computed. While the run
talks to the cluster, log records of the Dask libraries that carry a traceback are not
printed (their message reaches the user as the one line given to ``notify`` about the lost
chunk or scheduler; MECHREPORT_DEBUG=1 prints them). A scheduler address is checked for its
form (``tcp://HOST:PORT`` or ``HOST:PORT``) before any connection is tried, and a client is
closed by whoever connected it (:func:`close_client`), never left to the garbage collector.

A stop (``stop_check()`` raising, or KeyboardInterrupt) cancels the run's tasks; the
cluster itself keeps running.
"""
from __future__ import annotations

import logging
import os
import queue
import re
import time
from collections import deque
from contextlib import contextmanager

from ..errors import MechreportError, internal_error
from .executor import STUDY_WORDS, Losses, Words

#: chunks in flight per Dask worker thread
IN_FLIGHT = 3
#: seconds a Dask cluster may have no worker (or no scheduler connection) before the run
#: stops waiting for one
NO_WORKERS_WAIT = 30.0
#: seconds between checks of the Dask cluster while no chunk finishes
POLL = 2.0
#: seconds to fetch a finished chunk's result from a Dask worker
FETCH_TIMEOUT = 60.0
#: seconds to close a Dask client
CLOSE_TIMEOUT = 5.0

SCHEDULER_LOST = "not computed: the connection to the Dask scheduler was lost"


class SchedulerError(MechreportError):
    """The Dask scheduler cannot be used (not installed, unreachable, no workers, versions)."""


def dask_lost(words: Words = STUDY_WORDS) -> str:
    """The reason of a chunk whose Dask task was lost (and its exception type follows)."""
    return f"the Dask task computing this {words.item} was lost"


#: the reason of a lost Dask task in a study
DASK_LOST = dask_lost()


def _worker_version() -> str:
    """The mechreport version a Dask worker runs (a task sent to every worker)."""
    from ..version import __version__
    return __version__


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


def run_dask(client, task, shared, todo, args_of, on_done, on_lost=None, notify=None,
             stop_check=None, words: Words = STUDY_WORDS) -> None:
    """The chunks of ``todo`` on the Dask cluster of ``client``: ``task(shared,
    *args_of(chunk))`` each (``shared`` scattered to every worker once), a few per worker
    thread in flight, ``on_done(chunk, result)`` as each finishes; lost tasks are submitted
    again, a lost scheduler or a cluster without workers ends the run with the rest not
    computed (see the module docstring and :mod:`.executor`)."""
    from distributed import KilledWorker
    lost_errors = _dask_lost_errors()
    losses = Losses(on_lost, notify, words)
    notify = losses.notify
    slots = dask_workers(client) * IN_FLIGHT
    todo = deque(todo)
    running: dict = {}                       # future -> chunk
    scattered: dict = {}                     # future -> the spec's scatter it uses
    finished: queue.Queue = queue.Queue()    # futures, as their tasks end (any way)
    base = {"future": None, "n": 0}          # the scattered spec, how many scatters so far

    def scatter() -> None:
        _release(base["future"])
        base["future"] = None
        # a fresh key each time: the old one may be lost with the workers that held it
        [base["future"]] = client.scatter([shared], broadcast=True, hash=False,
                                          timeout=NO_WORKERS_WAIT)
        base["n"] += 1

    def submit(chunk) -> None:
        fut = client.submit(task, base["future"], *args_of(chunk), pure=False)
        running[fut] = chunk
        scattered[fut] = base["n"]
        fut.add_done_callback(finished.put)

    def stop(reason: str, event: str) -> None:
        n = sum(b - a for a, b in list(running.values()) + list(todo))
        notify(f"error: {event}; the {n} {words.item}(s) not computed yet are marked "
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
        if not losses.lost(chunk, f"{dask_lost(words)}: {type(exc).__name__}",
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
                    if stop_check is not None:
                        stop_check()
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
                if stop_check is not None:
                    stop_check()
                chunk = running.pop(fut, None)
                if chunk is None:                # released already (stopped)
                    continue
                idle_since = None
                try:
                    result = fut.result(timeout=FETCH_TIMEOUT)
                except KilledWorker:
                    losses.fail(chunk, f"the Dask workers computing this {words.item} died "
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
                on_done(chunk, result)
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
