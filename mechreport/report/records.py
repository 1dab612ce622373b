"""The report's machine-readable records: results.csv's header and rows, summary.json
(SI, the unit in every field) with its ``quantities`` (what ``mechreport diff`` compares), and
the index row built from a summary."""
from __future__ import annotations

import math

import numpy as np

from .. import post as q
from ..post.columns import sweep_rows
from ..post.sweep import SweepSummary
from ..quantities import unit_of
from ..units import DASH, deg, fmt, kind_of
from .provenance import Meta
from .section import jnum
from .sweep_section import SweepData


def results_csv(analysis) -> tuple[list[str], list[list[str]]]:
    """One row per analysed crank angle; left-out angles keep their row, with the reason in
    ``flag`` and empty cells; undefined values (NaN) are empty cells; round-off is 0."""
    columns = analysis.columns()
    names = [c.name for c in columns]
    data = np.column_stack([c.values for c in columns]) if columns else \
        np.zeros((analysis.kinematics.n, 0))
    rows = []
    for a, k, why in zip(*sweep_rows(analysis.angles, analysis.flags)):
        cells = ([""] * len(names) if k is None else
                 [f"{v:.10g}" if math.isfinite(v) else "" for v in data[k].tolist()])
        rows.append([deg(a), why, *cells])
    return [analysis.spec.axis_column, "flag", *names], rows


def _peak_json(p: q.Peak | None, unit: str, scale: float | None = None) -> dict | None:
    return None if p is None else {"value": jnum(p.value, scale), "unit": unit,
                                   "angle_deg": p.angle}


def summary_record(analysis, summary: SweepSummary, sw: SweepData, status_line: str,
             power: dict | None, symbols, meta: Meta, fails: list[dict], sc: dict) -> dict:
    st = summary.torque
    ref = summary.method
    F, M = sc["force"], sc["moment"]
    EU, ES = ("N", F) if sw.effort == "force" else ("N·m", M)   # a T driver pushes
    effort_key = "driver_force" if sw.effort == "force" else "driver_torque"
    largest = summary.largest
    refs = {}
    for angle in analysis.spec.at:
        k = analysis.kinematics.index_of(angle)
        if k is None:
            continue
        refs[deg(angle)] = {
            effort_key: {m: jnum(r.driver_torque[k], ES) for m, r in analysis.forces.items()},
            "reactions": {j: {m: {"fx": jnum(r.reactions[j].fx[k], F),
                                  "fy": jnum(r.reactions[j].fy[k], F)}
                              for m, r in analysis.forces.items() if j in r.reactions}
                          for j in symbols},
            "units": {effort_key: EU, "reactions": "N"}}
    w = analysis.worst
    cycle = analysis.review.values if analysis.review is not None else {}
    if analysis.strength is not None:   # the members' quantities: key figures too (diff)
        cycle = {**cycle, **analysis.strength.values}
    return {
        "mechreport_version": meta.version, "spec": analysis.spec.file,
        "axis_unit": analysis.spec.axis_unit,
        "spec_sha256": meta.sha256, "date": meta.date,
        "name": analysis.spec.name, "title": meta.title or analysis.spec.name,
        "project": meta.project or None, "author": meta.author or None,
        "revision": meta.revision or None,
        "status": "PASS" if analysis.passed else "FAIL", "check": status_line,
        "failures": fails,
        "reference_method": ref, "n_angles": int(analysis.kinematics.n),
        "units": {"force": "N", "torque": "N·m", "moment": "N·m", "power": "W",
                  "length": "m", "angle": "deg", "note": "summary.json and results.csv are SI"},
        effort_key: None if st is None else {
            "unit": EU, "mean": jnum(st.mean, ES), "rms": jnum(st.rms, ES),
            "peak": _peak_json(st.peak, EU, ES), "min": _peak_json(st.low, EU, ES),
            "max": _peak_json(st.high, EU, ES)},
        "driver_effort": "force" if EU == "N" else "torque",
        "mean_power": None if st is None else {"value": jnum(st.power), "unit": "W"},
        "reactions": {js.name: {"symbol": js.symbol, "unit": "N",
                                "peak": _peak_json(jl.peak, "N", F),
                                "peak_away_from_left_out": _peak_json(jl.peak_far, "N", F),
                                "rms": None if jl.rms is None else jnum(jl.rms, F),
                                "fx_peak": _peak_json(jl.fx_peak, "N", F),
                                "fy_peak": _peak_json(jl.fy_peak, "N", F)}
                      for js in sw.joints if (jl := summary.joints[js.name])},
        "largest_bearing_load": None if largest is None else {
            "joint": largest[0], **_peak_json(largest[1], "N", F),
            "away_from_left_out": _peak_json(summary.joints[largest[0]].peak_far, "N", F)},
        "shaking": {"force_peak": _peak_json(summary.shaking_force, "N", F),
                    "moment_peak": _peak_json(summary.shaking_moment, "N·m", M)},
        "reference_angles": refs,
        "branches": [{"dyad": b.dyad, "type": b.kind, "rule": b.rule}
                     for b in analysis.kinematics.branches],
        "agreement": {
            "worst": None if w is None else {"quantity": w.quantity, "relative": w.relative,
                                             "absolute": w.absolute,
                                             "unit": analysis.spec.unit_of(w.quantity) or "N",
                                             "methods": list(w.methods), "angle_deg": w.angle},
            "quantities": [{"quantity": a.quantity, "relative": a.relative,
                            "absolute": a.absolute,
                            "unit": analysis.spec.unit_of(a.quantity) or "N",
                            "methods": list(a.methods),
                            "angle_deg": a.angle} for a in analysis.agreement]},
        "power_balance": power,
        "residuals": [{"method": r.method, "force_N": r.force, "moment_N_m": r.moment}
                      for r in analysis.residuals],
        "flags": [{"angle_deg": f.angle, "kind": f.kind, "reason": f.reason}
                  for f in analysis.flags],
        "near_singular_deg": sw.near_deg,
        "notes": analysis.kinematics.notes(),
        "quantities": _quantities(summary, cycle, sc, EU),
    }


def _quantities(summary: SweepSummary, cycle: dict, sc: dict, effort_unit: str = "N·m") -> dict:
    """Every key figure by name -> {value [SI], unit}: what ``mechreport diff`` compares and
    the index lists, each once: where the cycle quantities are defined, a sweep peak that
    one of them states (a joint's peak load is ``joint.J.f_max``, the shaking force's and
    moment's ``cycle.shaking.*_max``, the effort's mean and RMS and the mean power are
    ``cycle.torque.mean``, ``cycle.torque.rms`` and ``cycle.power.mean``) is not listed again
    under another name. The driver's signed peak and its angle stay: no cycle quantity says
    where it is."""
    out: dict[str, dict] = {}
    cyclic = bool(cycle)

    def put(name, value, unit, kind=None, angle=None):
        if value is None:
            return
        entry = {"value": jnum(value, sc.get(kind) if kind else None), "unit": unit}
        if angle is not None:
            entry["angle_deg"] = float(angle)
        out[name] = entry

    st = summary.torque
    if st is not None:
        name, kind = (("driver.force", "force") if effort_unit == "N"
                      else ("driver.torque", "moment"))
        if "cycle.torque.rms" not in cycle:   # over a whole turn the cycle's names say them
            put(f"{name}.mean", st.mean, effort_unit, kind)
            put(f"{name}.rms", st.rms, effort_unit, kind)
            put("driver.power.mean", st.power, "W")
        put(f"{name}.peak", st.peak.value, effort_unit, kind, st.peak.angle)   # signed, where
    for name, jl in summary.joints.items():
        pk = jl.peak
        if pk is not None:
            if not cyclic or f"joint.{name}.f_max" not in cycle:
                put(f"joint.{name}.f.peak", pk.value, "N", "force", pk.angle)
            put(f"joint.{name}.f.rms", jl.rms, "N", "force")
    sh = summary.shaking_force
    if sh is not None and "cycle.shaking.force_max" not in cycle:
        put("shaking.force.peak", sh.value, "N", "force", sh.angle)
    shm = summary.shaking_moment
    if shm is not None and "cycle.shaking.moment_max" not in cycle:
        put("shaking.moment.peak", shm.value, "N·m", "moment", shm.angle)
    for name, value in cycle.items():
        unit = unit_of(name) or ""
        put(name, value, unit, kind_of(unit))
    return out


def _away_value(big: dict | None) -> float | None:
    """The largest bearing load's peak away from left-out angles, where it is another."""
    far = (big or {}).get("away_from_left_out")
    if not far or far.get("angle_deg") == big.get("angle_deg"):
        return None
    return far.get("value")


def _away(big: dict, at: str) -> str:
    """``; 973.6 N at 84° away from left-out angles`` where that is another value."""
    value = _away_value(big)
    if value is None:
        return ""
    return f"; {fmt(value)} N at {deg(big['away_from_left_out']['angle_deg'])}{at} away " \
           "from left-out angles"


def check_failure_reason(s: dict) -> str:
    """Why the check of a summary (summary.json) failed, in one line for the index: the
    design verdicts missed, the expectations failed, the methods' disagreement."""
    parts = []
    verdicts = ((s.get("design") or {}).get("verdicts")) or []
    missed = [v["item"] for v in verdicts if not v.get("passed")]
    if missed:
        parts.append(f"design verdict(s) missed: {', '.join(missed)}")
    fails = s.get("failures") or []
    if fails:
        unit = s.get("axis_unit", "deg")
        shown = [f["quantity"] + (f" at {deg(f['angle_deg'])} {unit}"
                                  if f.get("angle_deg") is not None else "")
                 for f in fails[:3]]
        more = f" and {len(fails) - 3} more" if len(fails) > 3 else ""
        parts.append(f"expectation(s) failed: {', '.join(shown)}{more}")
    if not parts:
        w = (s.get("agreement") or {}).get("worst")
        if not s.get("n_angles"):
            parts.append("no angle could be analysed")
        elif w:
            parts.append(f"methods disagree by {fmt(w['relative'], 2)} on {w['quantity']}")
    return "; ".join(parts) or "its check failed (see its report)"


def index_row(model_summary: dict, stem: str) -> dict:
    """One index row (index.md/pdf/csv/json) from a report's summary.json."""
    s = model_summary
    t = s.get("driver_torque") or s.get("driver_force") or {}
    big = s.get("largest_bearing_load")
    w = (s.get("agreement") or {}).get("worst")
    verdicts = ((s.get("design") or {}).get("verdicts")) or []
    failed = [v["item"] for v in verdicts if not v.get("passed")]
    power = s.get("mean_power")
    power_value = power.get("value") if isinstance(power, dict) else power

    def si(x, unit):
        return f"{fmt(x)} {unit}" if x is not None else DASH

    peak = t.get("peak") if t else None
    eu = t.get("unit", "N·m") if t else "N·m"
    at = "°" if s.get("axis_unit", "deg") == "deg" else " " + s["axis_unit"]
    return {
        "stem": stem, "spec": s["spec"], "name": s["name"], "ok": True,
        "status": s["status"],
        "peak": (f"{si(peak['value'], eu)} at {deg(peak['angle_deg'])}{at}" if peak else DASH),
        "rms": si(t.get("rms"), eu) if t else DASH,
        "bearing": (f"{si(big['value'], 'N')} ({big['joint']}, {deg(big['angle_deg'])}{at})"
                    + _away(big, at) if big else DASH),
        "power": si(power_value, "W") if power_value is not None else DASH,
        "worst": f"{fmt(w['relative'], 2)} ({w['quantity']})" if w else DASH,
        "verdicts": (f"{len(verdicts) - len(failed)}/{len(verdicts)} passed"
                     if verdicts else DASH),
        "failed_verdicts": failed,
        "failures": len(s.get("failures") or []),
        "report_md": f"{stem}/report.md", "report_pdf": f"{stem}/report.pdf",
        "message": "" if s["status"] == "PASS" else check_failure_reason(s),
        "data": {"peak_torque_N_m": peak["value"] if peak and eu != "N" else None,
                 "peak_torque_angle_deg": peak["angle_deg"] if peak and eu != "N" else None,
                 "rms_torque_N_m": t.get("rms") if t and eu != "N" else None,
                 "peak_driver_force_N": peak["value"] if peak and eu == "N" else None,
                 "rms_driver_force_N": t.get("rms") if t and eu == "N" else None,
                 "largest_bearing_load_N": big["value"] if big else None,
                 "largest_bearing_load_away_N": _away_value(big),
                 "largest_bearing_joint": big["joint"] if big else None,
                 "mean_power_W": power_value,
                 "worst_disagreement": w["relative"] if w else None,
                 "verdicts_passed": len(verdicts) - len(failed),
                 "verdicts_total": len(verdicts),
                 "failed_verdicts": failed,
                 "failed_expectations": len(s.get("failures") or []),
                 "spec_sha256": s.get("spec_sha256"),
                 "mechreport_version": s.get("mechreport_version")},
    }
