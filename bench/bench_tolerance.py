"""Benchmark: `mechreport tolerance` on N samples of specs/four_bar.yaml (360 angles) with four
tolerances, wall time.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python bench/bench_tolerance.py [N] [--jobs J]
        [--scheduler ADDRESS]

N defaults to 2000 (the target: at most 45 s on 2 cores). The four tolerances: the coupler's
length (±0.2 mm), the rocker's length (±0.2 mm), the frame's length (normal, σ = 0.1 mm) and
the coupler's mass (uniform 210 to 230 g); kept: the peak and RMS torque and joint B's peak
load, with the spec's eight design verdicts. Run by the CLI in a subprocess into a temporary
folder, so the figure includes start-up, the nominal analysis and writing tolerance.parquet,
.csv, .json, .md and .pdf.

Not a test: timings depend on the machine.
"""
from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
SPEC = ROOT / "specs" / "four_bar.yaml"


def tolerance_spec(n: int, folder: Path) -> Path:
    text = SPEC.read_text(encoding="utf-8").rstrip("\n") + f"""

tolerances:
  vary:
    - {{key: links.coupler.points.C.0, tol: 0.2}}
    - {{key: links.rocker.points.C.0, tol: 0.2}}
    - {{key: ground.D.0, sigma: 0.1}}
    - {{key: links.coupler.mass, from: 210, to: 230}}
  count: {n}
  seed: 1
  keep: [cycle.torque.max, cycle.torque.rms, joint.B.f_max]
"""
    path = folder / "four_bar_tolerances.yaml"
    path.write_text(text, encoding="utf-8")
    return path


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("n", nargs="?", type=int, default=2000)
    ap.add_argument("--jobs", type=int, default=None)
    ap.add_argument("--scheduler", default=None)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        spec = tolerance_spec(args.n, Path(tmp))
        cmd = [sys.executable, "-m", "mechreport", "tolerance", str(spec), "-o",
               str(Path(tmp) / "out")]
        if args.jobs:
            cmd += ["--jobs", str(args.jobs)]
        if args.scheduler:
            cmd += ["--scheduler", args.scheduler]
        env = dict(os.environ, PYTHONPATH=str(ROOT))
        start = time.perf_counter()
        done = subprocess.run(cmd, env=env, capture_output=True, text=True)
        seconds = time.perf_counter() - start
        tail = [line for line in done.stderr.splitlines() if "sample(s) in" in line]
        print(f"{args.n} samples, 4 tolerances, jobs {args.jobs or 'default'}: "
              f"{seconds:.1f} s wall (exit {done.returncode})")
        for line in tail + done.stdout.splitlines():
            print("  " + line)
        if done.returncode:
            print(done.stderr[-2000:], file=sys.stderr)
        return done.returncode


if __name__ == "__main__":
    sys.exit(main())
