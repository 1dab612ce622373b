"""The strength keys of a spec: a link's ``section``, ``material`` and ``members``, and the
top-level ``materials:`` (format 1.1), as the models of :mod:`.schema` validated them,
converted to SI, with what needs more than one value checked (a section needs a material,
members name points of the link and make one tree, strengths below the ultimate).

Called by the loader once the links and joints are read, with its checker ``ck`` (which
records problems as ``file:line: key.path: message``). Section sizes are in the spec's length
unit; materials are always in Pa.
"""
from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

from .types import Buckling, Joint, Link, Material, Section, Strength

MATERIAL_KEYS = ("E", "yield", "endurance", "ultimate")
SECTION_SIZES = {"rect": ("width", "height"), "round": ("d",), "tube": ("d", "t"),
                 "area": ("area", "inertia", "c")}


def materials(value: Any, ck) -> dict[str, Material]:
    """The top-level ``materials:`` by name (those the models accepted and that check out)."""
    if not isinstance(value, dict):
        return {}
    out = {}
    for name, body in value.items():
        m = material(body, ("materials", name), ck, str(name))
        if m is not None:
            out[name] = m
    return out


def material(body: Any, path: tuple, ck, name: str = "") -> Material | None:
    """{E, yield, endurance, ultimate} [Pa] as the models validated it, as a Material; None
    (reported) when the yield or endurance strength exceeds the ultimate strength."""
    if ck.refused(path):
        return None
    v = {k: float(body[k]) for k in MATERIAL_KEYS}
    bad = False
    for key in ("yield", "endurance"):
        if v[key] > v["ultimate"]:
            ck.error(path + (key,), f"{v[key]:g} Pa exceeds the ultimate strength "
                                    f"{v['ultimate']:g} Pa")
            bad = True
    return None if bad else Material(name, v["E"], v["yield"], v["endurance"], v["ultimate"])


def section(value: Any, path: tuple, ck, ls: float, unit: str) -> Section | None:
    """A section as the models validated it (sizes in the length unit, ``ls`` m each) in SI;
    None (reported) when its sizes do not make one. rect: ``height`` in the plane
    (I = w h^3 / 12, c = h / 2); round; tube (wall ``t`` at most d / 2); or {area, inertia,
    c} (area in unit^2, inertia in unit^4)."""
    if ck.refused(path):
        return None
    if len(value) == 1 and next(iter(value)) in SECTION_SIZES and next(iter(value)) != "area":
        kind, dims = next(iter(value.items()))
        where = path + (kind,)
    else:
        kind, dims, where = "area", value, path
    keys = SECTION_SIZES[kind] + (("inertia_out",) if kind == "area" and "inertia_out" in dims
                                  else ())
    powers = {"area": 2, "inertia": 4, "inertia_out": 4}
    sizes = {k: ck.si(dims[k], where + (k,), scale=ls ** powers.get(k, 1),
                      unit=unit + ("^" + str(powers[k]) if k in powers else ""))
             for k in keys}
    if any(x is None for x in sizes.values()):
        return None
    if kind == "tube" and sizes["t"] > sizes["d"] / 2:
        ck.error(where + ("t",), f"a wall of {dims['t']} {unit} is thicker than the "
                                 f"radius {sizes['d'] / 2 / ls:g} {unit} (at most d / 2)")
        return None
    made = _section(kind, sizes)
    if not all(math.isfinite(x) and x > 0 for x in (made.area, made.inertia, made.c,
                                                    made.inertia_min)):
        ck.error(where, f"gives an area of {made.area:.6g} m^2 and a second moment of area of "
                        f"{made.inertia:.6g} m^4: sizes this far apart are beyond double "
                        "precision (both must be positive finite numbers)")
        return None
    return made


def _section(kind: str, sizes: dict[str, float]) -> Section:
    """The section of ``kind`` from its sizes [m]. A tube's area pi t (d - t) and inertia
    pi t (d - t) (d^2 + di^2) / 16 are the factored differences of the outer and inner
    circles' (d^2 - di^2 = 4 t (d - t)): no cancellation for a thin wall on a large tube."""
    if kind == "rect":
        w, h = sizes["width"], sizes["height"]
        return Section(kind, w * h, w * h ** 3 / 12, h / 2, min(w * h ** 3, h * w ** 3) / 12,
                       tuple(sizes.items()))
    if kind == "round":
        d = sizes["d"]
        i = math.pi * d ** 4 / 64
        return Section(kind, math.pi * d ** 2 / 4, i, d / 2, i, tuple(sizes.items()))
    if kind == "tube":
        d, t = sizes["d"], sizes["t"]
        di = d - 2 * t
        i = math.pi * t * (d - t) * (d ** 2 + di ** 2) / 16
        return Section(kind, math.pi * t * (d - t), i, d / 2, i, tuple(sizes.items()))
    return Section(kind, sizes["area"], sizes["inertia"], sizes["c"],
                   min(sizes["inertia"], sizes.get("inertia_out", sizes["inertia"])),
                   tuple(sizes.items()))


def joint_points(link: Link, joints: list[Joint]) -> list[str]:
    """The points of ``link`` where its joints act, in the order written (a T joint's only
    when the link is the slider)."""
    out = []
    for j in joints:
        if link.name not in j.links or j.point not in link.points:
            continue
        if j.type == "T" and j.links[1] != link.name:
            continue
        out.append(j.point)
    return list(dict.fromkeys(out))


def strength_links(raw_links: Any, raw_materials: Any, ck, links: list[Link],
                   joints: list[Joint] | None, ls: float, unit: str) -> list[Link]:
    """``links`` with each one's ``strength`` from its ``section``, ``material`` and
    ``members`` (checked: a section needs a material and the other way round, members name
    two different points of the link, at two different places, and join into one tree
    without a closed loop; without ``members``, the link has exactly two joint points)."""
    if not isinstance(raw_links, dict):
        return links
    named = materials(raw_materials, ck)
    out = []
    for link in links:
        body = raw_links.get(link.name)
        if not isinstance(body, dict) or not {"section", "material", "members",
                                              "buckling"} & set(body):
            out.append(link)
            continue
        strength = _link_strength(link, body, ("links", link.name), ck, joints, named,
                                  raw_materials, ls, unit)
        out.append(replace(link, strength=strength) if strength is not None else link)
    return out


def _link_strength(link: Link, body: dict, path: tuple, ck, joints, named, raw_materials,
                   ls: float, unit: str) -> Strength | None:
    if "section" not in body:
        for key in ("material", "members", "buckling"):
            if key in body:
                ck.error(path + (key,), "is for a link with a 'section' (give the section "
                                        "too, or leave this out)")
        return None
    sec = section(body["section"], path + ("section",), ck, ls, unit)
    mat = None
    if "material" not in body:
        ck.error(path, "a link with a 'section' needs a 'material' (a name from "
                       "'materials:' or {E, yield, endurance, ultimate} in Pa)")
    elif isinstance(body["material"], str):
        mat = named.get(body["material"])
        given = raw_materials if isinstance(raw_materials, dict) else {}
        if mat is None and body["material"] not in given:
            choices = ", ".join(map(str, given)) or "none"
            ck.error(path + ("material",), f"no material named '{body['material']}' in "
                                           f"'materials:' (materials: {choices})")
    else:
        mat = material(body["material"], path + ("material",), ck)
    members = _members(link, body, path, ck, joints)
    if sec is None or mat is None or members is None:
        return None
    return Strength(sec, mat, members, "members" in body, _bucklings(body, len(members), ck,
                                                                     path))


def buckling(value: dict | None) -> Buckling:
    """``buckling:`` as the models validated it (None: pinned-pinned Euler-Johnson)."""
    if value is None:
        return Buckling()
    k = float(value.get("k", 1.0))
    rankine = value.get("rankine") or {}
    return Buckling(k, float(value.get("k_out", k)), value.get("formula", "euler-johnson"),
                    float(rankine["crushing"]) if rankine else None,
                    float(rankine["a"]) if rankine else None)


def _bucklings(body: dict, n: int, ck, path: tuple) -> tuple[Buckling, ...]:
    """How each of the ``n`` members buckles: its own ``buckling`` (in ``members``), else the
    link's; () when neither is given (all pinned-pinned, Euler-Johnson)."""
    raw = body.get("members") if "members" in body else None
    own = [m.get("buckling") if isinstance(m, dict) else None for m in raw or ()]
    if "buckling" not in body and not any(own):
        return ()
    link = None if ck.refused(path + ("buckling",)) else body.get("buckling")
    return tuple(buckling(own[i] if i < len(own) and own[i] is not None else link)
                 for i in range(n))


def _members(link: Link, body: dict, path: tuple, ck, joints) -> tuple | None:
    if "members" not in body:
        if joints is None:
            return None
        ends = joint_points(link, joints)
        if len(ends) != 2:
            ck.error(path + ("section",), f"link '{link.name}' has {len(ends)} joint points "
                     f"({', '.join(ends) or 'none'}): list its straight members as "
                     "'members: [[P, Q], ...]' (points of the link)")
            return None
        pairs = [tuple(ends)]
        where = [path + ("section",)]
    else:
        if ck.refused(path + ("members",)):
            return None         # the models say what is wrong
        pairs, where = [], []
        for i, pq in enumerate(body["members"]):
            at = path + ("members", i)
            if isinstance(pq, dict):          # {points: [P, Q], buckling} (format 1.2)
                pq, at = pq["points"], at + ("points",)
            missing = [x for x in pq if x not in link.points]
            if missing:
                ck.error(at, f"link '{link.name}' has no point named '{missing[0]}' "
                             f"(points: {', '.join(link.points)})")
                return None
            pairs.append(tuple(pq))
            where.append(at)
    for pq, at in zip(pairs, where):
        p, q = (link.points[x] for x in pq)
        if math.hypot(q[0] - p[0], q[1] - p[1]) == 0:
            ck.error(at, f"member [{pq[0]}, {pq[1]}] of link '{link.name}' has zero length: "
                         "its two points are at the same place")
            return None
    if len(set(frozenset(pq) for pq in pairs)) < len(pairs):
        ck.error(path + ("members",), "lists a member twice")
        return None
    problem = tree_problem(pairs)
    if problem:
        ck.error(path + ("members",), problem)
        return None
    return tuple(pairs)


def tree_problem(members) -> str | None:
    """Why ``members`` (point-name pairs) are not one tree (a closed loop of members is
    statically indeterminate; separate pieces carry nothing between them), or None."""
    nodes = {x for pq in members for x in pq}
    parent = {x: x for x in nodes}

    def find(x):
        while parent[x] != x:
            x = parent[x]
        return x
    for p, q in members:
        a, b = find(p), find(q)
        if a == b:
            return (f"the members close a loop (through {p} and {q}): a closed frame is "
                    "statically indeterminate; leave one member out")
        parent[a] = b
    if len({find(x) for x in nodes}) > 1:
        return "the members must join into one piece (each sharing a point with another)"
    return None
