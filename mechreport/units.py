"""Display units and the one number formatter of every report, plot, sheet and terminal table.

Results are computed and stored in SI (results.csv and summary.json stay SI, with the unit in
every column name or field). What a person reads goes through :class:`Display`: values are
converted to the spec's ``report.units`` (docs/spec.md, section 16) and printed by
:func:`fmt` with ``SIG_DIGITS`` significant digits, never as ``-0``; a value whose magnitude is
below round-off of its quantity's scale (``ZERO_RTOL`` times the largest value of that kind in
the analysis) prints as ``0``.

Kinds of quantity (the ``kind`` argument): ``length``, ``velocity``, ``acceleration``,
``force``, ``moment``, ``mass``, ``mass_length`` (a counterweight's m r), ``inertia`` (kg·m²,
always SI, as written in a spec), ``energy`` (J), ``power`` (W), ``angle`` (deg), ``omega``
(rad/s), ``alpha`` (rad/s²), ``time`` (h: a bearing's life), ``duration`` (s), ``speed``
(rpm: a crank's speed in machine dynamics), ``ratio`` (no unit).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

#: significant digits of every number a person reads (reports, plots, index, terminal)
SIG_DIGITS = 4
#: solution sheets are worked equations checked by hand against the textbook: more digits,
#: so that their sums balance to the book's rounding (same formatter otherwise)
SHEET_DIGITS = 6
#: a value below this fraction of its quantity's scale is round-off: printed (and stored) as 0
ZERO_RTOL = 1e-9
DASH = "—"

# US customary units, exact by definition (the international yard and pound, 1959; the
# pound-force is the pound's weight at standard gravity 9.80665 m/s^2)
INCH = 0.0254                   #: [m]
FOOT = 12 * INCH                #: [m] (0.3048)
POUND = 0.45359237              #: [kg]
POUND_FORCE = 4.4482216152605   #: [N] (POUND x 9.80665)
PSI = POUND_FORCE / INCH ** 2   #: [Pa] (lbf / in^2)

#: display unit -> size in SI (m, N, N m, kg)
LENGTH_UNITS = {"m": 1.0, "cm": 0.01, "mm": 0.001, "in": INCH, "ft": FOOT}
FORCE_UNITS = {"N": 1.0, "kN": 1000.0, "lbf": POUND_FORCE, "kip": 1000 * POUND_FORCE}
MOMENT_UNITS = {"N*m": 1.0, "N*mm": 0.001, "kN*m": 1000.0, "lbf*in": POUND_FORCE * INCH,
                "lbf*ft": POUND_FORCE * FOOT}
MASS_UNITS = {"kg": 1.0, "g": 0.001, "lb": POUND}
#: a moment of inertia's units [kg m^2]
INERTIA_UNITS = {"kg*m^2": 1.0, "g*mm^2": 1e-9, "lb*in^2": POUND * INCH ** 2,
                 "lb*ft^2": POUND * FOOT ** 2}
#: a stress's units [Pa] (the reports' default: MPa)
STRESS_UNITS = {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9, "psi": PSI, "ksi": 1000 * PSI}
#: a pressure's units [Pa] (a pressure load's ``unit``, ``report.units.pressure``)
PRESSURE_UNITS = {"Pa": 1.0, "kPa": 1e3, "bar": 1e5, "MPa": 1e6, "psi": PSI}
#: rad/s in one rpm (pi / 30): ``rpm * RPM`` is in rad/s, ``omega / RPM`` in rpm
RPM = math.pi / 30.0
#: units an ``expect`` entry may be written in, by the SI unit of its quantity (those of
#: ``report.units`` for its kind, and the SI unit itself): name -> size in SI
EXPECT_UNITS = {
    "m": LENGTH_UNITS,
    "N": FORCE_UNITS,
    "N·m": {**MOMENT_UNITS, "N·m": 1.0},
    "m/s": {"m/s": 1.0, "mm/s": 0.001, "in/s": INCH, "ft/s": FOOT},
    "m/s^2": {"m/s^2": 1.0, "mm/s^2": 0.001, "in/s^2": INCH, "ft/s^2": FOOT},
    "deg": {"deg": 1.0, "rad": 57.29577951308232},
    "rad/s": {"rad/s": 1.0, "rpm": RPM},
    "Pa": STRESS_UNITS,
}


# The rpm conversion, in the two orders of operations the project uses. They agree to the
# last bit only most of the time (``x * 30 / pi`` and ``x / (pi / 30)`` differ in the last
# bit for about a third of all x): a call site whose result is stored (summary.json, CSV)
# keeps the order it always had, ``/ RPM`` and ``* RPM`` or one of these two.

def rpm_to_rad_s(rpm):
    """A speed in rpm (a number or an array) in rad/s, computed as ``rpm * pi / 30``."""
    return rpm * math.pi / 30.0


def rad_s_to_rpm(omega):
    """A speed in rad/s (a number or an array) in rpm, computed as ``omega * 30 / pi``."""
    return omega * 30.0 / math.pi


#: the units a spec's own numbers may be written in (its ``units:``); a report may show any
#: unit of the tables above (``report.units``)
SPEC_UNITS = {"length": ("m", "cm", "mm", "in", "ft"), "mass": ("kg", "g", "lb"),
              "force": ("N", "lbf", "kip"), "moment": ("N*m", "N*mm", "lbf*in", "lbf*ft"),
              "inertia": tuple(INERTIA_UNITS)}
UNIT_TABLES = {"length": LENGTH_UNITS, "force": FORCE_UNITS, "moment": MOMENT_UNITS,
               "mass": MASS_UNITS, "inertia": INERTIA_UNITS, "stress": STRESS_UNITS,
               "pressure": PRESSURE_UNITS}


def with_unit(label: str, unit: str) -> str:
    """A column heading or name with its unit: ``x [mm]``, ``cycle.torque.rms [N·m]``; the
    label alone for a quantity without a unit."""
    return f"{label} [{unit}]" if unit else label


def pretty(unit: str) -> str:
    """``N*m`` -> ``N·m`` (how a unit is printed)."""
    return unit.replace("*", "·")


def fmt(x, digits: int = SIG_DIGITS, scale: float | None = None) -> str:
    """``x`` to ``digits`` significant digits: ``5747``, ``155.3``, ``0.04330`` printed as
    ``0.0433``, ``1.25e-05``; "—" for None or NaN; ``0`` (never ``-0``) for zero, for a value
    that rounds to zero, and for ``|x| <= ZERO_RTOL * scale`` (round-off of its quantity)."""
    if x is None:
        return DASH
    x = float(x)
    if not math.isfinite(x):
        return DASH
    if x == 0 or (scale is not None and abs(x) <= ZERO_RTOL * abs(scale)):
        return "0"
    mag = abs(x)
    exp = math.floor(math.log10(mag))
    rounded = round(x, digits - 1 - exp)
    if rounded == 0:
        return "0"
    if abs(rounded) >= 10 ** (exp + 1):            # 9.9996 -> 10.00
        exp += 1
    if -4 <= exp < 6:
        decimals = max(digits - 1 - exp, 0)
        s = f"{rounded:.{decimals}f}"
        if "." in s:
            s = s.rstrip("0").rstrip(".")
    else:
        s = f"{x:.{digits - 1}e}"
        mant, e = s.split("e")
        if "." in mant:
            mant = mant.rstrip("0").rstrip(".")
        s = f"{mant}e{int(e):+03d}"
    return "0" if s in ("-0", "0") else s


def deg(x: float) -> str:
    """A crank angle [deg] as printed: ``45``, ``12.5`` (angles are inputs: shown exactly)."""
    s = f"{float(x):g}"
    return "0" if s == "-0" else s


def clean(x: float, scale: float | None = None) -> float:
    """``x`` with round-off of its quantity (``|x| <= ZERO_RTOL * scale``) and -0 made 0."""
    x = float(x)
    if x == 0 or (scale is not None and abs(x) <= ZERO_RTOL * abs(scale)):
        return 0.0
    return x


def all_round_off(values, scale: float | None) -> bool:
    """Every finite value of ``values`` (a number or an array) is 0 or round-off of its
    quantity (``|x| <= ZERO_RTOL * scale``): what :func:`fmt` prints as ``0`` everywhere
    (a figure of such values has nothing to show). Undefined values (NaN) are skipped."""
    v = np.abs(np.asarray(values, float)).ravel()
    v = v[np.isfinite(v)]
    if not v.size:
        return True
    return bool(v.max() <= (ZERO_RTOL * abs(scale) if scale is not None else 0.0))


@dataclass(frozen=True)
class Display:
    """How values are shown: the unit of each base kind (keys of ``report.units``), and the
    scale [SI] of each kind of quantity in this analysis (for the round-off rule)."""

    length: str = "m"
    force: str = "N"
    moment: str = "N*m"
    mass: str = "kg"
    scales: dict = field(default_factory=dict, compare=False)
    stress: str = "MPa"
    pressure: str = "Pa"

    # ------------------------------------------------------------------ units
    def factor(self, kind: str) -> float:
        """SI value x factor = displayed value."""
        L = LENGTH_UNITS[self.length]
        return {"length": 1 / L, "velocity": 1 / L, "acceleration": 1 / L,
                "force": 1 / FORCE_UNITS[self.force], "moment": 1 / MOMENT_UNITS[self.moment],
                "mass": 1 / MASS_UNITS[self.mass],
                "mass_length": 1 / (MASS_UNITS[self.mass] * L),
                "stress": 1 / STRESS_UNITS[self.stress],
                "pressure": 1 / PRESSURE_UNITS[self.pressure]}.get(kind, 1.0)

    def unit(self, kind: str) -> str:
        """The printed unit of ``kind`` ("" for a ratio)."""
        L = self.length
        return {"length": L, "velocity": f"{L}/s", "acceleration": f"{L}/s²",
                "force": self.force, "moment": pretty(self.moment), "mass": self.mass,
                "mass_length": f"{self.mass}·{L}", "inertia": "kg·m²", "energy": "J",
                "power": "W", "angle": "deg", "omega": "rad/s", "alpha": "rad/s²",
                "time": "h", "duration": "s", "speed": "rpm", "ratio": "",
                "stress": self.stress, "pressure": self.pressure}[kind]

    def value(self, x, kind: str):
        """``x`` [SI] (a number or an array) in display units."""
        return x * self.factor(kind) if x is not None else None

    # --------------------------------------------------------------- numbers
    def num(self, x, kind: str, digits: int = SIG_DIGITS) -> str:
        """``x`` [SI] converted and formatted, without its unit."""
        if x is None:
            return DASH
        scale = self.scales.get(kind)
        f = self.factor(kind)
        return fmt(float(x) * f, digits, None if scale is None else scale * f)

    def zero(self, values, kind: str) -> bool:
        """Every value of ``values`` [SI] prints as 0: round-off of ``kind`` in this analysis
        (:func:`all_round_off`)."""
        return all_round_off(values, self.scales.get(kind))

    def q(self, x, kind: str, digits: int = SIG_DIGITS) -> str:
        """``x`` [SI] converted, formatted, with its unit: ``155.3 N``, ``0.0433 m``."""
        text = self.num(x, kind, digits)
        unit = self.unit(kind)
        return text if text == DASH or not unit else f"{text} {unit}"

    def head(self, label: str, kind: str) -> str:
        """A column heading with the unit: ``x [mm]``."""
        return with_unit(label, self.unit(kind))

    def describe(self) -> str:
        """``lengths in mm, forces in kN, moments in N·m, masses in g``."""
        return (f"lengths in {self.length}, forces in {self.force}, moments in "
                f"{pretty(self.moment)}, masses in {self.mass}")


#: kind of each SI unit as written in quantity tables (``mechreport.quantities``)
KIND_OF_UNIT = {"m": "length", "m/s": "velocity", "m/s^2": "acceleration", "N": "force",
                "N·m": "moment", "kg": "mass", "kg·m": "mass_length", "kg·m^2": "inertia",
                "J": "energy", "W": "power", "deg": "angle", "rad/s": "omega",
                "rad/s^2": "alpha", "h": "time", "s": "duration", "rpm": "speed",
                "Pa": "stress"}


def kind_of(si_unit: str | None) -> str:
    """The kind of quantity measured in ``si_unit`` (``ratio`` when unknown)."""
    return KIND_OF_UNIT.get(si_unit or "", "ratio")
