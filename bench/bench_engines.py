"""Benchmark: CPU seconds of the whole-cycle check (720 angles of a four-stroke cycle) of
the in-line four-cylinder engine against the single-cylinder one (specs/inline_four_engine,
specs/single_cylinder_engine): the analysis in-process (kinematics, every force method, the
checks, the cycle quantities), best of N runs, and its ratio. The issue's goal: the four at
most 3x the one.

    .venv/bin/python bench/bench_engines.py [--runs N]

CPU time of this process (time.process_time), the specs loaded once and the first run
discarded (imports, the validators' first build). Not a test.
"""
from __future__ import annotations

import argparse
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SPECS = ("single_cylinder_engine.yaml", "inline_four_engine.yaml")


def cpu(spec, runs: int) -> float:
    """The best CPU seconds of ``runs`` analyses of ``spec`` (with its checks)."""
    from mechreport.pipeline.analysis import analyse
    analyse(spec)                          # warm: imports, the validators' first build
    best = float("inf")
    for _ in range(runs):
        start = time.process_time()
        a = analyse(spec)
        assert a.review is not None        # the cycle quantities are part of the check
        best = min(best, time.process_time() - start)
    return best


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=5)
    args = ap.parse_args()
    from mechreport.spec import load_spec
    times = {}
    for name in SPECS:
        spec = load_spec(ROOT / "specs" / name)
        times[name] = cpu(spec, args.runs)
        print(f"{name:32s} {len(spec.sweep.angles()):4d} angles, {len(spec.links):2d} links: "
              f"{times[name]:.3f} s CPU")
    ratio = times[SPECS[1]] / times[SPECS[0]]
    print(f"four cylinders / one: {ratio:.2f}x (goal: at most 3x)")


if __name__ == "__main__":
    main()
