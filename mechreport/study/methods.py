"""Which force method a study runs: one method for every variant (the full cross-check of all
methods is for single reports; ``--cross-check N`` re-runs N variants with every method).

``power`` (the power balance) gives only the driver's effort, no joint reactions, so it can
serve neither joint quantities (``joint.J.*``), nor the shaking force and moment (they are
summed from the reactions at the frame), nor the design items judged on them (bearing lives,
``limits.joint_force``, ``limits.shaking_force``). Every other method gives everything.
"""
from __future__ import annotations

from ..forces import METHODS
from ..spec import Design

#: the methods, fastest first: time per variant of `analyse(spec, methods=[m])` on
#: specs/four_bar.yaml (360 angles), best of 15-25 on the 2-core reference machine: power
#: 8.9-9.1 ms; newton_euler, dalembert and dyad 10.9-11.8 ms (tied within the machine's
#: noise: newton_euler first, as it is the reference method whose values single reports
#: show); contour 14.4-14.6 ms (bench/bench_study.py --methods measures it again)
FASTEST = ("power", "newton_euler", "dalembert", "dyad", "contour")

#: cycle quantities computed from the joint reactions (not available from ``power``)
FROM_REACTIONS = ("cycle.shaking.force_max", "cycle.shaking.force_rms",
                  "cycle.shaking.moment_max")


def needs_reactions(quantity: str) -> bool:
    return quantity.startswith(("joint.", "member.")) or quantity in FROM_REACTIONS


def design_items_needing_reactions(design: Design) -> list[str]:
    """The design items whose verdicts are judged on joint reactions."""
    items = [f"bearings.{j}.life_h" for j, b in design.bearings.items() if b.life_h is not None]
    items += [f"limits.{k}" for k in ("joint_force", "shaking_force", "static_safety",
                                       "fatigue_safety", "buckling_safety")
              if k in design.limits]
    return items


def cannot_serve(method: str, keep, design: Design) -> str | None:
    """Why ``method`` cannot give the kept quantities and the design verdicts (None if it can)."""
    if method not in METHODS:
        return f"unknown method '{method}'; valid: {', '.join(METHODS)}"
    if method != "power":
        return None
    missing = [q for q in keep if needs_reactions(q)] + design_items_needing_reactions(design)
    if not missing:
        return None
    return ("the power balance gives only the driver's effort, no joint reactions, so it "
            f"cannot give {', '.join(missing)}")


def default_method(keep, design: Design) -> str:
    """The fastest method that can give every kept quantity and design verdict."""
    for name in FASTEST:
        if name in METHODS and cannot_serve(name, keep, design) is None:
            return name
    return next(m for m in METHODS if cannot_serve(m, keep, design) is None)


def choose_method(method: str | None, keep, design: Design,
                  named: str = "--method") -> tuple[str, str]:
    """(the method a study runs, why): ``method`` when it can give every kept quantity and
    design verdict (else :class:`~mechreport.errors.MechreportError` saying why, the choice
    called ``named`` as the caller's user knows it), the fastest that can when None."""
    from ..errors import MechreportError
    if method is None:
        return (default_method(keep, design),
                "the fastest method that gives every kept quantity and design verdict")
    why = cannot_serve(method, keep, design)
    if why:
        raise MechreportError(f"{named} {method}: {why}; leave {named} out to use the "
                              "fastest method that can")
    return method, f"chosen with {named}"
