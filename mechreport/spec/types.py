"""The loaded spec: frozen dataclasses, all quantities SI (m, kg, s, rad for internal angles).

Angles that users wrote in degrees stay in degrees where they are *crank angles* (sweep, at,
expect, profiles); directions are stored as unit vectors.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..quantities import joint_unit, unit_of
from ..quantities import split as split_quantity
from ..units import rad_s_to_rpm

Vec = tuple[float, float]
GROUND = "ground"


@dataclass(frozen=True)
class Shape:
    """``bar``: plate from x=0 to x=length along the link x-axis, centred on y=0.
    ``block``: rectangle of ``length`` (the spec's width) x height centred on the link origin.
    All sizes in m."""

    kind: str
    length: float
    height: float
    depth: float

    @property
    def volume(self) -> float:
        """[m^3]"""
        return self.length * self.height * self.depth

    @property
    def centroid(self) -> Vec:
        """Centroid in the link frame [m]."""
        return (self.length / 2, 0.0) if self.kind == "bar" else (0.0, 0.0)

    def inertia(self, mass: float) -> float:
        """Polar moment of inertia about the centroid [kg m^2]."""
        return mass * (self.length**2 + self.height**2) / 12.0


@dataclass(frozen=True)
class Section:
    """A member's cross-section, SI: ``area`` A [m^2], ``inertia`` I [m^4] about the axis
    normal to the plane of motion (in-plane bending), ``c`` [m] the distance from the neutral
    axis to the outer fibre in the plane, ``inertia_min`` [m^4] the smallest second moment of
    the section (about either axis: what a pinned column buckles about); ``kind`` rect |
    round | tube | area (given as {area, inertia, c}); ``sizes`` as written, SI."""

    kind: str
    area: float
    inertia: float
    c: float
    inertia_min: float
    sizes: tuple[tuple[str, float], ...] = ()

    @property
    def inertia_out(self) -> float:
        """[m^4] The second moment about the axis in the plane of motion (out-of-plane
        bending and buckling): a rect's height width^3 / 12; a round bar's or tube's I; a
        section given by its properties, its ``inertia_out`` (default: ``inertia``)."""
        sizes = dict(self.sizes)
        if self.kind == "rect" and "width" in sizes:
            return sizes["height"] * sizes["width"] ** 3 / 12
        # (a section made without its sizes: the weaker axis, if it is not the plane's)
        return sizes.get("inertia_out", min(self.inertia_min, self.inertia))


@dataclass(frozen=True)
class Buckling:
    """How a member buckles (format 1.2 ``buckling:``): effective-length factors ``k`` in the
    plane of motion and ``k_out`` out of it; ``formula`` euler-johnson | rankine, with
    Rankine's ``crushing`` stress [Pa] and constant ``a`` (P = crushing A / (1 + a (kL /
    r)^2))."""

    k: float = 1.0
    k_out: float = 1.0
    formula: str = "euler-johnson"
    crushing: float | None = None
    a: float | None = None


@dataclass(frozen=True)
class Material:
    """A material, SI: Young's modulus ``E``, ``yield_`` and ``ultimate`` strengths and the
    (fully corrected) ``endurance`` limit [Pa]; ``name`` as in ``materials:`` ("" inline)."""

    name: str
    E: float
    yield_: float
    endurance: float
    ultimate: float


@dataclass(frozen=True)
class Strength:
    """A link's strength data: its ``section`` and ``material`` and its ``members``, the
    straight beams it is made of, each (P, Q) two of its point names."""

    section: Section
    material: Material
    members: tuple[tuple[str, str], ...]
    members_given: bool = False      # written as `members:` (else the segment between joints)
    buckling: tuple[Buckling, ...] = ()     # one per member ((): pinned-pinned Euler-Johnson)

    def buckling_of(self, i: int) -> Buckling:
        """How member ``i`` buckles (the default: pinned-pinned, Euler-Johnson)."""
        return self.buckling[i] if self.buckling else Buckling()


@dataclass(frozen=True)
class Link:
    """A moving link. ``number`` is 1, 2, ... in the order written (ground is 0). ``strength``
    its section, material and members (None without a ``section``)."""

    name: str
    number: int
    points: dict[str, Vec]
    mass: float          # [kg]
    com: Vec             # centre of mass in the link frame [m]
    inertia: float       # about the centre of mass [kg m^2]
    shape: Shape | None = None
    strength: Strength | None = None


@dataclass(frozen=True)
class Line:
    """A sliding line in the guide's frame: ``through`` [m] and unit ``direction``."""

    through: Vec
    direction: Vec
    through_name: str | None = None


@dataclass(frozen=True)
class Joint:
    """``R``: pin at the point named like the joint on both links.
    ``T``: ``links[0]`` is the guide, ``links[1]`` the slider; ``point`` is the slider's point on
    ``line``. The reaction is the force (and, for T, couple) that links[0] exerts on links[1]."""

    name: str
    type: str
    links: tuple[str, str]
    point: str
    line: Line | None = None

    @property
    def written(self) -> str:
        """The joint's name as the spec writes it (a pin joining several links is solved as
        two-link joints named ``E.on.<link>``; each is written ``E``)."""
        return self.point if self.type == "R" else self.name

    @property
    def guide(self) -> str:
        return self.links[0]

    @property
    def slider(self) -> str:
        return self.links[1]


@dataclass(frozen=True)
class Pin:
    """A pin joining three or more links (``links``, in the order written; one may be ground),
    at the point named ``name`` on each. It is solved as the pin of one link, the ``hub`` (the
    first link written), with a two-link R joint from the hub to each other link, named
    ``{name}.on.{link}``: that joint's reaction is the force the pin exerts on that link. The
    force on the hub is minus their sum. As a driver, it turns its second link written
    against its first (the joint ``{name}.on.{second}``)."""

    name: str
    links: tuple[str, ...]
    hub: str

    def joint_name(self, link: str) -> str:
        """The name of the two-link joint that carries the pin's force on ``link``."""
        return f"{self.name}.on.{link}"

    @property
    def others(self) -> tuple[str, ...]:
        """The links the pin joins to its hub."""
        return tuple(x for x in self.links if x != self.hub)


@dataclass(frozen=True)
class Friction:
    """Coulomb friction in the two-link joint ``joint`` (format 1.1 ``friction:``): ``mu``;
    an R joint's journal ``radius`` [m]; a T joint's slider ``length`` [m] (None: the normal
    force alone presses); ``sense`` +1 or -1, which way the joint is about to move in a static
    analysis (None: no friction at rest). See :mod:`mechreport.forces.friction`."""

    joint: str
    mu: float
    radius: float | None = None
    length: float | None = None
    sense: int | None = None
    # format 1.2: an R joint's law, ``couple`` (mu r |F|) or ``circle`` (the friction
    # circle, r sin(atan mu) |F|); out of the repr (the specs before 1.2 keep their reprs)
    model: str = field(default="couple", repr=False)

    @property
    def journal_mu(self) -> float:
        """The factor of r |F| in an R joint's friction couple: mu, or sin(atan mu) =
        mu / sqrt(1 + mu^2) for the friction circle."""
        return self.mu / math.sqrt(1.0 + self.mu * self.mu) if self.model == "circle" \
            else self.mu


@dataclass(frozen=True)
class Driver:
    """The driven joint ``joint`` between ``links`` (first, second).

    R (``kind``): the driven coordinate is the relative angle of the second link to the first;
    for a joint with ground, the moving link's x-axis angle (the crank angle), whichever link
    is written first. ``omega`` [rad/s], ``alpha`` [rad/s^2]. T: the stroke of the slider's
    point along the guide's line from its ``through`` point; ``omega`` holds the ``speed``
    [m/s] and ``alpha`` the ``accel`` [m/s^2]. ``link`` is the driven link (the moving one for
    a joint with ground, else the second). Sweep values are in degrees (R) or the spec's length
    unit (T); ``unit`` is SI per sweep unit (rad per degree, or m per length unit)."""

    joint: str
    link: str
    omega: float
    alpha: float = 0.0
    rpm_given: float | None = None
    kind: str = "R"
    links: tuple[str, str] = (GROUND, "")
    unit: float = math.pi / 180.0

    @property
    def rpm(self) -> float:
        """An R driver's speed in rpm: as the spec wrote it (``rpm_given``), or ``omega``
        converted; what every output prints beside omega."""
        return self.rpm_given if self.rpm_given is not None else rad_s_to_rpm(self.omega)

    @property
    def at_rest(self) -> bool:
        """The driven coordinate does not move (``rpm``, ``omega`` or ``speed`` 0): a static
        analysis (``alpha`` 0) or the instant of starting from rest."""
        return self.omega == 0.0

    @property
    def holds(self) -> bool:
        """At rest without acceleration: a static problem (no inertia forces; the driver's
        effort holds the mechanism)."""
        return self.at_rest and self.alpha == 0

    @property
    def crank(self) -> bool:
        """An R joint with ground: the classic crank, whose angle is the sweep's."""
        return self.kind == "R" and GROUND in self.links

    @property
    def quantity(self) -> str:
        """The name of the driver's effort: ``driver.torque`` (R, N m) or ``driver.force``
        (T, N: the force the first link exerts on the second along the line)."""
        return "driver.torque" if self.kind == "R" else "driver.force"

    @property
    def coordinate(self) -> str:
        """What the sweep axis is: ``crank angle``, ``relative angle`` or ``stroke``."""
        return "crank angle" if self.crank else ("relative angle" if self.kind == "R"
                                                 else "stroke")


@dataclass(frozen=True)
class Sweep:
    """Crank angles start, start+step, ... up to stop [deg]; a whole turn leaves stop out.
    (A spec without ``sweep:`` has the defaults of the format's model, spec/schema.py.)"""

    start: float
    stop: float
    step: float
    wraps: bool = True     # an angle (False for a T driver's stroke: a plain range)
    # the spec's ``cycle`` [deg], the period of its loads (out of the repr: see Spec.cycle)
    cycle: float = field(default=360.0, repr=False)

    @property
    def whole_turn(self) -> bool:
        """One whole turn: stop - start is 360 degrees (stop itself then repeats start)."""
        span = self.stop - self.start
        return self.wraps and abs(span - 360.0) < 1e-9

    @property
    def whole_cycle(self) -> bool:
        """One whole cycle: stop - start is ``cycle`` degrees (one turn unless the spec's
        ``cycle`` is longer); stop itself then repeats start."""
        span = self.stop - self.start
        return self.wraps and abs(span - self.cycle) < 1e-9

    def cycle_problem(self) -> str | None:
        """Why this sweep of a crank has no cycle quantities (None when it is one whole
        cycle, a turn unless ``cycle`` is longer, in steps that divide it evenly)."""
        whole = "whole turn of the crank" if self.cycle == 360.0 else \
            f"whole cycle of {self.cycle:g} crank degrees"
        if not self.whole_cycle:
            return (f"cycle quantities need a sweep over one {whole}; this one "
                    f"runs from {self.start:g} to {self.stop:g} deg")
        per_cycle = self.cycle / self.step
        if abs(per_cycle - round(per_cycle)) > 1e-6:
            what = "turn" if self.cycle == 360.0 else "cycle"
            return (f"cycle quantities need a sweep step that divides the {what} evenly; "
                    f"{self.step:g} deg gives {per_cycle:.4g} steps per {what}")
        return None

    def angles(self) -> np.ndarray:
        span = self.stop - self.start
        n = int(math.floor(span / self.step + 1e-9))
        values = self.start + self.step * np.arange(n + 1)
        turns = round(span / 360.0)
        whole_turns = self.wraps and turns >= 1 and abs(span - 360.0 * turns) < 1e-9
        if whole_turns and abs(values[-1] - self.stop) < 1e-9:
            values = values[:-1]
        return values


@dataclass(frozen=True)
class Pressure:
    """A ``type: pressure`` load as written (format 1.2): the piston's ``area`` [m^2] (from
    ``bore`` when ``bore`` [m] is given), the pressure ``unit`` (Pa, kPa, bar, MPa, psi) and
    its size ``scale`` [Pa per unit], ``ambient`` and the ``profile`` of (crank angle [deg],
    pressure) pairs, both in ``unit``. The load's force profile is (p - ambient) scale area."""

    area: float
    unit: str
    scale: float
    ambient: float
    profile: tuple[tuple[float, float], ...]
    bore: float | None = None

    def pressure_pa(self, p):
        """Gauge pressure over ambient, p - ambient, in Pa (``p`` in ``unit``)."""
        return (p - self.ambient) * self.scale


@dataclass(frozen=True)
class Load:
    """An applied force (at ``point`` of ``link``, global N) or moment (N m, CCW positive).

    Either a constant ``value`` or ``direction`` (unit, forces) with a ``profile`` of
    (crank angle [deg], magnitude) pairs, interpolated periodically. ``oppose`` is ``velocity``
    (forces) or ``rotation`` (moments). ``reacts_on`` ``ground``: the load's reaction acts on
    the frame (left out of the shaking force). ``spring`` and ``damper`` act ``between`` two
    (link, point) ends (either may be ground); a ``torsion_spring`` at an R ``joint``; their
    ``link`` is the first moving link they act on."""

    kind: str
    link: str
    index: int
    point: str | None = None
    value: Vec | float | None = None
    direction: Vec | None = None
    profile: tuple[tuple[float, float], ...] | None = None
    oppose: str | None = None
    name: str | None = None
    reacts_on: str | None = None    # "ground": its reaction acts on the frame
    between: tuple[tuple[str, str], tuple[str, str]] | None = None  # spring, damper ends
    stiffness: float | None = None  # spring [N/m], torsion spring [N m/rad]
    free_length: float | None = None  # spring [m]
    damping: float | None = None    # damper [N s/m]
    joint: str | None = None        # torsion spring: its R joint
    free_angle: float | None = None  # torsion spring [deg]
    # format 1.2 (out of the repr, so that the loads written before keep their reference
    # reprs): the profile's phase [deg], value at phi = profile(phi - shift), and a
    # pressure load's data (its ``profile`` then holds the force (p - ambient) A [N])
    shift: float = field(default=0.0, repr=False)
    pressure: "Pressure | None" = field(default=None, repr=False)

    @property
    def label(self) -> str:
        """The load's ``name``, or ``load i`` (1-based, in list order)."""
        return self.name or f"load {self.index + 1}"


@dataclass(frozen=True)
class Expectation:
    """``quantity`` at crank ``angle`` [deg] must equal ``value`` within ``tol`` (absolute,
    both SI); ``angle`` is None for a cycle quantity (one value per turn). ``unit``: the unit
    the spec wrote them in (None: SI), ``scale`` its size in SI (value written x scale =
    ``value``), for messages that print them as written."""

    angle: float | None
    quantity: str
    value: float
    tol: float
    line: int | None = None
    unit: str | None = None
    scale: float = 1.0


@dataclass(frozen=True)
class BearingSpec:
    """A bearing at a joint: dynamic load ``rating`` C [N]; required ``life_h`` [h] or None."""

    rating: float
    life_h: float | None = None


@dataclass(frozen=True)
class Design:
    """The design review's inputs: ``speed_fluctuation`` Cs (for the flywheel inertia),
    ``motor`` limits (``rated_torque``, ``peak_torque`` [N m], ``rated_power`` [W]),
    ``bearings`` by joint, and ``limits`` (``joint_force`` [N], ``transmission_angle`` [deg],
    ``shaking_force`` [N]). Every given item except Cs is a verdict."""

    speed_fluctuation: float | None = None
    motor: dict[str, float] = field(default_factory=dict)
    bearings: dict[str, BearingSpec] = field(default_factory=dict)
    limits: dict[str, float] = field(default_factory=dict)

    @property
    def empty(self) -> bool:
        return not (self.speed_fluctuation or self.motor or self.bearings or self.limits)


@dataclass(frozen=True)
class MotorCurve:
    """The motor of ``dynamics:``: its torque [N m] against its speed, one of a ``constant``
    torque, a ``curve`` of (speed [rpm], torque [N m]) points (speeds increasing; linear
    between them and along the end segments beyond them), or a ``linear`` characteristic
    from ``stall_torque`` [N m] at rest to 0 at ``no_load_rpm`` (and on, braking beyond)."""

    constant: float | None = None
    curve: tuple[tuple[float, float], ...] = ()
    stall_torque: float | None = None
    no_load_rpm: float | None = None
    # format 1.2: the gearing to the crank (motor speed = ratio x crank speed) and its
    # efficiency; out of the repr, so that the specs written before 1.2 keep their reprs
    ratio: float = field(default=1.0, repr=False)
    efficiency: float = field(default=1.0, repr=False)

    @property
    def kind(self) -> str:
        return ("torque" if self.constant is not None else "curve" if self.curve
                else "linear")

    def points(self) -> tuple[tuple[float, float], ...]:
        """The characteristic as (rpm, N m) points: two for a constant or linear motor."""
        if self.constant is not None:
            return ((0.0, self.constant), (1.0, self.constant))
        if self.curve:
            return self.curve
        return ((0.0, self.stall_torque), (self.no_load_rpm, 0.0))


@dataclass(frozen=True)
class Dynamics:
    """``dynamics:`` (format 1.1): the ``motor`` (None with ``mean_rpm``), the ``flywheel``'s
    extra inertia on the crank shaft [kg m^2], the initial state (``start_angle`` [deg], ``start_rpm``), ``until``
    (None: until the steady state; else a time [s]) and ``output_step`` [s] of the time
    histories (None: 200 samples per steady cycle)."""

    motor: MotorCurve | None
    flywheel: float = 0.0
    start_angle: float = 0.0
    start_rpm: float = 0.0
    until: float | None = None
    output_step: float | None = None
    # format 1.2 (out of the repr: the specs written before 1.2 keep their reprs): the
    # steady state's time-mean speed [rpm] instead of a motor (None: the motor's motion),
    # and a geared flywheel as written, (its own inertia [kg m^2], its speed ratio to the
    # crank), whose ratio^2 x inertia is ``flywheel`` (None: a flywheel on the crank)
    mean_rpm: float | None = field(default=None, repr=False)
    flywheel_geared: tuple[float, float] | None = field(default=None, repr=False)


@dataclass(frozen=True)
class Vary:
    """One varied leaf of a study: ``key`` as written (``links.rod.points.C.0``), ``path`` the
    same as keys and list indices (``("links", "rod", "points", "C", 0)``). Either ``values``
    (as written, in the spec's own units) or a range ``start`` (``from``) .. ``stop`` (``to``)
    with ``count`` grid points (``count`` is used by grid sampling only)."""

    key: str
    path: tuple
    values: tuple[float, ...] | None = None
    start: float | None = None
    stop: float | None = None
    count: int | None = None
    line: int | None = None


@dataclass(frozen=True)
class Study:
    """The ``study`` section: the varied leaves, how variants are drawn (``sample`` grid,
    random or lhs; ``count`` variants for random and lhs, ``seed``) and the cycle quantities
    tabulated (``keep``). Only ``mechreport study`` uses it."""

    vary: tuple[Vary, ...]
    keep: tuple[str, ...]
    sample: str = "grid"
    count: int | None = None
    seed: int = 0
    line: int | None = None

    @property
    def size(self) -> int:
        """How many variants the study has: every combination for grid, else ``count``."""
        if self.sample != "grid":
            return int(self.count or 0)
        n = 1
        for v in self.vary:
            n *= len(v.values) if v.values is not None else int(v.count or 0)
        return n


@dataclass(frozen=True)
class TolVary:
    """One uncertain leaf (``tolerances.vary``): ``key`` as written, ``path`` its keys and
    list indices, ``nominal`` the spec's value there (the spec's own units). ``dist``
    ``uniform`` over [``low``, ``high``] or ``normal`` with mean ``mean`` and standard
    deviation ``sigma`` (a ``tol`` or range given as normal: ``low``..``high`` is plus or minus
    3 sigma); ``given`` says how it was written (``tol``, ``sigma`` or ``range``)."""

    key: str
    path: tuple
    nominal: float
    dist: str
    low: float
    high: float
    mean: float
    sigma: float
    given: str
    line: int | None = None

    @property
    def std(self) -> float:
        """The distribution's standard deviation [the key's unit]."""
        if self.dist == "normal":
            return self.sigma
        return (self.high - self.low) / (2.0 * 3.0 ** 0.5)


@dataclass(frozen=True)
class Tolerances:
    """The ``tolerances`` section: the uncertain leaves, how many samples are drawn
    (``count``, by ``sample`` lhs or random, ``seed``) and the cycle quantities reported
    (``keep``). Only ``mechreport tolerance`` uses it."""

    vary: tuple[TolVary, ...]
    keep: tuple[str, ...]
    count: int = 1000
    sample: str = "lhs"
    seed: int = 0
    line: int | None = None


@dataclass(frozen=True)
class SheetVary:
    """One varied datum of a problem's variants: ``key`` as written, ``path`` its keys and
    list indices; ``values`` (as written, spec units) or the range ``start`` .. ``stop``
    (both included) by ``step`` (None: any value of the range)."""

    key: str
    path: tuple
    values: tuple[float, ...] | None = None
    start: float | None = None
    stop: float | None = None
    step: float | None = None
    line: int | None = None


@dataclass(frozen=True)
class SheetVariants:
    """``sheet.variants``: ``count`` variants drawn from ``seed``, their varied data printed
    to ``digits`` significant digits, each meeting ``require`` (name -> bound) at the sheet's
    angles."""

    vary: tuple[SheetVary, ...]
    count: int = 30
    seed: int = 0
    digits: int = 3
    require: tuple[tuple[str, float], ...] = ()
    line: int | None = None


@dataclass(frozen=True)
class Bound:
    """A ``subject_to`` bound of an optimisation: ``quantity`` (a cycle quantity) kept at
    least ``low`` and at most ``high`` [SI; None: no such bound]; ``unit`` the unit they were
    written in (None: SI)."""

    quantity: str
    low: float | None = None
    high: float | None = None
    unit: str | None = None
    line: int | None = None


@dataclass(frozen=True)
class Optimize:
    """The ``optimize`` section (format 1.2): the varied leaves (each a :class:`Vary` with a
    range ``start`` .. ``stop`` in the spec's own units), the ``objective`` cycle quantity
    (made largest when ``maximize``, else smallest), the ``bounds`` besides every design
    verdict, the ``budget`` of evaluations and the ``seed``. Only ``mechreport optimize``
    uses it."""

    vary: tuple[Vary, ...]
    objective: str
    maximize: bool = False
    bounds: tuple[Bound, ...] = ()
    budget: int = 1000
    seed: int = 0
    line: int | None = None


@dataclass(frozen=True)
class SheetSettings:
    """The ``sheet`` mapping beyond on/off: the problem's own ``statement`` (Markdown, None:
    written from the data) and its ``variants`` (None: one problem)."""

    statement: str | None = None
    variants: SheetVariants | None = None


@dataclass(frozen=True)
class ReportSettings:
    """The spec's ``report`` section: display ``units`` (``length`` m|cm|mm|in, ``force``
    N|kN|lbf, ``moment`` N*m|N*mm|kN*m|lbf*in, ``mass`` kg|g|lb; lengths default to the spec's
    ``units.length``, the rest to SI) and the first page's metadata ("" when not given);
    ``animation``: write animation.gif (the loader sets it: default true for a whole-turn
    sweep); ``dxf``: write mechanism.dxf."""

    units: dict[str, str] = field(default_factory=dict)
    title: str = ""
    project: str = ""
    author: str = ""
    revision: str = ""
    animation: bool = False
    dxf: bool = False
    #: report.html (default true); out of the repr, which the loaded-spec reference holds
    html: bool = field(default=True, repr=False)


@dataclass(frozen=True)
class Spec:
    """A validated mechanism spec, SI throughout."""

    file: str
    name: str
    description: str
    gravity: Vec
    ground: dict[str, Vec]
    links: tuple[Link, ...]
    joints: tuple[Joint, ...]
    driver: Driver
    sweep: Sweep
    at: tuple[float, ...]
    assembly: dict[str, Vec]
    loads: tuple[Load, ...] = ()
    expect: tuple[Expectation, ...] = ()
    sheet: bool = False
    units: dict[str, str] = field(default_factory=lambda: {"length": "m", "mass": "kg"})
    design: Design = field(default_factory=Design)
    report: "ReportSettings" = field(default_factory=lambda: ReportSettings())
    study: Study | None = None        # only `mechreport study` uses it
    pins: tuple[Pin, ...] = ()        # pins joining three or more links (solved as joints)
    friction: tuple[Friction, ...] = ()   # by solved joint, in spec order
    dynamics: Dynamics | None = None      # machine dynamics (format 1.1 ``dynamics:``)
    # only `mechreport tolerance` uses it (not in the repr: the shipped specs' reference
    # reprs stay as they were)
    tolerances: Tolerances | None = field(default=None, repr=False)
    # only `mechreport optimize` uses it (format 1.2); out of the repr, which stays the
    # loaded specs' reference (tests/spec/data/loaded_reprs.json)
    optimize: Optimize | None = field(default=None, repr=False)
    # the ``sheet`` mapping's statement and variants (format 1.2); left out of the repr so
    # that a spec without them reads as before
    sheet_settings: SheetSettings = field(default_factory=SheetSettings, repr=False)

    @property
    def axis_unit(self) -> str:
        """The sweep coordinate's unit as written: ``deg``, or the length unit of a stroke."""
        return "deg" if self.driver.kind == "R" else self.units["length"]

    @property
    def axis_column(self) -> str:
        """The sweep coordinate's column name in results.csv and ``to_dataframe()``:
        ``crank_angle [deg]``, ``relative_angle [deg]`` (an R driver between two moving
        links) or ``stroke [mm]`` (a T driver's, in the spec's length unit)."""
        return f"{self.driver.coordinate.replace(' ', '_')} [{self.axis_unit}]"

    @property
    def idle_friction(self) -> tuple[str, ...]:
        """The joints (as written) whose friction entry acts nowhere: at rest (the driver's
        speed 0) no joint moves, and friction acts only where ``friction_sense`` says which
        way the joint is about to move."""
        if not self.driver.at_rest:
            return ()
        return tuple(self.joint(f.joint).written for f in self.friction if f.sense is None)

    def idle_friction_note(self) -> str:
        """The sentence on :attr:`idle_friction` ("" when every entry acts)."""
        idle = self.idle_friction
        if not idle:
            return ""
        names = ", ".join(idle[:-1]) + " and " + idle[-1] if len(idle) > 1 else idle[0]
        return (f"the friction in joint{'s' if len(idle) > 1 else ''} {names} adds nothing: at "
                "rest no joint moves, and friction acts only where friction_sense (1 or -1) "
                "says which way the joint is about to move")

    @property
    def size(self) -> float:
        """The mechanism's characteristic length [m]: the largest distance between two points
        of one body (the ground's points, or one link's points, centre of mass and shape
        included). It turns forces into moments of the same order (the agreement check)."""
        def spread(points) -> float:
            pts = list(points)
            return max((math.dist(a, b) for a in pts for b in pts), default=0.0)
        bodies = [self.ground.values()]
        for link in self.links:
            extra = [link.com]
            if link.shape is not None:     # the ends of a bar, two corners of a block
                a, h = link.shape.length, link.shape.height
                extra += [(0.0, 0.0), (a, 0.0)] if link.shape.kind == "bar" else \
                    [(-a / 2, -h / 2), (a / 2, h / 2)]
            bodies.append([*link.points.values(), *extra])
        return max(spread(b) for b in bodies)

    @property
    def cycle(self) -> float:
        """The loads' period [crank degrees] (format 1.2 ``cycle:``, 360 by default): the
        sweep's."""
        return self.sweep.cycle

    def cycle_problem(self) -> str | None:
        """Why cycle quantities are undefined for this spec (None when the sweep is one whole
        turn of a crank: an R driver with ground)."""
        joint = self.joint(self.driver.joint)
        if joint.type != "R" or GROUND not in joint.links:
            return "cycle quantities need an R driver with ground (a crank)"
        return self.sweep.cycle_problem()

    def link(self, name: str) -> Link:
        for link in self.links:
            if link.name == name:
                return link
        raise KeyError(name)

    def number(self, name: str) -> int:
        """Link number: 0 for ground, 1.. in spec order."""
        return 0 if name == GROUND else self.link(name).number

    def symbol(self, src: str, dst: str, prefix: str = "F") -> str:
        """Textbook name of what link ``src`` exerts on ``dst``: F12, or M03 for a couple."""
        return f"{prefix}{self.number(src)}{self.number(dst)}"

    def joint(self, name: str) -> Joint:
        for joint in self.joints:
            if joint.name == name:
                return joint
        raise KeyError(name)

    def pin(self, name: str) -> Pin | None:
        """The pin joining three or more links named ``name`` (None if there is none)."""
        return next((p for p in self.pins if p.name == name), None)

    def reaction_terms(self, name: str) -> tuple[tuple[str, float], ...] | None:
        """The force named ``name`` as a signed sum of joint reactions, ((joint, sign), ...):
        a joint's own (``B``: what its first link exerts on its second), or what a pin exerts
        on one link, ``J.on.<link>`` (a two-link joint's second link: +J, its first: -J; a
        pin joining several links: its joint to that link, or for its hub minus the sum of
        them all). None if ``name`` names no force."""
        if any(j.name == name for j in self.joints):
            return ((name, 1.0),)
        joint, sep, link = name.partition(".on.")
        if not sep:
            return None
        pin = self.pin(joint)
        if pin is not None:
            if link == pin.hub:
                return tuple((pin.joint_name(x), -1.0) for x in pin.others)
            return ((pin.joint_name(link), 1.0),) if link in pin.others else None
        two = next((j for j in self.joints if j.name == joint), None)
        if two is None or link not in two.links:
            return None
        return ((joint, 1.0 if link == two.links[1] else -1.0),)

    def unit_of(self, quantity: str) -> str | None:
        """The SI unit of ``quantity`` in this mechanism (a joint's friction is a couple in
        an R joint, a force in a T joint); see :func:`mechreport.quantities.unit_of`."""
        parts = split_quantity(quantity)
        if parts is not None and parts[0] == "joint" and parts[2] == "friction":
            joint = next((j for j in self.joints if j.name == parts[1]), None)
            return joint_unit("friction", joint.type if joint is not None else "R")
        return unit_of(quantity)

    def reported_reactions(self) -> tuple[str, ...]:
        """The reaction names every output lists, in the order written: each two-link joint's,
        and each pin joining several links' force on every link it joins (``E.on.<link>``)."""
        out: list[str] = []
        for j in self.joints:
            pin = self.pin(j.name.partition(".on.")[0]) if ".on." in j.name else None
            if pin is None:
                out.append(j.name)
            elif j.name == pin.joint_name(pin.others[0]):
                out += [pin.joint_name(x) for x in pin.links]
        return tuple(out)

    def points_of(self, link: str) -> dict:
        """The named points of ``link`` (the ground's, for the ground) in its frame [m]."""
        return self.ground if link == GROUND else self.link(link).points

    def point_owner(self, point: str) -> str | None:
        """The first link, in ``links`` order, that has ``point`` (None if no link has it)."""
        for link in self.links:
            if point in link.points:
                return link.name
        return None

    def named_points(self) -> list[tuple[str, str]]:
        """(point, link) for every point name, with the first link in spec order that has it."""
        out: dict[str, str] = {}
        for link in self.links:
            for name in link.points:
                out.setdefault(name, link.name)
        return list(out.items())

    def _extra_angles(self) -> list[float]:
        """The reference angles and the expectations' angles [deg], as written."""
        return list(self.at) + [e.angle for e in self.expect if e.angle is not None]

    def off_sweep_angles(self) -> np.ndarray:
        """The reference and expectation angles that are not angles of the sweep [deg],
        sorted, unique, rounded as :meth:`analysed_angles` rounds them."""
        extra = np.unique(np.round(np.asarray(self._extra_angles(), float), 9))
        return extra[~np.isin(extra, np.round(self.sweep.angles(), 9))]

    def analysed_angles(self) -> np.ndarray:
        """Sweep angles plus the reference and expectation angles, sorted, unique [deg]."""
        angles = np.concatenate([self.sweep.angles(), np.asarray(self._extra_angles(), float)])
        angles = np.unique(np.round(angles, 9))
        return angles
