"""The answer key (solution.md, solution.pdf) as a :class:`~mechreport.report.document.Doc`:
the data, the conventions, then for each reference angle the kinematics derivation, the
inertia forces and loads, the free-body diagrams, each method's equations in symbols and with
numbers, and the answers (a :class:`.model.SheetModel`)."""
from __future__ import annotations

from ..document import (Code, Columns, Description, Doc, Either, Emph, Equation, Figure, Figures,
                        Found, Gap, Heading, Items, Layout, Math, NewLine, Number, Paragraph, Print,
                        Strong, Table, Wording, rich)
from .expr import Raw
from .flywheel import flywheel_blocks
from .symbols import rich_label

#: a sheet's page: small text, its title a heading, derivations flush left
LAYOUT = Layout(margin=(1.7, 1.6, 1.8), size=9.5, title_size=15,
                heading_sizes=((2, 13), (3, 11), (4, 9.5)), heading_space=(1.0, 0.5),
                leading=0.55, spacing=0.8, title_heading=True, equations_left=True)
#: the tables: ruled cells in small text
TABLE = Print(grid=True, size=8, inset=3)


def _sym(tex: str, typ: str | None = None) -> Math:
    """A symbol or formula of a column header, in TeX and in Typst."""
    return Math(Raw(tex, tex if typ is None else typ, tex))


def _unit(math: Math, unit: str) -> list:
    return [math, Wording(f" [{unit}]")]


LINKS = ["link", "name", Wording("points (link frame) [m]"), _unit(_sym("m"), "kg"),
         _unit(_sym("I_C"), "kg m²"), _unit(_sym("C"), "m")]
ACTIONS = ["link", "name", _unit(_sym("m"), "kg"), _unit(_sym("I_C"), "kg m²"),
           _unit(_sym(r"F_{in} = -m\,a_C", 'bold(F)_"in" = -m bold(a)_C'), "N"),
           _unit(_sym(r"M_{in} = -I_C\,\alpha", 'M_"in" = -I_C alpha'), "N·m"),
           _unit(_sym(r"G = m\,g", "bold(G) = m bold(g)"), "N")]
ANSWERS = ["reaction", Either(Wording("x [N]"), _unit(_sym("x"), "N")),
           Either(Wording("y [N]"), _unit(_sym("y"), "N")), Wording("magnitude [N]"),
           Wording("couple or torque [N·m]")]
CUT = ["action", "at", _unit(_sym("F_x"), "N"), _unit(_sym("F_y"), "N"),
       Wording("moment about the cut [N·m]")]


def _label(text) -> list:
    """A joint's or step's name with its subscripts (C_T)."""
    return rich(rich_label(str(text)))


def solution_document(sheet) -> Doc:
    """The answer key of the :class:`.model.SheetModel` ``sheet``."""
    doc = Doc(f"Worked solution: {sheet.name}", layout=LAYOUT, end_blank=True)
    if sheet.description:
        doc.add(Description(sheet.description))
    doc.p("Spec: ", Code(sheet.file), ". ", *rich(sheet.driver))
    links = Table(LINKS, sheet.links, right={0, 3, 4}, print=TABLE)
    joints = Table(["joint", "type", "reaction of", "symbol"],
                   [[_label(n), t, who, Math(sym)] for n, t, who, sym in sheet.joints],
                   print=TABLE)
    doc.add(Columns([links, joints]))
    doc.p("Methods shown: " + ", ".join(sheet.method_titles) + ".")
    doc.h("Conventions")
    items = [rich(c) for c in sheet.conventions]
    if sheet.t_note:
        items.append(rich(sheet.t_note))
    if sheet.exact_note:
        items.append(sheet.exact_note)
    doc.add(Items(items, small=True))
    for a in sheet.angles:
        _angle(doc, sheet, a)
    if sheet.flywheel is not None:
        flywheel_blocks(doc, sheet.flywheel)
    return doc


def _angle(doc: Doc, sheet, a) -> None:
    doc.h(a.title)
    if a.skipped:
        doc.p("This reference angle is left out of the analysis: ", *_label(a.skipped),
              ". No solution can be written for it.")
        return
    doc.p(*rich(a.intro))
    doc.add(Figure(a.figure.path, rich(a.figure.caption), width=0.62))
    doc.h("Kinematics", 3)
    for b in a.kinematics:
        doc.add(Heading(_label(b.title), 4))
        for kind, x, y in b.items:
            if kind == "text":
                doc.p(*rich(x))
            elif kind == "eq":
                if x:
                    doc.p(*rich(x))
                for e in (y if isinstance(y, (list, tuple)) else [y]):
                    doc.add(Equation(e))
            else:
                doc.add(Found("Found:", [Math(e) for e in x], print_label=False, gap=0.6))
    doc.h("Inertia forces, weights and loads", 3)
    doc.add(Table(ACTIONS, a.actions, right={0, 2, 3, 4, 5, 6},
                  print=Print(grid=True, size=8, inset=3, right=frozenset(range(7)))))
    if a.loads:
        doc.add(Table(["load", "on link", "at", "value at this angle", "rule"],
                      [[Math(r[0]), *r[1:]] for r in a.loads], print=TABLE))
    doc.h("Free-body diagrams", 3)
    doc.add(Figures([Figure(f.path, rich(f.caption)) for f in a.fbds]))
    doc.add(Paragraph(rich(a.fbd_note), small=True))
    if a.friction:
        doc.h("Friction in the joints", 3)
        doc.p(*rich(a.friction))
    if a.dynamics:
        doc.h("Equation of motion", 3)
        for p in a.dynamics:
            doc.p(*rich(p))
    for m in a.methods:
        _method(doc, m)
    _answers(doc, sheet, a)


def _method(doc: Doc, m) -> None:
    doc.h(f"{m.title} ({m.section})", 3)
    doc.add(Paragraph(rich(m.intro), small=True))
    for s in m.steps:
        if len(m.steps) > 1:
            doc.add(Heading([f"Step {s.number}: ", *_label(s.title)], 4))
        text = [s.free_body, ". Unknowns: ", Math(s.unknowns), "."]
        for note, mth in s.notes:
            text += [NewLine(), note[0].upper() + note[1:], " ", Math(mth), "."]
        doc.p(*text)
        for g in s.groups:
            if g.heading:
                doc.add(Paragraph(Either(Emph(g.heading), Strong(g.heading)), small=True))
            for e in g.equations:
                doc.add(Equation(e.symbolic, e.number, e.numeric))
        more = []
        for jn, vec, pe in s.points:
            more.append([Math(vec), " acts ",
                         *(["at ", Math(pe), " on the line of ", Math(jn)] if pe else
                           ["at no finite point (it vanishes)"])])
        doc.add(Found(Wording(s.cited), [Math(r) for r in s.results], more))
    if m.check:
        text = ["Compared with the other methods: "]
        for i, (title, eq, diff) in enumerate(m.check):
            text += [title, " ", Math(eq), " (difference ", Number(diff), ")"]
            if i < len(m.check) - 1:
                text.append("; ")
        doc.p(*text, ".")


def _answers(doc: Doc, sheet, a) -> None:
    doc.h("Answers", 3)
    header = ANSWERS + (["exact"] if sheet.exact else [])
    rows = [[Math(sym), Number(x), Number(y), Number(mag), Number(cpl),
             *([rich(forms)] if sheet.exact else [])]
            for sym, x, y, mag, cpl, forms in a.answers]
    doc.add(Table(header, rows, right={1, 2, 3, 4}, print=TABLE))
    doc.add(Paragraph(a.answers_note, small=True))
    if a.shown:
        doc.p(Wording("Results in the report's units ("), sheet.units, "):")
        doc.add(Table(["reaction", "x", "y", "magnitude", "couple"], a.shown,
                      right={1, 2, 3, 4}, print=TABLE))
    if a.cuts:
        doc.h("Strength: the members cut open", 3)
        for c in a.cuts:
            doc.add(Heading(c.title, 4))
            doc.p(*rich(c.intro))
            doc.add(Table(CUT, [[rich(r[0]), *r[1:]] for r in c.rows], right={2, 3, 4},
                          print=TABLE))
            doc.p(*rich(c.result))
        doc.add(Gap())
