"""User text in figures is literal text (the issue "A `$` in a name breaks `build` after
`check` passed"): names from the spec (links, joints, points, loads) and a study's keys and
quantities are drawn as written in every figure (plots, drawings, solution-sheet figures,
study figures), never read as matplotlib mathtext; mechreport's own symbols ($F_{21x}$) stay
maths.

The SVGs keep text as text (``svg.fonttype: none``): a plain string is one ``<text>`` element
holding it, and a mathtext string is written as the comment ``<!-- $...$ -->`` followed by its
glyphs, so both are read straight from the file."""
from __future__ import annotations

import re
from pathlib import Path
from xml.sax.saxutils import escape

import pytest

ROOT = Path(__file__).resolve().parents[2]

CRANK = r"c\rank{}%_1"      # a backslash, braces, % and _, but no $
ROD = "$x^2$"               # valid mathtext
B = "$B_2$"                 # a joint and point name that is valid mathtext
C = "C\\$"                  # a backslash before a dollar sign (matplotlib's escaped $)
SLIDE = "_slide"            # a slider joint whose name starts with an underscore
LOAD = "a$b_{$"             # the load name: mathtext that does not parse

HOSTILE = [LOAD, ROD, B, C, SLIDE, CRANK, "$", "$$", "a$b", "\\", "x\\", "\\$\\$", "{}", "%",
           "_", "50% of $\\alpha$", "$\\frac{1}{0}$", "<a & b>"]


def q(name: str) -> str:
    """``name`` as a single-quoted YAML scalar (backslashes stay as they are)."""
    return "'" + name.replace("'", "''") + "'"


def hostile_text() -> str:
    """specs/slider_crank.yaml on a 30-degree sweep with hostile link, joint, point and load
    names (renamed consistently), and a small study that varies and keeps some of them."""
    text = (ROOT / "specs" / "slider_crank.yaml").read_text(encoding="utf-8")
    text = text[:text.index("# Textbook 4.6")]                      # no expectations

    def rep(old: str, new: str) -> None:
        nonlocal text
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    rep("sweep: {start: 0, stop: 360, step: 1}", "sweep: {start: 0, stop: 360, step: 30}")
    rep("  crank:\n", f"  {q(CRANK)}:\n")
    rep("  rod:\n", f"  {q(ROD)}:\n")
    rep("points: {A: [0, 0], B: [1, 0]}", f"points: {{A: [0, 0], {q(B)}: [1, 0]}}")
    rep("points: {B: [0, 0], C: [1, 0]}", f"points: {{{q(B)}: [0, 0], {q(C)}: [1, 0]}}")
    rep("points: {C: [0, 0]}", f"points: {{{q(C)}: [0, 0]}}")
    rep("  A:   {type: R, links: [ground, crank]}",
        f"  A: {{type: R, links: [ground, {q(CRANK)}]}}")
    rep("  B:   {type: R, links: [crank, rod]}",
        f"  {q(B)}: {{type: R, links: [{q(CRANK)}, {q(ROD)}]}}")
    rep("  C:   {type: R, links: [rod, slider]}",
        f"  {q(C)}: {{type: R, links: [{q(ROD)}, slider]}}")
    rep("  C_T: {type: T, links: [ground, slider], point: C,",
        f"  {q(SLIDE)}: {{type: T, links: [ground, slider], point: {q(C)},")
    rep("assembly: {C: [1.4, 0]}", f"assembly: {{{q(C)}: [1.4, 0]}}")
    rep("point: C, value: [100, 0], oppose: velocity}",
        f"point: {q(C)}, value: [100, 0], oppose: velocity, name: {q(LOAD)}}}")
    return text + ("study:\n  vary:\n"
                   f"    - {{key: {q('links.' + ROD + '.mass')}, values: [1, 2]}}\n"
                   f"  keep: [{q('joint.' + B + '.f_max')}, cycle.torque.rms]\n")


@pytest.fixture(scope="module")
def hostile(tmp_path_factory):
    """(analysis, report model, index of the reference angle 45) of the hostile spec."""
    import mechreport
    from mechreport.report.model import build_model

    path = tmp_path_factory.mktemp("figure-text") / "hostile.yaml"
    path.write_text(hostile_text(), encoding="utf-8")
    analysis = mechreport.analyse(path)
    return analysis, build_model(analysis, path, sha256=""), analysis.kinematics.index_of(45)


def svg(make, folder: Path, stem: str) -> str:
    """The SVG text of the figure ``make()`` draws, made and saved in the report's style."""
    from mechreport.report.plots import save, style
    with style():
        path = save(make(), folder, stem)[0]
    return path.read_text(encoding="utf-8")


def literally(text: str) -> str:
    """How a plain (not mathtext) string ``text`` stands in an SVG: one text element."""
    return f">{escape(text)}</text>"


def maths(svg_text: str) -> list[str]:
    """The mathtext strings of an SVG (each is written as a comment before its glyphs)."""
    return re.findall(r"<!-- (.*?) -->", svg_text)


def texts_of(svg_text: str) -> list[str]:
    """The strings of the plain text elements of an SVG (XML entities undone)."""
    return [t.replace("&lt;", "<").replace("&gt;", ">").replace("&amp;", "&")
            for t in re.findall(r">([^<>]*)</text>", svg_text)]


# ------------------------------------------------------------------------ the helper

@pytest.mark.parametrize("text", HOSTILE)
def test_literal_text_is_drawn_as_written_by_any_matplotlib_text(text, tmp_path):
    """A title, axis label, annotation, free text and legend entry of ``literal(text)`` all
    show ``text`` itself, whatever dollar signs and backslashes it has."""
    from matplotlib.figure import Figure
    from mechreport.report.plots import literal

    def make():
        fig = Figure(figsize=(4, 3))
        ax = fig.subplots()
        lines = ax.plot([0, 1], [0, 1], label=literal(text))
        ax.set_title(literal(text))
        ax.set_xlabel(literal(text))
        ax.text(0.5, 0.5, literal(text))
        ax.annotate(literal(text), (0.2, 0.2))
        ax.legend(handles=lines)             # given, as the report's: "_..." stays in
        return fig
    out = svg(make, tmp_path, "t")
    assert out.count(literally(text)) == 5
    assert maths(out) == []


@pytest.mark.parametrize("text", ["A", "O2", "C_T", "B_R C_R C_T", CRANK, "x\\", "{}", "%",
                                  "group 50%", "φ = 45°"])
def test_literal_leaves_text_without_a_dollar_unchanged(text):
    """Names without a dollar sign reach matplotlib exactly as before (figures of such
    specs stay byte for byte the same)."""
    from mechreport.report.plots import literal
    assert literal(text) == text


# ------------------------------------------------------------------------- the plots

def test_a_dollar_in_a_load_name_is_drawn_literally(hostile, tmp_path):
    """The issue's load name ``a$b_{$`` (an unparsable mathtext) in the torque breakdown's
    legend: drawn as written instead of raising while the figure is drawn."""
    from mechreport.report.plots import breakdown_figure
    _, model, _ = hostile
    out = svg(lambda: breakdown_figure(model.design.data, model.display), tmp_path, "bd")
    assert literally(LOAD) in out
    assert maths(out) == []


def test_a_load_name_starting_with_an_underscore_keeps_its_legend_entry(hostile, tmp_path):
    """matplotlib leaves labels that start with ``_`` out of a legend it collects itself;
    a load named ``_gas`` is still named in the torque breakdown."""
    import dataclasses
    from mechreport.report.plots import breakdown_figure
    _, model, _ = hostile
    cd = model.design.data
    sources = {("_gas" if name == LOAD else name): v for name, v in cd.sources.items()}
    cd = dataclasses.replace(cd, sources=sources)
    out = svg(lambda: breakdown_figure(cd, model.display), tmp_path, "bd")
    assert literally("_gas") in out
    assert literally("inertia") in out and literally("total") in out


def test_mathtext_in_a_link_name_is_not_rendered_as_maths(hostile, tmp_path):
    """A link named ``$x^2$`` (the frame of a polar bearing diagram) and a joint named
    ``$B_2$``: the title shows them as written, not as x squared and B sub 2."""
    from mechreport.report.plots import polar_figure
    _, model, _ = hostile
    out = svg(lambda: polar_figure(model.sweep, model.display), tmp_path, "polar")
    title = f"{B} (F12), frame of {ROD}"
    # one line, or two where it would be wider than its axes (each line one text element)
    assert literally(title) in out or (literally(f"{B} (F12),") in out
                                       and literally(f"frame of {ROD}") in out)
    assert maths(out) == []


def test_mathtext_in_a_joint_name_is_not_rendered_as_maths_in_the_reactions(hostile, tmp_path):
    from mechreport.report.plots import reactions_figure
    _, model, _ = hostile
    out = svg(lambda: reactions_figure(model.sweep, model.display), tmp_path, "reactions")
    assert literally(f"{B} (F12)") in out
    assert literally(f"{C} (F23)") in out          # its backslash kept, not eaten as an escape
    assert maths(out) == []


def test_a_joint_name_starting_with_an_underscore_keeps_its_legend_entry(hostile, tmp_path):
    from mechreport.report.plots import reactions_figure
    _, model, _ = hostile
    out = svg(lambda: reactions_figure(model.sweep, model.display), tmp_path, "reactions")
    texts = texts_of(out)
    assert [t for t in texts if t.endswith(")") and t.split(" (")[0] in
            ("A", B, C, SLIDE)] == ["A (F01)", f"{B} (F12)", f"{C} (F23)", f"{SLIDE} (F03)"]


def test_joint_names_in_transmission_groups_are_drawn_literally(hostile, tmp_path):
    from mechreport.report.plots import transmission_figure
    _, model, _ = hostile
    out = svg(lambda: transmission_figure(model.design.data, model.display), tmp_path, "tr")
    assert literally(f"group {B} {C} {SLIDE}") in out
    assert maths(out) == []


# ----------------------------------------------------------------------- the drawings

def test_point_names_with_dollars_and_backslashes_are_drawn_literally(hostile, tmp_path):
    """The reference-angle drawing names points ``$B_2$`` and ``C\\$`` as written; its
    arrows keep their symbols."""
    from mechreport.report.drawing import write_drawings
    _, model, _ = hostile
    (path,) = write_drawings(model, tmp_path)
    out = path.read_text(encoding="utf-8")
    assert literally(B) in out and literally(C) in out
    assert maths(out) == []


def test_sheet_figures_draw_point_names_literally_and_symbols_as_maths(hostile, tmp_path):
    """The solution sheet's mechanism and free-body diagrams: the spec's point names as
    written; mechreport's own symbols ($F_{12x}$, $C_{2}$, $\\omega_{1}$) still mathtext."""
    from mechreport.report.sheet.figures import fbd_figure, mechanism_figure
    analysis, _, k = hostile
    mech = mechanism_figure(analysis, k, tmp_path / "mechanism.svg").read_text(encoding="utf-8")
    assert literally(B) in mech and literally(C) in mech
    assert r"$\omega_{1}$" in maths(mech)
    rod, _ = fbd_figure(analysis, k, ROD, tmp_path / "fbd-2.svg", set())
    rod = rod.read_text(encoding="utf-8")
    assert literally(B) in rod and literally(C) in rod
    assert {"$F_{12x}$", "$F_{12y}$", "$C_{2}$"} <= set(maths(rod))
    assert not any(name in m for m in maths(mech) + maths(rod) for name in (B, C, ROD))


# ---------------------------------------------------------------------- study figures

def test_study_keys_and_quantities_with_a_dollar_are_drawn_literally(tmp_path):
    """A varied key through a link named ``$x^2$`` and a kept quantity of the joint ``$B_2$``
    label the study's figures as written."""
    from mechreport.study.run import run_variants
    from mechreport.spec.loader import parse_source, spec_from_data
    from mechreport.study import plan_of
    from mechreport.study.report import StudyRun, write_figures
    from mechreport.study.variants import base_of

    src = parse_source(hostile_text(), "hostile.yaml")
    base = base_of(spec_from_data(src.data, src), src)
    plan = plan_of(base.spec.study)
    table = run_variants(base, plan, "newton_euler", base.spec.study.keep, jobs=1)
    assert table.ok.all()
    run = StudyRun(base, table, "newton_euler", "test", 0.0, "this process", 1)
    figures = write_figures(run, tmp_path)
    key, quantity = f"links.{ROD}.mass [kg]", f"joint.{B}.f_max [N]"
    first = (tmp_path / "quantity-1.svg").read_text(encoding="utf-8")
    assert literally(key) in first and literally(quantity) in first
    pareto = (tmp_path / "pareto.svg").read_text(encoding="utf-8")
    assert literally(quantity) in pareto and literally("cycle.torque.rms [N·m]") in pareto
    assert set(figures) == {"quantity-1", "quantity-2", "pareto"}
    for name in figures:
        assert maths((tmp_path / f"{name}.svg").read_text(encoding="utf-8")) == []


# ------------------------------------------------------------------ one round-off rule

@pytest.mark.parametrize("spec", ["static_press", "toggle_press", "slider_crank", "four_bar"])
def test_moment_and_force_scales_share_the_load_scale_through_the_mechanism_size(spec):
    """The round-off scale of moments includes the largest force times the mechanism's size
    (and that of forces the largest moment over it): a moment that is round-off next to the
    forces prints 0 (a static press's shaking moment, 1e-13 N·m beside 20 kN)."""
    import mechreport
    import numpy as np
    a = mechreport.analyse(ROOT / "specs" / f"{spec}.yaml")
    sc, size = a.scales(), a.spec.size
    forces = [np.abs(v).max() for r in a.forces["newton_euler"].reactions.values()
              for v in (r.fx, r.fy)]
    top = max(forces)
    assert sc["force"] >= top and sc["moment"] >= top * size * (1 - 1e-12)
    assert sc["moment"] == pytest.approx(sc["force"] * size)      # one load scale


@pytest.mark.parametrize("spec, limit", [("static_press", False), ("four_bar_motor", True)])
def test_transmission_caption_names_the_design_limit_only_where_one_is_set(spec, limit):
    """The caption said "with the design limit" where the spec sets none."""
    import mechreport
    from mechreport.report.model import build_model
    m = build_model(mechreport.analyse(ROOT / "specs" / f"{spec}.yaml"))
    assert (m.design.data.transmission_limit is not None) == limit
    assert ("with the design limit" in m.figures["transmission"].caption) == limit
