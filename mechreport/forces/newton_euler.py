"""Newton-Euler equations of motion (textbook 4.1, eqs. 4.26-4.28; worked in 4.6.1 and 4.7.1).

For every moving link: m a_C = sum F (x and y) and I_C alpha = sum M_C, moments about the
link's own centre of mass; the joint reactions and the driver torque are the unknowns. Each T
joint adds F . Delta = 0 (its force is normal to the line, eqs. 4.77, 4.85). All links'
equations form one system (3 per link + 1 per T joint).

Departure from the text: the text finds a T joint's application point P (nonlinear in the
unknowns); we solve for the couple about the slider's point instead (linear), and derive P.
"""
from __future__ import annotations

from .builders import newton_euler_equations, normal_constraint
from .context import ForceContext, reaction_unknowns
from .equations import Step
from .result import ForceResult, method_steps, run_steps

NAME = "newton_euler"
TITLE = "Newton-Euler"
SECTION = "4.1, 4.6.1, 4.7.1"


def build_steps(ctx: ForceContext) -> tuple[Step, ...]:
    spec = ctx.spec
    equations = []
    for link in spec.links:
        equations += newton_euler_equations(ctx, link.name)
    equations += [normal_constraint(ctx, j) for j in spec.joints if j.type == "T"]
    unknowns = [u for j in spec.joints for u in reaction_unknowns(j)] + [ctx.driver_unknown]
    step = Step("Newton-Euler equations of every moving link", unknowns, equations,
                tuple(l.name for l in spec.links))
    return (step,)


def solve(ctx: ForceContext) -> ForceResult:
    return run_steps(NAME, ctx, method_steps(ctx, NAME, build_steps))
