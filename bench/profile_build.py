"""Profile: CPU seconds per stage of `mechreport build --jobs 1` over a folder of specs (or
one spec), in this process; ``--cprofile FILE`` also writes a cProfile of the whole build
(read it with ``python -m pstats FILE``).

    .venv/bin/python bench/profile_build.py [SPECS] [--cprofile /tmp/build.prof]

Each stage function of a report folder is wrapped and its CPU time (time.process_time)
summed over the batch; a stage called inside another counts in both (compile_typst is in
write_report and write_sheet). Interpreter start and the imports before the build are left
out (``bench_build.py`` counts everything). Not a test; see docs/performance.md.
"""
from __future__ import annotations

import argparse
import collections
import importlib
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: (module, function): the stages of a report folder, as report/build.py calls them
STAGES = [("mechreport.report.model", "build_model"),
          ("mechreport.report.plots", "write_plots"),
          ("mechreport.report.drawing", "write_drawings"),
          ("mechreport.report.animation", "write_animation"),
          ("mechreport.report.animation", "gif_bytes"),
          ("mechreport.report.render", "write_report"),
          ("mechreport.report.render", "write_index"),
          ("mechreport.report.html_page", "write_html_report"),
          ("mechreport.report.sheet", "write_sheet"),
          ("mechreport.report.pdf", "compile_typst")]


def wrap_stages(seconds: dict, calls: collections.Counter) -> None:
    for modname, name in STAGES:
        mod = importlib.import_module(modname)
        func = getattr(mod, name)

        def timed(*a, _f=func, _n=name, **k):
            t = time.process_time()
            try:
                return _f(*a, **k)
            finally:
                seconds[_n] += time.process_time() - t
                calls[_n] += 1
        setattr(mod, name, timed)
        for other in list(sys.modules.values()):      # names imported `from .pdf import`
            if (getattr(other, "__name__", "").startswith("mechreport.")
                    and getattr(other, name, None) is func):
                setattr(other, name, timed)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("specs", nargs="?", default=str(ROOT / "specs"))
    ap.add_argument("--cprofile", default=None, help="write a cProfile of the build here")
    ns = ap.parse_args()
    import mechreport.app.cli as cli
    for modname, _ in STAGES:
        importlib.import_module(modname)
    seconds: dict = collections.defaultdict(float)
    calls: collections.Counter = collections.Counter()
    if ns.cprofile is None:
        wrap_stages(seconds, calls)
    start = time.process_time()
    with tempfile.TemporaryDirectory() as tmp:
        argv = ["build", str(Path(ns.specs).resolve()), "-o", str(Path(tmp) / "out"),
                "--jobs", "1"]
        try:
            if ns.cprofile:
                import cProfile
                cProfile.runctx("cli.main(argv)", globals(), {"cli": cli, "argv": argv},
                                ns.cprofile)
            else:
                cli.main(argv)
        except SystemExit:
            pass
    total = time.process_time() - start
    print(f"build: {total:.2f} s CPU in this process (imports before it left out)")
    for name, s in sorted(seconds.items(), key=lambda kv: -kv[1]):
        print(f"  {name:20s} {s:6.2f} s  ({calls[name]} calls)")


if __name__ == "__main__":
    main()
