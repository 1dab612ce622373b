"""Power balance (virtual work): the driver torque alone, using no joint reaction.

Ideal joints do no work, so with d'Alembert's inertia loads the total power vanishes:
M omega_1 + sum_links (Fin . v_C + Min omega + G . v_C) + sum_loads (F . v_P or M omega) = 0,
i.e. M omega_1 = sum(m a_C . v_C + I alpha omega) - sum(load power) - power of gravity.
Not in the textbook: an independent check of the other methods' driver torque. At zero
speed (a static analysis, or the instant of starting from rest) it is the virtual-work
balance: every velocity replaced by its velocity coefficient, the velocity at unit rate of the
driven coordinate (valid at any speed; at speed it is the power balance divided by it).
"""
from __future__ import annotations

import numpy as np

from ..kinematics import at_unit_rate
from ..kinematics.frames import project
from .context import ForceContext
from .equations import Action, Equation, Step, Term, no_coefficients, no_constant
from .friction_law import relative_rate
from .result import ForceResult, method_steps, run_steps

NAME = "power"
TITLE = "Power balance"
SECTION = "(independent check)"


def power_equation(ctx: ForceContext) -> Equation:
    """The power balance, or at zero speed (a static analysis, the instant of starting from
    rest) the virtual-work balance: the same sum with each velocity replaced by its velocity
    coefficient (the velocity at unit rate of the driven coordinate)."""
    n = ctx.n
    terms = []
    at_rest = ctx.spec.driver.at_rest
    rates = ctx.once(("unit rate",), at_unit_rate, ctx.kin) if at_rest else ctx.kin
    # the driver's power: its effort times the driven coordinate's rate (rad/s for an R
    # driver, relative to its first link; m/s for a T driver; 1 for virtual work)
    rate = np.ones(n) if at_rest else ctx.kin.driver_rate.copy()
    driver = next(a for link in ctx.spec.driver.links for a in ctx.driver_actions(link))
    driver = Action(driver.symbol, driver.kind, "driver", ctx.spec.driver.link,
                    unknowns=driver.unknowns)
    terms.append(Term(driver, rate[:, None].copy(), no_constant(n), rate=rate, kind="power"))
    for link in ctx.spec.links:
        s = ctx.links[link.name]
        for act in ctx.inertia_actions(link.name) + [ctx.gravity_action(link.name)] + \
                ctx.load_actions(link.name):
            if act.kind == "force":  # inertia and weight act at the centre of mass
                v = rates.com(link.name).v if act.category != "load" else \
                    rates.named_point(act.at_name, link.name).v   # loads: their own point
                terms.append(Term(act, no_coefficients(n), project(act.value, v),
                                  rate=v, kind="power"))
            else:
                omega = rates.omega[:, s.number]
                terms.append(Term(act, no_coefficients(n), act.value * omega, rate=omega,
                                  kind="power"))
    terms += _friction_terms(ctx, rates)
    label = ("sum dW = M + sum F . dr/dq + sum M dtheta/dq = 0 (virtual work)" if at_rest
             else "sum P = M omega1 + sum F . v + sum M omega = 0")
    return Equation(label, "power", tuple(l.name for l in ctx.spec.links), terms)


#: a known action's power below this share of |its value| x |the rate it works on| is a
#: cancellation (an inertia force normal to its point's velocity): rounding, not a share
RESOLVED = 1e-9


def resolvable_effort(ctx: ForceContext) -> float:
    """The largest driver effort [N m, or N for a T driver] that any one known action
    (a load, a weight, an inertia force or couple, a friction) requires at any angle, counting
    an action only where its power is resolvable (see ``RESOLVED``). 0 when no action's is:
    the effort is then zero by construction (a balanced rotor at constant speed: its inertia
    force is normal to its centre's velocity), whatever rounding its computed value carries.
    The agreement check reads it (:mod:`mechreport.checks.agreement`)."""
    eq = power_equation(ctx)
    driver, known = eq.terms[0], eq.terms[1:]
    rate = np.abs(np.asarray(driver.rate, float))
    best = 0.0
    with np.errstate(all="ignore"):
        for term in known:
            value, along = term.action.value, term.rate
            if value is None or along is None:
                continue
            size = (np.hypot(value[:, 0], value[:, 1]) if np.ndim(value) == 2 else
                    np.abs(value)) * (np.hypot(along[:, 0], along[:, 1]) if np.ndim(along) == 2
                                      else np.abs(along))
            power = np.abs(term.const)
            ok = (power > RESOLVED * size) & (rate > 0) & np.isfinite(power)
            if ok.any():
                best = max(best, float(np.max(power[ok] / rate[ok])))
    return best


def _friction_terms(ctx: ForceContext, rates) -> list[Term]:
    """The power each joint's friction dissipates: its value on the second link times the
    second link's rate relative to the first (omega_rel for a couple, v_rel for a force)."""
    out = []
    for joint in (ctx.spec.joint(name) for name in (ctx.kin.friction or {})):
        act = next(a for a in ctx.reaction(joint, joint.links[1]) if a.category == "friction")
        rate = relative_rate(rates, joint)
        if act.kind == "force":        # the sliding velocity along the line
            rate = rate[:, None] * ctx.line_direction(joint)
            out.append(Term(act, no_coefficients(ctx.n), project(act.value, rate), rate=rate,
                            kind="power"))
        else:
            out.append(Term(act, no_coefficients(ctx.n), act.value * rate, rate=rate,
                            kind="power"))
    return out


def build_steps(ctx: ForceContext) -> tuple[Step, ...]:
    step = Step("Power balance of the whole mechanism", [ctx.driver_unknown], [power_equation(ctx)],
                tuple(l.name for l in ctx.spec.links))
    return (step,)


def solve(ctx: ForceContext) -> ForceResult:
    return run_steps(NAME, ctx, method_steps(ctx, NAME, build_steps))
