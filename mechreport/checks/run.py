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
    flags = f", {len(result.flags)} angle(s) left out ({left_out(result.flags)})" \
        if result.flags else ""
    status = "PASS" if result.passed else "FAIL"
    design = ""
    if result.verdicts:
        missed = sum(not v.passed for v in result.verdicts)
        design = (f", {len(result.verdicts)} design verdict(s)"
                  + (f" ({missed} missed)" if missed else ""))
    return (f"{status} {path}: {n_exp} expectation(s) ({n_checks} checks){design}, {agree}, "
            f"largest residual {res:.1e} N / {resm:.1e} N·m{flags}")


def left_out(flags) -> str:
    """``2 singular, 3 near-singular``: how many angles were left out, by kind."""
    counts: dict[str, int] = {}
    for f in flags:
        counts[f.kind] = counts.get(f.kind, 0) + 1
    return ", ".join(f"{n} {kind}" for kind, n in counts.items())


def check_files(paths: list[Path], tol: float) -> int:
    """One PASS/FAIL line per spec on stdout (details indented below a FAIL); a spec that
    cannot be read or analysed is a FAIL line with its message and the others go on. Exit
    code 1 if any spec fails (or none is given)."""
    from ..analysis import analyse
    from ..cli import print_traceback_if_debug, describe_failure

    failed = 0
    if not paths:
        print("no spec files given", file=sys.stderr)
        return 1
    for path in paths:
        try:
            result = analyse(path, tol=tol)
            line = summary_line(path, result)
        except MechreportError as exc:
            failed += 1
            print(f"FAIL {path}: {exc}")
            continue
        except Exception as exc:  # noqa: BLE001 - one bad spec must not stop the others
            failed += 1
            print(f"FAIL {path}: {describe_failure(exc)}")
            print_traceback_if_debug()
            continue
        print(line)
        for note in result.kinematics.notes():
            print(f"  note: {note}")
        if not result.passed:
            failed += 1
            for v in result.verdicts:
                if not v.passed:
                    print(f"  design verdict missed: {v.describe()}")
            for e in result.expectations:
                if not e.ok:
                    print(f"  {e.message}")
            if result.worst and result.worst.relative > tol:
                print(f"  methods disagree beyond {tol:g} on {result.worst.quantity}")
            if result.kinematics.n == 0:
                print("  no crank angle could be solved")
    return 1 if failed else 0
