"""The animation's data: the mechanism at evenly spaced angles of the sweep, each as a
:class:`~mechreport.report.scene.Scene` built by the same function as the reference-angle
drawings, with what a frame says beside the drawing (the driver's effort, a left-out angle
nearby). No matplotlib here: :mod:`mechreport.report.animation` draws and writes it.

Angles are the sweep's coordinate (crank angle [deg], or a T driver's stroke in the spec's
length unit); forces [N], moments [N m], lengths [m]."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..spec import GROUND
from ..units import deg
from .scene import Scene, build_scene, sweep_extent

#: frames per sweep (at most): 24 over a whole turn is one frame per 15 degrees of a 1-degree
#: sweep; with SECONDS_PER_SWEEP the cycle runs in about 3 s
FRAMES_PER_SWEEP = 24
SECONDS_PER_SWEEP = 3.0
#: an arrow longer than CLIP times the scale's reference force is cut to that length, marked
#: // and labelled with its value
CLIP = 1.3
#: where a few frames carry much larger forces than the rest (beside a dead centre, a press
#: stroke), at most one frame in CUT_SHARE has its arrows cut, so that the others' arrows
#: are long enough to read; none is cut where the largest force is within SPREAD times the
#: median frame's
CUT_SHARE = 4
SPREAD = 2.0


@dataclass
class Frame:
    """One frame: the ``scene`` at sweep value ``angle``, its ``title`` ("φ = 40°"), whether
    it lies ``near`` a left-out angle (within the report's near-singular band), the
    ``note`` that says so or that arrows are cut ("" otherwise), the driver's ``effort``
    [N m or N] there, whether any of its arrows is ``cut`` (longer than CLIP times the
    scale's reference force)."""

    scene: Scene
    angle: float
    title: str
    near: bool
    note: str
    effort: float
    cut: bool = False


@dataclass
class Animation:
    """The animation of one spec: ``frames`` over the sweep, ``strip`` the frames at the
    solved reference angles (the PDF's filmstrip; their SVGs ``strip_stems``), the drawing's
    ``extent`` [m] shared by all, ``force_ref`` [N] the force the one arrow scale is set by
    (:func:`force_reference`; arrows longer than CLIP times it are cut), ``step``
    between frames, ``seconds`` per frame (whole hundredths); ``caption`` and
    ``strip_caption`` as the reports print them. For the effort gauge and the sweep strip
    under the drawing: ``angles`` (n,) the analysed angles, ``effort`` (n,) the driver's torque [N m] or force
    [N] (``effort_kind`` moment|force, ``effort_symbol`` M|Fd), ``near`` (n,) the
    near-singular mask, ``flagged`` the left-out angles, ``xrange`` (start, stop) of the
    sweep; ``unit`` what follows a sweep value ("°" or " mm")."""

    frames: list[Frame]
    strip: list[Frame]
    strip_stems: list[str]
    extent: float
    force_ref: float
    step: float
    seconds: float
    angles: np.ndarray
    effort: np.ndarray
    effort_kind: str
    effort_symbol: str
    near: np.ndarray
    flagged: list[float]
    xrange: tuple[float, float]
    unit: str = "°"
    caption: str = ""
    strip_caption: str = ""

    @property
    def strip_svgs(self) -> list[str]:
        """The filmstrip's files, relative to the report folder."""
        return [f"figures/{stem}.svg" for stem in self.strip_stems]


def frame_indices(sweep_angles: np.ndarray, analysed: np.ndarray,
                  per_sweep: int = FRAMES_PER_SWEEP) -> tuple[list[int], float]:
    """Analysed indices of the frames and the step between them: every ``e``-th angle of
    the sweep's grid ``sweep_angles`` (e the smallest whole number that gives at most
    ``per_sweep`` frames, or a little larger where that divides the grid evenly), each
    taken at the nearest analysed angle within half a frame step (a left-out angle of the
    grid takes its solved neighbour; none within reach: no frame)."""
    grid = np.asarray(sweep_angles, float)
    analysed = np.asarray(analysed, float)
    if grid.size == 0 or analysed.size == 0:
        return [], 0.0
    every = max(1, math.ceil(grid.size / per_sweep))
    # a step that divides the sweep evenly when one is near (180 steps: every 9th, not 8th)
    every = next((e for e in range(every, every + every // 2 + 1) if grid.size % e == 0),
                 every)
    step = float(grid[1] - grid[0]) * every if grid.size > 1 else 0.0
    out: list[int] = []
    for target in grid[::every]:
        k = int(np.argmin(np.abs(analysed - target)))
        if abs(analysed[k] - target) <= abs(step) / 2 + 1e-9 and k not in out:
            out.append(k)
    return out, step


def arrow_forces(analysis, res) -> np.ndarray:
    """The largest force [N] drawn as an arrow at each analysed angle (n,): joint reactions,
    applied forces, a T driver's push (NaN where none is finite)."""
    mags = [np.hypot(r.fx, r.fy) for r in res.reactions.values()]
    mags += [np.hypot(*np.asarray(ld.force, float).T) for ld in analysis.loads
             if ld.force is not None and ld.link != GROUND]
    if analysis.spec.driver.kind == "T":
        mags.append(np.abs(np.asarray(res.driver_torque, float)))
    if not mags:
        return np.full(analysis.kinematics.n, np.nan)
    stack = np.vstack([np.where(np.isfinite(m), m, -np.inf) for m in mags])
    top = stack.max(axis=0)
    return np.where(np.isfinite(top), top, np.nan)


def force_reference(largest: np.ndarray, near: np.ndarray, ks: list[int]) -> float:
    """The force [N] the animation's one arrow scale is set by (drawn ARROW_LEN of the
    extent; arrows longer than CLIP times it are cut), from the largest arrow at each
    analysed angle ``largest`` (n,) [N], the near-singular mask ``near`` (n,) and the drawn
    frames' indices ``ks``.

    The largest force away from left-out angles (all angles if every one is near), unless
    the drawn frames' largest forces spread wider than SPREAD times their median: then the
    largest force of the frames after the 1 in CUT_SHARE with the largest (at least SPREAD
    times the median). Beside a dead centre forces grow steeply even outside the
    near-singular band (a slider-crank's 969 N at 84 deg against 150 N at 45 deg): the one
    largest force made the arrows of most frames too short to see; now those few frames
    are cut and labelled with their value."""
    away = ~near if (~near).any() else np.ones_like(near)
    far = largest[away]
    far = far[np.isfinite(far)]
    top = float(far.max()) if far.size else 0.0
    drawn = np.array([largest[k] for k in ks], float)
    drawn = np.sort(drawn[np.isfinite(drawn) & (drawn > 0)])[::-1]
    if not drawn.size or top <= SPREAD * float(np.median(drawn)):
        return top
    kept = drawn[max(1, len(drawn) // CUT_SHARE):]
    return min(top, max(float(kept[0]) if kept.size else top,
                        SPREAD * float(np.median(drawn))))


def animation_data(analysis, ref: str, sweep, colors: dict[str, str],
                   symbols: dict[str, str], effort_kind: str, coord: str, coord_unit: str,
                   strip_angles: list[float], method_title: str) -> Animation | None:
    """The animation of ``analysis`` drawn from the reference method ``ref``'s reactions:
    ``sweep`` the report's :class:`~mechreport.report.model.SweepData` (near-singular mask,
    left-out angles), ``coord`` and ``coord_unit`` the sweep's name and unit ("crank
    angle", "°"), ``strip_angles`` the reference angles of the filmstrip (the solved ones),
    ``method_title`` the reference method's name. None when no angle was solved."""
    spec, kin = analysis.spec, analysis.kinematics
    ks, step = frame_indices(spec.sweep.angles(), kin.angles)
    if not ks:
        return None
    strip_ks = [k for a in strip_angles if (k := kin.index_of(a)) is not None]
    extent = sweep_extent(kin, ks + strip_ks)
    res = analysis.forces[ref]
    torque = np.asarray(res.driver_torque, float)
    near = np.asarray(sweep.near, bool) if len(sweep.near) == kin.n else np.zeros(kin.n, bool)
    flagged = [float(a) for a in sweep.flagged]
    unit = coord_unit

    largest = arrow_forces(analysis, res)
    force_ref = force_reference(largest, near, ks + strip_ks)

    def frame(k: int) -> Frame:
        angle = float(kin.angles[k])
        title = f"φ = {deg(angle)}°" if unit == "°" else f"s = {deg(angle)}{unit}"
        cut = bool(force_ref > 0 and largest[k] > CLIP * force_ref)
        note = "arrows cut (//)" if cut else ""
        if near[k] and flagged:
            fa = min(flagged, key=lambda a: abs(a - angle))
            note = f"near the left-out {deg(fa)}{unit}" + (f": {note}" if cut else "")
        scene = build_scene(analysis, res, k, colors, symbols, extent)
        return Frame(scene, angle, title, bool(near[k]), note, float(torque[k]), cut)

    frames = [frame(k) for k in ks]
    strip = [frame(k) for k in strip_ks]
    stems = [f"frame_{deg(f.angle).replace('.', 'p').replace('-', 'm')}" for f in strip]
    symbol = "M" if effort_kind == "moment" else "Fd"
    effort = "torque M" if effort_kind == "moment" else "push Fd along its line"
    # a GIF counts in hundredths of a second
    seconds = max(0.02, round(SECONDS_PER_SWEEP / max(len(frames), 1), 2))
    cut = (" Arrows marked // are longer than drawn (off the scale), their value beside "
           "them." if any(f.cut for f in frames + strip) else "")
    caption = (f"The mechanism over the sweep, one frame every {deg(abs(step))}{unit} "
               f"({len(frames)} frames, {seconds * len(frames):.3g} s a cycle): the joint "
               f"reactions (first link on second, {method_title}, coloured per joint, named "
               f"in the key), applied loads (black) and the driver's {effort} (wine red), "
               "every arrow to one scale for the whole sweep (the arrow in the top-right "
               f"corner).{cut} Right: the driver's {symbol} as a gauge over its range; "
               f"bottom: {symbol} over the sweep, this frame's place on it"
               + (" and the left-out angles (red)." if flagged else "."))
    strip_caption = ("Frames of animation.gif at the reference "
                     + ("angles" if len(strip) > 1 else "angle") + ": "
                     + ", ".join(f"{coord} {deg(f.angle)}{unit}" for f in strip)
                     + "; the same scale as the animation, symbols on the drawing.")
    return Animation(frames, strip, stems, extent, force_ref, step,
                     seconds,
                     np.asarray(kin.angles, float), torque, effort_kind, symbol,
                     near, flagged, (float(spec.sweep.start), float(spec.sweep.stop)), unit,
                     caption, strip_caption)
