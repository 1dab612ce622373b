"""``mechreport check``: one line per spec, exit code 1 if any fails."""
from __future__ import annotations

import sys
from pathlib import Path

from ..errors import MechreportError


def summary_line(path, result) -> str:
    """PASS/FAIL line for an analysis (shared by `check` and the reports)."""
    n_exp = len({(e.expect.angle, e.expect.quantity) for e in result.expectations})
    n_bad = len({(e.expect.angle, e.expect.quantity) for e in result.expectations if not e.ok})
    n_checks = len(result.expectations)
    w = result.worst
    agree = (f"worst disagreement {w.relative:.1e} ({w.quantity}, {w.methods[0]} vs "
             f"{w.methods[1]} at {w.angle:g} {result.spec.axis_unit})" if w
             else "no quantity to compare")
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
    bad = f", {n_bad} failed" if n_bad else ""
    return (f"{status} {path}: {n_exp} expectation(s) ({n_checks} checks{bad}){design}, {agree}, "
            f"largest residual {res:.1e} N / {resm:.1e} N·m{flags}")


def left_out(flags) -> str:
    """``2 singular, 3 near-singular``: how many angles were left out, by kind."""
    counts: dict[str, int] = {}
    for f in flags:
        counts[f.kind] = counts.get(f.kind, 0) + 1
    return ", ".join(f"{n} {kind}" for kind, n in counts.items())


def check_files(paths: list[Path], tol: float, junit: str | Path | None = None) -> int:
    """One PASS/FAIL line per spec on stdout (details indented below a FAIL); a spec that
    cannot be read or analysed is a FAIL line with its message and the others go on. Exit
    code 1 if any spec fails (or none is given). ``junit``: also write JUnit XML there."""
    from ..cli import print_traceback_if_debug, describe_failure

    failed = 0
    cases: list = []
    if not paths:
        print("no spec files given", file=sys.stderr)
        if junit is not None:
            write_junit(junit, [])
        return 1
    for path in paths:
        try:
            result = check_one(path, tol)
            line = summary_line(path, result)
        except Exception as exc:  # noqa: BLE001 - one bad spec must not stop the others
            failed += 1
            text = str(exc) if isinstance(exc, MechreportError) else describe_failure(exc)
            print(f"FAIL {path}: {text}")
            if not isinstance(exc, MechreportError):
                print_traceback_if_debug()
            if junit is not None:
                cases.append((str(path), [("load and analyse", text)]))
            continue
        print(line)
        for note in result.notes():
            print(f"  note: {note}")
        if not result.passed:
            failed += 1
            for text in problems(result, tol):
                print(f"  {text}")
        if junit is not None:
            cases.append(_junit_cases(path, result, tol))
    if junit is not None:
        write_junit(junit, cases)
    return 1 if failed else 0


def check_one(path, tol: float):
    """The analysis `check` judges: in memory, or chunk by chunk for a sweep of more than
    ``STREAM_ANGLES`` analysed angles (bounded memory; see ``mechreport.streamed``)."""
    from ..analysis import analyse
    from ..spec import load_spec
    from ..streamed import STREAM_ANGLES, check_sweep
    spec = load_spec(path)
    if len(spec.analysed_angles()) > STREAM_ANGLES:
        return check_sweep(spec, tol=tol)
    return analyse(spec, tol=tol)


def verdict_line(v) -> str:
    """A missed design verdict by the one formatter: ``motor.rated_torque: cycle.torque.rms =
    2.278 N·m > limit 2 N·m``."""
    from ..units import fmt
    return v.describe(fmt)


def problems(result, tol: float) -> list[str]:
    """Why an analysis failed its check, one line each: missed verdicts, each failed
    expectation once (expected, computed, difference, tolerance, methods), disagreement."""
    from ..report.model import failure_line, failures
    out = [f"design verdict missed: {verdict_line(v)}" for v in result.verdicts
           if not v.passed]
    out += [f"expectation failed: {failure_line(f)}" for f in failures(result)]
    if result.worst and result.worst.relative > tol:
        w = result.worst
        out.append(f"methods disagree beyond {tol:g} on {w.quantity}: {w.relative:.1e} "
                   f"({w.methods[0]} vs {w.methods[1]} at {w.angle:g} deg)")
    if result.n == 0:
        out.append("no crank angle could be solved")
    return out


# ----------------------------------------------------------------------------- JUnit XML

def _junit_cases(path, result, tol: float) -> tuple[str, list[tuple[str, str | None]]]:
    """(spec, [(test case name, failure message or None)]): the spec's overall check, each
    expectation (once, however many methods computed it) and each design verdict."""
    from ..report.model import failure_line, failures
    bad = {(f["angle_deg"], f["quantity"], f["expected"]): f for f in failures(result)}
    cases: list[tuple[str, str | None]] = []
    lines = problems(result, tol)
    cases.append(("check", None if result.passed else "; ".join(lines) or "failed"))
    seen = set()
    for e in result.expectations:
        key = (e.expect.angle, e.expect.quantity, e.expect.value)
        if key in seen:
            continue
        seen.add(key)
        where = f" at {e.expect.angle:g} deg" if e.expect.angle is not None else ""
        name = f"expect {e.expect.quantity}{where}"
        cases.append((name, failure_line(bad[key]) if key in bad else None))
    for v in result.verdicts:
        cases.append((f"design {v.item}", None if v.passed else verdict_line(v)))
    if result.worst is not None:
        w = result.worst
        cases.append(("methods agree",
                      None if w.relative <= tol else f"{w.quantity}: {w.relative:.1e} > {tol:g}"))
    return str(path), cases


def write_junit(file, suites: list) -> None:
    """JUnit XML (one test suite per spec, one test case per check, expectation and design
    verdict; a spec that cannot be analysed is one failing test case) to ``file``."""
    import xml.etree.ElementTree as ET
    from ..report.files import atomic_write_bytes

    root = ET.Element("testsuites", name="mechreport check")
    total = fails = 0
    for spec, cases in suites:
        suite = ET.SubElement(root, "testsuite", name=spec, tests=str(len(cases)),
                              failures=str(sum(1 for _, m in cases if m is not None)),
                              errors="0", skipped="0")
        for name, message in cases:
            case = ET.SubElement(suite, "testcase", name=name, classname=spec)
            if message is not None:
                fail = ET.SubElement(case, "failure", message=message, type="mechreport")
                fail.text = message
        total += len(cases)
        fails += sum(1 for _, m in cases if m is not None)
    root.set("tests", str(total))
    root.set("failures", str(fails))
    root.set("errors", "0")
    ET.indent(root)
    data = ET.tostring(root, encoding="utf-8", xml_declaration=True) + b"\n"
    atomic_write_bytes(Path(file), data)
