"""Benchmark: how long the spec loader takes on the shipped specs and on the worst inputs
at the size cap (the hostile-input tests in tests/spec count events instead of timing).

    .venv/bin/python bench/bench_loader.py [--runs N]

Best of N runs (default 5) of process CPU time per load; the targets the loader was built to:
a shipped spec in a few milliseconds, any input at the size cap (128 KiB) under a second.
Not a test.
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "spec"))


def best_of(runs: int, fn) -> float:
    best = float("inf")
    for _ in range(runs):
        t0 = time.process_time()
        try:
            fn()
        except Exception:  # noqa: BLE001 - refusals are what is timed here
            pass
        best = min(best, time.process_time() - t0)
    return best


def main() -> None:
    from mechreport.spec import load_spec, parse_spec
    from test_loader_hostile import ALIAS_BOMB, WORST_CASES

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=5)
    runs = ap.parse_args().runs
    print("shipped specs (target: a few ms)")
    for path in sorted((ROOT / "specs").glob("*.yaml")):
        print(f"  {path.stem:32s} {1000 * best_of(runs, lambda: load_spec(path)):7.2f} ms")
    print("hostile inputs at the size cap (target: under 1 s)")
    cases = dict(WORST_CASES, **{"alias-bomb": ALIAS_BOMB})
    for name, text in cases.items():
        print(f"  {name:32s} {1000 * best_of(runs, lambda: parse_spec(text, 'x.yaml')):7.1f} ms")


if __name__ == "__main__":
    main()
