"""The failed expectations of a check, each once: the record `check`, the report, JUnit and
the index read."""
from __future__ import annotations

from ..quantities import unit_of


def failed_expectations(analysis) -> list[dict]:
    """Each failing ``expect`` entry of ``analysis`` (anything with ``expectations``) once (not once per method): quantity, angle, expected,
    computed, difference, tolerance [SI], unit, the methods that computed it (or why there is
    no value)."""
    groups: dict[tuple, list] = {}
    for e in analysis.expectations:
        key = (e.expect.angle, e.expect.quantity, e.expect.value)
        groups.setdefault(key, []).append(e)
    out = []
    for (angle, quantity, value), results in groups.items():
        bad = [e for e in results if not e.ok]
        if not bad:
            continue
        tol = bad[0].expect.tol
        got = [e for e in bad if e.got is not None]
        worst = max(got, key=lambda e: abs(e.got - value), default=None)
        methods = [e.source for e in bad if e.got is not None]
        written = bad[0].expect
        out.append({
            "quantity": quantity, "angle_deg": angle, "expected": value,
            "computed": None if worst is None else worst.got,
            "difference": None if worst is None else worst.got - value,
            "tolerance": tol, "unit": unit_of(quantity) or "",
            "methods": methods, "line": written.line,
            "why": "" if worst is not None else bad[0].message,
            # as the spec wrote it: shown in this unit (``shown_scale`` its size in SI)
            "shown_unit": written.unit or unit_of(quantity) or "",
            "shown_scale": written.scale})
    return out
