"""Figures a reviewer can read: no text on top of other text, none cut off by the figure's or
its axes' edge, labels that curves do not cross, scales set by the data.

The general check draws every report figure of every spec in specs/ (the sweep and cycle
plots of plots.py, as write_plots makes them, and the drawings) with matplotlib's Agg canvas
and compares the window extents of every visible, non-empty Text: texts placed on the axes
(off-scale values, ΔE, limits, reference angles), titles, axis labels, the tick labels
matplotlib draws (those inside the view; tick labels among themselves included), legend
texts. Two texts may touch (within OVERLAP_PX); none may overlap, and none may run past the
figure's edge or its clip box (the axes, for text drawn clipped)."""
from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

import mechreport
from mechreport.report import plots
from mechreport.report.model import build_model

ROOT = Path(__file__).resolve().parents[2]
SPECS = sorted((ROOT / "specs").glob("*.yaml"))
SLIDER = ROOT / "specs" / "slider_crank.yaml"
FOUR_BAR = ROOT / "specs" / "four_bar.yaml"
OVERLAP_PX = 1.5            # texts may touch by this much [px at 100 dpi] (antialiasing)

CYCLE = {"flywheel": plots.flywheel_figure, "breakdown": plots.breakdown_figure,
         "transmission": plots.transmission_figure, "balance": plots.balance_figure}
STRENGTH = {"strength": plots.strength_figure, "stress": plots.stress_figure}
SWEEP = {"torque": plots.torque_figure, "reactions": plots.reactions_figure,
         "polar": plots.polar_figure, "shaking": plots.shaking_figure}


# ----------------------------------------------------------------------------- helpers

_models: dict = {}


def model_of(path: Path):
    """The report model of a spec file, built once per session."""
    key = str(path)
    if key not in _models:
        _models[key] = build_model(mechreport.analyse(path))
    return _models[key]


def drawings(model) -> dict:
    """The drawings write_drawings makes for ``model``: stem -> (scene, title)."""
    refs = [r for r in model.refs if r.drawing is not None]
    return {r.drawing.stem: (scene, f"φ = {r.angle}°" if model.coord_unit == "°" else r.title)
            for r, scene in zip(refs, model.scenes)}


def make(model, key: str):
    """The figure ``key`` of ``model`` as write_plots or write_drawings makes it (call in the
    report's style)."""
    if key in CYCLE:
        return CYCLE[key](model.design.data, model.display)
    if key in SWEEP:
        return SWEEP[key](model.sweep, model.display)
    if key == "friction":
        return plots.friction_figure(model.friction.plot, model.display)
    if key == "dynamics":
        from mechreport.report.dynamics_plots import dynamics_figure
        return dynamics_figure(model.dynamics.plot, model.display)
    if key in STRENGTH:
        return STRENGTH[key](model.strength.plot, model.display)
    if key in frames(model):
        from mechreport.report import animation
        anim = model.animation
        frame, draw = frames(model)[key]
        return draw(anim, frame, animation.view_of(anim), model.display)
    from mechreport.report.drawing import draw_scene
    scene, title = drawings(model)[key]
    return draw_scene(scene, model.display, title)


def frames(model) -> dict:
    """The animation's frames to check: stem -> (frame, how it is drawn): the filmstrip's
    (as write_animation saves them) and, as the GIF shows them, the first frame, one at a
    reference angle and the frame with the largest effort."""
    from mechreport.report import animation
    anim = model.animation
    if anim is None:
        return {}
    out = {stem: (f, animation.draw_frame) for f, stem in zip(anim.strip, anim.strip_stems)}
    peak = max(anim.frames, key=lambda f: abs(f.effort))
    for f in [anim.frames[0], peak] + anim.strip[:1]:
        out[f"gif_{f.angle:g}"] = (f, animation.draw_gif_frame)
    return out


def figure_keys(model) -> list[str]:
    """The figures write_plots and write_drawings make for ``model``."""
    figs, sw = model.figures, model.sweep
    keys = [k for k in CYCLE if model.design.data is not None and k in figs]
    if len(sw.angles):
        keys += [k for k in SWEEP if k in figs and (k != "reactions" or sw.joints)]
    keys += [k for k in ("friction", "dynamics") if k in figs]
    keys += [k for k in STRENGTH if k in figs]
    return keys + list(drawings(model)) + list(frames(model))


def drawn_tick_labels(axis):
    """The tick labels matplotlib draws on ``axis``: one per current tick location inside
    the view (``get_ticklabels`` also returns ticks kept from earlier draws and ticks out of
    view, which are not drawn)."""
    locs = axis.get_majorticklocs()
    lo, hi = sorted(axis.get_view_interval())
    eps = 1e-9 * (hi - lo)
    return [t.label1 for t, loc in zip(axis.get_major_ticks(len(locs)), locs)
            if lo - eps <= loc <= hi + eps and t.label1.get_visible()]


def drawn_texts(fig) -> list:
    """Every visible, non-empty Text of ``fig`` that is drawn."""
    texts = list(fig.texts)
    for leg in fig.legends:
        texts += leg.get_texts()
    for ax in fig.axes:
        if not ax.get_visible():
            continue
        texts += list(ax.texts) + [ax.title, ax._left_title, ax._right_title]
        if ax.axison:
            for axis in (ax.xaxis, ax.yaxis):
                if axis.get_visible():
                    texts += [axis.label] + drawn_tick_labels(axis)
        if ax.get_legend() is not None:
            texts += ax.get_legend().get_texts()
    return [t for t in texts if t.get_visible() and t.get_text().strip()]


def draw(fig):
    """Draw ``fig`` with Agg (in the report's style); its renderer."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    canvas = FigureCanvasAgg(fig)
    with plots.style():
        canvas.draw()
    return canvas.get_renderer()


def layout_problems(fig) -> list[str]:
    """Pairs of drawn texts that overlap, and texts cut by the figure's edge or their clip
    box, as messages (none: the figure's text is readable)."""
    r = draw(fig)
    W, H = fig.bbox.width, fig.bbox.height
    boxes = [(t, t.get_window_extent(r)) for t in drawn_texts(fig)]
    out = []
    for t, b in boxes:
        if b.x0 < -1 or b.y0 < -1 or b.x1 > W + 1 or b.y1 > H + 1:
            out.append(f"{t.get_text()!r} runs past the figure's edge")
        clip = t.get_clip_box() if t.get_clip_on() else None
        if clip is not None and (b.x0 < clip.x0 - 1 or b.x1 > clip.x1 + 1
                                 or b.y0 < clip.y0 - 1 or b.y1 > clip.y1 + 1):
            out.append(f"{t.get_text()!r} is cut by its axes")
    for i, (t, a) in enumerate(boxes):
        for u, b in boxes[i + 1:]:
            dx = min(a.x1, b.x1) - max(a.x0, b.x0)
            dy = min(a.y1, b.y1) - max(a.y0, b.y0)
            if dx > OVERLAP_PX and dy > OVERLAP_PX:
                out.append(f"{t.get_text()!r} overlaps {u.get_text()!r}")
    return out


def curve_crosses(ax, x, y, box) -> bool:
    """The curve y(x) (data coordinates, x increasing, drawn as straight segments) passes
    through ``box`` (a Bbox in display coordinates)."""
    (x0, _), (x1, _) = ax.transData.inverted().transform([(box.x0, 0.0), (box.x1, 0.0)])
    xs = np.linspace(x0, x1, 400)
    pts = ax.transData.transform(np.column_stack([xs, np.interp(xs, x, y)]))
    return bool(np.any((pts[:, 1] >= box.y0) & (pts[:, 1] <= box.y1)))


def with_text(path: Path, extra: str, tmp_path: Path, name: str) -> Path:
    p = tmp_path / name
    p.write_text(path.read_text() + extra)
    return p


def texts_of(fig) -> list[str]:
    return [t.get_text() for ax in fig.axes for t in ax.texts]


# ------------------------------------------------------------------- the general check

@pytest.mark.slow
@pytest.mark.parametrize("spec", SPECS, ids=[p.stem for p in SPECS])
def test_no_text_overlaps_or_is_cut_off_in_any_figure_of_any_spec(spec):
    m = model_of(spec)
    keys = figure_keys(m)
    assert keys
    problems = []
    with plots.style():
        for key in keys:
            problems += [f"{spec.stem}/{key}: {p}" for p in layout_problems(make(m, key))]
    assert not problems, "\n".join(problems)


def test_the_layout_check_finds_overlapping_and_cut_text():
    """The check itself: two labels on top of each other, one past the edge."""
    with plots.style():
        fig, axes = plots.figure(2.5)
        ax = axes[0, 0]
        ax.text(0.5, 0.5, "5747 N at 89°", transform=ax.transAxes)
        ax.text(0.5, 0.5, "5737 N at 89°", transform=ax.transAxes)
        ax.text(1.2, 0.5, "far right", transform=ax.transAxes)
        problems = layout_problems(fig)
    assert any("overlaps" in p for p in problems)
    assert any("far right" in p and "edge" in p for p in problems)


# ---------------------------------------------------------- off-scale values, one label

def test_off_scale_values_at_the_same_angle_share_one_label():
    """slider_crank: A and B run off the scale at 89°, C and C_T at 269°: one label each,
    with both values and names, none overlapping ('5747 N at 89°' and '5737 N at 89°' were
    printed on top of each other)."""
    m = model_of(SLIDER)
    with plots.style():
        fig = plots.reactions_figure(m.sweep, m.display)
    labels = [t for t in texts_of(fig) if " N" in t and " at " in t]
    at89 = [t for t in labels if "89°" in t]
    at269 = [t for t in labels if "269°" in t]
    assert at89 == ["5747 N (A), 5737 N (B) at 89°"]
    assert at269 == ["5747 N (C_T), 5738 N (C) at 269°"]
    assert layout_problems(fig) == []


def test_off_scale_labels_never_overlap_when_many_marks_crowd_the_edge():
    """Marks that touch share a label (the largest two, then 'and N more'); labels of marks
    at neighbouring angles go to the other side of their mark or one line further in."""
    sw = model_of(SLIDER).sweep
    with plots.style():
        fig, axes = plots.figure(3.0)
        ax = axes[0, 0]
        plots.crank_axis(ax, sw)
        ax.set_ylim(0, 1000)
        marks = [("hi", a, 5000.0 + a, f"J{i}")
                 for i, a in enumerate([10.0, 10.5, 11.0, 11.5, 60.0, 80.0, 100.0, 340.0])]
        marks += [("lo", 89.0, -5000.0, "J9"), ("lo", 91.0, -4000.0, "J10")]
        plots.off_scale_labels(ax, sw, marks, "N")
        texts = texts_of(fig)
        problems = layout_problems(fig)
    assert "5012 N (J3) at 11.5°, 5011 N (J2) at 11° and 2 more" in texts
    assert "-5000 N (J9) at 89°, -4000 N (J10) at 91°" in texts
    for a in (60, 80, 100, 340):
        assert sum(f"at {a}°" in t for t in texts) == 1
    assert len(texts) == 6 and problems == []


# -------------------------------------------------------------- flywheel: motor limits

MOTOR = "\ndesign:\n  motor: {rated_torque: 150, peak_torque: 600}\n"


def test_flywheel_torque_panel_is_scaled_to_the_torque_with_a_far_limit_as_an_edge_arrow(
        tmp_path):
    """slider_crank (torque -10 to 201 N·m) with a 600 N·m motor peak: the panel is scaled
    to the torque, no ±600 line; the peak is an arrow at the top edge with its value, clear
    of the curve; the rated 150 N·m, within the torque's range, stays a line."""
    m = build_model(mechreport.analyse(with_text(SLIDER, MOTOR, tmp_path, "motor.yaml")))
    cd = m.design.data
    with plots.style():
        fig = plots.flywheel_figure(cd, m.display)
        ax = fig.axes[0]
        r = draw(fig)
    lo, hi = ax.get_ylim()
    assert hi < 1.2 * float(np.max(cd.torque)) and lo > -0.2 * float(np.max(cd.torque))
    levels = {round(float(y), 6) for ln in ax.get_lines()
              for y in [ln.get_ydata()[0]] if len(set(np.ravel(ln.get_ydata()))) == 1}
    assert 150.0 in levels and 600.0 not in levels and -600.0 not in levels
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert "motor rated (RMS) 150 N·m" in legend and not any("peak" in t for t in legend)
    (label,) = [t for t in ax.texts if t.get_text() == "motor peak 600 N·m"]
    (arrow,) = [t for t in ax.texts if t.get_text() == "" and t.arrow_patch is not None]
    assert arrow.xy[1] == 1.0 and arrow.xy[0] == label.xy[0]       # at the top edge
    assert not curve_crosses(ax, cd.angles, cd.torque, label.get_window_extent(r))
    assert layout_problems(fig) == []


def test_flywheel_motor_limit_near_the_torque_stays_a_line():
    """four_bar: a 6 N·m peak beside torque from -3.2 to 3.8 N·m is drawn as ±6 lines, as
    before (the figure is unchanged)."""
    m = model_of(FOUR_BAR)
    with plots.style():
        fig = plots.flywheel_figure(m.design.data, m.display)
    ax = fig.axes[0]
    flat = [ln.get_ydata()[0] for ln in ax.get_lines() if len(set(ln.get_ydata())) == 1]
    assert 6.0 in flat and -6.0 in flat and 3.0 in flat
    assert not [t for t in ax.texts if "motor" in t.get_text()]


def _delta_e_label(spec_path):
    """The flywheel figure of a spec drawn: (its cycle data, the figure, the energy panel,
    the renderer, the ΔE label)."""
    m = model_of(spec_path)
    cd = m.design.data
    with plots.style():
        fig = plots.flywheel_figure(cd, m.display)
        ax2 = fig.axes[1]
        r = draw(fig)
    (label,) = [t for t in ax2.texts if t.get_text().startswith("ΔE = ")]
    return cd, fig, ax2, r, label


@pytest.mark.parametrize("spec", ["r_rtr_rtr", "scotch_yoke", "slider_crank"])
def test_delta_e_label_is_not_crossed_by_the_energy_curve(spec):
    """The ΔE label sits beside its arrow where the energy curve does not run through it
    (r_rtr_rtr's crossed it halfway up the arrow)."""
    cd, fig, ax2, r, label = _delta_e_label(ROOT / "specs" / f"{spec}.yaml")
    assert not curve_crosses(ax2, cd.angles, cd.energy, label.get_window_extent(r))
    assert layout_problems(fig) == []


# ------------------------------------------------------------------ labels that fit

def units_kn(path: Path, tmp_path: Path) -> Path:
    """``path`` with its report showing forces in kN."""
    text = re.sub(r"(?m)^report:.*\n(?:  .*\n)*", "", path.read_text())
    p = tmp_path / f"{path.stem}_kn.yaml"
    p.write_text(text + "\nreport: {units: {force: kN}}\n")
    return p


@pytest.mark.parametrize("spec", ["four_bar", "r_rtr_rtr", "slider_crank"])
def test_shaking_force_polar_in_kn_keeps_its_axis_labels_in_the_figure(spec, tmp_path):
    """The balance polar in kN (tick labels like −0.0010) had its 'y [kN]' cut off at the
    left edge: the margin widens until the label fits."""
    m = build_model(mechreport.analyse(units_kn(ROOT / "specs" / f"{spec}.yaml", tmp_path)))
    with plots.style():
        fig = plots.balance_figure(m.design.data, m.display)
    problems = layout_problems(fig)
    ax = fig.axes[0]
    assert ax.get_ylabel() == "y [kN]"
    assert ax.yaxis.label.get_window_extent(draw(fig)).x0 >= 0
    assert problems == []


def test_pin_polar_labels_fit_the_figure_and_their_axes():
    """hydraulic_boom's pin polars in N: 'y [N]' beside −15000 was cut at the left edge and
    the '300°' label by its axes; offset_slider_crank's '60°' too."""
    for name in ("hydraulic_boom", "offset_slider_crank"):
        m = model_of(ROOT / "specs" / f"{name}.yaml")
        with plots.style():
            fig = plots.polar_figure(m.sweep, m.display)
        assert layout_problems(fig) == [], name


def test_reference_angle_lines_of_the_torque_plot_are_labelled():
    """four_bar: the dotted lines at 30° and 210° say what they are, beside the line."""
    m = model_of(FOUR_BAR)
    with plots.style():
        fig = plots.torque_figure(m.sweep, m.display)
        r = draw(fig)
    ax = fig.axes[0]
    names = {t.get_text(): t for t in ax.texts}
    assert {"φ = 30°", "φ = 210°"} <= set(names)
    for ref in (30.0, 210.0):
        box = names[f"φ = {ref:g}°"].get_window_extent(r)
        x = ax.transData.transform((ref, 0.0))[0]
        assert min(abs(box.x0 - x), abs(box.x1 - x)) < 6           # beside its line
        assert not curve_crosses(ax, m.sweep.angles, m.sweep.torque, box)
    assert layout_problems(fig) == []


def test_reference_lines_of_a_stroke_sweep_name_the_stroke():
    m = model_of(ROOT / "specs" / "hydraulic_boom.yaml")
    with plots.style():
        fig = plots.torque_figure(m.sweep, m.display)
    assert "stroke 300 mm" in texts_of(fig)


# ------------------------------------------------- at rest: figures with nothing to show

STATIC = [ROOT / "specs" / "static_press.yaml", ROOT / "specs" / "toggle_press.yaml"]


def legend_texts(fig) -> list[str]:
    return [t.get_text() for ax in fig.axes if ax.get_legend() is not None
            for t in ax.get_legend().get_texts()]


@pytest.mark.parametrize("spec", STATIC, ids=[p.stem for p in STATIC])
def test_at_rest_specs_leave_out_the_flywheel_and_balance_figures_and_say_why(spec):
    """A driver at rest (rpm: 0): the driver's torque does no work over a turn and no link
    accelerates, so there is no flywheel diagram (it spoke of "energy the flywheel absorbs")
    nor an empty counterweight polar; one line of the report says why, in Markdown and
    Typst."""
    from mechreport.report.pdf import typst_escape
    from mechreport.report.render import report_markdown, report_typst
    m = model_of(spec)
    assert "flywheel" not in m.figures and "balance" not in m.figures
    assert m.design.absent["flywheel"] == ("No flywheel diagram: at rest the driver's torque "
                                           "does no work over a turn.")
    assert m.design.absent["balance"].startswith("No balancing diagram: at rest no link "
                                                 "accelerates")
    md = report_markdown(m)
    typ = report_typst(m)
    for text in m.design.absent.values():
        assert text in md and typst_escape(text) in typ
    assert "flywheel.svg" not in md and "balance.svg" not in md


@pytest.mark.parametrize("spec", STATIC, ids=[p.stem for p in STATIC])
def test_torque_by_source_leaves_out_a_source_that_is_zero_at_every_angle(spec):
    """At rest the inertia's share of the torque is 0 at every angle: no legend entry with
    nothing drawn for it; the caption names it."""
    m = model_of(spec)
    assert m.design.data.silent == ["inertia"]
    with plots.style():
        fig = plots.breakdown_figure(m.design.data, m.display)
    assert "inertia" not in legend_texts(fig) and "total" in legend_texts(fig)
    assert "Not drawn: inertia (its torque is 0 N·m at every angle)" in \
        m.figures["breakdown"].caption


def test_a_static_press_shaking_moment_is_zero_and_not_drawn():
    """static_press: the shaking moment is round-off (1e-13 N·m beside 20 kN forces): it
    was drawn on a 1e-13 axis whose offset label ran into the legend while the text said 0.
    Now the figure is the force panel alone, and the caption and text say the moment is 0
    at every angle."""
    m = model_of(STATIC[0])
    assert m.sweep.shaking_zero == ("moment",)
    with plots.style():
        fig = plots.shaking_figure(m.sweep, m.display)
    assert len(fig.axes) == 1 and fig.axes[0].get_ylabel() == "force on frame [kN]"
    assert fig.axes[0].get_xlabel() == "crank angle [deg]"
    assert "is 0 N·m at every angle (not drawn)" in m.figures["shaking"].caption
    assert m.shaking["moment"] == "0 N·m at every angle"
    assert layout_problems(fig) == []


def test_toggle_press_shaking_moment_is_drawn_it_is_not_round_off():
    """toggle_press at rest: its shaking moment (the brake's reaction, -19690 N·m) is a real
    value: both panels stay."""
    m = model_of(STATIC[1])
    assert m.sweep.shaking_zero == ()
    with plots.style():
        assert len(plots.shaking_figure(m.sweep, m.display).axes) == 2


@pytest.mark.parametrize("spec", STATIC, ids=[p.stem for p in STATIC])
def test_plot_legends_print_round_off_as_zero(spec):
    """The torque figure's legend printed the mean as "6e-14 N·m" (and the flywheel's as
    "-1.737e-14 N·m") while the tables said 0: legends use the tables' round-off rule."""
    m = model_of(spec)
    with plots.style():
        fig = plots.torque_figure(m.sweep, m.display)
    legend = legend_texts(fig)
    assert any(t.startswith("mean 0 N·m (RMS ") for t in legend), legend
    for key in figure_keys(m):
        with plots.style():
            texts = [t.get_text() for t in drawn_texts(make(m, key))]
        assert not [t for t in texts if re.search(r"\de-\d", t)], (key, texts)


def test_a_flywheel_mean_that_is_round_off_prints_zero(tmp_path):
    """The flywheel legend's mean goes through the one round-off rule too (a moving
    mechanism whose mean torque is round-off of its loads)."""
    m = model_of(SLIDER)
    cd = m.design.data
    from dataclasses import replace
    zero_mean = replace(cd, mean=1e-14)
    with plots.style():
        fig = plots.flywheel_figure(zero_mean, m.display)
    assert "mean 0 N·m" in legend_texts(fig)


# ------------------------------------------------- labels clear of the gauge and the guides

FRICTION_PRESS = ROOT / "specs" / "crank_press_friction.yaml"


def drawing_labels(fig, renderer):
    """(text, window box) of the labels on a drawing's axes (point names, symbols, values)."""
    ax = fig.axes[0]
    return [(t.get_text(), t.get_window_extent(renderer)) for t in ax.texts
            if t.get_visible() and t.get_text().strip()]


def test_frame_labels_stay_inside_the_drawing_clear_of_the_gauge():
    """four_bar's filmstrip: "M3ext" at 30° ran under the torque gauge, F03 at 210° beside
    it: a label stays inside the drawing's axes (the gauge, the key and the title lie
    outside them)."""
    from mechreport.report import animation
    m = model_of(FOUR_BAR)
    anim = m.animation
    view = animation.view_of(anim)
    for f in anim.strip:
        with plots.style():
            fig = animation.draw_frame(anim, f, view, m.display)
            r = draw(fig)
        frame = fig.axes[0].bbox
        for text, box in drawing_labels(fig, r):
            assert (box.x0 >= frame.x0 - 1 and box.x1 <= frame.x1 + 1
                    and box.y0 >= frame.y0 - 1 and box.y1 <= frame.y1 + 1), (f.angle, text)


def test_no_label_crosses_a_guide_wall_or_its_hatching():
    """crank_press_friction at 260°: F03 and F3ext were crossed by the ram guide's wall and
    hatching, in the drawing and in the filmstrip's frame."""
    from mechreport.report import animation
    from mechreport.report.drawing import draw_scene, guide_strokes
    m = model_of(FRICTION_PRESS)
    scene, title = drawings(m)["drawing_260"]
    anim = m.animation
    (frame,) = [f for f in anim.strip if f.angle == 260.0]
    for make_fig in (lambda: draw_scene(scene, m.display, title),
                     lambda: animation.draw_frame(anim, frame, animation.view_of(anim),
                                                  m.display)):
        with plots.style():
            fig = make_fig()
            r = draw(fig)
        ax = fig.axes[0]
        walls = []
        for g in scene.guides:
            w, ticks = guide_strokes(*g)
            walls += w + ticks
        assert walls
        for text, box in drawing_labels(fig, r):
            for a, b in walls:
                pa, pb = ax.transData.transform([a, b])
                ts = np.linspace(0, 1, 200)[:, None]
                pts = pa + ts * (pb - pa)
                inside = ((pts[:, 0] > box.x0 + 0.5) & (pts[:, 0] < box.x1 - 0.5)
                          & (pts[:, 1] > box.y0 + 0.5) & (pts[:, 1] < box.y1 - 0.5))
                assert not inside.any(), (text, a, b)


def test_delta_e_label_is_clear_of_the_zero_line_the_grid_and_the_left_out_bands():
    """crank_press_friction: "ΔE = 126.1 J" sat on the energy panel's zero line and across
    the grey band of the left-out 270°."""
    cd, fig, ax2, r, label = _delta_e_label(FRICTION_PRESS)
    box = label.get_window_extent(r)
    lo, hi = ax2.get_ylim()
    for y in {0.0} | {float(t) for t in ax2.get_yticks() if lo <= t <= hi}:
        py = ax2.transData.transform((0.0, y))[1]
        assert not box.y0 <= py <= box.y1, y
    for a in cd.interpolated:
        px = ax2.transData.transform((a, 0.0))[0]
        assert not box.x0 - 2 <= px <= box.x1 + 2, a
    assert not curve_crosses(ax2, cd.angles, cd.energy, box)
