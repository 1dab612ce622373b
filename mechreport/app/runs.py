"""What ``study``, ``tolerance`` and ``optimize`` share while they run: where the items go
(:func:`placement`: the Dask cluster or local processes), the Dask client
(:func:`cluster_client`), a stop's message (:func:`stop_said`) and the line about chunks
that could not be computed (:func:`lost_line`)."""
from __future__ import annotations

from contextlib import contextmanager


def placement(client, scheduler: str | None, n: int, jobs: int | None, chunk: int | None,
              err) -> tuple[int, int, str]:
    """Where ``n`` items run, for `study`, `tolerance` and `optimize`: the workers, the chunk
    size and the words for them: the Dask cluster of ``client`` (at ``scheduler``), else local
    processes (``--jobs``, saying on ``err`` why fewer were taken)."""
    from ..study.cluster import dask_workers
    from ..study.run import auto_chunk, local_jobs
    if client is not None:
        workers = dask_workers(client)
        return (workers, chunk or auto_chunk(n, workers),
                f"the Dask cluster at {scheduler} ({workers} worker thread(s))")
    workers, size, lowered = local_jobs(n, jobs, chunk)
    if lowered:
        print(f"--jobs {jobs}: using {workers} process(es), because {lowered}", file=err,
              flush=True)
    return workers, size, "this process" if workers == 1 else f"{workers} local processes"


@contextmanager
def stop_said(err, words, before=None):
    """Ctrl-C or SIGTERM inside the block: ``before()`` (a progress bar's line ended), then
    ``words()`` on ``err``, the stop marked as reported (the CLI adds nothing) and raised
    again. For `study`, `tolerance` and `optimize` alike."""
    try:
        yield
    except KeyboardInterrupt as exc:
        if before is not None:
            before()
        print(words(), file=err)
        exc.reported = True
        raise


@contextmanager
def cluster_client(scheduler: str | None, err):
    """The Dask client of ``scheduler`` (None: local processes), closed when the block ends
    however it ends, a trouble in closing said on ``err`` as a warning."""
    from ..study.cluster import close_client, connect
    client = connect(scheduler) if scheduler is not None else None
    try:
        yield client
    finally:
        trouble = close_client(client)
        if trouble:
            print(f"warning: {trouble}", file=err, flush=True)


def lost_line(lost, n: int, words=None) -> str:
    """One line about the chunks that could not be computed (``Lost`` entries), in
    ``words`` (the executor's :class:`~mechreport.study.executor.Words`; default: a
    study's)."""
    from ..study.executor import STUDY_WORDS
    w = words or STUDY_WORDS
    count = sum(x.count for x in lost)
    reasons: dict[str, int] = {}
    for x in lost:
        reasons[x.reason] = reasons.get(x.reason, 0) + x.count
    said = "; ".join(f"{k} {w.item}(s): {r}" for r, k in reasons.items())
    return (f"{count} of {n} {w.item}(s) could not be computed ({said}); the {w.run} was "
            "written with them as failed rows")
