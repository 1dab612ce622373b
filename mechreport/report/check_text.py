"""A check's verdict as text: the PASS/FAIL line of `check` and the report, why a check
failed, the failed expectations' table rows and lines (numbers by the one formatter)."""
from __future__ import annotations

import math

from ..checks.failures import failed_expectations
from ..forces import METHODS
from ..units import DASH, SIG_DIGITS, deg, fmt


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


def verdict_line(v) -> str:
    """A missed design verdict by the one formatter: ``motor.rated_torque: cycle.torque.rms =
    2.278 N·m > limit 2 N·m``."""
    return v.describe(fmt)


def problems(result, tol: float) -> list[str]:
    """Why an analysis failed its check, one line each: missed verdicts, each failed
    expectation once (expected, computed, difference, tolerance, methods), disagreement."""
    out = [f"design verdict missed: {verdict_line(v)}" for v in result.verdicts
           if not v.passed]
    out += [f"expectation failed: {failure_line(f, result.spec.axis_unit)}"
            for f in failed_expectations(result)]
    if result.worst and result.worst.relative > tol:
        w = result.worst
        out.append(f"methods disagree beyond {tol:g} on {w.quantity}: {w.relative:.1e} "
                   f"({w.methods[0]} vs {w.methods[1]} at {w.angle:g} "
                   f"{result.spec.axis_unit})")
    if result.n == 0:
        out.append(f"no {result.spec.driver.coordinate} could be solved")
    return out


def _digits_for(value: float, diff: float | None) -> int:
    """Enough significant digits to see ``diff`` in ``value`` (the one formatter's digits at
    least, at most 12)."""
    if diff is None or diff == 0 or not value:
        return SIG_DIGITS
    return int(min(12, max(SIG_DIGITS, math.ceil(math.log10(abs(value) / abs(diff))) + 2)))


def failure_rows(fails: list[dict]) -> list[list[str]]:
    """Table rows (quantity, angle, expected, computed, difference, tolerance, method), in
    the unit the spec's ``expect`` entry is written in (SI without one)."""
    rows = []
    for f in fails:
        s = f.get("shown_scale", 1.0)
        if s != 1.0:                  # every value as the spec wrote its expectation
            f = dict(f, **{k: None if f[k] is None else f[k] / s
                           for k in ("expected", "computed", "difference", "tolerance")})
        unit = f.get("shown_unit", f["unit"]).replace("^2", "²")
        u = f" {unit}" if unit else ""
        angle = DASH if f["angle_deg"] is None else f"{deg(f['angle_deg'])}"
        if f["computed"] is None:
            rows.append([f["quantity"], angle, fmt(f["expected"]) + u, DASH, DASH,
                         fmt(f["tolerance"], 2) + u, f["why"]])
            continue
        digits = _digits_for(f["expected"], f["difference"])
        methods = ", ".join(METHODS[m].TITLE if m in METHODS else m for m in f["methods"])
        rows.append([f["quantity"], angle, fmt(f["expected"], digits) + u,
                     fmt(f["computed"], digits) + u, f"{fmt(f['difference'], 3)}{u}",
                     "±" + fmt(f["tolerance"], 2) + u, methods])
    return rows


def failure_line(f: dict, axis_unit: str = "deg") -> str:
    """One line for the terminal: ``driver.torque at 45 deg: expected 151.5 N·m, computed
    151.49 N·m, difference -0.0076 N·m, tolerance ±0.0001 N·m (Newton-Euler, ...)``."""
    row = failure_rows([f])[0]
    where = f" at {row[1]} {axis_unit}" if f["angle_deg"] is not None else ""
    if f["computed"] is None:
        return f"{f['quantity']}{where}: expected {row[2]}: {f['why']}"
    return (f"{f['quantity']}{where}: expected {row[2]}, computed {row[3]}, difference "
            f"{row[4]}, tolerance {row[5]} ({row[6]})")
