"""Worker processes that end with the command: their initialiser.

Ctrl-C or SIGTERM (:func:`.process.stop_requests`) stops the executor's pool, which
terminates its workers (:mod:`mechreport.study.executor`), and a worker whose parent has
died exits by itself within a second.
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
