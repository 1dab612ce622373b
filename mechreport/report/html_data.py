"""The data of report.html's interactive parts, as one JSON-ready dict: the mechanism at every
analysed angle (each link's points, each joint's point, the applied forces), the reference
method's joint reactions and the driver's effort there, read from the analysis' result
records (the kinematics' point paths, the report model's sweep series), never recomputed;
their colours are the figures' (:mod:`.mpl`'s palette: the joints', the driver's wine,
the loads' black, the shaking force's ink).

Values are in the report's display units; the numbers the page shows beside the slider are
formatted here by the report's one formatter (so they read as report.md's), the plotted ones
are floats of 5 significant digits, and positions are whole numbers of 1/10 000 of the
drawing's size (the JSON of a 360-angle spec stays well under its 1 MB budget; a sweep of
more than MAX_ANGLES angles is thinned, keeping its peaks). Left-out angles are not among
the analysed ones: the page steps over them."""
from __future__ import annotations

import numpy as np

from ..spec import GROUND
from ..units import deg
from .drawing import ARROW_LEN     # an arrow of the reference force: as animation.gif
from .frames import CLIP, arrow_forces, force_reference
from .mpl import INK, LOAD_COLOR, MOMENT_COLOR

#: positions are stored as whole numbers of extent / GRID
GRID = 10000
#: a finer sweep is thinned to about this many angles (the page stays under 1 MB; a 0.25
#: degree sweep keeps every angle), keeping every peak and reference angle
MAX_ANGLES = 1441


def kept_angles(n: int, peaks: list, refs: list[int]) -> list[int]:
    """The analysed indices a page of ``n`` > MAX_ANGLES angles keeps: evenly spaced ones,
    the largest of each of ``peaks`` (arrays (n,)) and the reference angles ``refs``."""
    step = -(-n // MAX_ANGLES)
    keep = set(range(0, n, step)) | set(refs) | {n - 1}
    for values in peaks:
        finite = np.where(np.isfinite(values), values, -np.inf)
        if np.isfinite(finite).any():
            keep.add(int(np.argmax(finite)))
    return sorted(keep)


def _thin(node, n: int, keep: list[int]):
    """``node`` with each list of ``n`` items (one per analysed angle) cut to ``keep``."""
    if isinstance(node, dict):
        return {k: _thin(v, n, keep) for k, v in node.items()}
    if isinstance(node, list):
        if len(node) == n:
            return [node[i] for i in keep]
        return [_thin(v, n, keep) for v in node]
    return node


def _floats(a) -> list:
    """A float array as a JSON list: 5 significant digits, None where not finite."""
    a = np.asarray(a, float)
    return [None if not np.isfinite(v) else float(f"{v:.5g}") for v in a.tolist()]


def _texts(a, kind: str, d) -> list[str]:
    """Each value of ``a`` [SI] as the report prints it (without its unit)."""
    return [d.num(v if np.isfinite(v) else None, kind) for v in np.asarray(a, float).tolist()]


def _push(analysis, effort) -> np.ndarray:
    """A T driver's push (n, 2) [N]: its force ``effort`` (n,) [N] along its joint's line,
    which turns with the guide (as the animation draws it)."""
    joint = analysis.spec.joint(analysis.spec.driver.joint)
    u = analysis.kinematics.frames.rotate(joint.guide, joint.line.direction)
    return np.asarray(effort, float)[:, None] * u


def _where(joint: str, at: dict) -> np.ndarray:
    """Where joint ``joint``'s reaction acts (n, 2) [m]: its point, or for a pin joining
    several links (``C.on.hub``: the pin's force on its hub) the pin's, which all its
    joints share."""
    if joint in at:
        return at[joint]
    pin = joint.split(".on.")[0]
    return next(xy for name, xy in at.items() if name.split(".on.")[0] == pin)


def html_data(analysis, model) -> dict:
    """The interactive data of the report of ``model`` (a
    :class:`~mechreport.report.model.ReportModel` built from ``analysis``)."""
    kin, spec, d, sw = analysis.kinematics, analysis.spec, model.display, model.sweep
    n = len(sw.angles)
    paths: dict[tuple[str, str], np.ndarray] = {}
    for link in spec.links:
        for name in link.points:
            paths[(link.name, name)] = np.asarray(kin.named_point(name, link.name).r, float)
    ground = {name: np.tile(np.asarray(xy, float), (n, 1)) for name, xy in spec.ground.items()}
    at = {name: np.asarray(xy, float) for name, xy in analysis.joint_points().items()}
    loads = [ld for ld in analysis.loads if ld.link != GROUND and ld.force is not None]
    load_at = {ld.symbol: np.asarray(kin.named_point(ld.point, ld.link).r, float)
               for ld in loads}

    every = [*paths.values(), *ground.values(), *at.values()]
    stack = np.concatenate([p[np.isfinite(p).all(axis=1)] for p in every]) if every else \
        np.zeros((1, 2))
    lo, hi = stack.min(axis=0), stack.max(axis=0)
    extent = float(max((hi - lo).max(), 1e-9))
    origin = lo - 0.05 * extent

    def grid(p: np.ndarray) -> list:
        q = np.rint((p - origin) / extent * GRID)
        return [[int(x), int(y)] if np.isfinite([x, y]).all() else None for x, y in q.tolist()]

    effort_kind = "force" if sw.effort == "force" else "moment"
    push = _push(analysis, sw.torque) if effort_kind == "force" else None
    joints = [{"name": j.name, "symbol": j.symbol, "color": j.color,
               "at": grid(_where(j.name, at)),
               "fx": _floats(j.fx), "fy": _floats(j.fy),
               "f": _floats(d.value(np.asarray(j.f, float), "force")),
               "text": {"f": _texts(j.f, "force", d), "fx": _texts(j.fx, "force", d),
                        "fy": _texts(j.fy, "force", d)}}
              for j in sw.joints]
    near = np.asarray(sw.near, bool) if len(sw.near) == n else np.zeros(n, bool)
    # the arrows' scale is the animation's (without one, set as it would be: no frame cut)
    force_ref = (model.animation.force_ref if model.animation is not None else
                 force_reference(arrow_forces(analysis, analysis.forces[
                     analysis.sweep_summary().method]), near, []))
    force_ref = force_ref if np.isfinite(force_ref) else 0.0        # no arrows then
    shaking = np.asarray(sw.shaking.f, float) if sw.shaking is not None else None
    data = {
        "title": model.name,
        "coord": model.coord, "unit": model.coord_unit,
        "angles": [float(deg(a)) for a in np.asarray(sw.angles, float)],
        "near": [bool(x) for x in near],
        "flagged": [float(a) for a in sw.flagged],
        "refs": [float(a) for a in sw.ref_angles],
        "method": sw.method_title,
        "units": {"force": d.unit("force"), "effort": d.unit(effort_kind),
                  "length": d.unit("length")},
        "effort": {"label": model.effort, "kind": effort_kind, "color": MOMENT_COLOR,
                   "values": _floats(d.value(np.asarray(sw.torque, float), effort_kind)),
                   "text": _texts(sw.torque, effort_kind, d)},
        "geometry": {"grid": GRID, "extent": extent, "force_ref": force_ref,
                     "arrow": ARROW_LEN, "clip": CLIP,
                     "links": [{"name": link.name,
                                "points": [grid(paths[(link.name, p)]) for p in link.points]}
                               for link in spec.links],
                     "ground": [grid(g[:1])[0] for g in ground.values()],
                     "loads": [{"symbol": ld.symbol, "at": grid(load_at[ld.symbol]),
                                "color": LOAD_COLOR,
                                "fx": _floats(np.asarray(ld.force, float)[:, 0]),
                                "fy": _floats(np.asarray(ld.force, float)[:, 1])}
                               for ld in loads]
                              + ([] if push is None else [
                                  {"symbol": "Fd", "at": grid(_where(spec.driver.joint, at)),
                                   "fx": _floats(push[:, 0]), "fy": _floats(push[:, 1]),
                                   "color": MOMENT_COLOR}]),
                     "driver": spec.driver.joint},
        "joints": joints,
        "shaking": None if shaking is None or len(shaking) != n else {
            "label": "shaking force on the frame |F|", "color": INK,
            "values": _floats(d.value(shaking, "force")), "text": _texts(shaking, "force", d)},
    }
    if n <= MAX_ANGLES:
        return data
    peaks = [np.asarray(j.f, float) for j in sw.joints] + [np.asarray(sw.torque, float),
                                                           -np.asarray(sw.torque, float)]
    if shaking is not None and len(shaking) == n:
        peaks.append(shaking)
    refs = [int(np.argmin(np.abs(np.asarray(sw.angles, float) - a))) for a in sw.ref_angles]
    return _thin(data, n, kept_angles(n, peaks, refs))
