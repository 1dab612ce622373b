"""Plain-text tables for the terminal."""
from __future__ import annotations

from ..kinematics import Kinematics


def _table(header: list[str], rows: list[list[str]]) -> str:
    widths = [max(len(h), *(len(r[i]) for r in rows)) for i, h in enumerate(header)]
    line = "  ".join(h.rjust(w) if i else h.ljust(w) for i, (h, w) in enumerate(zip(header, widths)))
    out = [line, "  ".join("-" * w for w in widths)]
    for r in rows:
        out.append("  ".join(c.rjust(w) if i else c.ljust(w) for i, (c, w) in enumerate(zip(r, widths))))
    return "\n".join(out)


def _f(x: float) -> str:
    return f"{x:.6g}" if abs(x) >= 1e-12 else "0"


def kinematics_rows(kin: Kinematics, k: int, fmt=_f) -> tuple[list[list[str]], list[list[str]]]:
    """Rows at angle index ``k``: points (name (link), x, y, vx, vy, ax, ay) and links
    (number name, angle [deg], omega, alpha, a_C x, a_C y), numbers formatted by ``fmt``."""
    spec = kin.mechanism.spec
    points = []
    for name, owner in spec.named_points():
        s = kin.named_point(name, owner)
        points.append([f"{name} ({owner})", *(fmt(v) for v in (*s.r[k], *s.v[k], *s.a[k]))])
    links = []
    for link in spec.links:
        i = link.number
        c = kin.com(link.name)
        links.append([f"{i} {link.name}", fmt(kin.angle_deg(link.name)[k]), fmt(kin.omega[k, i]),
                      fmt(kin.alpha[k, i]), fmt(c.a[k, 0]), fmt(c.a[k, 1])])
    return points, links


def kinematics_table(kin: Kinematics) -> str:
    """Points (x, y, vx, vy, ax, ay) and links (angle, omega, alpha) at each angle of ``kin``."""
    spec = kin.mechanism.spec
    blocks = []
    for k, angle in enumerate(kin.angles):
        rows, lrows = kinematics_rows(kin, k)
        pts = _table(["point", "x [m]", "y [m]", "vx [m/s]", "vy [m/s]", "ax [m/s^2]",
                      "ay [m/s^2]"], rows)
        lks = _table(["link", "angle [deg]", "omega [rad/s]", "alpha [rad/s^2]",
                      "aC x [m/s^2]", "aC y [m/s^2]"], lrows)
        blocks.append(f"{spec.name}: crank angle {angle:g} deg\n\n{pts}\n\n{lks}")
    return "\n\n".join(blocks) if blocks else f"{spec.name}: no angle could be solved"
