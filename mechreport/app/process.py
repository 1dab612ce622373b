"""Process set-up for the command line and its workers: done here, never on import.

Two settings make the batched small solves of an analysis fast. Both change only speed,
never a number, and both are set by :func:`set_up` at the start of ``mechreport`` and in
each worker process it starts.
"""
from __future__ import annotations

import os


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
