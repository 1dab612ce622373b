"""Benchmark: what report.html adds to a build, in CPU seconds, per spec of a folder (default
specs/): the report folder written by ``write_report_folder`` (figures, animation, Markdown,
PDF, CSV, JSON and report.html) against the report.html step alone (the per-angle data, the
HTML writer, the page written); the ratio is the build's added CPU (budget: 15 %). Also the
page's size and the shared scripts' size (budgets: 1 MB for 360 angles, 500 kB).

    .venv/bin/python bench/bench_html.py [SPEC_DIR] [--runs N]

In one process, CPU time (time.process_time), best of N runs (default 3) of each step; the
analysis is not counted (it only makes the added share smaller). Not a test.
"""
from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def best(f, runs: int) -> float:
    out = []
    for _ in range(runs):
        start = time.process_time()
        f()
        out.append(time.process_time() - start)
    return min(out)


def main() -> None:
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("specs", nargs="?", default=str(ROOT / "specs"))
    ap.add_argument("--runs", type=int, default=3)
    ns = ap.parse_args()
    sys.path.insert(0, str(ROOT))
    import mechreport
    from mechreport.report.build import write_report_folder
    from mechreport.report.html_page import ASSET_FILES, asset_bytes, write_html_report
    from mechreport.report.model import build_model

    paths = sorted(Path(ns.specs).glob("*.yaml"))
    total = html = 0.0
    print(f"{'spec':32} {'angles':>6} {'build s':>8} {'html s':>7} {'added':>6} {'page kB':>8}")
    with tempfile.TemporaryDirectory() as tmp:
        for path in paths:
            a = mechreport.analyse(path)
            folder = Path(tmp) / path.stem
            whole = best(lambda: write_report_folder(a, folder, path, ""), ns.runs)
            m = build_model(a, path)
            alone = best(lambda: write_html_report(a, m, folder), ns.runs)
            size = (folder / "report.html").stat().st_size / 1000
            total, html = total + whole, html + alone
            print(f"{path.stem[:32]:32} {a.kinematics.n:6d} {whole:8.2f} {alone:7.3f} "
                  f"{alone / (whole - alone):6.1%} {size:8.0f}")
    print(f"{'all':32} {'':6} {total:8.2f} {html:7.3f} {html / (total - html):6.1%}")
    print(f"shared scripts: {sum(len(asset_bytes(n)) for n in ASSET_FILES) / 1000:.1f} kB")


if __name__ == "__main__":
    main()
