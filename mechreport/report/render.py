"""Render a :class:`~mechreport.report.model.ReportModel` to report.md, report.pdf,
results.csv and summary.json, and a batch's index; every file written atomically.

report.md / report.pdf and index.md / index.pdf are documents (:mod:`.report_doc`,
:mod:`.index_doc`: blocks of :mod:`.document`) written by the one Markdown and the one Typst
writer, which escape every string that can hold user text."""
from __future__ import annotations

import csv
import io
import json
from pathlib import Path

from .files import atomic_write_text
from .pdf import compile_typst
from .write_markdown import markdown
from .write_typst import typst


def csv_text(header: list[str], rows: list[list[str]]) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(header)
    w.writerows(rows)
    return buf.getvalue()


def report_markdown(model) -> str:
    """report.md of the :class:`~.model.ReportModel` ``model``."""
    from .report_doc import report_document
    return markdown(report_document(model))


def report_typst(model) -> str:
    """The Typst source of report.pdf."""
    from .report_doc import report_document
    return typst(report_document(model))


def write_report(model, outdir: Path) -> list[Path]:
    """results.csv, summary.json, report.md and report.pdf of ``model`` in ``outdir``
    (figures must already be there: the PDF embeds them)."""
    outdir = Path(outdir)
    out = [atomic_write_text(outdir / "results.csv", csv_text(model.csv_header, model.csv_rows)),
           atomic_write_text(outdir / "summary.json",
                             json.dumps(model.summary, indent=2, allow_nan=False) + "\n"),
           atomic_write_text(outdir / "report.md", report_markdown(model))]
    out.append(compile_typst(report_typst(model), outdir / "report.pdf", outdir))
    return out


def write_index(rows: list[dict], out: Path, title: str = "mechreport batch") -> list[Path]:
    """OUT/index.md, index.pdf, index.csv and index.json: one row per spec (failed ones carry
    their message); the CSV and JSON are SI with the unit in each field name, for CI."""
    from ..version import __version__
    from .index_doc import index_document
    from .provenance import build_time

    out = Path(out)
    when = build_time().strftime("%Y-%m-%d %H:%M UTC")
    records = index_records(rows)
    csv_rows = [[_csv_cell(r[k]) for k in INDEX_FIELDS] for r in records]
    files = [atomic_write_text(out / "index.csv", csv_text(list(INDEX_FIELDS), csv_rows)),
             atomic_write_text(out / "index.json", json.dumps(
                 {"mechreport_version": __version__, "date": when, "specs": records},
                 indent=2, allow_nan=False) + "\n")]
    for r in rows:                  # the reports written as HTML link their page
        if r.get("ok") and r.get("stem") and (out / str(r["stem"]) / "report.html").is_file():
            r.setdefault("report_html", f"{r['stem']}/report.html")
    doc = index_document(rows, title, __version__, when)
    files.append(atomic_write_text(out / "index.md", markdown(doc)))
    files.append(compile_typst(typst(doc), out / "index.pdf", out))
    files += write_index_html(doc, out)
    return files


def write_index_html(doc, out: Path) -> list[Path]:
    """OUT/index.html (its table sorts and filters) and the folder's scripts, when a report
    folder of ``out`` has a report.html (none has one: no index.html, an earlier one
    removed)."""
    from .html_page import index_html, write_assets
    if not any(Path(out).glob("*/report.html")):
        (Path(out) / "index.html").unlink(missing_ok=True)       # no stale page left
        return []
    return [atomic_write_text(Path(out) / "index.html", index_html(doc)), *write_assets(out)]


def _csv_cell(value) -> str:
    if value is None:
        return ""
    if isinstance(value, list):
        return " ".join(str(v) for v in value)
    if isinstance(value, float):
        return f"{value:.10g}"
    return str(value)


INDEX_FIELDS = ("folder", "name", "spec", "status", "peak_torque_N_m", "peak_torque_angle_deg",
                "rms_torque_N_m", "peak_driver_force_N", "rms_driver_force_N",
                "largest_bearing_load_N", "largest_bearing_joint",
                "largest_bearing_load_away_N",
                "mean_power_W", "worst_disagreement", "verdicts_passed", "verdicts_total",
                "failed_verdicts", "failed_expectations", "spec_sha256", "mechreport_version",
                "message")


def index_records(rows: list[dict]) -> list[dict]:
    """index.csv / index.json records: one per spec, SI, the unit in each field name."""
    out = []
    for r in rows:
        data = r.get("data") or {}
        rec = {"folder": r.get("stem") or r.get("folder"), "name": r.get("name"),
               "spec": r.get("spec"), "status": r.get("status", "FAIL"),
               **{k: data.get(k) for k in INDEX_FIELDS if k in data},
               "message": r.get("message") or ""}
        out.append({k: rec.get(k) for k in INDEX_FIELDS})
    return out
