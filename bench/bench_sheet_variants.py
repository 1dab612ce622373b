"""Time `mechreport build --sheet` of the classroom slider-crank (bench/data/
slider_crank_class.yaml) with 30 variants: each variant drawn, analysed by every method,
checked, and written as problem.pdf and solution.pdf, plus answers.pdf and moodle.xml.
Target (issue 46): at most 60 s on 2 cores.

    PYTHONPATH=. python bench/bench_sheet_variants.py
"""
from __future__ import annotations

import subprocess
import sys
import tempfile
import time
from pathlib import Path

SPEC = Path(__file__).parent / "data" / "slider_crank_class.yaml"


def main() -> None:
    with tempfile.TemporaryDirectory() as out:
        start = time.perf_counter()
        subprocess.run([sys.executable, "-m", "mechreport", "build", str(SPEC), "--sheet",
                        "--no-animation", "-q", "-o", out, "--variants", "30"], check=True)
        took = time.perf_counter() - start
        n = len(list((Path(out) / SPEC.stem / "variants").glob("[0-9]*/problem.pdf")))
    print(f"{n} variants with sheets, answers and moodle.xml: {took:.1f} s")


if __name__ == "__main__":
    main()
