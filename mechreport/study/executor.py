"""The executor: items ``0 .. n-1`` computed in chunks of consecutive items, in this process
or on a local process pool (one worker process per chunk in flight), with retries of lost
chunks, partial results and a stop request honoured between waits. Dask clusters run the
same chunks through :mod:`.cluster`; :mod:`.run` chooses between them (``run_chunks``).

A chunk ``(start, stop)`` is computed by ``task(shared, *args_of(chunk))`` in a worker;
``shared`` (a study's base spec) is sent to each worker once (the pool's initializer), a
task carries only its chunk's own arguments. Results arrive through ``on_done(chunk,
result)`` in this process, in the order the chunks finish.

**Local processes.** Each process is a pool of its own holding one chunk at a time, so a
process that dies (killed, out of memory, a crash in native code) loses exactly the chunk it
was computing: that chunk is computed again in a fresh process, up to ``MAX_TRIES`` times in
all, and the other chunks go on.

**Lost chunks.** A chunk lost for good becomes ``on_lost(start, stop, reason)``, the reason
saying why ("a worker process died while computing this variant (after 3 tries)"); after
``GIVE_UP_AFTER`` chunks in a row lost for good (and no chunk done in between) no more
chunks are started and the rest are lost with "not computed: ...". Without an ``on_lost`` a
lost chunk raises :class:`MechreportError`. A task that raises (a bug, not a failure the task
reports in its result) loses its chunk with that internal error, without retries.

**Stopping.** ``stop_check()`` (given by the caller: the command line's raises on Ctrl-C or
SIGTERM) is called at least every ``POLL_LOCAL`` seconds while waiting; whatever it (or
anything else) raises stops the run: pool workers are terminated and the exception goes on
to the caller. Nothing here prints, exits or touches signals: lines for the user go to
``notify(line)``.
"""
from __future__ import annotations

import multiprocessing
import os
import signal
from collections import deque
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from dataclasses import dataclass
from typing import Callable

from ..errors import MechreportError, internal_error

#: times a chunk is computed before its loss is final (the first try and two more)
MAX_TRIES = 3
#: chunks lost for good in a row (none done in between) after which the run stops
GIVE_UP_AFTER = 3
#: seconds between stop checks while local workers compute
POLL_LOCAL = 0.2

Chunk = tuple[int, int]


@dataclass(frozen=True)
class Words:
    """How the executor's lines and reasons name what it computes: ``item`` (one,
    "variant"), ``part`` (its jobs, "chunks"), ``run`` (the whole, "study"), ``kept`` (what
    is kept when it stops early) and ``label`` (a chunk's items for the user; default:
    ``variant(s) 3-4``)."""

    item: str = "variant"
    part: str = "chunks"
    run: str = "study"
    kept: str = "the rows computed are kept"
    label: Callable[[Chunk], str] | None = None

    def span(self, chunk: Chunk) -> str:
        """``variant(s) 3-4`` (1-based, as the user counts), or the ``label`` of ``chunk``."""
        if self.label is not None:
            return self.label(chunk)
        a, b = chunk
        return f"{self.item}(s) " + (f"{a + 1}" if b == a + 1 else f"{a + 1}-{b}")

    @property
    def worker_died(self) -> str:
        return f"a worker process died while computing this {self.item}"


STUDY_WORDS = Words()


@dataclass(frozen=True)
class Lost:
    """Items ``start`` to ``stop - 1`` could not be computed (a worker or the scheduler was
    lost, or the task raised): their rows are failed with ``reason``."""

    start: int
    stop: int
    reason: str

    @property
    def count(self) -> int:
        return self.stop - self.start


def chunks(n: int, size: int) -> list[Chunk]:
    """``(start, stop)`` of each chunk of up to ``size`` consecutive items of ``n``."""
    return [(a, min(a + size, n)) for a in range(0, n, size)]


def usable_cores() -> int:
    """The cores this process may run on (its CPU affinity where the system tells it)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):
        return max(1, os.cpu_count() or 1)


def lost_raises(start: int, stop: int, reason: str) -> None:
    """Without an ``on_lost``: a lost chunk fails the run."""
    raise MechreportError(f"variants {start + 1}-{stop}: {reason}")


def no_notes(line: str) -> None:
    """Without a ``notify``: the lines for the user are dropped."""


class Losses:
    """The retry book of one run: tries per chunk, chunks lost for good in a row."""

    def __init__(self, on_lost, notify, words: Words = STUDY_WORDS):
        self.tries: dict[Chunk, int] = {}
        self.in_a_row = 0
        self.on_lost = on_lost or lost_raises
        self.notify = notify or no_notes
        self.words = words

    def lost(self, chunk: Chunk, reason: str, event: str) -> bool:
        """``chunk`` was lost (``event`` says how, for the user); True when it is to be
        computed again, else it is lost for good with ``reason (after N tries)``."""
        n = self.tries[chunk] = self.tries.get(chunk, 0) + 1
        if n < MAX_TRIES and not self.give_up:
            self.notify(f"warning: {event} while computing {self.words.span(chunk)}; "
                        f"computing them again (try {n + 1} of {MAX_TRIES})")
            return True
        self.fail(chunk, f"{reason} (after {n} tr{'y' if n == 1 else 'ies'})")
        return False

    def fail(self, chunk: Chunk, reason: str) -> None:
        """``chunk`` is lost for good with ``reason``."""
        self.on_lost(chunk[0], chunk[1], reason)
        self.in_a_row += 1
        if self.in_a_row == GIVE_UP_AFTER:
            self.notify(f"error: {GIVE_UP_AFTER} {self.words.part} in a row could not be "
                        f"computed; the {self.words.run} stops here ({self.words.kept})")

    def done(self) -> None:
        self.in_a_row = 0

    @property
    def give_up(self) -> bool:
        return self.in_a_row >= GIVE_UP_AFTER

    def abandon(self, todo, reason: str | None = None) -> None:
        """The chunks of ``todo`` will not be computed: lost with ``reason``."""
        reason = reason or (f"not computed: the {self.words.run} stopped after "
                            f"{GIVE_UP_AFTER} {self.words.part} in a row could not be "
                            "computed")
        for a, b in todo:
            self.on_lost(a, b, reason)
        todo.clear()


# ------------------------------------------------------------------------- in process

def run_serial(task, shared, todo: list[Chunk], args_of, on_done, stop_check=None) -> None:
    """The chunks of ``todo`` one after the other in this process (what a task raises goes
    on to the caller)."""
    for chunk in todo:
        if stop_check is not None:
            stop_check()
        on_done(chunk, task(shared, *args_of(chunk)))


# ----------------------------------------------------------------------- process pool

_WORKER: dict = {}                      # in a pool's worker: its shared object


def _pool_init(shared, setup) -> None:
    if setup is not None:
        setup()                         # the caller's process set-up (the command line's)
    _WORKER["shared"] = shared


def _pool_call(task, args: tuple):
    return task(_WORKER["shared"], *args)


def run_pool(task, shared, todo: list[Chunk], args_of, jobs: int, on_done, on_lost=None,
             notify=None, stop_check=None, setup=None, words: Words = STUDY_WORDS,
             kept: list | None = None) -> None:
    """The chunks of ``todo`` on ``jobs`` worker processes, each a one-process pool computing
    one chunk at a time, so that a process that dies loses exactly its chunk (see the module
    docstring). ``setup()``: called first in each worker process (picklable). ``kept``: a
    list holding the worker pools from one run to the next (an optimisation's generations,
    with the same ``shared``): they are taken from it and left running in it; the caller
    ends them with :func:`stop_pools`."""
    from concurrent.futures.process import BrokenProcessPool

    # fresh interpreters: forking a process whose BLAS or Typst threads are running can
    # deadlock the child
    ctx = multiprocessing.get_context("spawn")
    todo = deque(todo)
    losses = Losses(on_lost, notify, words)
    pools: list[ProcessPoolExecutor | None] = kept if kept is not None else []
    pools.extend([None] * (jobs - len(pools)))
    running: dict = {}                      # future -> (slot, chunk)

    def start(slot: int) -> None:
        chunk = todo.popleft()
        for fresh in (False, True):
            if pools[slot] is None:
                pools[slot] = ProcessPoolExecutor(max_workers=1, mp_context=ctx,
                                                  initializer=_pool_init,
                                                  initargs=(shared, setup))
            try:
                fut = pools[slot].submit(_pool_call, task, args_of(chunk))
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
            finished, _ = wait(running, timeout=POLL_LOCAL, return_when=FIRST_COMPLETED)
            if stop_check is not None:
                stop_check()                # also while no chunk finishes
            for fut in finished:
                slot, chunk = running.pop(fut)
                try:
                    result = fut.result()
                except BrokenProcessPool:
                    how = exit_codes(pools[slot])
                    stop_pool(pools[slot])
                    pools[slot] = None
                    event = "a worker process died" + (f" ({how})" if how else "")
                    if losses.lost(chunk, words.worker_died, event):
                        todo.appendleft(chunk)
                    continue
                except Exception as exc:  # noqa: BLE001 - a bug: this chunk's rows say it
                    losses.fail(chunk, internal_error(exc, "the spec file"))
                    continue
                losses.done()
                on_done(chunk, result)
    except BaseException:
        stop_pools(pools)
        raise
    if kept is None:
        for pool in pools:
            if pool is not None:
                pool.shutdown(wait=True)


def stop_pools(pools: list) -> None:
    """Stop every pool of ``pools`` (see :func:`stop_pool`) and empty the list."""
    for pool in pools:
        if pool is not None:
            stop_pool(pool)
    pools.clear()


def stop_pool(pool) -> None:
    """Cancel what has not started in ``pool`` (a ProcessPoolExecutor) and terminate its
    workers (they must not outlive the run)."""
    import time
    procs = list((getattr(pool, "_processes", None) or {}).values())
    pool.shutdown(wait=False, cancel_futures=True)
    for p in procs:
        if p.is_alive():
            p.terminate()
    deadline = time.monotonic() + 3.0
    for p in procs:
        p.join(max(0.0, deadline - time.monotonic()))
        if p.is_alive():
            p.kill()
            p.join(1.0)


def exit_codes(pool) -> str:
    """How the worker processes of ``pool`` (a broken ProcessPoolExecutor) ended, for a
    message: "killed by SIGKILL", "exit status 1"; "" when not known."""
    said = []
    for p in list((getattr(pool, "_processes", None) or {}).values()):
        code = getattr(p, "exitcode", None)
        if code is None or code == 0:
            continue
        if code < 0:
            try:
                name = signal.Signals(-code).name
            except ValueError:
                name = f"signal {-code}"
            text = f"killed by {name}"
        else:
            text = f"exit status {code}"
        if text not in said:
            said.append(text)
    return ", ".join(said)
