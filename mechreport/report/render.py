"""Render a :class:`~mechreport.report.model.ReportModel` to report.md, report.pdf,
results.csv and summary.json, and a batch's index; every file written atomically.

Templates live in ``templates/`` (Jinja2); they format nothing but strings the model holds,
and every string that can hold user text goes through an escaping filter (see
:func:`environment`)."""
from __future__ import annotations

import csv
import io
import json
from functools import lru_cache
from pathlib import Path

from .templating import loader
from .files import atomic_write_text
from .markdown import md_inline, md_text, md_url
from .pdf import compile_typst, typst_escape, typst_markdown, typst_string


@lru_cache(maxsize=1)
def environment():
    """The Jinja2 environment of the report and index templates. User text reaches a template
    only through a filter: Markdown ``md`` (inline text: names, paths, messages), ``md_text``
    (a spec's Markdown description: no raw HTML), ``url`` (link targets); Typst ``typ``
    (markup text), ``ts`` (a string literal) and ``md_typ`` (a spec's Markdown description,
    a string or a list of its paragraphs, as Typst markup: :func:`.pdf.typst_markdown`)."""
    import jinja2
    env = jinja2.Environment(loader=loader(),
                             undefined=jinja2.StrictUndefined, keep_trailing_newline=True,
                             trim_blocks=True, lstrip_blocks=True, autoescape=False)
    env.filters["typ"] = typst_escape
    env.filters["ts"] = typst_string
    env.filters["md_typ"] = _description_typst
    env.filters["md"] = md_inline
    env.filters["md_text"] = md_text
    env.filters["url"] = md_url
    return env


def _description_typst(description) -> str:
    """A description (its text, or the list of paragraphs a ReportModel holds) as Typst."""
    if not isinstance(description, str):
        description = "\n\n".join(description)
    return typst_markdown(description)


def render(template: str, **context) -> str:
    return environment().get_template(template).render(**context)


def csv_text(header: list[str], rows: list[list[str]]) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(header)
    w.writerows(rows)
    return buf.getvalue()


def write_report(model, outdir: Path) -> list[Path]:
    """results.csv, summary.json, report.md and report.pdf of ``model`` in ``outdir``
    (figures must already be there: the PDF embeds them)."""
    outdir = Path(outdir)
    out = [atomic_write_text(outdir / "results.csv", csv_text(model.csv_header, model.csv_rows)),
           atomic_write_text(outdir / "summary.json",
                             json.dumps(model.summary, indent=2, allow_nan=False) + "\n"),
           atomic_write_text(outdir / "report.md", render("report.md.j2", m=model))]
    source = render("report.typ.j2", m=model)
    out.append(compile_typst(source, outdir / "report.pdf", outdir))
    return out


def write_index(rows: list[dict], out: Path, title: str = "mechreport batch") -> list[Path]:
    """OUT/index.md, index.pdf, index.csv and index.json: one row per spec (failed ones carry
    their message); the CSV and JSON are SI with the unit in each field name, for CI."""
    from ..version import __version__
    from .index_doc import index_document
    from .model import build_time

    out = Path(out)
    when = build_time().strftime("%Y-%m-%d %H:%M UTC")
    records = index_records(rows)
    csv_rows = [[_csv_cell(r[k]) for k in INDEX_FIELDS] for r in records]
    files = [atomic_write_text(out / "index.csv", csv_text(list(INDEX_FIELDS), csv_rows)),
             atomic_write_text(out / "index.json", json.dumps(
                 {"mechreport_version": __version__, "date": when, "specs": records},
                 indent=2, allow_nan=False) + "\n")]
    doc = index_document(rows, title, __version__, when)
    files.append(atomic_write_text(out / "index.md", doc.markdown()))
    files.append(compile_typst(doc.typst(), out / "index.pdf", out))
    return files


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
