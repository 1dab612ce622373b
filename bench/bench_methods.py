"""Benchmark: microseconds per crank angle for each force method on a 3600-angle sweep of
specs/r_rtr_rtr.yaml, and the wall time of `mechreport check specs` (interpreter included).

    make bench        (or: OPENBLAS_NUM_THREADS=1 .venv/bin/python bench/bench_methods.py)

Not a test: timings depend on the machine. One BLAS thread is faster for batched small
systems (each is solved on its own); the Makefile and CLI set it.
"""
from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import dataclasses  # noqa: E402
import statistics  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

from mechreport.pipeline.analysis import analyse  # noqa: E402
from mechreport.forces import METHODS, ForceContext  # noqa: E402
from mechreport.post import review  # noqa: E402
from mechreport.kinematics import solve_kinematics  # noqa: E402
from mechreport.model import build_mechanism  # noqa: E402
from mechreport.spec import Sweep, load_spec  # noqa: E402
from mechreport.spec.loader import parse_spec  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def best_of(fn, repeat: int = 7) -> float:
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times), statistics.median(times)


def fixed_cost(spec, repeat: int = 40) -> list[float]:
    """CPU seconds of load + analyse of a 36-angle sweep, ``repeat`` times. Measured first,
    in a fresh process: after the long sweeps the allocator's state adds a few ms."""
    text = (ROOT / "specs" / "r_rtr_rtr.yaml").read_text()
    short = Sweep(0.0, 360.0, 10.0)

    def fixed() -> None:
        s = parse_spec(text, "r_rtr_rtr.yaml")
        analyse(dataclasses.replace(s, sweep=short, at=(30.0,), expect=()))
    times = []
    for _ in range(repeat):
        t = time.process_time()
        fixed()
        times.append(time.process_time() - t)
    return times


def main() -> None:
    spec = load_spec(ROOT / "specs" / "r_rtr_rtr.yaml")
    times = fixed_cost(spec)
    spec = dataclasses.replace(spec, sweep=Sweep(0.0, 360.0, 0.1), at=(30.0,), expect=())
    mech = build_mechanism(spec)
    kin = solve_kinematics(mech)
    n = kin.n
    print(f"r_rtr_rtr, {n} crank angles, OPENBLAS_NUM_THREADS="
          f"{os.environ.get('OPENBLAS_NUM_THREADS')}")
    print(f"{'stage':<28}{'best us/angle':>15}{'median us/angle':>17}")
    b, m = best_of(lambda: solve_kinematics(mech))
    print(f"{'kinematics':<28}{b / n * 1e6:>15.2f}{m / n * 1e6:>17.2f}")
    b, m = best_of(lambda: ForceContext(dataclasses.replace(kin)))
    print(f"{'force context (loads)':<28}{b / n * 1e6:>15.2f}{m / n * 1e6:>17.2f}")
    for name, module in METHODS.items():
        # a fresh context each time: its own points and actions (the contour plan, kept per
        # structure, is replayed)
        contexts = [ForceContext(dataclasses.replace(kin)) for _ in range(7)]
        b, m = best_of(lambda: module.solve(contexts.pop()))
        print(f"{name:<28}{b / n * 1e6:>15.2f}{m / n * 1e6:>17.2f}")
    a = analyse(spec)
    post, post_m = best_of(lambda: review(a, 0.02))
    print(f"{'post (cycle review)':<28}{post / n * 1e6:>15.2f}{post_m / n * 1e6:>17.2f}")
    total, total_m = best_of(lambda: analyse(spec), repeat=3)
    print(f"{'analyse (all, with post)':<28}{total / n * 1e6:>15.2f}{total_m / n * 1e6:>17.2f}")
    print(f"post stage: {post / (total - post) * 100:.1f} % of the analysis without it")
    print(f"fixed cost (load + analyse, 36 angles): best {min(times) * 1e3:.1f} ms, "
          f"median {statistics.median(times) * 1e3:.1f} ms CPU")
    cmd = [sys.executable, "-m", "mechreport", "check", str(ROOT / "specs")]
    walls = []
    for _ in range(3):
        t = time.perf_counter()
        subprocess.run(cmd, capture_output=True, check=False)
        walls.append(time.perf_counter() - t)
    print(f"`mechreport check specs` wall time: best {min(walls):.2f} s, "
          f"median {statistics.median(walls):.2f} s")


if __name__ == "__main__":
    main()
