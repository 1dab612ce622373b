"""Benchmark: CPU seconds per spec of `mechreport build --jobs 1` over a folder of specs
(default specs/), interpreter start, imports and the index included; then the same build
again, where every spec is unchanged and skipped. ``--no-animation-too``: also the fresh
build with ``--no-animation`` (what the animations cost: the difference).

    make bench-build        (or: .venv/bin/python bench/bench_build.py [SPEC_DIR] [--runs N])
    .venv/bin/python bench/bench_build.py --against bf87766     (this tree and that revision,
                            measured in the same run, runs interleaved)

``--against REV``: a git worktree of revision REV is made in a temporary folder (removed
after) and built by the same interpreter with ``PYTHONPATH`` pointing at it, run for run
alternating with this tree, so that both see the same load on the machine.

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


def checkout(rev: str, where: Path) -> Path:
    """A detached git worktree of ``rev`` (of this repository) in ``where``."""
    path = where / "rev"
    subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", "--quiet",
                    str(path), rev], check=True)
    return path


def drop(path: Path) -> None:
    subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force", str(path)],
                   check=False)


def measure(base: list[str], env: dict, specs: str, runs: int, no_animation: bool):
    """(fresh, again, still) lists of (CPU, wall) of ``runs`` builds of ``specs``."""
    fresh, again, still = [], [], []
    for _ in range(runs):
        with tempfile.TemporaryDirectory() as tmp:     # run elsewhere: no checkout shadows
            out = str(Path(tmp) / "out")               # the mechreport being measured
            cmd = base + ["build", specs, "-o", out, "--jobs", "1"]
            fresh.append(cpu_of(cmd, env, tmp))
            again.append(cpu_of(cmd, env, tmp))
        if no_animation:
            with tempfile.TemporaryDirectory() as tmp:
                cmd = base + ["build", specs, "-o", str(Path(tmp) / "out"), "--jobs", "1",
                              "--no-animation"]
                still.append(cpu_of(cmd, env, tmp))
    return fresh, again, still


def report(label: str, n: int, fresh, again, still) -> None:
    cpu, wall = min(fresh)
    print(f"{label}{n} specs, build --jobs 1, best of {len(fresh)}: {cpu:.2f} s CPU "
          f"({cpu / n:.2f} s per spec), {wall:.2f} s wall  (all runs: "
          + ", ".join(f"{c:.2f}" for c, _ in fresh) + ")")
    cpu, wall = min(again)
    print(f"{label}again, every spec unchanged: {cpu:.2f} s CPU ({cpu / n:.2f} s per spec), "
          f"{wall:.2f} s wall")
    if still:
        cpu, wall = min(still)
        print(f"{label}--no-animation: {cpu:.2f} s CPU ({cpu / n:.2f} s per spec), "
              f"{wall:.2f} s wall")


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
    ap.add_argument("--against", metavar="REV", default=None,
                    help="also measure git revision REV (a temporary worktree), interleaved")
    ap.add_argument("--its-specs", action="store_true",
                    help="with --against: build that revision's specs/ (by both trees), "
                    "e.g. the specs an older revision can read")
    ns = ap.parse_args()
    ns.specs = str(Path(ns.specs).resolve())
    n = len(list(Path(ns.specs).glob("*.yaml")) + list(Path(ns.specs).glob("*.yml")))
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1")
    base = ns.mechreport.split() if ns.mechreport else [sys.executable, "-m", "mechreport"]
    print(f"load average before: {os.getloadavg()[0]:.2f}")
    if ns.against is None:
        report("", n, *measure(base, env, ns.specs, ns.runs, ns.no_animation_too))
    else:
        with tempfile.TemporaryDirectory() as where:
            rev = checkout(ns.against, Path(where))
            try:
                if ns.its_specs:
                    ns.specs = str(rev / "specs")
                    n = len(list(Path(ns.specs).glob("*.y*ml")))
                env_rev = dict(env, PYTHONPATH=str(rev))
                env_now = dict(env, PYTHONPATH=str(ROOT))
                now, then = ([], [], []), ([], [], [])
                for _ in range(ns.runs):             # interleaved: the same load for both
                    for acc, e in ((now, env_now), (then, env_rev)):
                        for a, b in zip(acc, measure(base, e, ns.specs, 1,
                                                     ns.no_animation_too)):
                            a.extend(b)
            finally:
                drop(rev)
        report("this tree:  ", n, *now)
        report(f"{ns.against}: ", n, *then)
    print(f"load average after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
