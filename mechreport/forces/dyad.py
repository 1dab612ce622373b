"""Dyad (Assur group) method (textbook 4.4, eqs. 4.37-4.48; worked in 4.6.3 and 4.7.2).

Dyads are solved from the last (farthest from the driver) back toward the driver, each with
d'Alembert loads and the reactions already found on its later neighbours:

1. the outer reactions, from the group's own equations: sum F^(i&j) . i and . j; then
   - interior pin: moments of link i and of link j about it (RRR 4.39-4.40, RRT 4.44);
   - interior slider: the slider link's forces projected on the sliding direction and the
     moments of both links about the first outer pin (RTR 4.47-4.48);
   - each outer T joint: F . Delta = 0 (RRT 4.41);
2. the interior reaction from link i's force balance (F32 = -F12 - Fin2 - G2), with, for an
   interior slider, link i's moment about the slider point for the couple;
3. the driver link last: F01 and the torque M from its forces and moment about the pivot.

Generalised to Assur groups of any class (the "Assur-group method"): a group with no closed
form, or a driver group of several links, is one system of its links' d'Alembert equations for
the reactions of all its joints; groups are taken from the last back to the driver's.
"""
from __future__ import annotations

from ..model import Dyad, Group
from .builders import force_equation, moment_equation, normal_constraint
from .context import ForceContext, reaction_unknowns
from .equations import Step
from .result import ForceResult, method_steps, run_steps

NAME = "dyad"
TITLE = "Dyad (Assur groups)"
SECTION = "4.4, 4.6.3, 4.7.2"


def _outer_step(ctx: ForceContext, dyad: Dyad) -> Step:
    i, j = dyad.links
    inner = dyad.inner
    both = ctx.actions_on([i, j], inertia=True)
    eqs = [force_equation(ctx, [i, j], both, "x"), force_equation(ctx, [i, j], both, "y")]
    if inner.type == "R":
        for link in (i, j):
            acts = ctx.actions_on([link], inertia=True, exclude=(inner.name,))
            eqs.append(moment_equation(ctx, [link], acts, inner.point))
    else:
        s = inner.slider
        acts = ctx.actions_on([s], inertia=True, exclude=(inner.name,))
        eqs.append(force_equation(ctx, [s], acts, f"Delta_{inner.name}",
                                  ctx.line_direction(inner), kind="force"))
        pin = next(o for o in dyad.outer if o.type == "R")
        eqs.append(moment_equation(ctx, [i, j], both, pin.point))
    eqs += [normal_constraint(ctx, o) for o in dyad.outer if o.type == "T"]
    unknowns = [u for o in dyad.outer for u in reaction_unknowns(o)]
    return Step(f"Dyad {dyad.label}: outer reactions", unknowns, eqs, dyad.links)


def _inner_step(ctx: ForceContext, dyad: Dyad) -> Step:
    i = dyad.links[0]
    inner = dyad.inner
    acts = ctx.actions_on([i], inertia=True)
    eqs = [force_equation(ctx, [i], acts, "x"), force_equation(ctx, [i], acts, "y")]
    if inner.type == "T":
        eqs.append(moment_equation(ctx, [i], acts, inner.point,
                                   at=ctx.joint_points[inner.name]))
    return Step(f"Dyad {dyad.label}: interior joint {inner.name}", list(reaction_unknowns(inner)),
                eqs, (i,))


def _driver_step(ctx: ForceContext, group: Group) -> Step:
    """The driver's link last (textbook 4.73-4.75 for a crank): its forces and its moments
    about the driver joint give that joint's reaction and the driver's effort."""
    link = group.links[0]
    joint = ctx.spec.joint(ctx.spec.driver.joint)
    acts = ctx.actions_on([link], inertia=True)
    eqs = [force_equation(ctx, [link], acts, "x"), force_equation(ctx, [link], acts, "y"),
           moment_equation(ctx, [link], acts, joint.point, at=ctx.joint_points[joint.name])]
    eqs += [normal_constraint(ctx, j) for j in group.joints if j.type == "T"]
    unknowns = [u for j in group.joints for u in reaction_unknowns(j)] + [ctx.driver_unknown]
    return Step(f"Driver link {link}", unknowns, eqs, (link,))


def _group_step(ctx: ForceContext, group: Group) -> Step:
    """A group with no closed form (or a driver group of several links): every link's
    d'Alembert equations (forces x and y, moments about its centre of mass) and F . Delta = 0
    for each slider, solved together for the reactions of all the group's joints (and the
    driver's effort)."""
    eqs = []
    for link in group.links:
        acts = ctx.actions_on([link], inertia=True)
        s = ctx.links[link]
        eqs += [force_equation(ctx, [link], acts, "x"), force_equation(ctx, [link], acts, "y"),
                moment_equation(ctx, [link], acts, f"C{s.number}", at=s.r)]
    eqs += [normal_constraint(ctx, j) for j in group.joints if j.type == "T"]
    unknowns = [u for j in group.joints for u in reaction_unknowns(j)]
    if group.driver is not None:
        unknowns.append(ctx.driver_unknown)
    name = group.class_name
    return Step(f"{name[0].upper()}{name[1:]} {group.label}", unknowns, eqs, group.links)


def build_steps(ctx: ForceContext) -> tuple[Step, ...]:
    steps = []
    for group in reversed(ctx.mech.groups):
        if group.dyad is not None:
            steps += [_outer_step(ctx, group.dyad), _inner_step(ctx, group.dyad)]
        elif group.driver is not None and len(group.links) == 1:
            steps.append(_driver_step(ctx, group))
        else:
            steps.append(_group_step(ctx, group))
    return tuple(steps)


def solve(ctx: ForceContext) -> ForceResult:
    return run_steps(NAME, ctx, method_steps(ctx, NAME, build_steps))
