"""Benchmark: CPU per angle and peak memory of `mechreport check` on long sweeps of
specs/r_rtr_rtr.yaml, each in a fresh process (peak RSS from the kernel's rusage).

    OPENBLAS_NUM_THREADS=1 .venv/bin/python bench/bench_memory.py [N ...]

Default N: 3600, 100000 and 1000000 angles (the last takes a minute or two). Not a test.
"""
from __future__ import annotations

import os
import re
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def run(n: int) -> tuple[float, float, int]:
    """CPU seconds, peak RSS [MB] and exit code of `mechreport check` on an n-angle sweep."""
    text = (ROOT / "specs" / "r_rtr_rtr.yaml").read_text()
    text = re.sub(r"(?m)^sweep:.*$", f"sweep: {{start: 0, stop: 360, step: {360 / n!r}}}", text)
    with tempfile.TemporaryDirectory() as tmp:
        spec = Path(tmp) / "long_sweep.yaml"
        spec.write_text(text)
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        code = subprocess.run([sys.executable, "-m", "mechreport", "check", str(spec)],
                              capture_output=True, env={**os.environ,
                                                        "OPENBLAS_NUM_THREADS": "1"}).returncode
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)
    return cpu, after.ru_maxrss / 1024, code


def main() -> None:
    sizes = [int(a) for a in sys.argv[1:]] or [3600, 100_000, 1_000_000]
    print(f"{'angles':>10}{'CPU s':>9}{'us/angle':>10}{'peak RSS MB':>13}{'exit':>6}")
    for n in sizes:
        t = time.perf_counter()
        cpu, rss, code = run(n)
        print(f"{n:>10}{cpu:>9.1f}{cpu / n * 1e6:>10.1f}{rss:>13.0f}{code:>6}"
              f"   (wall {time.perf_counter() - t:.1f} s)")


if __name__ == "__main__":
    main()
