"""D'Alembert's principle (textbook 4.2, eqs. 4.31-4.36; worked in 4.6.2).

The inertia force Fin = -m a_C at the centre of mass and the inertia couple Min = -I_C alpha
are added to each link as loads; each link is then in static equilibrium: sum F . i = 0,
sum F . j = 0 and a moment equation about one of the link's own joints (eq. 4.36), not about
its centre of mass: its first pin in `joints` order (crank about A, rod about B in 4.6.2), or
the slider point of its first T joint if it has no pin. All links' equations are solved
together as one system, with F . Delta = 0 for each T joint.
"""
from __future__ import annotations

from .builders import force_equation, moment_equation, normal_constraint
from .context import ForceContext, reaction_unknowns
from .equations import Step
from .result import ForceResult, method_steps, run_steps

NAME = "dalembert"
TITLE = "D'Alembert"
SECTION = "4.2, 4.6.2"


def moment_centre(ctx: ForceContext, link: str) -> str:
    """The joint point a link's d'Alembert moment equation is taken about."""
    joints = ctx.mech.joints_of(link)
    pins = [j for j in joints if j.type == "R"]
    return pins[0].point if pins else joints[0].point


def build_steps(ctx: ForceContext) -> tuple[Step, ...]:
    spec = ctx.spec
    equations = []
    for link in spec.links:
        acts = ctx.actions_on([link.name], inertia=True)
        equations.append(force_equation(ctx, [link.name], acts, "x"))
        equations.append(force_equation(ctx, [link.name], acts, "y"))
        equations.append(moment_equation(ctx, [link.name], acts, moment_centre(ctx, link.name)))
    equations += [normal_constraint(ctx, j) for j in spec.joints if j.type == "T"]
    unknowns = [u for j in spec.joints for u in reaction_unknowns(j)] + [ctx.driver_unknown]
    step = Step("D'Alembert equilibrium of every moving link", unknowns, equations,
                tuple(l.name for l in spec.links))
    return (step,)


def solve(ctx: ForceContext) -> ForceResult:
    return run_steps(NAME, ctx, method_steps(ctx, NAME, build_steps))
