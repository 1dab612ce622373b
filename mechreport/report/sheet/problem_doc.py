"""The problem version of a solution sheet (problem.md, problem.pdf) as a
:class:`~mechreport.report.document.Doc`: statement, data, figures, what to find. It holds no
computed result: only what the spec gives (a :class:`.model.ProblemModel`)."""
from __future__ import annotations

from ..document import Description, Doc, Either, Figure, Layout, Math, Print, Wording, rich
from .expr import Raw
from .symbols import rich_label

#: a sheet's page: 10 pt text, its title a heading
LAYOUT = Layout(margin=(1.8, 1.8, 2), size=10, title_size=15, heading_sizes=((2, 12),),
                heading_space=None, leading=0.6, title_heading=True)
#: the data tables: ruled cells in small text
DATA = Print(grid=True, size=8.5, inset=3.5)


def _sym(name: str) -> Math:
    """A quantity's symbol, written the same in TeX and Typst (``m``, ``I_C``)."""
    return Math(Raw(name, name, name))


LINK_HEADER = ["link", "name", Wording("points [m]"), "lengths", "shape",
               [_sym("m"), Wording(" [kg]")], [_sym("I_C"), Wording(" [kg m²]")],
               [_sym("C"), Wording(" [m]")]]


def problem_document(p) -> Doc:
    """The problem sheet of the :class:`.model.ProblemModel` ``p``."""
    doc = Doc(f"Problem: {p.name}", layout=LAYOUT)
    if p.own_statement:           # the sheet's own statement (Markdown, never raw HTML)
        doc.add(Description(p.statement))
    else:                         # a statement written from the data
        for par in p.statement:
            doc.p(par)
    doc.h("Data")
    doc.p(Wording("SI units. Links (each with its own frame; points and centre of mass "),
          Either("C", _sym("C")), Wording(" in that frame):"))
    doc.table(LINK_HEADER, p.links, right={0, 5, 6}, print=DATA)
    doc.p("Joints:")
    doc.table(["joint", "type", "between"],
              [[rich(rich_label(str(r[0]))), *r[1:]] for r in p.joints], print=DATA)
    doc.p(Wording("Ground points [m]: "), ", ".join(p.ground), ". ", *rich(p.driver),
          " Gravity: g = ", p.gravity, ".")
    if p.loads:
        doc.items(list(p.loads), intro="Loads:")
    for title, fig in p.angles:
        if fig:
            text = f"{title}: the mechanism, links numbered, joints lettered"
            doc.add(Figure(fig.path, text + ".", alt=text, width=0.62))
    doc.h("Find")
    doc.items(list(p.tasks), ordered=True)
    return doc
