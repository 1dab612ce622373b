"""The batch index (index.md, index.pdf) as a :class:`~.document.Doc`: a count of the specs by
outcome and one table row per spec (from :meth:`ReportModel.index_row`, or a failure row with
its message). The machine-readable index.csv and index.json are :mod:`.render`'s."""
from __future__ import annotations

from .document import Aside, Cell, Code, Doc, Either, Layout, Link, Print, Verdict

HEADER = ["spec", "check", "design verdicts", "peak driver torque/force", "RMS torque/force",
          "largest bearing load", "mean power", "worst disagreement", "report"]
#: a landscape page of small text: the index is one wide table
LAYOUT = Layout(landscape=True, margin=(1.5,), size=8.5, heading_sizes=(), heading_space=None)
#: the columns' relative widths in print (None: as wide as the content)
WIDTHS = (2, None, 1.2, 1.3, None, 1.5, None, 1.4, 1.2)


def index_document(rows: list[dict], title: str, version: str, date: str) -> Doc:
    """The index of ``rows`` (``ok`` rows from a built report, the others failures)."""
    built = [r for r in rows if r["ok"]]
    passed = sum(1 for r in built if r["status"] == "PASS")
    doc = Doc(title, layout=LAYOUT)
    doc.p(f"{len(rows)} spec(s): {passed} passed their check, {len(built) - passed} failed it, "
          f"{len(rows) - len(built)} could not be built. mechreport {version}, {date}.",
          Either([" Machine-readable: ", Link("index.csv", "index.csv"), ", ",
                  Link("index.json", "index.json"), "."], ""))
    doc.table(HEADER, [_row(r) if r["ok"] else _failure(r) for r in rows], right={3, 4, 6, 7},
              print=Print(widths=WIDTHS, inset=3, right=frozenset({3, 4, 6})))
    return doc


def _row(r: dict) -> list:
    verdicts = r["verdicts"]
    if r["failed_verdicts"]:
        verdicts += " (failed: " + ", ".join(r["failed_verdicts"]) + ")"
    return [[r["name"], Aside(r["spec"])], Verdict(r["status"], r["message"] or ""), verdicts,
            r["peak"], r["rms"], r["bearing"], r["power"], r["worst"],
            Either(_links(r), Link("report.pdf", r["report_pdf"]))]


def _links(r: dict) -> list:
    """The report's files, its animation and its sheets, each a link (the PDF index shows only
    the report's PDF)."""
    links = [Link("md", r["report_md"]), Link("pdf", r["report_pdf"])]
    if r.get("report_html"):
        links.append(Link("html", r["report_html"]))
    if r.get("animation"):
        links.append(Link("animation", r["animation"]))
    links += [Link(label, path) for label, path in r["sheets"]]
    out = []
    for link in links:
        out += [" · ", link] if out else [link]
    return out


def _failure(r: dict) -> list:
    return [Either(r["spec"], Code(r["spec"])), Verdict("FAIL", "could not be built"),
            Cell(r["message"], span=7, small=True)]
