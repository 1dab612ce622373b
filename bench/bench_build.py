"""Benchmark: CPU seconds per spec of `mechreport build --jobs 1` over a folder of specs
(default specs/), interpreter start, imports and the index included; then the same build
again, where every spec is unchanged and skipped. ``--no-animation-too``: also the fresh
build with ``--no-animation`` (what the animations cost: the difference).

    make bench-build        (or: .venv/bin/python bench/bench_build.py [SPEC_DIR] [--runs N])

CPU time (user + system) of the child process, from resource.getrusage, best of N runs
(default 3): wall time on a shared 2-core machine varies too much to compare. Not a test.
"""
from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def cpu_of(cmd: list[str], env: dict, cwd: str) -> tuple[float, float]:
    """(CPU seconds, wall seconds) of running ``cmd`` in ``cwd`` to completion."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(cmd, check=False, env=env, cwd=cwd, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime), wall


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("specs", nargs="?", default=str(ROOT / "specs"))
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--mechreport", default=None,
                    help="command to run (default: `python -m mechreport` of this "
                    "interpreter); e.g. 'env PYTHONPATH=/tmp/old python -m mechreport' for an "
                    "exported older version")
    ap.add_argument("--no-animation-too", action="store_true",
                    help="also measure `build --no-animation` (needs a mechreport that has it)")
    ns = ap.parse_args()
    ns.specs = str(Path(ns.specs).resolve())
    n = len(list(Path(ns.specs).glob("*.yaml")) + list(Path(ns.specs).glob("*.yml")))
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1")
    base = ns.mechreport.split() if ns.mechreport else [sys.executable, "-m", "mechreport"]
    fresh, again, still = [], [], []
    for _ in range(ns.runs):
        with tempfile.TemporaryDirectory() as tmp:     # run elsewhere: no checkout shadows
            out = str(Path(tmp) / "out")               # the mechreport being measured
            cmd = base + ["build", ns.specs, "-o", out, "--jobs", "1"]
            fresh.append(cpu_of(cmd, env, tmp))
            again.append(cpu_of(cmd, env, tmp))
        if ns.no_animation_too:
            with tempfile.TemporaryDirectory() as tmp:
                cmd = base + ["build", ns.specs, "-o", str(Path(tmp) / "out"), "--jobs", "1",
                              "--no-animation"]
                still.append(cpu_of(cmd, env, tmp))
    cpu, wall = min(fresh)
    print(f"{n} specs, build --jobs 1, best of {ns.runs}: {cpu:.2f} s CPU ({cpu / n:.2f} s per "
          f"spec), {wall:.2f} s wall")
    cpu, wall = min(again)
    print(f"again, every spec unchanged: {cpu:.2f} s CPU ({cpu / n:.2f} s per spec), "
          f"{wall:.2f} s wall")
    if still:
        cpu, wall = min(still)
        print(f"--no-animation: {cpu:.2f} s CPU ({cpu / n:.2f} s per spec), {wall:.2f} s wall")


if __name__ == "__main__":
    main()
