"""summary.json as the report writes it: the title block and the check line (the report's
words), then the analysis's summary record (``Analysis.summary_record``, built once in the
pipeline, :mod:`mechreport.pipeline.records`, the dynamics and strength records included);
and the index row read back from a summary."""
from __future__ import annotations

from ..units import DASH, deg, fmt
from .provenance import Meta


def summary_json(analysis, meta: Meta, status_line: str, fails: list[dict]) -> dict:
    """summary.json of ``analysis``: provenance, status and check line, the failed
    expectations ``fails``, then the analysis's records (SI, the unit beside every value)."""
    spec = analysis.spec
    return {
        "mechreport_version": meta.version, "spec": spec.file, "axis_unit": spec.axis_unit,
        "spec_sha256": meta.sha256, "date": meta.date,
        "name": spec.name, "title": meta.title or spec.name,
        "project": meta.project or None, "author": meta.author or None,
        "revision": meta.revision or None,
        "status": "PASS" if analysis.passed else "FAIL", "check": status_line,
        "failures": fails,
        **analysis.summary_record()}


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
