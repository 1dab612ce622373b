"""Benchmark: `mechreport optimize specs/four_bar_optimize.yaml` (four varied keys: crank,
coupler, rocker and frame lengths; two subject_to bounds besides the eight design verdicts;
minimize cycle.torque.rms; budget 2000), wall time and evaluations.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python bench/bench_optimize.py [--jobs J] [--seed S]
        [--scheduler ADDRESS]

Run by the CLI in a subprocess into a temporary folder, so the time includes start-up, the
original's analysis, the search (each generation one batch on J local processes), the
polish, the proof (every method), the optimum's full report and optimize.pdf. The target
(issue 44): at most 2000 evaluations and 60 s of wall time on 2 cores.

Not a test: timings depend on the machine.
"""
from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse  # noqa: E402
import csv  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
SPEC = ROOT / "specs" / "four_bar_optimize.yaml"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--seed", type=int, default=None)
    ap.add_argument("--scheduler", default=None)
    ns = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        cmd = [sys.executable, "-m", "mechreport", "optimize", str(SPEC), "-o", tmp,
               "--jobs", str(ns.jobs)]
        if ns.seed is not None:
            cmd += ["--seed", str(ns.seed)]
        if ns.scheduler:
            cmd += ["--scheduler", ns.scheduler]
        env = dict(os.environ, PYTHONPATH=str(ROOT))
        t0 = time.perf_counter()
        done = subprocess.run(cmd, env=env, capture_output=True, text=True)
        wall = time.perf_counter() - t0
        with open(Path(tmp) / SPEC.stem / "history.csv", encoding="utf-8") as fh:
            rows = list(csv.DictReader(fh))
        polish = sum(r["phase"] == "polish" for r in rows)
        feasible = sum(r["feasible"] == "true" for r in rows)
    print(done.stdout.rstrip())
    print(f"exit {done.returncode}; {len(rows)} evaluations ({polish} polish, {feasible} "
          f"feasible); wall {wall:.1f} s with --jobs {ns.jobs} "
          f"(target: <= 2000 evaluations, <= 60 s on 2 cores)")
    if done.returncode not in (0, 1):
        print(done.stderr, file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
