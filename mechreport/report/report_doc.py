"""One spec's report (report.md, report.pdf) as a :class:`~.document.Doc`, built from the
:class:`~.model.ReportModel`'s records: traceability and the check, the design summary, the
mechanism, each reference angle, the sweep, friction, machine dynamics, strength, method
agreement and the left-out angles. It formats nothing: every string is the model's."""
from __future__ import annotations

from dataclasses import replace

from ..units import with_unit
from .document import (Blank, Box, Code, Columns, Description, Doc, Either, Emph, Figure,
                       Gap, Heading, Item, Items, Key, Layout, Link, NewLine, Only, Pairs,
                       Paragraph, Print, Ref, Space, Strong, Table, Wording)
from .text import cycle_name

#: the report's pages: justified 10 pt text, numbered sections, figures never split
LAYOUT = Layout(margin=(1.8, 1.9, 1.8), size=10, title_size=17, heading_sizes=(),
                heading_space=None, justify=True, numbered=True, heading_shift=1,
                level_spaces=((1, 1.3, 0.7), (2, 1.1, 0.6)), figures_whole=True,
                title_center=True)
#: the design summary's figures of the cycle, in order (the balance one narrower)
CYCLE_FIGURES = ("pressure", "turning_moment", "flywheel", "breakdown", "transmission",
                 "balance")


def _u(label: str, unit: str) -> Wording:
    """A column heading with its unit: ``peak [kN]``."""
    return Wording(with_unit(label, unit))


def _table(header, rows, right=frozenset(), size: float = 8, **how) -> Table:
    """A data table: small print (``size`` pt), kept whole up to 30 rows; ``right``: its
    right-aligned columns."""
    return Table(header, rows, set(right), print=Print(keep=True, size=size, inset=2), **how)


def _first_left(header, rows, size: float = 8, **how) -> Table:
    """A table whose first column is text, the others numbers (right-aligned)."""
    return _table(header, rows, range(1, len(header)), size, **how)


def report_document(m) -> Doc:
    """The report of the :class:`~.model.ReportModel` ``m``."""
    title = m.meta.title or m.name
    rev = f" · rev. {m.meta.revision}" if m.meta.revision else ""
    layout = replace(LAYOUT, header=(f"{title}{rev}",
                                      f"mechreport {m.meta.version} · {m.meta.date}"))
    doc = Doc(title, layout=layout, author=m.meta.author or "mechreport",
              subtitle=m.name if m.meta.title and m.meta.title != m.name else "",
              byline=["Dynamic force analysis report · source ", Code(m.source)])
    _front(doc, m)
    _design(doc, m)
    _contents(doc, m)
    _mechanism(doc, m)
    for r in m.refs:
        _reference(doc, m, r)
    _sweep(doc, m)
    if m.friction:
        _friction(doc, m, m.friction)
    if m.dynamics:
        _dynamics(doc, m, m.dynamics)
    if m.strength:
        _strength(doc, m, m.strength)
    _agreement(doc, m)
    _left_out(doc, m)
    return doc


def _front(doc: Doc, m) -> None:
    """Traceability, the check and the description; the animation (Markdown only)."""
    rows = [[k, Code(v) if k == "Spec SHA-256" else v] for k, v in m.meta.rows()]
    files = [("results.csv", True), ("summary.json", True), ("report.pdf", True),
             ("animation.gif", bool(m.animation)), ("mechanism.dxf", bool(m.dxf))]
    source = [m.source]
    for name, present in files:
        if present:
            source += [" · ", Link(name, name)]
    doc.add(Pairs(rows, text_rows=[["Source", source]]))
    box = [Paragraph([Strong("Check:"), " ", m.status_line])]
    if m.failures:
        box += [Paragraph([Strong("Failed expectations"), " (each once; the computed value is "
                           "the one furthest from the expected one):"]),
                _table(["quantity", "angle [deg]", "expected", "computed", "difference",
                        "tolerance", "method"], m.failures, {1, 2, 3, 4, 5}, 7.5)]
    box += [Paragraph([Strong("Note:"), " ", note]) for note in m.notes]
    box.append(Paragraph([Strong("Left out:"), " ", m.left_out]))
    doc.add(Box(box, m.status))
    if m.description:
        doc.add(Description(m.description))
    if m.animation:
        doc.add(Only([Heading("In motion"),
                      Figure("animation.gif", m.animation.caption, caption_below=True,
                             alt="The mechanism moving over the sweep with its forces")],
                     print=False))


def _design(doc: Doc, m) -> None:
    dz = m.design
    doc.h("Design summary")
    if dz.problem:
        doc.add(Paragraph(["No cycle quantities: ", dz.problem, "."], tight=True))
        return
    if dz.verdicts:
        doc.add(_table(["design item", "checked quantity", "value", "limit", "margin",
                        "verdict"], dz.verdicts, {2, 3, 4}))
    doc.p(dz.counterweight, *([NewLine(hard=False), dz.interpolated] if dz.interpolated else []))
    values = Table(["cycle quantity", Either(Wording("name (for `expect`)"),
                                             "name (for expect)"), "value"],
                   [[r[0], Key(r[1]), r[2]] for r in dz.values], {2},
                   print=Print(size=7.5, inset=2, inset_x=3))
    columns = [values]
    if dz.bearings:
        force = m.heads["force"]
        columns.append([
            Only([Paragraph(["Joint loads over the cycle (", Code("joint.J.f_max"), ", ",
                             Code("f_mean"), ", ", Code("f_equivalent"),
                             ": the cube-mean load; ", Code("life_h"),
                             " where a rating is given):"])], print=False),
            _first_left(["joint", _u("peak", force), _u("mean", force),
                         _u("equivalent", force), Wording("L10 life [h]")], dz.bearings, 7.5),
            Only([Paragraph("Joint loads over the cycle (joint.J.f_max, f_mean, f_equivalent: "
                            "the cube-mean load; life_h where a rating is given).", small=7)],
                 print=True)])
    doc.add(Columns(columns, widths=(1.25, 1) if dz.bearings else (1,), gutter=12))
    for key in CYCLE_FIGURES:
        if key in m.figures:
            f = m.figures[key]
            doc.add(Figure(f.svg, f.caption, caption_below=True,
                           width=0.55 if key == "balance" else 1.0))
    for text in dz.absent.values():
        doc.p(text)


def _contents(doc: Doc, m) -> None:
    """The Markdown's contents (print numbers its sections instead)."""
    entries = [("In motion", "in-motion")] if m.animation else []
    entries += [("Design summary", "design-summary"), ("Mechanism", "mechanism")]
    entries += [(r.title, r.anchor) for r in m.refs]
    entries.append(("Over the sweep", "over-the-sweep"))
    entries += [(t, a) for t, a, on in (("Friction", "friction", m.friction),
                                         ("Machine dynamics", "machine-dynamics", m.dynamics),
                                         ("Strength", "strength", m.strength)) if on]
    entries += [("Method agreement", "method-agreement"), ("Left-out angles", "left-out-angles")]
    doc.add(Only([Heading("Contents"), Items([Ref(t, a) for t, a in entries])], print=False))


def _mechanism(doc: Doc, m) -> None:
    h = m.heads
    doc.h("Mechanism")
    doc.p(Wording("Links (number 0 is the frame; centre of mass in the link's frame; lengths "
                  f"in {h['length']}):"))
    doc.add(_table([Wording("#"), "link", _u("mass", h["mass"]), _u("inertia", h["inertia"]),
                    "centre of mass", "shape and points"], m.links, {0, 2, 3}))
    doc.p("Joints (a reaction is the force of the first link on the second):")
    doc.add(_table(["joint", "type", "links", "reaction", "where"], m.joints))
    doc.p("Assembly branch of each group (each can be assembled two or more ways; what chose "
          "the one analysed):")
    doc.add(_table(["group", "type", "branch taken, and why"], m.branches))
    methods = ", ".join(f"{mt.title} ({mt.cite})" for mt in m.methods)
    doc.items([[Strong("Driver:"), " ", m.driver], [Strong("Gravity:"), " ", m.gravity],
               Item([Strong("Loads:"), *([] if m.loads else [" none"])], list(m.loads)),
               [Strong("Sweep:"), " ", m.sweep_text], [Strong("Methods:"), " ", methods]])
    if m.animation and m.animation.strip_svgs:
        doc.add(Only([Heading("In motion", 3),
                      Paragraph([Wording("animation.gif, in the report's folder: "),
                                 m.animation.caption]),
                      Figure(list(m.animation.strip_svgs), m.animation.strip_caption)],
                     print=True))


def _reference(doc: Doc, m, r) -> None:
    h = m.heads
    doc.add(Space())
    doc.h(r.title)
    if r.flag:
        doc.p("This reference angle is left out: ", r.flag, ".")
        return
    doc.add(Figure(r.drawing.svg, r.drawing.caption, caption_below=True))
    doc.h(f"Kinematics at {r.phrase}", 3)
    length, v, a = h["length"], h["velocity"], h["acceleration"]
    doc.add(_first_left(["point", _u("x", length), _u("y", length), _u("vx", v), _u("vy", v),
                         _u("ax", a), _u("ay", a)], r.points))
    doc.add(_first_left(["link", Wording("angle [deg]"), Wording("ω [rad/s]"),
                         Wording("α [rad/s²]"), _u("a_C x", a), _u("a_C y", a)], r.links))
    doc.h(f"Joint reactions and {m.effort_name} at {r.phrase}", 3)
    rows = [[row[0], Either(Wording(row[1].replace("|", "\\|")), row[1]), *row[2:]]
            for row in r.reactions]
    doc.add(_table(["joint", "quantity", *[mt.title for mt in m.methods]], rows,
                   range(2, 2 + len(m.methods)), 7.5, header_blank=True))
    doc.add(Only([Items(list(r.vectors), intro=f"By {m.method_title}:")], print=False))


def _figure(doc: Doc, m, key: str) -> None:
    if key in m.figures:
        f = m.figures[key]
        doc.add(Figure(f.svg, f.caption, caption_below=True))


def _sweep(doc: Doc, m) -> None:
    h = m.heads
    doc.add(Space())
    doc.h("Over the sweep")
    doc.p(f"Values from {m.method_title} (every method agrees: ",
          Either(["see ", Ref("Method agreement", "method-agreement")],
                 "see the method agreement section"), ").")
    t = m.torque
    doc.add(_first_left([m.effort_name, "value"],
                        [["mean", t["mean"]], ["RMS", t["rms"]],
                         ["peak (largest magnitude)", t["peak"]], ["minimum", t["low"]],
                         ["maximum", t["high"]], ["mean input power", t["power"]]]))
    _figure(doc, m, "torque")
    doc.p(Wording("Bearing loads (magnitude of each joint's reaction): its peak over the "
                  "analysed angles, as\neverywhere else, its RMS, and, where the peak lies near "
                  "a left-out angle, the peak away from\nthem:"))
    doc.add(_table(["joint", "reaction", "kind", _u("peak", h["force"]), _u("at", h["axis"]),
                    _u("RMS", h["force"]),
                    _u("peak away from left-out angles", h["force"])], m.bearings, {3, 4, 5, 6}))
    _figure(doc, m, "reactions")
    _figure(doc, m, "polar")
    doc.p(f"Shaking force peak: {m.shaking['force']}; shaking moment peak: "
          f"{m.shaking['moment']}.")
    _figure(doc, m, "shaking")


def _friction(doc: Doc, m, f) -> None:
    doc.add(Space())
    doc.h("Friction")
    doc.p(f.intro)
    if f.problem:
        doc.p("Energy lost per cycle and efficiency: undefined (", f.problem, ").")
    else:
        doc.p(Strong("Mechanical efficiency:"), " ", f.efficiency, " (", Code("cycle.efficiency"),
              Wording(": 1 − the energy lost to friction / the driver's positive work, per "
                      "cycle). "), Strong("Energy lost to friction:"), " ", f.energy,
              " per cycle (", Code("cycle.friction.energy"), ").")
    rows = list(f.rows)
    if f.total:
        rows.append([Strong(c) if i in (0, 5) else (c or Blank())
                     for i, c in enumerate(f.total)])
    doc.add(_table(["joint", "type", "friction", "μ", Wording(f.size_head),
                    Wording("lost per cycle [J]"), "share", "largest magnitude",
                    _u("at", m.heads["axis"])], rows, range(3, 9)))
    for text in f.remarks:
        doc.p(text)
    _figure(doc, m, "friction")


def _dynamics(doc: Doc, m, y) -> None:
    doc.add(Space())
    doc.h("Machine dynamics")
    doc.p(y.intro)
    doc.p(y.outcome)
    if y.rows:
        doc.add(_table(["quantity", "value", "what it is"], y.rows, {1}))
        doc.p(y.why)
    else:
        doc.add(Gap())
    _figure(doc, m, "dynamics")
    # a 720° engine cycle is a cycle, not a turn; with mean_rpm the drive is no motor
    span = cycle_name(y.plot.cycle)
    drive = "motor's" if y.plot.startup_shown else "constant driving torque's"
    if y.compared:
        doc.p(Wording(f"The forces at that motion: the steady {span} analysed like the sweep, "
                      "by every method, with the crank's true speed and acceleration at each "
                      "angle, beside the sweep at the driver's constant speed:"))
        doc.add(_table(["quantity", "constant speed (sweep)", f"steady {span}"], y.compared,
                       {1, 2}))
    if y.verdicts:
        doc.items(list(y.verdicts), intro=[
            Wording(f"Design verdicts over the steady {span} ("
                    + ("the motor's against its own torque and power: " if y.plot.startup_shown
                       else "")
                    + "with a flywheel the crank shaft's torque, "),
            Code("cycle.torque.*"), Wording(f", is the {drive} and the flywheel's together):")])
    doc.p("Time histories: ", Code("dynamics.csv"), " and ", Code("dynamics.parquet"),
          " (time, crank angle unwrapped, speed, acceleration, motor torque; SI).")


def _strength(doc: Doc, m, st) -> None:
    h = m.heads
    doc.add(Space())
    doc.h("Strength")
    doc.p(st.intro)
    if st.links:
        doc.items(list(st.links))
    else:
        doc.add(Gap())
    doc.add(_first_left(["member", Wording(f"largest stress [{h['stress']}]"),
                         Wording(f"at [{h['axis']}], s [{h['length']}]"), "static safety",
                         "fatigue safety",
                         Wording(f"σa / σm [{h['stress']}] at s [{h['length']}]"),
                         "buckling safety", _u("largest compression", h["force"]),
                         _u("P_cr", h["force"])], st.rows, 7))
    if st.worst:
        doc.p(st.worst)
    else:
        doc.add(Gap())
    for text in st.notes:
        doc.p(Emph("Note:"), " ", text)
    _figure(doc, m, "strength")
    _figure(doc, m, "stress")


def _agreement(doc: Doc, m) -> None:
    h = m.heads
    doc.h("Method agreement")
    doc.p(Wording("Worst disagreement of each quantity between any two methods over the "
                  "sweep, relative to the\nquantity's largest magnitude."))
    doc.add(_table(["quantity", "relative", "absolute", "between", _u("at", h["axis"]),
                    "methods"], m.agreement, {1, 2, 4, 5}, 7.5))
    doc.p(m.power_check)
    doc.p(Wording("Equilibrium residuals (each method's reactions substituted into every "
                  "link's Newton-Euler\nequations):"))
    doc.add(_first_left(["method", _u("force", h["force"]), _u("moment", h["moment"])],
                        m.residuals))


def _left_out(doc: Doc, m) -> None:
    doc.h("Left-out angles")
    if not m.flags:
        doc.p("None: every angle of the sweep was solved.")
        return
    doc.p(Wording("Angles left out of every table and plot: positions the mechanism cannot "
                  "reach from its\nassembly, singular positions, and near-singular ones where "
                  "results would not be trustworthy:"))
    doc.add(_table([_u(m.coord, m.heads["axis"]), "reason"], m.flags, {0}))
