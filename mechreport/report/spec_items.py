"""The spec described once, for the report and the sheets: the driver (its joint as written,
its link, how it moves, its effort and the driven coordinate), the loads (each with the link
and point it acts on), the links' and joints' names as both print them. The values are the
spec's own (SI); the report's first page (:mod:`mechreport.report.spec_text`) and the sheets
(:mod:`mechreport.report.sheet.model`, :mod:`mechreport.report.sheet.statement`) phrase these
items, each in its own voice and units, and never read the driver or a load otherwise."""
from __future__ import annotations

from dataclasses import dataclass

#: how a joint's type is named in every table
JOINT_KINDS = {"R": "pin (R)", "T": "slider (T)"}


def link_label(spec, name: str) -> str:
    """``link 2 (crank)``: a link by its number and name."""
    return numbered_link(spec.number(name), name)


def numbered_link(number: int, name: str) -> str:
    """``link 2 (crank)`` for link ``name`` numbered ``number``."""
    return f"link {number} ({name})"


@dataclass(frozen=True)
class DriverItem:
    """The driver: ``joint`` as written (a pin's name), the driven ``link`` and its
    ``number``; ``kind`` R (a rotation, ``omega`` [rad/s], ``alpha`` [rad/s²], ``rpm``;
    ``crank``: an R joint with the frame) or T (a stroke, ``omega`` [m/s], ``alpha``
    [m/s²]); ``at_rest`` (the driven coordinate does not move), ``holds`` (at rest without
    acceleration: a static analysis); the ``effort``'s kind (moment or force) and label, the
    driven ``coordinate`` (crank angle, relative angle, stroke) and the suffix of its values
    (``°``, or `` mm`` for a stroke in the spec's length unit ``length_unit``)."""

    joint: str
    link: str
    number: int
    kind: str
    crank: bool
    at_rest: bool
    holds: bool
    omega: float
    alpha: float
    rpm: float | None
    coordinate: str
    effort: str
    effort_label: str
    axis_suffix: str
    length_unit: str

    @property
    def label(self) -> str:
        """``link 2 (crank)``."""
        return numbered_link(self.number, self.link)

    @property
    def rate_unit(self) -> str:
        return "rad/s" if self.kind == "R" else "m/s"

    @property
    def accel_unit(self) -> str:
        return "rad/s²" if self.kind == "R" else "m/s²"


def driver_item(spec) -> DriverItem:
    """The driver of ``spec`` described (see :class:`DriverItem`)."""
    d = spec.driver
    kind = d.kind
    unit = spec.units.get("length", "m")
    if kind == "T":
        effort, label, coord, suffix = "force", "driver force F", "stroke", " " + unit
    else:
        effort, label = "moment", "driver torque M"
        coord, suffix = d.coordinate, "°"
    return DriverItem(spec.joint(d.joint).written, d.link, spec.number(d.link), kind,
                      kind == "R" and d.crank, d.at_rest, d.holds,
                      d.omega, d.alpha, d.rpm if kind == "R" else None, coord, effort, label,
                      suffix, unit)


def effort_of(spec) -> tuple[str, str, str, str]:
    """(kind, label, coordinate, unit suffix) of the driver: a crank's torque over the crank
    angle in degrees, or a T driver's force over its stroke in the spec's length unit."""
    d = driver_item(spec)
    return d.effort, d.effort_label, d.coordinate, d.axis_suffix


@dataclass(frozen=True)
class LoadItem:
    """A load: its ``label`` ("" unnamed), ``kind`` as the spec writes it, what it is in
    words (``what``: force, moment, pressure, spring, damper, torsion spring), the ``link``
    and ``point`` ("" for a moment or an element) it acts on, and the spec's load itself
    (``load``: its values, SI)."""

    label: str
    kind: str
    what: str
    link: str
    number: int
    point: str
    load: object

    @property
    def where(self) -> str:
        """``link 2 (crank) at B``."""
        return numbered_link(self.number, self.link) + (f" at {self.point}" if self.point else "")


def load_items(spec) -> list[LoadItem]:
    """Every load of ``spec`` described, in spec order (see :class:`LoadItem`)."""
    return [LoadItem(ld.label, ld.kind,
                     "pressure" if ld.pressure is not None else ld.kind.replace("_", " "),
                     ld.link, spec.number(ld.link), ld.point or "", ld)
            for ld in spec.loads]
