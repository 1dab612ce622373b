"""Benchmark: `mechreport study` on N variants of specs/four_bar.yaml (360 angles, every cycle
quantity kept), wall time and peak memory.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python bench/bench_study.py [N] [--jobs J]
        [--scheduler ADDRESS] [--methods]

N defaults to 10000. The study is a Latin hypercube over the coupler's length, its mass and
the crank speed (every variant assembles and turns fully), run by the CLI in a subprocess
into a temporary folder, so the figures include start-up and writing study.parquet, .csv, .md
and .pdf. Memory: the largest resident set of any one process (getrusage of the children,
grandchildren included) and the largest sum over the whole process tree (sampled every 0.2 s).
``--methods`` first times one variant per force method (the order behind the default method).

Not a test: timings depend on the machine.
"""
from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse  # noqa: E402
import re  # noqa: E402
import resource  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import threading  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
SPEC = ROOT / "specs" / "four_bar.yaml"


def every_cycle_quantity() -> list[str]:
    from mechreport.quantities import CYCLE_UNITS
    from mechreport.spec import load_spec
    spec = load_spec(SPEC)
    out = list(CYCLE_UNITS)
    for j in spec.joints:
        out += [f"joint.{j.name}.{a}" for a in ("f_max", "f_mean", "f_equivalent")]
        if j.name in spec.design.bearings:
            out.append(f"joint.{j.name}.life_h")
    return out


def study_spec(n: int, folder: Path) -> Path:
    text = SPEC.read_text(encoding="utf-8").rstrip("\n")
    text += f"""

study:
  vary:
    - {{key: links.coupler.points.C.0, from: 170, to: 190}}
    - {{key: links.coupler.mass, from: 180, to: 260}}
    - {{key: driver.rpm, from: 200, to: 400}}
  sample: lhs
  count: {n}
  seed: 1
  keep: [{", ".join(every_cycle_quantity())}]
"""
    path = folder / "four_bar.yaml"
    path.write_text(text, encoding="utf-8")
    return path


def tree_rss(pid: int) -> int:
    """Resident memory [bytes] of ``pid`` and all its descendants."""
    import psutil
    try:
        p = psutil.Process(pid)
        procs = [p] + p.children(recursive=True)
    except psutil.Error:
        return 0
    total = 0
    for q in procs:
        try:
            total += q.memory_info().rss
        except psutil.Error:
            pass
    return total


def time_methods() -> None:
    import dataclasses
    import statistics
    from mechreport.pipeline.analysis import analyse
    from mechreport.forces import METHODS
    from mechreport.spec import load_spec
    spec = dataclasses.replace(load_spec(SPEC), expect=())
    times: dict[str, list[float]] = {m: [] for m in METHODS}
    for _ in range(15):
        for m in METHODS:
            t = time.perf_counter()
            analyse(spec, methods=[m])
            times[m].append(time.perf_counter() - t)
    print("one variant of four_bar (360 angles), analyse(spec, methods=[m]):")
    for m, v in sorted(times.items(), key=lambda kv: min(kv[1])):
        print(f"  {m:<14} best {min(v) * 1e3:6.2f} ms   median {statistics.median(v) * 1e3:6.2f} ms")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("n", nargs="?", type=int, default=10000, help="variants (default 10000)")
    ap.add_argument("--jobs", type=int, default=None)
    ap.add_argument("--scheduler", default=None)
    ap.add_argument("--methods", action="store_true", help="also time each force method")
    ns = ap.parse_args()
    if ns.methods:
        time_methods()
    with tempfile.TemporaryDirectory(prefix="bench-study-") as tmp:
        spec = study_spec(ns.n, Path(tmp))
        cmd = [sys.executable, "-m", "mechreport", "study", str(spec), "-o",
               str(Path(tmp) / "out")]
        if ns.jobs:
            cmd += ["--jobs", str(ns.jobs)]
        if ns.scheduler:
            cmd += ["--scheduler", ns.scheduler]
        peak = [0]
        start = time.perf_counter()
        proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        stop = threading.Event()

        def sample():
            while not stop.is_set():
                peak[0] = max(peak[0], tree_rss(proc.pid))
                stop.wait(0.2)
        watcher = threading.Thread(target=sample, daemon=True)
        watcher.start()
        out, err = proc.communicate()
        wall = time.perf_counter() - start
        stop.set()
        watcher.join()
        one = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss * 1024   # KiB on Linux
        if proc.returncode != 0:
            print(err[-3000:], file=sys.stderr)
            print(f"mechreport study exited with {proc.returncode}", file=sys.stderr)
            return 1
        m = re.search(r"(\d+) variant\(s\) in ([^:]+):", err)
        variants_time = m.group(2) if m else "?"
        header = err.splitlines()[0] if err else ""
        print(header)
        print(out.strip())
        print(f"variants: {ns.n}; wall (whole command, start-up and outputs included): "
              f"{wall:.1f} s; variants alone: {variants_time}; "
              f"{wall / ns.n * 1e3:.2f} ms per variant")
        print(f"peak memory: largest process {one / 2**20:.0f} MiB, whole process tree "
              f"{peak[0] / 2**20:.0f} MiB (sampled)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
