"""Benchmark: what friction costs `check`. The same spec analysed with and without its
`friction:` entries (specs/crank_press_friction.yaml, and a 3600-angle sweep of it); the
issue's budget is 3 times the frictionless analysis.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python bench/bench_friction.py

Not a test: timings depend on the machine.
"""
from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import dataclasses  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

from mechreport.pipeline.analysis import analyse  # noqa: E402
from mechreport.spec import Design, Sweep, load_spec  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def best_of(fn, repeat: int = 7) -> float:
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)


def main() -> None:
    rubbed = load_spec(ROOT / "specs" / "crank_press_friction.yaml")
    for label, spec in (("1-degree sweep", rubbed),
                        ("0.1-degree sweep", dataclasses.replace(
                            rubbed, sweep=Sweep(0.0, 360.0, 0.1)))):
        # the design's efficiency limit needs friction: the frictionless twin has none
        plain = dataclasses.replace(spec, friction=(), design=Design())
        with_friction = best_of(lambda: analyse(spec))
        without = best_of(lambda: analyse(plain))
        print(f"{label:18s} without friction {without * 1e3:8.1f} ms, with friction "
              f"{with_friction * 1e3:8.1f} ms: x{with_friction / without:.2f}")


if __name__ == "__main__":
    main()
