"""Benchmark: a non-dyad Assur group against dyads of the same number of links, per angle.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python bench/bench_groups.py

Kinematics (positions, velocities, accelerations) over 3600 crank angles of
tests/data/class_iii_triad.yaml (a crank and one triad: four group links, Newton-Raphson
continued along the sweep) and specs/stephenson3_six_bar.yaml (a crank and two dyads: four
group links, closed forms). The target: the triad at most 3x the two dyads. Not a test.
"""
from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import dataclasses  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

from mechreport.kinematics import solve_kinematics  # noqa: E402
from mechreport.model import build_mechanism  # noqa: E402
from mechreport.spec import Sweep, load_spec  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def per_angle(path: Path, repeat: int = 5) -> tuple[float, int]:
    spec = load_spec(path)
    spec = dataclasses.replace(spec, sweep=Sweep(0.0, 360.0, 0.1), expect=())
    mech = build_mechanism(spec)
    kin = solve_kinematics(mech)
    best = float("inf")
    for _ in range(repeat):
        t = time.process_time()
        solve_kinematics(mech)
        best = min(best, time.process_time() - t)
    return best / kin.n * 1e6, kin.n


def main() -> None:
    triad, n = per_angle(ROOT / "tests" / "data" / "class_iii_triad.yaml")
    dyads, _ = per_angle(ROOT / "specs" / "stephenson3_six_bar.yaml")
    print(f"kinematics over {n} angles, CPU us per angle (best of 5)")
    print(f"  crank + triad (Newton, 4 links):     {triad:8.2f}")
    print(f"  crank + two dyads (closed, 4 links): {dyads:8.2f}")
    print(f"  ratio: {triad / dyads:.2f} (target at most 3)")


if __name__ == "__main__":
    main()
