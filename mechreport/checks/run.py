"""``mechreport check``: one line per spec, exit code 1 if any fails."""
from __future__ import annotations

import sys
from pathlib import Path

from ..errors import MechreportError


def summary_line(path, result) -> str:
    """PASS/FAIL line for an analysis (shared by `check` and the reports)."""
    n_exp = len({(e.expect.angle, e.expect.quantity) for e in result.expectations})
    n_checks = len(result.expectations)
    w = result.worst
    agree = (f"worst disagreement {w.relative:.1e} ({w.quantity}, {w.methods[0]} vs "
             f"{w.methods[1]} at {w.angle:g} deg)" if w else "no quantity to compare")
    res = max((r.force for r in result.residuals), default=0.0)
    resm = max((r.moment for r in result.residuals), default=0.0)
    flags = f", {len(result.flags)} angle(s) left out" if result.flags else ""
    status = "PASS" if result.passed else "FAIL"
    return (f"{status} {path}: {n_exp} expectation(s) ({n_checks} checks), {agree}, "
            f"largest residual {res:.1e} N / {resm:.1e} N·m{flags}")


def check_files(paths: list[Path], tol: float) -> int:
    from ..analysis import analyse

    failed = 0
    if not paths:
        print("no spec files given", file=sys.stderr)
        return 1
    for path in paths:
        try:
            result = analyse(path, tol=tol)
        except MechreportError as exc:
            failed += 1
            print(f"FAIL {path}: {exc}")
            continue
        print(summary_line(path, result))
        if not result.passed:
            failed += 1
            for e in result.expectations:
                if not e.ok:
                    print(f"  {e.message}")
            if result.worst and result.worst.relative > tol:
                print(f"  methods disagree beyond {tol:g} on {result.worst.quantity}")
            if result.kinematics.n == 0:
                print("  no crank angle could be solved")
    return 1 if failed else 0
