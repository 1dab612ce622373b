"""Geometry of a mechanism drawing at one analysed crank angle, as plain primitives (global
coordinates [m], forces [N]) that drawing.py draws. No matplotlib here."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..forces import ForceResult
from ..kinematics.frames import rotate
from ..spec import GROUND
from .mpl import LOAD_COLOR, MOMENT_COLOR

BAR_MIN = 0.022     # bar width at least this fraction of the drawing's extent
BLOCK_MIN = 0.07    # block sides at least this fraction of the extent


@dataclass
class Shape2D:
    """A link outline: ``kind`` bar|block|plate|line, polygon ``xy`` (m, 2) [m]."""

    link: str
    number: int
    kind: str
    xy: list


@dataclass
class Arrow:
    """A force ``f`` [N] at ``at`` [m]; ``kind`` reaction|load; ``color`` hex."""

    at: tuple
    f: tuple
    label: str
    kind: str
    color: str


@dataclass
class Couple:
    """A moment [N m] (CCW positive) about ``at`` [m]."""

    at: tuple
    value: float
    label: str
    color: str


@dataclass
class Scene:
    """Everything drawn at one crank angle [deg]."""

    angle: float
    extent: float
    shapes: list = field(default_factory=list)
    pins: list = field(default_factory=list)          # (x, y, on_ground)
    guides: list = field(default_factory=list)   # (p0, p1, on_ground, normal, offset [m])
    labels: list = field(default_factory=list)        # (x, y, text)
    arrows: list = field(default_factory=list)
    couples: list = field(default_factory=list)
    driver: str = ""                                  # the driver link, drawn on top
    elements: list = field(default_factory=list)      # (kind, p0, p1): spring, damper ends;
                                                      # a torsion spring at its joint (p0 = p1)
    links: list = field(default_factory=list)    # (name, [(x, y), ...]): each link's points
                                                 # in the order the spec writes them
    joints: list = field(default_factory=list)   # (name, type R|T, (x, y)): each joint's point


def _point_positions(kin, k: int) -> dict[str, tuple]:
    spec = kin.mechanism.spec
    pts = {name: tuple(map(float, xy)) for name, xy in spec.ground.items()}
    for link in spec.links:
        for name in link.points:
            pts.setdefault(name, tuple(map(float, kin.named_point(name, link.name).r[k])))
    return pts


def _to_global(kin, k: int, link_number: int, local: np.ndarray) -> list:
    th = kin.theta[k, link_number]
    xy = rotate(np.asarray(local, float), np.full(len(local), th)) + kin.r[k, link_number]
    return [tuple(map(float, p)) for p in xy]


def _extent(pts: dict) -> float:
    xy = np.array(list(pts.values()))
    span = np.ptp(xy, axis=0) if len(xy) > 1 else np.zeros(2)
    return float(max(span.max(), 1e-3))


def _link_shapes(kin, k: int, extent: float) -> list[Shape2D]:
    out = []
    for link in kin.mechanism.spec.links:
        local = np.array(list(link.points.values()), float)
        s = link.shape
        if len(local) >= 3:
            out.append(Shape2D(link.name, link.number, "plate", _to_global(kin, k, link.number,
                                                                             local)))
        if s is not None and s.kind == "bar":
            h = max(s.height, BAR_MIN * extent) / 2
            box = np.array([[0, -h], [s.length, -h], [s.length, h], [0, h]])
            out.append(Shape2D(link.name, link.number, "bar",
                               _to_global(kin, k, link.number, box)))
        elif s is not None or len(local) == 1:
            w, h = block_half(s, extent)
            box = np.array([[-w, -h], [w, -h], [w, h], [-w, h]])
            out.append(Shape2D(link.name, link.number, "block",
                               _to_global(kin, k, link.number, box)))
        elif len(local) == 2:
            out.append(Shape2D(link.name, link.number, "line",
                               _to_global(kin, k, link.number, local)))
    return out


def block_half(shape, extent: float) -> tuple[float, float]:
    """Half width (along the link's x-axis) and half height of a block as drawn [m]: its
    shape, enlarged to stay visible in a drawing of ``extent``."""
    w = max(shape.length if shape is not None else 0.0, BLOCK_MIN * extent) / 2
    h = max(shape.height if shape is not None else 0.0, BLOCK_MIN * extent * 0.7) / 2
    return w, h


def _guides(kin, k: int, pts: dict, extent: float) -> list:
    """Each T joint's guide: a line along the slider's travel over the sweep (plus the block),
    with walls (on ground) at the block's half-extent across the line: its height for a block
    sliding along its x-axis (not its length)."""
    spec = kin.mechanism.spec
    out = []
    for j in spec.joints:
        if j.type != "T":
            continue
        g = spec.number(j.guide)
        u = rotate(np.asarray(j.line.direction, float), kin.theta[k, g])
        normal = np.array([-u[1], u[0]])
        p = np.asarray(pts[j.point])
        slider = spec.link(j.slider) if j.slider != GROUND else None
        shape = slider.shape if slider is not None else None
        drawn_block = slider is not None and (
            (shape is not None and shape.kind == "block") or len(slider.points) == 1)
        across = along = BLOCK_MIN * extent / 2
        if drawn_block:
            w, h = block_half(shape, extent)
            # the slider's frame is parallel to the guide's: the line's direction in it
            d = np.asarray(j.line.direction, float)
            across = abs(d[1]) * w + abs(d[0]) * h
            along = abs(d[0]) * w + abs(d[1]) * h
        travel = np.zeros(1)
        if slider is not None and j.guide == GROUND:
            path = kin.named_point(j.point, j.slider).r
            travel = (path - p) @ u
        lo = min(float(np.min(travel)) - along, -0.25 * extent)
        hi = max(float(np.max(travel)) + along, 0.25 * extent)
        out.append((tuple(p + lo * u), tuple(p + hi * u), j.guide == GROUND,
                    (float(normal[0]), float(normal[1])), across * 1.04 if drawn_block
                    else across))
    return out


def sweep_extent(kin, ks) -> float:
    """The size [m] of a drawing that holds the mechanism at every analysed index of ``ks``:
    the largest span of its named points (frames of one animation share it, so that pins,
    blocks and arrows keep their size from frame to frame)."""
    return max(_extent(_point_positions(kin, k)) for k in ks)


def build_scene(analysis, res: ForceResult, k: int, colors: dict[str, str],
                symbols: dict[str, str], extent: float | None = None) -> Scene:
    """The drawing at analysed index ``k``: links, pins, guides, labels, the reactions of
    ``res`` (first link on second, at the joint point) and the applied loads. ``extent``
    [m]: the drawing's size (default: the span of the mechanism's points at ``k``)."""
    kin, spec = analysis.kinematics, analysis.spec
    points = analysis.joint_points()
    pts = _point_positions(kin, k)
    extent = extent if extent is not None else _extent(pts)
    sc = Scene(float(kin.angles[k]), extent, _link_shapes(kin, k, extent))
    for j in spec.joints:
        if j.type == "R":
            sc.pins.append((*pts[j.point], GROUND in j.links))
    sc.guides = _guides(kin, k, pts, extent)
    sc.links = [(link.name, [tuple(map(float, kin.named_point(name, link.name).r[k]))
                             for name in link.points]) for link in spec.links]
    sc.joints = [(j.name, j.type, pts[j.point]) for j in spec.joints]
    sc.labels = [(x, y, name) for name, (x, y) in pts.items()]
    for ld in spec.loads:
        if ld.kind in ("spring", "damper"):
            ends = [tuple(map(float, kin.named_point(p, l).r[k])) for l, p in ld.between]
            sc.elements.append((ld.kind, *ends))
        elif ld.kind == "torsion_spring":
            at = tuple(map(float, kin.named_point(ld.joint, spec.joint(ld.joint).links[1]).r[k]))
            sc.elements.append((ld.kind, at, at))
    for j in spec.joints:
        r = res.reactions.get(j.name)
        if r is None:
            continue
        at = tuple(map(float, points[j.name][k]))
        sc.arrows.append(Arrow(at, (float(r.fx[k]), float(r.fy[k])), symbols[j.name],
                               "reaction", colors[j.name]))
    for ld in analysis.loads:
        if ld.link == GROUND:            # a spring or damper's frame end: drawn on its link
            continue
        if ld.force is not None:
            at = tuple(map(float, kin.named_point(ld.point, ld.link).r[k]))
            sc.arrows.append(Arrow(at, tuple(map(float, ld.force[k])), ld.symbol, "load",
                                   LOAD_COLOR))
        else:
            c = tuple(map(float, kin.com(ld.link).r[k]))
            sc.couples.append(Couple(c, float(ld.moment[k]), ld.symbol, LOAD_COLOR))
    pivot = tuple(map(float, points[spec.driver.joint][k]))
    sc.driver = spec.driver.link
    if spec.driver.kind == "R":
        sc.couples.append(Couple(pivot, float(res.driver_torque[k]), "M", MOMENT_COLOR))
    else:                                 # the actuator's push along its line
        joint = spec.joint(spec.driver.joint)
        u = rotate(joint.line.direction, kin.theta[k, spec.number(joint.guide)])
        push = float(res.driver_torque[k]) * np.asarray(u)
        sc.arrows.append(Arrow(pivot, tuple(map(float, push)), "Fd", "driver", MOMENT_COLOR))
    return sc
