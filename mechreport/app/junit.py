"""``mechreport check --junit FILE``: JUnit XML for CI (one test suite per spec)."""
from __future__ import annotations

from pathlib import Path

from ..checks.failures import failed_expectations
from ..report.check_text import failure_line, problems, verdict_line
from ..report.files import atomic_write_bytes


def junit_cases(path, result, tol: float) -> tuple[str, list[tuple[str, str | None]]]:
    """(spec, [(test case name, failure message or None)]): each expectation (once, however
    many methods computed it), each design verdict, the methods' agreement (over a machine-
    dynamics steady turn too), and the spec's overall ``check``, which fails only for a
    reason no other case states: every failure is counted once."""
    bad = {(f["angle_deg"], f["quantity"], f["expected"]): f
           for f in failed_expectations(result)}
    cases: list[tuple[str, str | None]] = []
    seen = set()
    for e in result.expectations:
        key = (e.expect.angle, e.expect.quantity, e.expect.value)
        if key in seen:
            continue
        seen.add(key)
        unit = result.spec.axis_unit
        where = f" at {e.expect.angle:g} {unit}" if e.expect.angle is not None else ""
        name = f"expect {e.expect.quantity}{where}"
        cases.append((name, failure_line(bad[key], unit) if key in bad else None))
    for v in result.verdicts:
        cases.append((f"design {v.item}", None if v.passed else verdict_line(v)))
    if result.worst is not None:
        w = result.worst
        cases.append(("methods agree",
                      None if w.relative <= tol else f"{w.quantity}: {w.relative:.1e} > {tol:g}"))
    steady = getattr(getattr(result, "dynamics", None), "steady", None)
    if steady is not None and steady.worst is not None:
        w = steady.worst
        cases.append(("methods agree over the steady turn",
                      None if w.relative <= tol else f"{w.quantity}: {w.relative:.1e} > {tol:g}"))
    stated = any(message is not None for _, message in cases)
    unstated = not result.passed and not stated
    cases.insert(0, ("check", "; ".join(problems(result, tol)) or "failed" if unstated else None))
    return str(path), cases


def write_junit(file, suites: list) -> None:
    """JUnit XML (one test suite per spec, one test case per check, expectation and design
    verdict; a spec that cannot be analysed is one failing test case) to ``file``."""
    import xml.etree.ElementTree as ET

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
