"""Contour method (textbook 4.5, Table 4.1; worked in 4.6.4 and 4.7.3).

For each joint X of a loop, cut X (its reaction becomes the unknown) and walk the loop from X
along path I (into X's second link) and path II (into its first link). At each joint W met,
the links left behind form a free body S with d'Alembert loads; W's reaction is eliminated by
writing, for S,

- at a pin W: the moment about W of everything acting on S;
- at a slider W: the projection of everything acting on S on W's sliding direction.

A path stops before it would take in the ground. Candidates are taken alternately from paths I
and II; one is used when every unknown in it is X's (or already found) and it is independent
of those chosen (rank checked at three angles); a T joint X also gets F . Delta = 0. The driver
torque is solved with the driver joint (4.73-4.75), so a body holding the crank is usable only
then.

Loops come from the joint graph's cycle basis (model.graph). Multi-loop mechanisms are done
loop by loop, loops without the driver first, each joint as soon as enough equations are
usable with the reactions already found (4.7.3: E, D_T, D on 0-3-4-5-0; then C, B_T, B, A).
"""
from __future__ import annotations

import numpy as np

from ..errors import UnsupportedMechanism
from ..model import Loop
from ..spec import GROUND, Joint
from .builders import force_equation, moment_equation, normal_constraint, sliding_direction
from .context import DRIVER_TORQUE, ForceContext, reaction_unknowns
from .equations import Equation, Step
from .result import ForceResult, run_steps

NAME = "contour"
TITLE = "Contour"
SECTION = "4.5, 4.6.4, 4.7.3"


def _path(loop: Loop, x: int, forward: bool):
    """Yield (W, S) along the loop from joint index ``x``: W the joint met, S the links left
    behind (in order). Stops before the ground would join S, or back at X."""
    m = len(loop.joints)
    k = (x + 1) % m if forward else x          # index of the first link entered
    body: list[str] = []
    for step in range(m - 1):
        link = loop.links[k]
        if link == GROUND:
            return
        body.append(link)
        w = loop.joints[k] if forward else loop.joints[(k - 1) % m]
        yield w, list(body)
        k = (k + 1) % m if forward else (k - 1) % m


def _equation(ctx: ForceContext, w: Joint, body: list[str]) -> Equation:
    acts = ctx.actions_on(body, inertia=True, exclude=(w.name,))
    if w.type == "R":
        return moment_equation(ctx, body, acts, w.point)
    return force_equation(ctx, body, acts, f"Delta_{w.name}", sliding_direction(ctx, w))


def _rows(eq: Equation, unknowns: list[str], probes: np.ndarray) -> np.ndarray:
    row = np.zeros((len(probes), len(unknowns)))
    for t in eq.terms:
        for k, u in enumerate(t.action.unknowns):
            if u in unknowns:
                row[:, unknowns.index(u)] += t.coeffs[probes, k]
    return row


def _try_joint(ctx: ForceContext, loop: Loop, joint: Joint, known: set[str],
               probes: np.ndarray) -> Step | None:
    unknowns = list(reaction_unknowns(joint))
    if joint.name == ctx.spec.driver.joint:
        unknowns.append(DRIVER_TORQUE)
    chosen: list[Equation] = [normal_constraint(ctx, joint)] if joint.type == "T" else []
    x = [j.name for j in loop.joints].index(joint.name)
    paths = [list(_path(loop, x, True)), list(_path(loop, x, False))]
    candidates = [p[k] for k in range(max(map(len, paths))) for p in paths if k < len(p)]
    for w, body in candidates:
        if len(chosen) == len(unknowns):
            break
        eq = _equation(ctx, w, body)
        needed = set(eq.unknown_names())
        if not needed & set(unknowns) or not needed <= set(unknowns) | known:
            continue
        trial = np.stack([_rows(e, unknowns, probes) for e in chosen + [eq]], axis=1)
        ranks = [np.linalg.matrix_rank(trial[p], tol=1e-9 * max(1.0, np.abs(trial[p]).max()))
                 for p in range(len(probes))]
        if min(ranks) == len(chosen) + 1:
            chosen.append(eq)
    if len(chosen) < len(unknowns):
        return None
    return Step(f"Joint {joint.name} (loop {loop.label(ctx.spec)})", unknowns, chosen,
                tuple(sorted({b for e in chosen for b in e.bodies})))


def solve(ctx: ForceContext) -> ForceResult:
    spec = ctx.spec
    drv = spec.driver.joint
    loops = list(ctx.mech.loops)
    loops = [l for l in reversed(loops) if drv not in {j.name for j in l.joints}] + \
            [l for l in loops if drv in {j.name for j in l.joints}]
    probes = np.unique(np.linspace(0, ctx.n - 1, 3).astype(int))
    known: set[str] = set()
    solved: set[str] = set()
    steps: list[Step] = []
    order = [j for j in reversed(spec.joints)]
    for loop in loops:
        members = {j.name for j in loop.joints}
        progress = True
        while progress:
            progress = False
            for joint in order:
                if joint.name in solved or joint.name not in members:
                    continue
                step = _try_joint(ctx, loop, joint, known, probes)
                if step is not None:
                    steps.append(step)
                    solved.add(joint.name)
                    known.update(step.unknowns)
                    progress = True
                    break
    missing = [j.name for j in spec.joints if j.name not in solved]
    if missing:
        raise UnsupportedMechanism(
            f"{spec.file}: the contour method found no independent equations for joint(s) "
            f"{', '.join(missing)} along the loops {', '.join(l.label(spec) for l in loops)}")
    return run_steps(NAME, ctx, steps)
