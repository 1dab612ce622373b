"""The files of a problem's variants (``sheet.variants``): ``variants/NN/`` (each variant's
problem and solution sheets), ``answers.csv``, ``answers.md``/``answers.pdf`` (a one-page
key: variant, data, answers) and ``moodle.xml`` (a Moodle XML question bank).

The variants are made and analysed by :mod:`mechreport.study.sheet_variants`; this module
only writes what they hold (each answer is the one number of its variant's analysis).

``moodle.xml`` is built with :mod:`xml.etree.ElementTree` (never by joining strings): a
category per spec, then one numerical question per variant and asked quantity, with its
answer, absolute tolerance and unit. The question text is HTML whose every piece of user text
(names, the statement) is escaped; the statement's Markdown is rendered with raw HTML off; the
mechanism's figure is embedded (base64), so the bank imports without other files."""
from __future__ import annotations

import base64
import csv
import html
import io
import xml.etree.ElementTree as ET
from pathlib import Path

from ..document import Doc, Layout, Print
from ..files import atomic_write_bytes, atomic_write_text
from ..pdf import compile_typst
from ..write_html import description_html
from ..write_markdown import markdown
from ..write_typst import typst
from .expr import fmt, round_off
from .render import write_sheet
from .statement import driver_statement
from .symbols import Names

ANSWERS_HEADER = ["variant", "quantity", "value", "unit", "tolerance"]
#: the one-page key: landscape, small text
KEY_LAYOUT = Layout(landscape=True, margin=(1.2, 1.0), size=7, title_size=12,
                    heading_sizes=((2, 9),), title_heading=True)
KEY_TABLE = Print(grid=True, size=6.5, inset=2)


def folder_of(number: int) -> str:
    """A variant's folder name: 01, 02, ... (three digits from 100 variants on)."""
    return f"{number:02d}"


def write_variants(variants, outdir: Path, options=None, name: str = "") -> list[Path]:
    """Write every variant's sheets into ``outdir/variants/NN/`` and the class's files
    (answers.csv, answers.md, answers.pdf, moodle.xml) into ``outdir/variants/``, in this
    process; returns the class files' paths."""
    root = Path(outdir) / "variants"
    problems = [write_variant(v.analysis, root / folder_of(v.number), options)
                for v in variants]
    return write_class_files(variants, problems, root, name)


def write_variant(analysis, folder: Path, options=None) -> dict:
    """One variant's problem and solution sheets in ``folder``; its problem as question
    text (:func:`problem_html`)."""
    sheet, problem = write_sheet(analysis, folder, options, models=True)
    return problem_html(sheet, problem, folder, analysis.spec)


def write_class_files(variants, problems: list[dict], root: Path, name: str) -> list[Path]:
    """answers.csv, answers.md, answers.pdf and moodle.xml of ``variants`` in ``root``
    (``problems``: each variant's question text, in the same order)."""
    root.mkdir(parents=True, exist_ok=True)
    out = [atomic_write_text(root / "answers.csv", answers_csv(variants))]
    key = key_document(variants, name)
    out.append(atomic_write_text(root / "answers.md", markdown(key)))
    out.append(compile_typst(typst(key), root / "answers.pdf", root))
    out.append(atomic_write_bytes(root / "moodle.xml", moodle_xml(variants, problems, name)))
    return out


def answers_csv(variants) -> str:
    """answers.csv: one row per variant and asked quantity (SI units; the tolerance is
    absolute, in the same unit)."""
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(ANSWERS_HEADER)
    for v in variants:
        for a in v.answers:
            w.writerow([v.number, f"{a.quantity}@{fmt(a.angle)}", repr(a.value), a.unit,
                        repr(a.tolerance)])
    return buf.getvalue()


def _data_text(v) -> str:
    return "; ".join(f"{k} = {fmt(x)}" for k, x in v.values.items())


def key_document(variants, name: str) -> Doc:
    """The one-page key: a row per variant with its varied data and every answer."""
    doc = Doc(f"Answer key: {name}", layout=KEY_LAYOUT)
    first = variants[0].answers if variants else []
    doc.p("Varied data in the spec's units, rounded as printed (each problem gives its "
          "data in SI units); answers in SI units, computed from the printed data "
          "(tolerance ±1 %).")
    header = ["variant", "data"] + [f"{a.label} [{a.unit}]" for a in first]
    rows = [[folder_of(v.number), _data_text(v)] + [fmt(a.value) for a in v.answers]
            for v in variants]
    doc.table(header, rows, right=set(range(2, len(header))), print=KEY_TABLE)
    return doc


# ------------------------------------------------------------------------------ Moodle

def _table(header: list[str], rows: list[list]) -> str:
    head = "".join(f"<th>{html.escape(str(h))}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in r) + "</tr>"
                   for r in rows)
    return f'<table border="1"><tr>{head}</tr>{body}</table>'


def problem_html(sheet, p, folder: Path, spec) -> dict:
    """A variant's problem (its sheet and problem models, figures drawn in ``folder``) as
    question text: {"html": the statement and data as HTML (every piece of user text
    escaped), "figures": {angle: (file name, bytes, title)} (the mechanism at each angle,
    referenced as @@PLUGINFILE@@/name)}."""
    with round_off(p.zero):
        parts = []
        if p.own_statement:
            parts.append(description_html(p.statement[0]))   # no raw HTML, no images
        else:
            parts += [f"<p>{html.escape(s)}</p>" for s in p.statement]
        parts.append("<p>Data, SI units (points and centres of mass C in each link's own "
                     "frame):</p>")
        parts.append(_table(["link", "name", "points [m]", "lengths", "shape", "m [kg]",
                             "I_C [kg m²]", "C [m]"], p.links))
        parts.append(_table(["joint", "type", "between"], p.joints))
        loads = "".join(f"<li>{html.escape(str(x))}</li>" for x in p.loads)
        names = Names(spec)
        effort = "M: the driver torque" if spec.driver.kind == "R" else \
            "F_d: the actuator force"
        symbols = [effort] + [f"{names.vec[j.name]}: the force of {j.links[0]} on "
                              f"{j.links[1]} at joint {j.written}" for j in spec.joints]
        # a statement written from the data already says how the mechanism is driven
        drive = f"<p>{html.escape(driver_statement(spec))}</p>" if p.own_statement else ""
        parts.append(f"{drive}<p>Symbols: {html.escape('; '.join(symbols))}.</p>")
        parts.append(f"<p>Ground points [m]: {html.escape(', '.join(p.ground))}. Gravity: "
                     f"g = {html.escape(p.gravity)}.</p>" + (f"<ul>{loads}</ul>" if loads
                                                             else ""))
    figures = {}
    for am in sheet.angles:
        if am.figure is not None and (folder / am.figure.path).is_file():
            figures[am.angle] = (Path(am.figure.path).name,
                                 (folder / am.figure.path).read_bytes(), am.title)
    return {"html": "".join(parts), "figures": figures}


def _text(parent, tag: str, value: str, **attrs) -> ET.Element:
    el = ET.SubElement(parent, tag, attrs)
    ET.SubElement(el, "text").text = value
    return el


#: how the signed answers are signed (one number is marked: a student who finds the
#: magnitude of a negative torque must know the sign is asked for)
SIGNS = {"driver.torque": " (signed: the torque the driver applies, counter-clockwise "
                          "positive)",
         "driver.force": " (signed: the driver's push along its line's direction, positive "
                         "when it pushes the slider that way)"}


def moodle_xml(variants, problems: list[dict], name: str) -> bytes:
    """The Moodle XML question bank (UTF-8 bytes)."""
    quiz = ET.Element("quiz")
    cat = ET.SubElement(quiz, "question", {"type": "category"})
    _text(cat, "category", f"$course$/mechreport/{name}")
    for v, prob in zip(variants, problems):
        for a in v.answers:
            q = ET.SubElement(quiz, "question", {"type": "numerical"})
            _text(q, "name", f"{name}, variant {folder_of(v.number)}: {a.label}")
            figs = [prob["figures"][a.angle]] if a.angle in prob["figures"] else []
            imgs = "".join(f'<p><img src="@@PLUGINFILE@@/{html.escape(f[0])}" '
                           f'alt="{html.escape(f[2])}: the mechanism" /></p>' for f in figs)
            sign = SIGNS.get(getattr(a, "quantity", ""), "")
            ask = (f"<p><strong>Find</strong> {html.escape(a.label)}, in "
                   f"{html.escape(a.unit)}{html.escape(sign)}.</p>")
            qt = _text(q, "questiontext", prob["html"] + imgs + ask, format="html")
            for fname, data, _ in figs:
                el = ET.SubElement(qt, "file", {"name": fname, "path": "/",
                                                "encoding": "base64"})
                el.text = base64.b64encode(data).decode("ascii")
            _text(q, "generalfeedback", "", format="html")
            ET.SubElement(q, "defaultgrade").text = "1"
            ET.SubElement(q, "penalty").text = "0.3333333"
            ET.SubElement(q, "hidden").text = "0"
            ans = ET.SubElement(q, "answer", {"fraction": "100", "format": "moodle_auto_format"})
            ET.SubElement(ans, "text").text = repr(a.value)
            ET.SubElement(ans, "tolerance").text = repr(a.tolerance)
            _text(ans, "feedback", "", format="html")
            units = ET.SubElement(q, "units")
            unit = ET.SubElement(units, "unit")
            ET.SubElement(unit, "multiplier").text = "1"
            ET.SubElement(unit, "unit_name").text = a.unit
            ET.SubElement(q, "unitgradingtype").text = "0"
            ET.SubElement(q, "unitpenalty").text = "0.1000000"
            ET.SubElement(q, "showunits").text = "3"
            ET.SubElement(q, "unitsleft").text = "0"
    ET.indent(quiz)
    return ET.tostring(quiz, encoding="utf-8", xml_declaration=True) + b"\n"
