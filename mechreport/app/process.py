"""Process set-up for the command line and its workers: done here, never on import.

Two settings make the batched small solves of an analysis fast. Both change only speed,
never a number, and both are set by :func:`set_up` at the start of ``mechreport`` and in
each worker process it starts.

Stop requests (Ctrl-C, SIGTERM) while a command runs: :func:`stop_requests`.
"""
from __future__ import annotations

import os
import signal
import sys
import threading
from contextlib import contextmanager


def set_up() -> None:
    """Everything below, for a process that runs analyses."""
    one_blas_thread()
    keep_freed_memory()


def one_blas_thread() -> None:
    """``OPENBLAS_NUM_THREADS=1`` unless the user set it: batched small systems are solved
    one by one inside LAPACK, and a second BLAS thread only adds overhead (measured: 0.6 us
    against 2-7 us per angle for an 8x8 system). Takes effect only before numpy loads: the
    command line calls it first thing, and worker processes inherit it."""
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


def keep_freed_memory() -> bool:
    """Let glibc keep freed memory for reuse instead of handing it back to the system at
    once (whether it was applied).

    By default glibc returns the top of its heap to the system whenever more than 128 KiB
    there is free, and serves arrays above its mmap threshold (128 KiB at first) with fresh
    pages: a batched solve's temporaries of a few hundred KiB then fault their pages in
    again on every call (measured: a 2x2 block's solve over 3600 angles took 590 us, 160 us
    with these settings; an analysis about 20 % less CPU). Up to 64 MiB of free heap is kept
    and arrays below 32 MiB come from the heap; a long check gives the free heap back between
    its passes (:func:`give_back_free_memory`). Nothing is done where the C library is not
    glibc, or when ``MALLOC_TRIM_THRESHOLD_``, ``MALLOC_MMAP_THRESHOLD_`` or
    ``MECHREPORT_MALLOC=default`` is set in the environment."""
    env = os.environ
    if env.get("MECHREPORT_MALLOC") == "default" or "MALLOC_TRIM_THRESHOLD_" in env \
            or "MALLOC_MMAP_THRESHOLD_" in env:
        return False
    mallopt = _libc("mallopt")
    if mallopt is None:
        return False
    M_TRIM_THRESHOLD, M_MMAP_THRESHOLD = -1, -3
    return bool(mallopt(M_TRIM_THRESHOLD, 64 << 20)) and bool(mallopt(M_MMAP_THRESHOLD, 32 << 20))


def give_back_free_memory() -> None:
    """Return the heap's free pages to the system (glibc's ``malloc_trim``; nothing elsewhere).

    Memory a pass of a streamed check frees stays in the process: the allocator keeps it for
    reuse, and a heap fragmented by many chunk-sized arrays keeps most of it (measured: 116 of
    the 128 MB resident after pass 1 of a million-angle sweep was free). The next phase has
    other shapes and allocates afresh, so the peak would hold both. Called between phases
    only (``check_sweep(between_phases=...)``): pages given back cost a fault each when
    touched again."""
    trim = _libc("malloc_trim")
    if trim is not None:
        trim(0)


def _libc(name: str):
    """The C library's function ``name``, or None where there is none (not glibc)."""
    try:
        import ctypes
        return getattr(ctypes.CDLL(None), name)
    except (OSError, AttributeError, TypeError):
        return None


# ------------------------------------------------------------------------- stop requests
#
# A signal handler's exception is raised wherever the main thread happens to be. When that is
# a finaliser or a weak-reference callback (``WeakSet._remove`` during garbage collection),
# Python prints "Exception ignored in ..." and carries on: the stop was lost and the build
# finished with exit status 0 (about 1 SIGTERM in 21). So a request is also recorded, and
# raised again at safe points (:func:`check_stop`: between a build's stages and specs, before
# a folder is swapped in, before a command reports success); a folder swap holds requests
# until both of its renames are done (:func:`held_stops`).

class Terminated(KeyboardInterrupt):
    """SIGTERM, handled like Ctrl-C."""


_requested: int | None = None       # the first stop request's signal (SIGINT or SIGTERM)
_holding = 0                        # > 0 inside held_stops(): record, do not raise
_active = False                     # stop_requests() is in place


def _stop_exception(signum: int) -> KeyboardInterrupt:
    return Terminated() if signum == signal.SIGTERM else KeyboardInterrupt()


def _on_stop(signum, frame) -> None:
    global _requested
    if _requested is None:
        _requested = signum
    if not _holding:
        raise _stop_exception(signum)


def stop_requested() -> int | None:
    """The signal of the first stop request of the running command (None: none came)."""
    return _requested


def check_stop() -> None:
    """A safe point: raise the stop request (KeyboardInterrupt, :class:`Terminated` for
    SIGTERM) if one came, even if its first exception was lost."""
    if _requested is not None and not _holding:
        raise _stop_exception(_requested)


@contextmanager
def held_stops():
    """A stop request inside the block is raised when the block ends, not in it (two renames
    that must both happen, or neither)."""
    global _holding
    _holding += 1
    try:
        yield
    finally:
        _holding -= 1
    check_stop()


def _quiet_lost_stop(previous):
    """An unraisable-exception hook that says nothing of a stop request's exception (Python
    could not raise it where it landed: :func:`check_stop` raises it again)."""
    def hook(unraisable) -> None:
        if _requested is not None and isinstance(unraisable.exc_value, KeyboardInterrupt):
            return
        previous(unraisable)
    return hook


@contextmanager
def stop_requests(then_default: bool = False):
    """While the block runs (in the main thread), SIGINT raises KeyboardInterrupt and SIGTERM
    :class:`Terminated`, and each request is recorded for :func:`check_stop`; the previous
    handlers are restored afterwards, or with ``then_default`` (a process that ends with the
    command) set to the system's default: a request that comes after the command ended its
    work ends the process by that signal, which a shell reports as 130 or 143 too. A signal
    the process was started ignoring stays ignored. Inside another ``stop_requests()`` block
    it changes nothing."""
    global _requested, _holding, _active
    if _active or threading.current_thread() is not threading.main_thread():
        yield                                   # already in place (or not possible)
        return
    previous = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM)}
    wanted = [s for s, h in previous.items() if h is not signal.SIG_IGN]   # nohup, `cmd &`
    hook = sys.unraisablehook
    _requested, _holding = None, 0
    sys.unraisablehook = _quiet_lost_stop(hook)
    for s in wanted:
        signal.signal(s, _on_stop)
    _active = True
    try:
        yield
    finally:
        for s in wanted:
            back = previous[s] if previous[s] is not None and not then_default else signal.SIG_DFL
            signal.signal(s, back)
        sys.unraisablehook = hook
        _requested, _holding, _active = None, 0, False
