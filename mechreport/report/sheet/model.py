"""The model of a solution sheet (the answer key) and of its problem version, built from an
analysis: what the sheet documents (:mod:`.solution_doc`, :mod:`.problem_doc`) print, and the
figures to draw.

A sheet has, for each chosen reference angle: the mechanism's figure, the kinematics
derivation (:mod:`.kinematics`), the inertia forces, a free-body diagram of every link, each
chosen method's equations in symbols and with numbers (:mod:`.translate`, from the very
``Equation`` objects the method solved), the unknowns each step finds, and a table of the
answers (with exact closed forms under ``--exact``, :mod:`.exact`). The problem version has
the statement, the data, the figures and what to find, and no result.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ...forces import METHODS
from ...forces.equations import Equation as FEquation
from ...forces.equations import Step
from ...spec import GROUND
from ...kinematics.frames import perp
from .expr import (ZERO, Equation, Expr, Num, Op, Paren, Point, Raw, Sym, fmt, round_off,
                   sheet_zero)
from ..spec_items import (JOINT_KINDS, LoadItem, driver_item, link_label, load_items,
                          numbered_link)
from .kinematics import derive, scalar, vec_expr
from .pressure import pressure_rule
from .statement import eng, sci, statement
from .symbols import (M_, N_, NM_, R, Names, alpha, axis_atom, comp_sym, omega, scalar_sym,
                      unit_atom, vec_sym)
from .translate import Translator, zero_by_constraint

ALL_METHODS = tuple(METHODS)


@dataclass(frozen=True)
class SheetOptions:
    """What a sheet shows: ``methods`` (names, in this order; None: all), ``angles`` (the
    reference angles, sweep units; None: the spec's ``at``), ``exact`` closed forms."""

    methods: tuple[str, ...] | None = None
    angles: tuple[float, ...] | None = None
    exact: bool = False
    variants: int | None = None       # --variants: overrides sheet.variants.count
    seed: int | None = None           # --seed: overrides sheet.variants.seed

    def key(self) -> dict:
        """The options that change the output, for a build's up-to-date check (empty when
        they are the defaults)."""
        out = {}
        if self.methods is not None:
            out["sheet_methods"] = list(self.methods)
        if self.angles is not None:
            out["sheet_angles"] = [float(a) for a in self.angles]
        if self.variants is not None:
            out["sheet_variants"] = int(self.variants)
        if self.seed is not None:
            out["sheet_seed"] = int(self.seed)
        return out


METHOD_INTRO = {
    "newton_euler": ["For every moving link, Newton's and Euler's equations of motion ",
                     R(r"m\,\mathbf{a}_C = \sum \mathbf{F}", "m bold(a)_C = sum bold(F)"),
                     " and ", R(r"I_C\,\alpha = \sum M_C", "I_C alpha = sum M_C"),
                     " (moments about the link's own centre of mass), with the joint reactions "
                     "and the driver's effort as unknowns; all links' equations are solved "
                     "together."],
    "dalembert": ["The inertia force ", R(r"\mathbf{F}_{in} = -m\,\mathbf{a}_C",
                                          'bold(F)_"in" = -m bold(a)_C'),
                  " (at the centre of mass) and the inertia couple ",
                  R(r"M_{in} = -I_C\,\alpha", 'M_"in" = -I_C alpha'),
                  " are added to each link as loads; each link is then in static equilibrium: "
                  "its forces along x and y and its moments about one of its own joints sum to "
                  "zero. All links' equations are solved together."],
    "dyad": ["The dyads (groups of two links and three joints) are solved from the last one "
             "back toward the driver, with d'Alembert's loads: first the group's outer "
             "reactions, then its interior joint, and the driver's link last."],
    "contour": ["Each joint is cut in turn; walking the contour from it, a moment equation "
                "about each pin met (or a force projection on the sliding direction of each "
                "slider met) is written for the links left behind, so that the other joints' "
                "reactions do not enter."],
    "power": ["Independent check, not in the textbook: ideal joints do no work, so with "
              "d'Alembert's loads the total power vanishes, ",
              R(r"\sum P = M\,\omega_1 + \sum \mathbf{F} \cdot \mathbf{v} + \sum M\,\omega = 0",
                "sum P = M omega_1 + sum bold(F) dot bold(v) + sum M omega = 0"),
              "; it gives the driver's effort without any joint reaction."],
}
#: the power method's introduction when the driver is at rest (a static analysis, or the
#: instant of starting from rest): virtual work with velocity coefficients
VIRTUAL_WORK_INTRO = [
    "Independent check, not in the textbook: the driver is at rest, so there is no power; "
    "ideal joints do no virtual work either, so for a virtual displacement of the driven "
    "coordinate q the total virtual work of the driver, the loads and d'Alembert's loads "
    "vanishes, ",
    R(r"\sum \delta W / \delta q = M + \sum \mathbf{F} \cdot \mathbf{v}' + \sum M\,\omega' = 0",
      "sum delta W \\/ delta q = M + sum bold(F) dot bold(v)' + sum M omega' = 0"),
    ", where v' = dr/dq and ω' = dθ/dq are the velocity coefficients (the velocities at unit "
    "rate of q); it gives the driver's effort without any joint reaction."]

#: the power method's introduction, continued when joints rub
FRICTION_POWER = [
    " Here the joints rub: each friction's power is its value times its joint's relative "
    "rate, ", R(r"M_{fij}\,(\omega_j - \omega_i)", "M_(f i j) (omega_j - omega_i)"), " or ",
    R(r"\mathbf{F}_{fij} \cdot \mathbf{v}_{j/i}", "bold(F)_(f i j) dot bold(v)_(j \\/ i)"),
    " (at rest, per unit rate of q); friction opposes the relative motion, so this power is "
    "lost."]

T_NOTE = ["The textbook finds the point P (or Q) where a slider's reaction acts, which makes the "
          "equations nonlinear; here the reaction of a sliding joint is its force at the "
          "slider's point plus a couple about that point (linear unknowns), which is equivalent "
          "to the same force acting at P, given with the results."]


# ------------------------------------------------------------------------------ the model

@dataclass
class Figure:
    path: str                 # relative to the sheet's folder
    caption: list             # rich text
    draw: object = None       # callable(Path) that writes it


@dataclass
class EqModel:
    number: int
    symbolic: Equation
    numeric: Equation
    source: FEquation | None = None


@dataclass
class EqGroup:
    heading: str | None
    equations: list


@dataclass
class StepModel:
    number: int
    title: str
    free_bodies: list         # each free body the step's equations are written for, in order
    unknowns: list
    notes: list               # (text, math or list of math)
    groups: list              # EqGroup
    results: list             # Equation
    points: list = field(default_factory=list)   # (joint, vector symbol, Equation | None)

    @property
    def equations(self) -> list:
        return [e for g in self.groups for e in g.equations]

    @property
    def free_body(self) -> str:
        """"Free body: link 2 (rod)" or "Free bodies: link 3 (slider) and link 2 (rod)"."""
        return ("Free body: " if len(self.free_bodies) == 1 else "Free bodies: ") + \
            _join_and(self.free_bodies)

    @property
    def cited(self) -> str:
        """The equations the results come from, with the verb agreeing: "(41) gives",
        "(41)–(43) give"."""
        eqs = self.equations
        if len(eqs) == 1:
            return f"({eqs[0].number}) gives"
        return f"({eqs[0].number})–({eqs[-1].number}) give"


@dataclass
class MethodModel:
    name: str
    title: str
    section: str
    intro: list
    steps: list
    effort: Equation
    check: list = field(default_factory=list)    # power: (method title, Equation)


@dataclass
class AngleModel:
    angle: float
    title: str
    skipped: str | None = None
    intro: list = field(default_factory=list)
    figure: Figure | None = None
    kinematics: list = field(default_factory=list)     # KinBlock
    actions: list = field(default_factory=list)        # rows
    loads: list = field(default_factory=list)
    fbds: list = field(default_factory=list)           # Figure
    fbd_note: list = field(default_factory=list)
    methods: list = field(default_factory=list)
    answers: list = field(default_factory=list)        # (symbol, value Equation, exact)
    answers_note: str = ""
    shown: list = field(default_factory=list)
    friction: list = field(default_factory=list)      # rich text: how friction is found
    dynamics: list = field(default_factory=list)      # paragraphs: the equation of motion
    cuts: list = field(default_factory=list)          # strength.Cut: members cut open


@dataclass
class SheetModel:
    name: str
    file: str
    description: str
    exact: bool
    links: list
    joints: list
    driver: list              # rich text
    conventions: list
    t_note: list
    angles: list
    method_titles: list
    units: str = ""
    exact_note: str = ""
    zero: float = ZERO         # round-off [SI]: smaller magnitudes print as 0
    flywheel: object | None = None   # the flywheel problem (.flywheel.FlywheelSheet)

    def figures(self) -> list[Figure]:
        out = []
        for a in self.angles:
            if a.figure is not None:
                out.append(a.figure)
            out += a.fbds
        return out


@dataclass
class ProblemModel:
    name: str
    file: str
    description: str
    links: list
    joints: list
    ground: list
    driver: list
    gravity: str
    loads: list
    angles: list              # (title, Figure)
    tasks: list               # rich text items
    zero: float = ZERO        # round-off [SI]: smaller magnitudes print as 0
    statement: list = field(default_factory=list)   # paragraphs (never the description)
    own_statement: bool = False   # the statement is the spec's sheet.statement (Markdown)


# ------------------------------------------------------------------------------ helpers

def coordinate(spec, angle: float) -> tuple[str, str]:
    """(heading, short) for a reference value: ("Crank angle 45°", "φ = 45°") or
    ("Stroke 300 mm", "s = 300 mm")."""
    d = driver_item(spec)
    if d.kind == "R":
        what = "Crank angle" if d.crank else "Relative angle"
        return f"{what} {fmt(angle)}°", f"φ = {fmt(angle)}°"
    u = d.length_unit
    return f"Stroke {fmt(angle)} {u}", f"s = {fmt(angle)} {u}"


def _tag(angle: float) -> str:
    return fmt(angle).replace("-", "m").replace(".", "p")


def _vec(v) -> str:
    return f"({sci(v[0])}, {sci(v[1])})"


def _free_body(spec, bodies) -> str:
    links = sorted((spec.link(b) for b in bodies), key=lambda l: l.number)
    if len(links) == 1:
        return numbered_link(links[0].number, links[0].name)
    return "links " + " & ".join(str(l.number) for l in links) + \
        " (" + ", ".join(l.name for l in links) + ")"


def _scalar(x: float, unit) -> Expr:
    return scalar(x, unit)


# ------------------------------------------------------------------------------ methods

def _results(unknowns, values: dict, k: int, names: Names, result) -> tuple[list, list]:
    """Solved unknowns grouped by joint: F12 = Fx i + Fy j N, M03 = ... N·m, M = ... N·m;
    and each slider's equivalent point of application."""
    lines, points, done = [], [], set()
    for u in unknowns:
        if u in done:
            continue
        joint = names.joint_of.get(u)
        if joint is not None and names.comp_of[u] in ("x", "y"):
            fx, fy = (values[f"joint.{joint}.f{c}"][k] for c in ("x", "y"))
            done.update({f"joint.{joint}.fx", f"joint.{joint}.fy"})
            lines.append(Equation([Expr().add(1, vec_sym(names.vec[joint])),
                                   vec_expr((fx, fy), N_)]))
            continue
        done.add(u)
        lines.append(Equation([Expr().add(1, names[u]), _scalar(values[u][k], unit_atom(u))]))
        if joint is not None and result is not None:
            r = result.reactions.get(joint)
            if r is not None and r.px is not None:
                pe = None
                if np.isfinite(r.px[k]):
                    pe = Equation([Expr().add(1, Raw(r"\mathbf{r}_{P}", "bold(r)_P", "r_P")),
                                   vec_expr((r.px[k], r.py[k]), M_)])
                points.append((Point(joint), vec_sym(names.vec[joint]), pe))
    return lines, points


def _step_model(number: int, step: Step, tr: Translator, names: Names, spec, result,
                counter: list, origin: dict, group_by_link: bool) -> StepModel:
    k = tr.k
    unknowns = set(step.unknowns)
    zero_all = zero_by_constraint(step)
    zero_k = zero_by_constraint(step, k)
    groups: list[EqGroup] = []
    zero_notes = []
    for eq in step.equations:
        counter[0] += 1
        constraint = eq.kind == "constraint"
        em = EqModel(counter[0], tr.symbolic(eq, set() if constraint else zero_all),
                     tr.numeric(eq, unknowns, set() if constraint else zero_k), eq)
        if constraint:
            for u in sorted(zero_k & {p for t in eq.terms for p in t.action.unknowns}):
                zero_notes.append((u, counter[0]))
        heading = None
        if group_by_link and len(eq.bodies) == 1 and not constraint:
            link = spec.link(eq.bodies[0])
            heading = f"Link {link.number} ({link.name})"
        elif group_by_link and constraint:
            heading = "Sliders"
        if groups and groups[-1].heading == heading:
            groups[-1].equations.append(em)
        else:
            groups.append(EqGroup(heading, [em]))
    if not group_by_link:
        for g in groups:
            g.heading = None
    notes = []
    pairs, seen, earlier = [], set(), {}
    for eq in step.equations:
        for t in eq.terms:
            a = t.action
            if not a.unknowns:
                continue
            if a.sign < 0 and a.category == "reaction" and a.symbol not in seen:
                seen.add(a.symbol)
                joint = names.joint_of[a.unknowns[0]]
                canon = names.vec[joint] if a.kind == "force" else names.couple[joint]
                sym = vec_sym if a.kind == "force" else scalar_sym
                pairs.append(Equation([Expr().add(1, sym(a.symbol)),
                                       Expr().add(-1, sym(canon))]))
            for u in a.unknowns:
                if u not in unknowns and u in origin:
                    earlier.setdefault(origin[u], [])
                    if u not in earlier[origin[u]]:
                        earlier[origin[u]].append(u)
    if pairs:
        notes.append(("action and reaction:", pairs))
    for s, us in sorted(earlier.items()):
        notes.append((f"found in step {s}:",
                      [Equation([Expr().add(1, names[u]), _scalar(tr.values[u][k], unit_atom(u))])
                       for u in us]))
    deltas = {}
    for eq in step.equations:
        if eq.axis and eq.axis.startswith("Delta_") and eq.axis not in deltas:
            d = next((t.direction for t in eq.terms if t.direction is not None), None)
            if d is not None:
                deltas[eq.axis] = np.asarray(d)[k]
    for ax, d in deltas.items():
        notes.append(("sliding direction (unit vector):",
                      Equation([Expr().add(1, axis_atom(ax)), vec_expr(d)])))
    for u, n in zero_notes:
        notes.append((f"the slider's reaction is normal to its line, so by ({n})",
                      Equation([Expr().add(1, names[u]), Expr().add(1, Num(0.0))])))
    results, points = _results(step.unknowns, tr.values, k, names, result)
    bodies = list(dict.fromkeys(frozenset(eq.bodies) for eq in step.equations
                                if eq.kind != "constraint" and eq.bodies)) or [step.bodies]
    return StepModel(number, step.title, [_free_body(spec, b) for b in bodies],
                     [names[u] for u in step.unknowns], notes, groups, results, points)


def _method_model(name: str, result, worked: tuple, k: int, names: Names, spec, counter: list,
                  others: dict) -> MethodModel:
    """The sheet's part for method ``name``: its ``worked`` steps (the labelled systems its
    numbers ``result`` came from) at angle index ``k``."""
    mod = METHODS[name]
    values = result.values()
    tr = Translator(spec, values, k)
    origin: dict[str, int] = {}
    steps = []
    group = name in ("newton_euler", "dalembert")
    for i, step in enumerate(worked, 1):
        steps.append(_step_model(i, step, tr, names, spec, result, counter, origin, group))
        for u in step.unknowns:
            origin[u] = i
    effort = result.driver_quantity
    value = float(result.driver_torque[k])
    eq = Equation([Expr().add(1, names[effort]), _scalar(value, unit_atom(effort))])
    check = []
    if name == "power":
        for other, v in others.items():
            diff = value - v
            if abs(diff) <= 1e-9 * max(1.0, abs(value)):
                diff = 0.0
            check.append((METHODS[other].TITLE,
                          Equation([Expr().add(1, names[effort]), _scalar(v, unit_atom(effort))]),
                          fmt(diff)))
    section = mod.SECTION.strip("()")
    if section[:1].isdigit():
        section = "textbook " + section
    intro = VIRTUAL_WORK_INTRO if name == "power" and spec.driver.at_rest else \
        METHOD_INTRO.get(name, [])
    if name == "power" and spec.friction:
        intro = intro + FRICTION_POWER
    return MethodModel(name, mod.TITLE, section, intro, steps, eq, check)


# ------------------------------------------------------------------------------ angles

def _intro(analysis, k: int) -> list:
    kin, spec = analysis.kinematics, analysis.spec
    d = driver_item(spec)
    n = d.number
    if d.kind == "R":
        return [f"The driver {d.label} turns at ",
                Equation([Expr().add(1, omega(n)), scalar(kin.omega[k, n], Raw(
                    r"\mathrm{rad/s}", '"rad/s"', "rad/s"))]), " with ",
                Equation([Expr().add(1, alpha(n)), scalar(kin.alpha[k, n], Raw(
                    r"\mathrm{rad/s^2}", '"rad/s"^2', "rad/s^2"))]), "."]
    return [f"The actuator extends at {fmt(d.omega)} m/s (acceleration {fmt(d.alpha)} m/s²), "
            f"moving {d.label}."]


def _inertia_rows(analysis, k: int) -> list:
    spec = analysis.spec
    rows = []
    for link in spec.links:
        s = analysis.link_state(link.name)
        fin, mi = analysis.inertia_actions(link.name)
        g = analysis.gravity_action(link.name)
        rows.append([str(link.number), link.name, sci(s.mass), sci(s.inertia),
                     _vec(fin.value[k]), sci(mi.value[k]), _vec(g.value[k])])
    return rows


def _load_rows(analysis, k: int) -> list:
    kin, spec = analysis.kinematics, analysis.spec
    elements = {"spring": "spring force k (L − L0) along its line",
                "damper": "damper force c dL/dt along its line",
                "torsion_spring": "torsion spring couple k (θ_rel − θ0)"}
    rows = []
    for ld in analysis.loads:
        load = ld.load
        if ld.link == GROUND:            # a spring or damper's frame end acts on the frame
            continue
        link = spec.link(ld.link)
        if ld.force is not None:
            v = kin.named_point(ld.point, ld.link).v[k]
            rule = (f"opposes the velocity of {ld.point}, v = {_vec(v)} m/s"
                    if load.oppose == "velocity" else
                    pressure_rule(load, float(kin.angles[k]), spec.cycle)
                    if load.pressure is not None else elements.get(load.kind, "as given"))
            rows.append([vec_sym(ld.symbol), f"{link.number} ({link.name})", ld.point or "",
                         f"{_vec(ld.force[k])} N", rule])
        else:
            w = kin.omega[k, link.number]
            rule = (f"opposes the rotation of link {link.number}, ω = {fmt(w)} rad/s"
                    if load.oppose == "rotation" else elements.get(load.kind, "as given"))
            rows.append([scalar_sym(ld.symbol), f"{link.number} ({link.name})", "",
                         f"{fmt(ld.moment[k])} N·m", rule])
    return rows


def _answers(analysis, k: int, names: Names, exact, methods) -> tuple[list, str]:
    """The answers at ``k`` by the first method with reactions, one row per joint (and the
    driver): (symbol, x, y, magnitude, couple, exact forms or None); and how well the
    methods agree."""
    from ...post import reference_method
    forces = {m: analysis.forces[m] for m in methods if m in analysis.forces} or analysis.forces
    ref = forces[reference_method(forces)]
    spec = analysis.spec
    rows = []

    def ex(sym, x):
        if exact is None:
            return None
        c = exact(x)
        if c is None:
            return [sym, " none found"]
        return [Equation([Expr().add(1, sym), Expr().add(1, exact.atom(c))])]

    values = ref.values()
    for j in spec.joints:
        r = ref.reactions.get(j.name)
        if r is None:
            continue
        vec = names.vec[j.name]
        forms = None
        if exact is not None:
            forms = ex(comp_sym(vec, "x"), r.fx[k]) + [", "] + ex(comp_sym(vec, "y"), r.fy[k])
            if r.moment is not None:
                forms += [", "] + ex(scalar_sym(names.couple[j.name]), r.moment[k])
        rows.append((vec_sym(vec), fmt(r.fx[k]), fmt(r.fy[k]), fmt(r.f[k]),
                     fmt(r.moment[k]) if r.moment is not None else "", forms))
    q = ref.driver_quantity
    v = float(ref.driver_torque[k])
    rows.append((names[q], "", "", "", fmt(v), ex(names[q], v) if exact is not None else None))
    worst = 0.0
    for res in forces.values():
        for u, val in res.values().items():
            if u in values:
                worst = max(worst, abs(float(val[k]) - float(values[u][k])))
    n = len(forces)
    agree = "to round-off" if fmt(worst) == "0" else f"within {fmt(worst)} (N or N·m)"
    note = (f"By {METHODS[ref.method].TITLE}; the {n} methods shown agree {agree}."
            if n > 1 else f"By {METHODS[ref.method].TITLE}.")
    return rows, note


def _zero_actions(analysis, k: int, link: str) -> list[str]:
    out = []
    for a in analysis.free_body_actions([link]):
        if a.unknowns:
            continue
        v = np.asarray(a.value)
        v = v[k] if v.ndim else v
        if np.all(np.abs(v) == 0) or np.all(np.abs(v) < 1e-12):
            out.append(a.symbol)
    return out


def _fbds(analysis, k: int, tag: str, methods) -> tuple[list, list]:
    from .figures import fbd_figure
    spec = analysis.spec
    zero = set()
    ref = next((analysis.forces[m] for m in methods if m in analysis.forces
                and analysis.forces[m].reactions), None)
    if ref is not None:
        for step in analysis.worked_steps(ref.method):
            zero |= zero_by_constraint(step)
    figs = []
    omitted = []
    for link in spec.links:
        path = f"figures/sheet-{tag}-fbd-{link.number}.svg"
        omitted += _zero_actions(analysis, k, link.name)

        def draw(p, _link=link.name, _zero=frozenset(zero)):
            return fbd_figure(analysis, k, _link, p, set(_zero))[0]
        figs.append(Figure(path, [f"Link {link.number} ({link.name})"], draw))
    note = ["Unknown reactions (blue) are drawn as their components in the positive "
            "directions; a slider's reaction along the normal of its line, with its couple. "
            "The inertia force and couple (dashed, red) are d'Alembert's loads, used by every "
            "method but Newton-Euler, which writes ",
            R(r"m\,\mathbf{a}_C", "m bold(a)_C"), " and ", R(r"I_C\,\alpha", "I_C alpha"),
            " instead. Arrows show directions, not magnitudes."]
    if omitted:
        note.append(" Zero at this angle, not drawn: ")
        for i, sym in enumerate(omitted):
            note += [scalar_sym(sym) if sym.startswith("M") else vec_sym(sym),
                     ", " if i < len(omitted) - 1 else "."]
    return figs, note


def _angle_model(analysis, angle: float, names: Names, exact, methods, display,
                 parts: dict | None = None) -> AngleModel:
    kin, spec = analysis.kinematics, analysis.spec
    title, short = coordinate(spec, angle)
    k = kin.index_of(angle)
    if k is None:
        reasons = [f.reason for f in analysis.flags if abs(f.angle - angle) < 1e-9]
        return AngleModel(angle, title,
                          skipped="; ".join(reasons) or "left out of the analysis")
    am = AngleModel(angle, title)
    tag = _tag(angle)
    am.intro = _intro(analysis, k)
    from .figures import mechanism_figure
    am.figure = Figure(f"figures/sheet-{tag}-mechanism.svg",
                       [f"The mechanism at {short}: links numbered, joints lettered."],
                       lambda p: mechanism_figure(analysis, k, p))
    am.kinematics = derive(analysis, k, exact)
    am.actions = _inertia_rows(analysis, k)
    am.loads = _load_rows(analysis, k)
    am.fbds, am.fbd_note = _fbds(analysis, k, tag, methods)
    am.friction = _friction_iteration(analysis, k, parts)
    from .dynamics import equation_of_motion_text
    am.dynamics = [[text] for text in equation_of_motion_text(analysis, k)]
    counter = [0]
    others = {}
    for name in methods:
        res = analysis.forces.get(name)
        if res is None:
            continue
        mm = _method_model(name, res, analysis.worked_steps(name), k, names, spec, counter,
                           others if name == "power" else {})
        if name != "power":
            others[name] = float(res.driver_torque[k])
        am.methods.append(mm)
    am.answers, am.answers_note = _answers(analysis, k, names, exact, methods)
    from .strength import cuts
    am.cuts = cuts(analysis, k)
    if display is not None:
        from ...post import reference_method
        ref = analysis.forces[reference_method(analysis.forces)]
        F, M = display.unit("force"), display.unit("moment")
        for j in spec.joints:
            r = ref.reactions.get(j.name)
            if r is None:
                continue
            am.shown.append([spec.symbol(*j.links), f"{display.num(r.fx[k], 'force')} {F}",
                             f"{display.num(r.fy[k], 'force')} {F}",
                             f"{display.num(r.f[k], 'force')} {F}",
                             f"{display.num(r.moment[k], 'moment')} {M}"
                             if r.moment is not None else ""])
        am.shown.append(["M (driver)", "", "", "",
                         f"{display.num(ref.driver_torque[k], 'moment')} {M}"])
    return am


# ------------------------------------------------------------------------------ friction

ITERATION = ("Friction depends on the reactions it changes, so it is found by iteration: start "
             "from the frictionless reactions, compute each joint's friction from them, solve "
             "again with those frictions as known loads, and repeat until the frictions no "
             "longer change (the program solves the same equations by Newton's method). The "
             "equations below hold the converged values.")


def _friction_iteration(analysis, k: int, parts: dict | None) -> list:
    """How the friction at angle index ``k`` is found, in words, with the first iteration's
    numbers for the first friction joint (its frictionless reaction: every source of
    ``parts``, the reference method's unknowns split by source, but friction) and the
    converged friction of every joint."""
    spec, kin = analysis.spec, analysis.kinematics
    if not spec.friction or kin.friction is None:
        return []
    out: list = [ITERATION]
    first = _first_iteration(analysis, k, parts)
    if first:
        out += [" At this angle, for joint ", *first]
    out.append(" The converged frictions at this angle: ")
    for i, fr in enumerate(spec.friction):
        j = spec.joint(fr.joint)
        out += [Equation([Expr().add(1, _friction_atom_scalar(spec, j)),
                          _scalar(kin.friction[fr.joint][k], NM_ if j.type == "R" else N_)]),
                ", " if i < len(spec.friction) - 1 else "."]
    return out


def _friction_atom_scalar(spec, joint) -> Sym:
    """A friction's signed value: M_f12 (a pin's couple), F_f03 (a slider's force along its
    line)."""
    return scalar_sym(_friction_name(spec, joint))


def _first_iteration(analysis, k: int, parts: dict | None) -> list:
    """The first iteration at angle index ``k`` for the first friction joint, as rich text:
    its frictionless reaction, the friction the law gives from it, and the converged
    reaction and friction; [] where it cannot be shown (no split by source, no friction
    there: the joint does not move at this angle and has no friction_sense)."""
    from ...forces.friction_law import relative_rate, senses
    spec, kin = analysis.spec, analysis.kinematics
    fr = spec.friction[0]
    joint = spec.joint(fr.joint)
    s = float(senses(kin, spec.friction)[0][k, 0])
    if parts is None or s == 0:
        return []
    own = ("friction",)
    unknowns = [f"joint.{joint.name}.{c}" for c in ("fx", "fy", "moment")]
    base = {u: sum(float(p[u][k]) for src, p in parts.items() if src not in own and u in p)
            for u in unknowns}
    res = analysis.forces[reference_method_of(analysis)]
    r = res.reactions[joint.name]
    f0, f = math.hypot(base[unknowns[0]], base[unknowns[1]]), float(r.f[k])
    mag = _abs(vec_sym(spec.symbol(*joint.links)))
    value = _friction_atom_scalar(spec, joint)
    unit = NM_ if joint.type == "R" else N_
    if joint.type == "R" and fr.model == "circle":     # the friction circle's radius
        law = R(r"r\,\sin(\arctan\mu)", "r sin(arctan mu)")
        numbers = Expr().add(1, Num(fr.radius), Op("mul"), Num(fr.journal_mu), Op("mul"),
                             Num(f0))
        first = fr.journal_mu * fr.radius * f0
    elif joint.type == "R":
        law = R(r"\mu\,r", "mu r")
        numbers = Expr().add(1, Num(fr.mu), Op("mul"), Num(fr.radius), Op("mul"), Num(f0))
        first = fr.mu * fr.radius * f0
    elif fr.length is None:
        law = R(r"\mu", "mu")
        numbers = Expr().add(1, Num(fr.mu), Op("mul"), Num(f0))
        first = fr.mu * f0
    else:
        n = perp(kin.frames.rotate(joint.guide, joint.line.direction)[k])
        normal = base[unknowns[0]] * n[0] + base[unknowns[1]] * n[1]
        lo = normal / 2 - base[unknowns[2]] / fr.length
        hi = normal / 2 + base[unknowns[2]] / fr.length
        law = None
        inner = Expr().add(1, _abs(Num(lo))).add(1, _abs(Num(hi)))
        numbers = Expr().add(1, Num(fr.mu), Paren(inner))
        first = fr.mu * (abs(lo) + abs(hi))
    rate = relative_rate(kin, joint)[k]
    i, j = (spec.number(x) for x in joint.links)
    if joint.type == "R":
        rel = Expr()
        for sign, m in ((1, j), (-1, i)):
            if m:
                rel.add(sign, omega(m))
        rate_eq = Equation([rel, _scalar(rate, Raw(r"\mathrm{rad/s}", '"rad/s"', "rad/s"))])
    else:
        rate_eq = Equation([Expr().add(1, Raw(rf"v_{{{j}/{i}}}", f"v_({j} \\/ {i})",
                                                f"v_{j}/{i}")),
                            _scalar(rate, Raw(r"\mathrm{m/s}", '"m/s"', "m/s"))])
    if spec.driver.at_rest:
        opposing = [f"opposing the motion it is about to have (friction_sense {int(s):+d})"]
    else:
        opposing = ["opposing ", rate_eq]
    opposing.append(": ")
    lhs = Expr().add(1, _abs(value))
    if law is not None:
        middle = Expr().add(1, law, mag)
    else:
        middle = Expr().add(1, R(r"\mu\,(|N_1| + |N_2|)", "mu (|N_1| + |N_2|)"))
    return [f"{joint.written}: without friction ", Equation([Expr().add(1, mag), _scalar(f0, N_)]),
            ", so the first estimate is ",
            Equation([lhs, middle, numbers, _scalar(first, unit)]), ", ", *opposing,
            Equation([Expr().add(1, value), _scalar(-s * first, unit)]),
            "; converged, ", Equation([Expr().add(1, mag), _scalar(f, N_)]), " and ",
            Equation([Expr().add(1, value), _scalar(kin.friction[fr.joint][k], unit)]), "."]


def _abs(atom) -> Raw:
    """|atom|: a magnitude."""
    return Raw(f"|{atom.tex()}|", f"|{atom.typ()}|", f"|{atom.plain()}|")


def reference_method_of(analysis) -> str:
    """The reference method of ``analysis`` (the one its by-source split is of)."""
    from ...post import reference_method
    return reference_method(analysis.forces)


# ------------------------------------------------------------------------------ the sheet

def _conventions(spec) -> list:
    effort = ([R("M", "M"), " is the driver torque on the driver link."]
              if spec.driver.kind == "R" else
              [R("F_d", "F_d"), " is the actuator's force along its line (its first link on its "
               "second)."])
    return [
        ["Links are numbered in the spec's order, the ground is 0. ",
         R(r"\mathbf{F}_{ij}", "bold(F)_(i j)"), " is the force of link i on link j (",
         R(r"\mathbf{F}_{ji} = -\mathbf{F}_{ij}", "bold(F)_(j i) = -bold(F)_(i j)"),
         "); its components ", R(r"F_{ijx}, F_{ijy}", "F_(i j x), F_(i j y)"),
         " are global, along ", R(r"\mathbf{i}", "bold(i)"), " and ",
         R(r"\mathbf{j}", "bold(j)"), "."],
        ["Moments and couples are about the z-axis, counterclockwise positive; ",
         R(r"\mathbf{r}_{PQ} = \mathbf{r}_Q - \mathbf{r}_P", "bold(r)_(P Q) = bold(r)_Q - "
           "bold(r)_P"), ", so the moment about P of a force F applied at Q is ",
         R(r"\mathbf{r}_{PQ} \times \mathbf{F} = (x_Q - x_P) F_y - (y_Q - y_P) F_x",
           "bold(r)_(P Q) times bold(F) = (x_Q - x_P) F_y - (y_Q - y_P) F_x"), "."],
        [R(r"\mathbf{F}_{in\,i} = -m_i \mathbf{a}_{C_i}", 'bold(F)_("in" i) = -m_i bold(a)_(C_i)'),
         " is the inertia force of link i at its centre of mass ", R("C_i", "C_i"), ", ",
         R(r"M_{in\,i} = -I_{C_i} \alpha_i", 'M_("in" i) = -I_(C_i) alpha_i'),
         " its inertia couple, ", R(r"\mathbf{G}_i = m_i \mathbf{g}", "bold(G)_i = m_i bold(g)"),
         " its weight; ", *effort],
        ["Each method states its equations in symbols (the very equations the program "
         "solves), then with the numbers of the reference angle: terms that vanish there are "
         "left out, values found in an earlier step are substituted, coefficients are "
         "simplified. Numbers have 6 significant digits; SI units (m, kg, s, N, N·m)."],
    ] + [_pin_convention(spec, pin) for pin in spec.pins] + _friction_convention(spec)


def _friction_convention(spec) -> list:
    """What the friction symbols mean, the law of each kind of joint with friction, and each
    one's data (SI); none without friction."""
    if not spec.friction:
        return []
    joints = [(fr, spec.joint(fr.joint)) for fr in spec.friction]
    pins = any(j.type == "R" for _, j in joints)
    sliders = any(j.type == "T" for _, j in joints)
    out: list = []
    if pins:
        out += [R("M_{fij}", "M_(f i j)"), " is the friction couple of link i on link j in a "
                "pin joint" + (", " if sliders else " (")]
    if sliders:
        out += [R(r"\mathbf{F}_{fij}", "bold(F)_(f i j)"), " the friction force of link i on "
                "link j along a slider's line" if pins else " is the friction force of link i "
                "on link j along a slider's line", " ("]
    if pins:
        out.append(R(r"M_{fji} = -M_{fij}", "M_(f j i) = -M_(f i j)"))
    if sliders:
        out += [", " if pins else "", R(r"\mathbf{F}_{fji} = -\mathbf{F}_{fij}",
                                        "bold(F)_(f j i) = -bold(F)_(f i j)")]
    out.append("). Each opposes the motion of link j relative to link i: ")
    motion = []
    if pins:
        motion += ["the relative rotation ", R(r"\omega_j - \omega_i", "omega_j - omega_i")]
    if sliders:
        motion += [" or " if pins else "", "the sliding velocity ",
                   R(r"\mathbf{v}_{j/i}", "bold(v)_(j \\/ i)"), " along the line"]
    out += motion
    if spec.driver.at_rest:
        out.append(" (the driver at rest: the motion each joint is about to have, its "
                   "friction_sense)")
    out.append(". Its magnitude is ")
    laws = []
    if pins:
        laws.append([R(r"\mu\,r\,|\mathbf{F}_{ij}|", "mu r |bold(F)_(i j)|"),
                     " in a pin of journal radius r"])
    if any(j.type == "T" and fr.length is None for fr, j in joints):
        laws.append([R(r"\mu\,|N|", "mu |N|"), " in a slider (N its normal force)"])
    if any(fr.length is not None for fr, _ in joints):
        laws.append([R(r"\mu\,(|N_1| + |N_2|)", "mu (|N_1| + |N_2|)"), " in a slider of length "
                     "L, whose ends carry ", R(r"N_{1,2} = N/2 \mp M/L",
                                               "N_(1,2) = N \\/ 2 minus.plus M \\/ L"),
                     " (N its normal force, M its couple)"])
    for i, law in enumerate(laws):
        out += ([", " if i < len(laws) - 1 else " and "] if i else []) + law
    out.append(". The friction in the joints: ")
    for i, (fr, j) in enumerate(joints):
        size = (f"r = {fmt(fr.radius)} m" if j.type == "R" else
                f"L = {fmt(fr.length)} m" if fr.length is not None else "")
        out += [f"{j.written} (", _friction_atom(spec, j), f"): μ = {fmt(fr.mu)}"
                + (f", {size}" if size else "") + (";  " if i < len(joints) - 1 else ".")]
    return [out]


def _friction_name(spec, joint) -> str:
    """Mf12, the friction couple of link 1 on link 2 in an R joint; Ff03, the friction force
    of link 0 on link 3 along a T joint's line."""
    return spec.symbol(*joint.links, "Mf" if joint.type == "R" else "Ff")


def _friction_atom(spec, joint):
    """M_f12 (a pin's friction couple) or **F**_f03 (a slider's friction force)."""
    name = _friction_name(spec, joint)
    return scalar_sym(name) if joint.type == "R" else vec_sym(name)


def _pin_convention(spec, pin) -> list:
    """How a pin joining several links enters the free bodies: as part of its hub."""
    hub = spec.number(pin.hub)
    others = [spec.number(x) for x in pin.others]
    tex = [rf"\mathbf{{F}}_{{{hub}{n}}}" for n in others]
    typ = [f"bold(F)_({hub} {n})" for n in others]
    return [f"Pin {pin.name} joins links {', '.join(str(spec.number(x)) for x in pin.links)}"
            f" ({', '.join(pin.links)}). It is taken as part of link {hub} ({pin.hub}), so "
            f"each other link's free body meets it as one joint with link {hub}: ",
            R(", ".join(tex), ", ".join(typ)), " are the pin's forces on links "
            f"{', '.join(map(str, others))}, and its force on link {hub} is ",
            R(rf"\mathbf{{F}}_{{{pin.name}{hub}}} = -({' + '.join(tex)})",
              f"bold(F)_({pin.name} {hub}) = -({' + '.join(typ)})"),
            " (the pin is in equilibrium)."]


def choose_methods(analysis, methods) -> list[str]:
    """The methods to show, in the textbook's order (``methods`` None: all analysed)."""
    names = [m for m in ALL_METHODS if m in analysis.forces]
    if methods is None:
        return names
    return [m for m in methods if m in analysis.forces]


def build_sheet(analysis, options: SheetOptions | None = None) -> SheetModel:
    """The answer key of an analysis (figures not drawn yet: see ``SheetModel.figures``),
    its numbers below the analysis' round-off (:func:`~.expr.sheet_zero`) printed as 0."""
    zero = sheet_zero(analysis.scales())
    with round_off(zero):
        model = _build_sheet(analysis, options)
    model.zero = zero
    from .flywheel import flywheel_sheet
    model.flywheel = flywheel_sheet(analysis)
    return model


def _build_sheet(analysis, options: SheetOptions | None = None) -> SheetModel:
    options = options or SheetOptions()
    spec = analysis.spec
    names = Names(spec)
    angles = list(options.angles) if options.angles is not None else list(spec.at)
    exact = None
    exact_note = ""
    if options.exact:
        from .exact import ExactForms
        exact = ExactForms(spec, angles)
        exact_note = ("Exact values are " + exact.describe() + " that match the computed "
                      "value to 12 digits; “none found” means the value is not such a "
                      "combination (or needs more digits than a computed value can confirm).")
    methods = choose_methods(analysis, options.methods)
    from ..section import display_of
    display = display_of(analysis)
    si = (display.length, display.force, display.moment, display.mass) == ("m", "N", "N*m", "kg")
    links = [[str(l.number), l.name, ", ".join(f"{p} {_vec(xy)}" for p, xy in l.points.items()),
              sci(l.mass), sci(l.inertia), _vec(l.com)] for l in spec.links]
    joints = []
    for j in spec.joints:
        a, b = j.links
        joints.append([j.name, j.type, f"{spec.number(a)} ({a}) on {spec.number(b)} ({b})",
                       vec_sym(names.vec[j.name])])
    # the reference method's unknowns by source: the frictionless reactions the friction
    # iteration starts from (every source but friction)
    parts = analysis.by_source() if spec.friction and analysis.kinematics.friction else None
    angle_models = [_angle_model(analysis, float(a), names, exact, methods,
                                 None if si else display, parts) for a in angles]
    return SheetModel(spec.name, str(spec.file), spec.description.strip(), options.exact,
                      links, joints, driver_datum(spec), _conventions(spec),
                      T_NOTE if any(j.type == "T" for j in spec.joints) else [],
                      angle_models, [METHODS[m].TITLE for m in methods],
                      "" if si else display.describe(), exact_note)


def driver_datum(spec) -> list:
    """The problem's driver datum (:func:`~mechreport.report.spec_items.driver_item`)."""
    d = driver_item(spec)
    if d.holds:
        return [f"Driver: joint {d.joint} holds {d.label} at rest "
                "(a static problem: no inertia forces; the driver's effort holds the "
                "mechanism in each position)."]
    if d.at_rest:
        return [f"Driver: joint {d.joint} starts {d.label} from rest, "
                f"accelerating at {fmt(d.alpha)} {d.accel_unit}: at this instant every "
                "velocity is zero, and the inertia forces come from the accelerations alone."]
    if d.kind == "R":
        return [f"Driver: joint {d.joint}, {d.label} turns at ",
                Equation([Expr().add(1, omega(d.number)), scalar(d.omega, Raw(
                    r"\mathrm{rad/s}", '"rad/s"', "rad/s"))]),
                f" ({fmt(d.rpm)} rpm)" + (", constant" if d.alpha == 0 else
                                          f", accelerating at {fmt(d.alpha)} rad/s²") + "."]
    return [f"Driver: the actuator {d.joint} extends at {fmt(d.omega)} m/s, moving "
            f"{d.label}."]


# ------------------------------------------------------------------------------ problem

def _load_text(spec, item: LoadItem) -> str:
    """A load as the problem states it, SI (:func:`~mechreport.report.spec_items.load_items`)."""
    load = item.load
    if load.kind == "spring":
        (la, pa), (lb, pb) = load.between
        return (f"a spring of stiffness {fmt(load.stiffness)} N/m and free length "
                f"{fmt(load.free_length)} m between {pa} ({la}) and {pb} ({lb})")
    if load.kind == "damper":
        (la, pa), (lb, pb) = load.between
        return f"a damper of {fmt(load.damping)} N·s/m between {pa} ({la}) and {pb} ({lb})"
    if load.kind == "torsion_spring":
        return (f"a torsion spring of {fmt(load.stiffness)} N·m/rad at joint {load.joint}, "
                f"free at {fmt(load.free_angle)}°")
    if load.kind == "force":
        if load.value is not None:
            what = f"a force {_vec(load.value)} N"
        elif load.pressure is not None:      # format 1.2: (p - ambient) x area
            pr = load.pressure
            size = (f"bore {fmt(pr.bore)} m" if pr.bore is not None
                    else f"area {fmt(pr.area)} m²")
            what = (f"a gas pressure [{pr.unit}] following "
                    f"{_profile_text(pr.profile, spec, load.shift)}, less the ambient "
                    f"{fmt(pr.ambient)} {pr.unit}, on a piston of {size} (the force "
                    f"(p − ambient) × area along {_vec(load.direction)}, its reaction on the "
                    "frame)")
        else:
            what = (f"a force along {_vec(load.direction)} whose magnitude [N] follows "
                    f"{_profile_text(load.profile, spec, load.shift)}")
        rule = " opposing the velocity of its point" if load.oppose == "velocity" else ""
        return f"{what} on {item.where}{rule}"
    what = f"a moment {fmt(load.value)} N·m" if load.value is not None else \
        f"a moment [N·m] following {_profile_text(load.profile, spec, load.shift)}"
    rule = " opposing the link's rotation" if load.oppose == "rotation" else ""
    return f"{what} on {link_label(spec, item.link)}{rule}"


def _profile_text(profile, spec, shift: float = 0.0) -> str:
    """A load's profile as the problem states it: every point, and how values between them
    are read (as :func:`mechreport.forces.loads.evaluate_loads` reads them: repeating every
    cycle, phased by the load's ``shift``)."""
    unit = "°" if spec.axis_unit == "deg" else f" {spec.axis_unit}"
    points = ", ".join(f"{fmt(a)}{unit}: {fmt(v)}" for a, v in profile)
    if len(profile) == 1:
        return f"the profile {points} (constant)"
    cycle = spec.cycle
    turn = ("" if spec.axis_unit != "deg" else ", repeating every turn" if cycle == 360.0
            else f", repeating every {fmt(cycle)}° cycle")
    phase = (f"; shifted by {fmt(shift)}°: the value at φ is the profile's at φ − {fmt(shift)}°"
             if shift else "")
    return (f"the profile {points} over the {driver_item(spec).coordinate} (linear between "
            f"these points{turn}{phase})")


def build_problem(analysis, options: SheetOptions | None = None,
                  sheet: SheetModel | None = None) -> ProblemModel:
    """The problem version: statement, data, figures, what to find; no result."""
    zero = sheet_zero(analysis.scales())
    with round_off(zero):
        model = _build_problem(analysis, options, sheet)
    model.zero = zero
    return model


def _build_problem(analysis, options: SheetOptions | None = None,
                   sheet: SheetModel | None = None) -> ProblemModel:
    options = options or SheetOptions()
    spec = analysis.spec
    names = Names(spec)
    angles = [a for a in (options.angles if options.angles is not None else spec.at)
              if analysis.kinematics.index_of(a) is not None]   # a problem with an answer
    methods = choose_methods(analysis, options.methods)
    links = []
    for l in spec.links:
        pts = list(l.points.items())
        dims = []
        for a in range(len(pts)):
            for b in range(a + 1, len(pts)):
                d = np.hypot(*np.subtract(pts[b][1], pts[a][1]))
                dims.append(f"{pts[a][0]}{pts[b][0]} = {fmt(d)} m")
        shape = ""
        if l.shape is not None:
            shape = (f"{l.shape.kind} {fmt(l.shape.length)} × {fmt(l.shape.height)} × "
                     f"{fmt(l.shape.depth)} m")
        if l.strength is not None:
            shape = "; ".join(x for x in (shape, _strength_datum(l)) if x)
        links.append([str(l.number), l.name, ", ".join(f"{p} {_vec(xy)}" for p, xy in pts),
                      ", ".join(dims), shape, sci(l.mass), sci(l.inertia), _vec(l.com)])
    joints = [[j.name, JOINT_KINDS[j.type],
               f"{spec.number(j.links[0])} ({j.links[0]}) – {spec.number(j.links[1])} "
               f"({j.links[1]})" + (f", line through {_vec(j.line.through)} along "
                                    f"{_vec(j.line.direction)} in the frame of "
                                    f"{j.links[0]}" if j.type == "T" else "")]
              for j in spec.joints if spec.pin(j.point) is None]
    joints += [[pin.name, JOINT_KINDS["R"],
                " – ".join(f"{spec.number(x)} ({x})" for x in pin.links)]
               for pin in spec.pins]       # the pin as written, not its two-link joints
    for fr in spec.friction:               # its friction, with the joint (or the pin)
        joint = spec.joint(fr.joint)
        row = next(r for r in joints if r[0] == joint.written)
        row[2] += "; " + _friction_datum(spec, fr, joint)
    ground = [f"{n} {_vec(xy)}" for n, xy in spec.ground.items()]
    loads = [_load_text(spec, item) for item in load_items(spec)]
    figs = []
    if sheet is not None:
        for am in sheet.angles:
            if am.skipped is None:
                figs.append((am.title, am.figure))
    else:
        for a in angles:
            figs.append((coordinate(spec, a)[0], None))
    titles = [METHODS[m].TITLE for m in methods if m != "power"]
    effort = "the driver torque M" if spec.driver.kind == "R" else \
        "the actuator force F_d"
    shorts = ", ".join(coordinate(spec, a)[1] for a in angles)
    tasks = [_kinematics_task(spec, shorts)]
    if _has_inertia(spec):
        tasks.append("the inertia force and inertia couple of every link;")
    reactions = ", ".join(f"{names.vec[j.name]} at {j.written}" for j in spec.joints)
    couples = " and the couple of each slider" if any(j.type == "T" for j in spec.joints) \
        else ""
    tasks += [f"the reaction of every joint ({reactions}; Fij is the force link i exerts on "
              f"link j{couples}) and {effort}" + (f", by {_join_and(titles)}" if titles else "")
              + ";"]
    if spec.friction:
        named = [f"{spec.joint(fr.joint).written} ({_friction_name(spec, spec.joint(fr.joint))})"
                 for fr in spec.friction]
        tasks.append(f"the friction in joint{'s' if len(named) > 1 else ''} "
                     f"{_join_and(named)}, found together with the reactions it changes;")
    sized = [l for l in spec.links if l.strength is not None]
    if sized:
        tasks.append("the axial force N, shear force V and bending moment M at the middle of "
                     "each member of " + _join_and([numbered_link(l.number, l.name)
                                                    for l in sized])
                     + ", and the largest normal stress there;")
    if "power" in methods:
        tasks.append(f"check {effort} with " + ("virtual work." if spec.driver.at_rest
                                                 else "a power balance."))
    own = spec.sheet_settings.statement
    return ProblemModel(spec.name, str(spec.file), "", links, joints,
                        ground, driver_datum(spec), _vec(spec.gravity) + " m/s²", loads, figs,
                        tasks, statement=[own] if own else statement(spec, shorts),
                        own_statement=bool(own))


def _kinematics_task(spec, shorts: str) -> str:
    """What the kinematics asks: only what is not trivially zero (at rest, no velocity; at
    rest without acceleration, positions alone)."""
    d = spec.driver
    if d.holds:
        return f"the positions of the joints and of the centres of mass at {shorts};"
    if d.at_rest:
        return (f"the positions and accelerations of the joints and of the centres of mass, "
                f"and the angular accelerations of the links, at {shorts} (every velocity is "
                "zero at this instant);")
    return (f"the positions, velocities and accelerations of the joints and of the centres "
            f"of mass, and the angular velocities and accelerations of the links, at {shorts};")


def _has_inertia(spec) -> bool:
    """Whether some link has an inertia force or couple: the driver moves or accelerates,
    and some link has a mass or a moment of inertia."""
    d = spec.driver
    if d.holds:
        return False
    return any(l.mass > 0 or l.inertia > 0 for l in spec.links)


def _strength_datum(link) -> str:
    """A link's section, material and members as the problem states them (SI)."""
    st = link.strength
    sizes = ", ".join(f"{k} = {sci(v)}" for k, v in st.section.sizes)
    m = st.material
    return (f"section {st.section.kind} ({sizes}, SI), E = {eng(m.E, 'Pa')}, yield "
            f"{eng(m.yield_, 'Pa')}, ultimate {eng(m.ultimate, 'Pa')}, endurance "
            f"{eng(m.endurance, 'Pa')}; members " + ", ".join(f"{p}{q}" for p, q in st.members))


def _friction_datum(spec, fr, joint) -> str:
    """A joint's friction as the problem states it (SI): ``Coulomb friction mu = 0.05,
    journal radius 0.04 m``, of a pin's joint with one of its links naming the link."""
    size = (f", journal radius {fmt(fr.radius)} m" if joint.type == "R" else
            f", slider length {fmt(fr.length)} m" if fr.length is not None else "")
    pin = spec.pin(joint.point) if joint.type == "R" else None
    on = f" (in link {joint.links[1]}'s bearing)" if pin is not None else ""
    sense = ""
    if spec.driver.at_rest and fr.sense:
        a, b = joint.links
        sense = (f", {b} about to turn {'counterclockwise' if fr.sense > 0 else 'clockwise'} "
                 f"relative to {a}" if joint.type == "R" else
                 f", {b} about to slide {'along' if fr.sense > 0 else 'against'} its line's "
                 "direction")
    circle = " (friction circle: r sin(arctan μ) |F|)" if fr.model == "circle" else ""
    return f"Coulomb friction{on} μ = {fmt(fr.mu)}{size}{circle}{sense}"


def _join_and(items: list[str]) -> str:
    if len(items) <= 1:
        return "".join(items)
    return ", ".join(items[:-1]) + " and " + items[-1]


def sheet_spec(spec, options: SheetOptions):
    """The spec a sheet at ``options.angles`` must be analysed from: ``spec`` itself when
    every angle is analysed (the sweep's or a reference angle), else ``spec`` with those
    angles added to its reference angles (the branch is still followed from the first
    one). Whoever builds the sheet analyses it (the sheet never runs an analysis)."""
    if options.angles is None:
        return spec
    from dataclasses import replace
    have = spec.analysed_angles()
    missing = tuple(float(a) for a in options.angles
                    if not np.any(np.abs(have - float(a)) < 1e-9))
    return replace(spec, at=tuple(spec.at) + missing) if missing else spec


def sheet_analysis(analysis, options: SheetOptions):
    """``analysis`` if a sheet at ``options.angles`` (default: the spec's reference angles)
    can be written from it; else an ``AnalysisError`` naming the angles left out and why
    (analyse :func:`sheet_spec` for angles the sweep does not have)."""
    if options.angles is None:
        return _solvable(analysis, list(analysis.spec.at), "the spec's reference angles")
    return _solvable(analysis, list(options.angles), "--sheet-angles", every=True)


def _solvable(analysis, angles: list, what: str, every: bool = False):
    """``analysis`` if a sheet can be written at ``angles`` (each of them, with ``every``;
    else at least one); otherwise an error naming the angles left out and why."""
    from ...errors import AnalysisError
    spec = analysis.spec
    out = [a for a in angles if analysis.kinematics.index_of(a) is None]
    if out and (every or len(out) == len(angles)):
        why = "; ".join(
            f"{coordinate(spec, a)[1]}: " + ("; ".join(
                f.reason for f in analysis.flags if abs(f.angle - a) < 1e-9)
                or "left out of the analysis") for a in out)
        raise AnalysisError(f"{spec.file}: no solution sheet at {what}: {why}. Choose "
                            "angles away from singular or unreachable positions")
    return analysis
