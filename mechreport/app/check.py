"""``mechreport check SPEC|DIR...``: one PASS/FAIL line per spec, exit code 1 if any fails."""
from __future__ import annotations

import sys
from pathlib import Path

from ..errors import describe_failure
from .console import attempt, spec_files


def check_command(args: list[str], tol: float | None = None,
                  junit: str | Path | None = None) -> int:
    """``mechreport check`` on the SPEC|DIR arguments ``args``; ``tol`` None: the agreement
    check's default (:data:`mechreport.checks.agreement.DEFAULT_TOL`)."""
    if tol is None:
        from ..checks.agreement import DEFAULT_TOL
        tol = DEFAULT_TOL
    return check_files(spec_files(args), tol, junit)


def check_files(paths: list[Path], tol: float, junit: str | Path | None = None) -> int:
    """One PASS/FAIL line per spec on stdout (details indented below a FAIL); a spec that
    cannot be read or analysed is a FAIL line with its message and the others go on. Exit
    code 1 if any spec fails (or none is given). ``junit``: also write JUnit XML there."""
    from ..report.check_text import problems, summary_line
    from .junit import junit_cases

    failed = 0
    cases: list = []
    if not paths:
        print("no spec files given", file=sys.stderr)
        if junit is not None:
            _write_junit(junit, [])
        return 1
    for path in paths:
        def fail(text: str) -> None:
            print(f"FAIL {path}: {text}")
            if junit is not None:
                cases.append((str(path), [("load and analyse", text)]))

        def checked():
            result = check_one(path, tol)
            return result, summary_line(path, result)

        ok, done = attempt(path, checked, say=fail)
        if not ok:
            failed += 1
            continue
        result, line = done
        print(line)
        for note in result.notes():
            print(f"  note: {note}")
        if not result.passed:
            failed += 1
            for text in problems(result, tol):
                print(f"  {text}")
        if junit is not None:
            cases.append(junit_cases(path, result, tol))
    if junit is not None and not _write_junit(junit, cases):
        return 1
    return 1 if failed else 0


def _write_junit(file, cases: list) -> bool:
    """JUnit XML to ``file``; whether it was written (else a message on stderr)."""
    from .junit import write_junit
    try:
        write_junit(file, cases)
    except OSError as exc:
        print(f"error: cannot write the JUnit XML to {file}: {describe_failure(exc)}",
              file=sys.stderr)
        return False
    return True


def check_one(path, tol: float):
    """The analysis `check` judges: in memory, or chunk by chunk for a sweep of more than
    ``STREAM_ANGLES`` analysed angles (bounded memory; see ``mechreport.streamed``)."""
    from ..pipeline import analyse
    from ..pipeline.streamed import STREAM_ANGLES, check_sweep
    from ..spec import load_spec
    from .process import give_back_free_memory
    spec = load_spec(path)
    if len(spec.analysed_angles()) > STREAM_ANGLES:
        return check_sweep(spec, tol=tol, between_phases=give_back_free_memory)
    return analyse(spec, tol=tol)
