"""``mechanism.dxf`` (``report: {dxf: true}``): the mechanism at each solved reference angle
on its own layer, for CAD, written with ezdxf.

In the spec's length unit (``$INSUNITS`` says which), global frame, counter-clockwise angles:
each link a polyline through its points in the order the spec writes them (closed for three
or more points; a one-point slider as its block's outline), each joint a circle around its
point, each guide of a T joint a line along the slider's travel. Layers are named after the
angle (``crank_angle_45``, ``stroke_300``), each with its own colour."""
from __future__ import annotations

import io
from pathlib import Path

from .files import atomic_write_text

#: $INSUNITS codes of the spec's length units
INSUNITS = {"m": 6, "cm": 5, "mm": 4, "in": 1}
JOINT_RADIUS = 0.015      # joint circles: this fraction of the drawing's extent


def dxf_text(data) -> str:
    """The DXF file of a model's :class:`~mechreport.report.model.DxfData` (R2010, text)."""
    import ezdxf
    doc = ezdxf.new("R2010", setup=False)
    doc.units = INSUNITS.get(data.unit, 0)
    doc.header["$MEASUREMENT"] = 0 if data.unit == "in" else 1
    msp = doc.modelspace()
    s = data.scale
    for i, (name, scene) in enumerate(data.layers):
        doc.layers.add(name, color=1 + i % 7)
        attribs = {"layer": name}
        for _, points in scene.links:
            xy = [(x / s, y / s) for x, y in points]
            if len(xy) >= 2:
                msp.add_lwpolyline(xy, close=len(xy) >= 3, dxfattribs=attribs)
        for shape in scene.shapes:              # a slider with one point: its block
            if shape.kind == "block" and len(_points_of(scene, shape.link)) == 1:
                msp.add_lwpolyline([(x / s, y / s) for x, y in shape.xy], close=True,
                                   dxfattribs=attribs)
        r = JOINT_RADIUS * scene.extent / s
        for _, _, (x, y) in scene.joints:
            msp.add_circle((x / s, y / s), r, dxfattribs=attribs)
        for p0, p1, *_ in scene.guides:
            msp.add_line((p0[0] / s, p0[1] / s), (p1[0] / s, p1[1] / s), dxfattribs=attribs)
    buf = io.StringIO()
    doc.write(buf)
    return buf.getvalue()


def _points_of(scene, link: str) -> list:
    return next((pts for name, pts in scene.links if name == link), [])


def write_dxf(model, outdir: Path) -> list[Path]:
    """``mechanism.dxf`` in ``outdir`` (nothing when the model has no DXF)."""
    if model.dxf is None:
        return []
    return [atomic_write_text(Path(outdir) / "mechanism.dxf", dxf_text(model.dxf))]
