"""mechreport: dynamic force analysis reports for planar linkages, from YAML specs.

Pipeline (one package per stage): ``spec`` (load, validate) -> ``model`` (graph, dyads,
loops) -> ``kinematics`` -> ``forces`` (one module per method) -> ``checks`` -> ``report``.
The public entry point is ``mechreport.analysis.analyse(path)``.
"""
import os as _os

# Batched small systems are solved one by one inside LAPACK; a second BLAS thread only adds
# overhead (measured: 0.6 us vs 2-7 us per angle for 8x8). Must be set before numpy loads.
_os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


def _keep_freed_memory() -> bool:
    """Let glibc keep freed memory for reuse instead of handing it back to the system at
    once (whether it was applied).

    By default glibc returns the top of its heap to the system whenever more than 128 KiB
    there is free, and serves arrays above its mmap threshold (128 KiB at first) with fresh
    pages: a batched solve's temporaries of a few hundred KiB then fault their pages in
    again on every call (measured: a 2x2 block's solve over 3600 angles took 590 us, 160 us
    with these settings; an analysis about 20 % less CPU). Up to 64 MiB of free heap is kept
    and arrays below 32 MiB come from the heap; a long check gives the free heap back between
    its passes (:func:`mechreport.streamed.give_back_free_memory`). Nothing is done where
    the C library is not glibc, or when ``MALLOC_TRIM_THRESHOLD_``,
    ``MALLOC_MMAP_THRESHOLD_`` or ``MECHREPORT_MALLOC=default`` is set in the environment."""
    env = _os.environ
    if env.get("MECHREPORT_MALLOC") == "default" or "MALLOC_TRIM_THRESHOLD_" in env \
            or "MALLOC_MMAP_THRESHOLD_" in env:
        return False
    try:
        import ctypes
        mallopt = ctypes.CDLL(None).mallopt
    except (OSError, AttributeError, TypeError):
        return False
    M_TRIM_THRESHOLD, M_MMAP_THRESHOLD = -1, -3
    return bool(mallopt(M_TRIM_THRESHOLD, 64 << 20)) and bool(mallopt(M_MMAP_THRESHOLD, 32 << 20))


_keep_freed_memory()

__version__ = "0.1.0"
