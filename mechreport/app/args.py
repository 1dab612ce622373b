"""The command line's argument types (each refuses a bad value with 'must be ..., got ...')
and the options several commands share: where a run's chunks go (``study``, ``tolerance``,
``optimize``) and how long to wait for the output folder. Light: the parsers import nothing
of the pipeline (``--help`` stays free of numpy)."""
from __future__ import annotations

import argparse
import math
import textwrap


def checked(convert, ok, what: str):
    """An argparse type: ``convert`` the text, then require ``ok``; else 'must be what'."""
    def parse(text: str):
        try:
            value = convert(text)
        except ValueError:
            value = None
        if value is None or not ok(value):
            raise argparse.ArgumentTypeError(f"must be {what}, got {text!r}")
        return value
    return parse


int_at_least_0 = checked(int, lambda v: v >= 0, "a whole number >= 0")
int_at_least_1 = checked(int, lambda v: v >= 1, "a whole number >= 1")
finite_number = checked(float, math.isfinite, "a finite number")
number_above_0 = checked(float, lambda v: math.isfinite(v) and v > 0, "a finite number > 0")
seconds = checked(float, lambda v: math.isfinite(v) and v >= 0, "a number of seconds >= 0")


def filled(text: str, width: int = 79) -> str:
    """``text``'s paragraphs (separated by blank lines) filled to ``width`` columns: a
    terminal of 80 columns shows help text without wrapping it again."""
    return "\n\n".join(textwrap.fill(" ".join(par.split()), width)
                       for par in text.split("\n\n"))


def add_run_options(p: argparse.ArgumentParser, item: str, *, method: bool = True,
                    chunk: bool = True) -> None:
    """``--method`` (if ``method``), ``--scheduler``, ``--jobs`` and ``--chunk`` (if
    ``chunk``) of a command that runs many ``item``s ("variant", "sample") on the executor."""
    from ..quantities import METHOD_NAMES     # (not the methods: no solver on start-up)
    if method:
        p.add_argument("--method", choices=list(METHOD_NAMES), default=None,
                       help=f"the force method for every {item} (default: the fastest that "
                       "gives every kept quantity and design verdict)")
    p.add_argument("--scheduler", metavar="ADDRESS", default=None,
                   help="run on an existing Dask cluster at tcp://HOST:PORT or HOST:PORT, e.g. "
                   "tcp://127.0.0.1:8786 (needs mechreport[dask]); default: a local process "
                   "pool")
    p.add_argument("--jobs", type=int_at_least_1, default=None,
                   help="local processes, >= 1 (default: cores; ignored with --scheduler)")
    if chunk:
        p.add_argument("--chunk", type=int_at_least_1, default=None, metavar="N",
                       help=f"{item}s per task, >= 1 (default: about 8 tasks per worker, at "
                       f"most 100 {item}s each)")


def add_wait(p: argparse.ArgumentParser) -> None:
    """``--wait``: how long a command waits for another one writing to its output folder."""
    p.add_argument("--wait", type=seconds, default=120.0, metavar="SECONDS",
                   help="how long to wait for another command writing to the same output "
                   "folder (default 120)")
