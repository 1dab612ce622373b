"""Worker processes that end with the command: initialiser, pool shutdown.

Ctrl-C or SIGTERM (:func:`.process.stop_requests`) stops a pool and terminates its workers,
and a worker whose parent has died exits by itself within a second.
"""
from __future__ import annotations

import os
import signal
import threading
import time


def worker_init(parent: int) -> None:
    """In each worker: the process set up as the command's own (:mod:`.process`), Ctrl-C
    left to the parent (the terminal sends it to every process of the group; the parent then
    terminates the workers), and an exit if the parent dies."""
    from .process import set_up
    set_up()
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    threading.Thread(target=_watch_parent, args=(parent,), daemon=True,
                     name="mechreport-parent-watch").start()


def _watch_parent(parent: int, every: float = 0.5) -> None:
    while True:
        time.sleep(every)
        if os.getppid() != parent:
            os._exit(1)                    # orphaned: the command is gone, stop writing


def stop_pool(pool) -> None:
    """Cancel what has not started in ``pool`` (a ProcessPoolExecutor) and terminate its
    workers (they must not outlive us)."""
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
    message: "killed by signal 9", "exit status 1"; "" when not known."""
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
