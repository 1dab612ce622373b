"""animation.gif and mechanism.dxf (report.animation, report.dxf).

The GIF: one frame per chosen step of the sweep, every frame the same size, every arrow to
one scale across frames (the few frames with much larger forces cut, marked and labelled
with their values); left-out angles
marked in every frame. The DXF: read back with ezdxf, every point of every link and every
joint at its position from the kinematics, in the spec's length unit, one layer per solved
reference angle."""
from __future__ import annotations

import io
import math
from pathlib import Path

import numpy as np
import pytest

import mechreport
from mechreport.report import animation as A
from mechreport.report.drawing import ARROW_LEN, CUT_COLOR
from mechreport.report.frames import CLIP, CUT_SHARE, FRAMES_PER_SWEEP, frame_indices
from mechreport.report.model import build_model
from mechreport.spec import load_spec
from mechreport.errors import SpecError

ROOT = Path(__file__).resolve().parents[2]
SLIDER = ROOT / "specs" / "slider_crank.yaml"        # left out: 90 and 270 deg (singular)
FOUR_BAR = ROOT / "specs" / "four_bar.yaml"          # lengths in mm
BOOM = ROOT / "specs" / "hydraulic_boom.yaml"        # a T driver's stroke

_models: dict = {}


def shifted_slider(tmp_path_factory) -> Path:
    """The slider-crank's 1-degree sweep started so that a frame falls on 89 deg, next to the
    left-out 90 deg."""
    every = math.ceil(360 / FRAMES_PER_SWEEP)
    start = 89 % every
    path = tmp_path_factory.mktemp("shifted") / "slider_crank.yaml"
    path.write_text(SLIDER.read_text(encoding="utf-8").replace(
        "sweep: {start: 0, stop: 360, step: 1}",
        f"sweep: {{start: {start}, stop: {start + 360}, step: 1}}"), encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def shifted(tmp_path_factory):
    path = shifted_slider(tmp_path_factory)
    return mechreport.analyse(path), model_of(path)


def model_of(path: Path):
    if str(path) not in _models:
        _models[str(path)] = build_model(mechreport.analyse(path))
    return _models[str(path)]


def with_text(path: Path, extra: str, tmp_path: Path) -> Path:
    out = tmp_path / path.name
    out.write_text(path.read_text(encoding="utf-8") + extra, encoding="utf-8")
    return out


# ------------------------------------------------------------------------------- the keys

def test_animation_is_on_for_a_whole_turn_and_off_for_a_stroke_dxf_off_by_default():
    assert load_spec(SLIDER).report.animation is True
    assert load_spec(BOOM).report.animation is False
    assert load_spec(SLIDER).report.dxf is False


def test_report_keys_set_and_refused(tmp_path):
    spec = load_spec(with_text(SLIDER, "report: {animation: false, dxf: true}\n", tmp_path))
    assert (spec.report.animation, spec.report.dxf) == (False, True)
    part = SLIDER.read_text(encoding="utf-8").replace(
        "sweep: {start: 0, stop: 360, step: 1}", "sweep: {start: 0, stop: 180, step: 1}")
    (tmp_path / "half.yaml").write_text(part, encoding="utf-8")
    assert load_spec(tmp_path / "half.yaml").report.animation is False   # not a whole turn
    bad = with_text(SLIDER, "report: {animation: 'yes', dxf: 2}\n", tmp_path)
    with pytest.raises(SpecError) as info:
        load_spec(bad)
    text = str(info.value)
    assert "report.animation: must be true or false" in text
    assert "report.dxf: must be true or false" in text


def test_dxf_layers_of_angles_closer_than_shown_stay_distinct(tmp_path):
    """Issue 40: `at: [45, 45.00001]` with `report: {dxf: true}` named both layers
    crank_angle_45 and the build failed: a layer is named after the exact angle."""
    import ezdxf
    from mechreport.report.dxf import dxf_text
    text = SLIDER.read_text(encoding="utf-8")
    assert text.count("at: [45]") == 1
    spec = tmp_path / "close.yaml"
    spec.write_text(text.replace("at: [45]", "at: [45, 45.00001, 1e-5]")
                    + "report: {dxf: true, animation: false}\n", encoding="utf-8")
    m = build_model(mechreport.analyse(spec))
    names = [name for name, _ in m.dxf.layers]
    assert names == ["crank_angle_45", "crank_angle_45.00001", "crank_angle_1e-05"]
    doc = ezdxf.read(io.StringIO(dxf_text(m.dxf)))
    assert set(names) <= {layer.dxf.name for layer in doc.layers}


def test_no_animation_in_the_model_when_left_out():
    analysis = mechreport.analyse(SLIDER)
    assert build_model(analysis, animation=False).animation is None
    assert build_model(mechreport.analyse(BOOM)).animation is None


# ----------------------------------------------------------------------------- the frames

def test_frame_indices_every_kth_grid_angle_a_left_out_one_takes_its_neighbour():
    grid = np.arange(0.0, 360.0, 1.0)
    analysed = grid[(grid != 90) & (grid != 270)]
    ks, step = frame_indices(grid, analysed, per_sweep=24)
    assert step == 15.0 and len(ks) == 24
    angles = analysed[ks]
    assert list(angles[:6]) == [0, 15, 30, 45, 60, 75]
    assert 90 not in angles and (89 in angles or 91 in angles)
    # 180 steps of 2 deg, at most 24 frames: every 9th (18 deg, an even split), not every 8th
    ks, step = frame_indices(np.arange(0.0, 360.0, 2.0), np.arange(0.0, 360.0, 2.0), 24)
    assert step == 18.0 and len(ks) == 20
    # nothing analysed near a grid angle: no frame there
    ks, _ = frame_indices(grid, grid[grid < 97], 24)      # 105 is 9 deg from 96: none
    assert len(ks) == 7
    ks, step = frame_indices(grid, grid)                  # the default: at most
    assert len(ks) <= FRAMES_PER_SWEEP and step * len(ks) == 360.0


def test_gif_has_one_frame_per_chosen_step_all_the_same_size():
    from PIL import Image
    m = model_of(SLIDER)
    anim = m.animation
    data = A.gif_bytes(anim, m.display)
    assert len(data) < 2_000_000
    im = Image.open(io.BytesIO(data))
    assert im.n_frames == len(anim.frames) == round(360 / anim.step) <= FRAMES_PER_SWEEP
    sizes = set()
    for i in range(im.n_frames):
        im.seek(i)
        sizes.add(im.convert("RGB").size)
        assert im.info["duration"] == round(anim.seconds * 1000)
    assert len(sizes) == 1
    assert 2.0 <= anim.seconds * im.n_frames <= 4.0
    # the frames' angles step evenly by the chosen step (a left-out one by its neighbour)
    angles = np.array([f.angle for f in anim.frames])
    assert np.all(np.abs(angles - anim.step * np.arange(len(angles))) <= 1.0)


def arrows_drawn(fig):
    """(start, tip) in data coordinates of every arrow on the drawing's axes: a polygon
    whose first and last vertices flank the start and whose fourth is the tip."""
    ax = fig.axes[0]
    out = []
    for p in ax.patches:
        if p.get_gid() == "arrow":
            xy = np.asarray(p.get_xy(), float)
            out.append(((xy[0] + xy[6]) / 2, xy[3], p))
    return out


def largest_arrows(analysis, anim) -> list[float]:
    """The largest reaction or load [N] at each frame of ``anim``, computed here."""
    kin = analysis.kinematics
    res = analysis.forces[analysis.sweep_summary().method]
    out = []
    for f in anim.frames:
        k = kin.index_of(f.angle)
        mags = [math.hypot(r.fx[k], r.fy[k]) for r in res.reactions.values()]
        mags += [math.hypot(*ld.force[k]) for ld in analysis.loads if ld.force is not None]
        out.append(max(mags))
    return out


def test_one_arrow_scale_for_the_whole_sweep_the_few_longer_arrows_cut(shifted):
    """Every arrow of every frame to one scale [m per N]; an arrow longer than CLIP times
    the reference force is cut to that length, and only those; at most one frame in
    CUT_SHARE is cut (the slider-crank's frames beside its dead centres)."""
    analysis, m = shifted
    anim = m.animation
    assert any(f.near for f in anim.frames)
    view = A.view_of(anim)
    kin = analysis.kinematics
    res = analysis.forces[analysis.sweep_summary().method]
    assert view.scale == pytest.approx(ARROW_LEN * anim.extent / anim.force_ref)
    assert view.clip == pytest.approx(CLIP * ARROW_LEN * anim.extent)
    ratios, cut_frames = [], set()
    for f in anim.frames:
        k = kin.index_of(f.angle)
        fig = A.draw_frame(anim, f, view, m.display)
        drawn = arrows_drawn(fig)
        for j in analysis.spec.joints:
            r = res.reactions.get(j.name)
            if r is None:
                continue
            force = np.array([r.fx[k], r.fy[k]])
            mag = float(np.hypot(*force))
            at = np.asarray(analysis.joint_points()[j.name][k], float)
            hits = [(a, b) for a, b, _ in drawn if np.allclose(a, at, atol=1e-9 * anim.extent)
                    and mag > 0 and np.dot(b - a, force) > 0.999 * np.linalg.norm(b - a) * mag]
            if mag * view.scale < 1e-3 * anim.extent:
                continue
            assert hits, (f.angle, j.name)
            length = float(np.linalg.norm(hits[0][1] - hits[0][0]))
            if mag <= CLIP * anim.force_ref:
                ratios.append(length / mag)
            else:
                assert length == pytest.approx(view.clip)
                cut_frames.add(f.angle)
        assert f.cut == (f.angle in cut_frames)
    assert np.ptp(ratios) <= 1e-9 * np.mean(ratios)       # one scale [m per N]
    assert np.mean(ratios) == pytest.approx(view.scale)
    near = {f.angle for f in anim.frames if f.near}
    assert near <= cut_frames                                # 89 deg: 5747 N
    assert 0 < len(cut_frames) <= len(anim.frames) // CUT_SHARE


def test_slider_crank_arrows_are_long_enough_to_read_in_most_frames():
    """specs/slider_crank.yaml: the one scale was set by 969 N at 84 deg, next to the
    left-out dead centre, so that 150 N at 45 deg was 0.04 of the drawing: arrows too short
    to see in about 20 of 24 frames. Now at least three frames in four have their largest
    arrow at least 0.3 of the longest to scale, and the frames near the dead centres are
    cut, their arrows labelled with their value."""
    analysis = mechreport.analyse(SLIDER)
    m = model_of(SLIDER)
    anim = m.animation
    tops = largest_arrows(analysis, anim)
    readable = [t for t in tops if t >= 0.3 * anim.force_ref]
    assert len(readable) >= 0.75 * len(tops)
    at45 = tops[[f.angle for f in anim.frames].index(45.0)]
    assert at45 >= 0.4 * anim.force_ref
    view = A.view_of(anim)
    for f in anim.frames:
        if not f.cut:
            continue
        fig = A.draw_gif_frame(anim, f, view, m.display)
        texts = [t.get_text() for t in fig.axes[0].texts]
        values = [t for t in texts if t.endswith(" N")]
        cut = [math.hypot(*a.f) for a in f.scene.arrows if math.hypot(*a.f) > CLIP * anim.force_ref]
        assert len(values) == len(cut) > 0, (f.angle, texts)
        for v in cut:
            assert f"{m.display.num(v, 'force')} N" in values
    assert "Arrows marked // are longer than drawn (off the scale), their value beside them." \
        in anim.caption


def test_no_frame_is_cut_where_forces_spread_little():
    """four_bar: its largest force (180 N) is within SPREAD times the median frame's: every
    arrow drawn to scale, none cut, the caption says nothing of cut arrows."""
    anim = model_of(FOUR_BAR).animation
    assert not any(f.cut for f in anim.frames + anim.strip)
    assert "//" not in anim.caption


def test_left_out_angles_are_marked_in_every_frame_and_named_near_them(shifted):
    from matplotlib.lines import Line2D
    _, m = shifted
    anim = m.animation
    view = A.view_of(anim)
    near = [f for f in anim.frames if f.near]
    assert near and all("left-out 90" in f.note or "left-out 270" in f.note for f in near)
    for f in (anim.frames[0], near[0]):
        fig = A.draw_gif_frame(anim, f, view, m.display)
        red = [a for a in fig.artists if isinstance(a, Line2D) and a.get_color() == CUT_COLOR]
        assert len(red) == len(anim.flagged) == 2          # a red line at 90 and at 270
        texts = [t.get_text() for t in fig.texts]
        assert any("left out" in t for t in texts)
        assert any("arrows cut" in t for t in texts) == f.cut


def test_a_spec_without_left_out_angles_marks_none():
    m = model_of(FOUR_BAR)
    anim = m.animation
    assert not anim.flagged and not any(f.near or f.note for f in anim.frames)


# -------------------------------------------------------------------------------- the DXF

def test_dxf_round_trips_every_point_at_its_computed_position(tmp_path):
    import ezdxf
    from mechreport.report.dxf import dxf_text
    text = FOUR_BAR.read_text(encoding="utf-8").replace(
        "  units: {length: mm, force: N, moment: N*m, mass: g}\n",
        "  units: {length: mm, force: N, moment: N*m, mass: g}\n  dxf: true\n"
        "  animation: false\n")
    spec_path = tmp_path / "four_bar.yaml"
    spec_path.write_text(text, encoding="utf-8")
    analysis = mechreport.analyse(spec_path)
    m = build_model(analysis)
    assert m.animation is None and m.dxf is not None
    path = tmp_path / "mechanism.dxf"
    path.write_text(dxf_text(m.dxf), encoding="utf-8")
    doc = ezdxf.readfile(path)
    assert doc.units == 4                                  # millimetres, as the spec
    spec, kin = analysis.spec, analysis.kinematics
    msp = doc.modelspace()
    mm = 1e-3
    layers = {f"crank_angle_{a:g}": a for a in spec.at}
    assert set(layers) <= {layer.dxf.name for layer in doc.layers}
    for name, angle in layers.items():
        k = kin.index_of(angle)
        polys = [[tuple(v[:2]) for v in e.get_points()]
                 for e in msp.query(f'LWPOLYLINE[layer=="{name}"]')]
        circles = [tuple(c.dxf.center)[:2] for c in msp.query(f'CIRCLE[layer=="{name}"]')]
        for link in spec.links:
            want = [np.asarray(kin.named_point(p, link.name).r[k]) / mm for p in link.points]
            assert any(len(poly) == len(want) and all(
                np.allclose(v, w, atol=1e-9) for v, w in zip(poly, want)) for poly in polys), \
                (name, link.name)
        for j in spec.joints:
            moving = [x for x in (j.links[1], j.links[0]) if x != "ground"]
            owner = moving[0] if j.type == "T" else moving[-1]
            want = np.asarray(kin.named_point(j.point, owner).r[k]) / mm
            assert any(np.allclose(c, want, atol=1e-9) for c in circles), (name, j.name)
