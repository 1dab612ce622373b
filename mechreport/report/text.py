"""Plain-text tables for the terminal (numbers by the one formatter, :mod:`mechreport.units`)."""
from __future__ import annotations

from ..kinematics import Kinematics
from ..units import Display, fmt


def _table(header: list[str], rows: list[list[str]]) -> str:
    widths = [max(len(h), *(len(r[i]) for r in rows)) for i, h in enumerate(header)]
    line = "  ".join(h.rjust(w) if i else h.ljust(w) for i, (h, w) in enumerate(zip(header, widths)))
    out = [line, "  ".join("-" * w for w in widths)]
    for r in rows:
        out.append("  ".join(c.rjust(w) if i else c.ljust(w) for i, (c, w) in enumerate(zip(r, widths))))
    return "\n".join(out)


def kin_display(kin: Kinematics) -> Display:
    """The spec's display units (``report.units``; lengths by default in the spec's own
    length unit), as the reports show them, with this sweep's kinematic scales (the
    reports' :func:`~mechreport.post.columns.kinematic_scales`) so that round-off prints as
    0."""
    from ..post.columns import kinematic_scales

    return spec_display(kin.mechanism.spec, kinematic_scales(kin))


def spec_display(spec, scales: dict) -> Display:
    """The spec's display units (``report.units``; lengths, forces and moments by default in
    the spec's own units, pressures in the first pressure load's, the rest in
    :class:`~mechreport.units.Display`'s) with ``scales`` [SI] of each kind of quantity (the
    round-off rule): the one place that reads them, for the reports
    (:func:`.section.display_of`) and the terminal."""
    units = dict(spec.report.units)
    for key, si in (("length", "m"), ("force", "N"), ("moment", "N*m")):
        units.setdefault(key, spec.units.get(key, si))    # the spec's own units
    written = next((ld.pressure.unit for ld in spec.loads if ld.pressure is not None), "Pa")
    return Display(units["length"], units["force"], units["moment"], units.get("mass", "kg"),
                   scales, stress=units.get("stress", "MPa"),
                   pressure=units.get("pressure", written))


def kinematics_rows(kin: Kinematics, k: int, d: Display | None = None
                    ) -> tuple[list[list[str]], list[list[str]]]:
    """Rows at angle index ``k``: points (name (link), x, y, vx, vy, ax, ay) and links
    (number name, angle [deg], omega, alpha, a_C x, a_C y), in the units of ``d``."""
    d = d or kin_display(kin)
    spec = kin.mechanism.spec
    points = []
    for name, owner in spec.named_points():
        s = kin.named_point(name, owner)
        points.append([f"{name} ({owner})", d.num(s.r[k, 0], "length"),
                       d.num(s.r[k, 1], "length"), d.num(s.v[k, 0], "velocity"),
                       d.num(s.v[k, 1], "velocity"), d.num(s.a[k, 0], "acceleration"),
                       d.num(s.a[k, 1], "acceleration")])
    links = []
    for link in spec.links:
        i = link.number
        c = kin.com(link.name)
        links.append([f"{i} {link.name}", d.num(kin.angle_deg(link.name)[k], "angle"),
                      d.num(kin.omega[k, i], "omega"), d.num(kin.alpha[k, i], "alpha"),
                      d.num(c.a[k, 0], "acceleration"), d.num(c.a[k, 1], "acceleration")])
    return points, links


def branch_lines(kin: Kinematics) -> list[str]:
    """``dyad B C C_T (rod, slider) [RRT]: hint: C`` per group: which assembly branch each
    took and why (docs/spec.md, section 7); a group of more than two links is a group, not
    a dyad."""
    return [f"{'dyad' if _is_dyad(b.kind) else 'group'} {b.dyad} [{b.kind}]: {b.rule}"
            for b in kin.branches]


def _is_dyad(kind: str) -> bool:
    """Whether a group kind names a dyad (RRR, RRT, RTR, TRT ...: three joints, R or T)."""
    return len(kind) == 3 and set(kind) <= {"R", "T"}


def kinematics_table(kin: Kinematics) -> str:
    """Points (x, y, vx, vy, ax, ay) and links (angle, omega, alpha) at each angle of ``kin``."""
    spec = kin.mechanism.spec
    d = kin_display(kin)
    blocks = []
    for k, angle in enumerate(kin.angles):
        rows, lrows = kinematics_rows(kin, k, d)
        pts = _table(["point", d.head("x", "length"), d.head("y", "length"),
                      d.head("vx", "velocity"), d.head("vy", "velocity"),
                      d.head("ax", "acceleration"), d.head("ay", "acceleration")], rows)
        lks = _table(["link", "angle [deg]", "omega [rad/s]", "alpha [rad/s²]",
                      d.head("aC x", "acceleration"), d.head("aC y", "acceleration")], lrows)
        blocks.append(f"{spec.name}: {spec.driver.coordinate} {angle:g} {spec.axis_unit}"
                      f"\n\n{pts}\n\n{lks}")
    return "\n\n".join(blocks) if blocks else f"{spec.name}: no angle could be solved"


def cycle_name(period: float) -> str:
    """What one cycle of the loads is called in the report's text: ``turn`` (360 degrees),
    else ``720° cycle``."""
    return "turn" if period == 360 else f"{fmt(period)}° cycle"
