"""The equation of motion of a one-degree-of-freedom mechanism driven by its crank.

With phi the crank angle [rad] and omega = dphi/dt, every velocity of the mechanism is its
velocity coefficient k(phi) times omega and every acceleration k alpha + k' omega^2. The
torque the crank must receive to move the mechanism so (the driver torque of the
kinetostatic methods, the chapter's motor moment Mm) is therefore

    M(phi, omega, alpha) = J(phi) alpha + B(phi) omega^2 + C(phi) omega + D(phi)

for omega > 0: J the generalized inertia (the reduced moment of inertia on the crank), B =
J'/2 (the inertia forces of the changing velocity ratios), C the viscous loads (dampers), D
the loads that do not depend on the speed (gravity, springs, forces and moments, profiles,
and loads opposing the motion with a constant magnitude, whose sign is fixed for omega > 0).
A motor torque Mm(omega) and a flywheel If on the crank shaft then give

    (J(phi) + If) alpha = Mm(omega) - B(phi) omega^2 - C(phi) omega - D(phi).

J, B, C and D are found from mechreport's own reference method: its driver torque at four
rate states on a grid of crank angles (omega = 1, 2, 3 rad/s at alpha = 0, and alpha = 1 at
omega = 1), and interpolated between the grid angles by periodic quintic splines, B as half
the derivative of J's. So the equation conserves (J + If) omega^2 / 2 exactly when nothing
else acts (a spline of B's own values would not quite agree with J's slope: the energy
would drift by their difference, 2e-8 relative with cubic splines on a 0.5-degree grid),
and its right-hand side stays smooth enough for the integrator's error control (cubic
pieces would leave B with a kinked slope at every grid angle: 1e-6 drift at the same
tolerance). B's values from the method are checked against J's slope by the tests.
:func:`generalized_inertia` computes J independently, from the velocity coefficients
(J = sum m |v_G / omega|^2 + I (omega_link / omega)^2), for the tests and the sheets.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..errors import AnalysisError
from ..forces import METHODS, solve_forces
from ..kinematics import Kinematics, at_unit_rate, solve_kinematics, with_rates
from ..model import Mechanism
from ..spec import Spec
from ..spec.types import MotorCurve
from .friction import friction_scalar, friction_state, friction_terms, method_parts_of
from .motor import (RPM, constant_drive, motor_function, motor_torque, on_crank, own_power,
                    own_torque)
from .pieces import DEGREE, GRID_STEP_DEG, periodic_pieces, values_at

#: the rate states (omega [rad/s], alpha [rad/s^2]) the reference method is solved at
STATES = ((1.0, 0.0), (2.0, 0.0), (3.0, 0.0), (1.0, 1.0))


@dataclass(frozen=True)
class EquationOfMotion:
    """(J(phi) + flywheel) alpha = motor(omega) - B(phi) omega^2 - C(phi) omega - D(phi),
    phi the crank angle [rad] (periodic over a cycle, :attr:`period`), omega [rad/s];
    ``motor`` the torque the crank receives (the motor through its gearing, :func:`on_crank`,
    or ``mean_rpm``'s constant torque), ``drive`` the motor as the spec gives it (None with
    ``mean_rpm``). ``grid`` (N,) [deg] and
    ``J``, ``B``, ``C``, ``D`` (N,) their values there [kg m^2, kg m^2, N m s, N m];
    ``coefficients`` (N, 4, DEGREE + 1) the periodic splines through them, by grid
    interval, function and power of the angle from the interval's start (highest first; see
    :meth:`at`); ``viscous`` whether any load depends on the speed (a damper, or friction:
    C is not 0 but for round-off); ``friction`` the friction's parts
    (:class:`~mechreport.dynamics.friction.FrictionTerms`, None without friction), whose
    states' equation is solved with it; ``file`` the spec's, for messages."""

    grid: np.ndarray
    J: np.ndarray
    B: np.ndarray
    C: np.ndarray
    D: np.ndarray
    flywheel: float
    motor: MotorCurve
    coefficients: np.ndarray
    viscous: bool = True
    friction: object | None = None
    file: str = ""
    drive: MotorCurve | None = None

    @property
    def period(self) -> float:
        """One cycle [rad]: the period of J, B, C, D (a turn, or the loads' longer cycle)."""
        return len(self.grid) * math.radians(GRID_STEP_DEG)

    def motor_own(self, omega: np.ndarray) -> np.ndarray:
        """The motor's own torque [N m] at crank speeds ``omega`` [rad/s] (through its
        gearing, ``drive``); the constant driving torque on the crank without a motor
        (``mean_rpm``)."""
        return own_torque(self.drive or self.motor, omega)   # the constant one: ratio 1

    def motor_power(self, omega: np.ndarray) -> np.ndarray:
        """The motor's own power [W] at crank speeds ``omega`` [rad/s] (the driving
        torque's on the crank without a motor)."""
        return own_power(self.drive or self.motor, omega)

    def at(self, phi: np.ndarray) -> np.ndarray:
        """(J, B, C, D) at crank angles ``phi`` (n,) [rad], (n, 4)."""
        return values_at(self.coefficients, phi)

    def alpha(self, phi: np.ndarray, omega: np.ndarray) -> np.ndarray:
        """The crank's angular acceleration [rad/s^2] at ``phi`` [rad] and ``omega``
        [rad/s], (n,)."""
        if self.friction is not None:
            return friction_state(self, phi, omega, self.file)[0]
        j, b, c, d = self.at(phi).T
        omega = np.asarray(omega, float)
        return (motor_torque(self.motor, omega) - b * omega ** 2 - c * omega - d) \
            / (j + self.flywheel)

    def load_torque(self, phi: np.ndarray, omega: np.ndarray, alpha: np.ndarray) -> np.ndarray:
        """The torque the mechanism takes from the crank shaft [N m] (without the
        flywheel's): J alpha + B omega^2 + C omega + D."""
        j, b, c, d = self.at(phi).T
        return j * alpha + b * omega ** 2 + c * omega + d

    def scalar(self):
        """alpha(phi, omega) for one state in plain floats: the integrator calls it about
        2100 times a turn, and it takes 3.1 us a call against 92 us for :meth:`alpha` on
        one-element arrays (bench/bench_dynamics.py: the steady state in 0.5 s of CPU, not
        2.8 s). With friction: :func:`~mechreport.dynamics.friction.friction_scalar`."""
        if self.friction is not None:
            return friction_scalar(self)
        coef = self.coefficients.tolist()
        h = math.radians(GRID_STEP_DEG)
        n = len(coef)
        fly = self.flywheel
        torque = motor_function(self.motor)
        period = n * h

        def alpha(phi: float, omega: float) -> float:
            x = (phi % period) / h
            i = min(int(x), n - 1)
            t = (x - i) * h
            (j5, j4, j3, j2, j1, j0), (b5, b4, b3, b2, b1, b0), (c5, c4, c3, c2, c1, c0), \
                (d5, d4, d3, d2, d1, d0) = coef[i]
            j = ((((j5 * t + j4) * t + j3) * t + j2) * t + j1) * t + j0
            b = ((((b5 * t + b4) * t + b3) * t + b2) * t + b1) * t + b0
            c = ((((c5 * t + c4) * t + c3) * t + c2) * t + c1) * t + c0
            d = ((((d5 * t + d4) * t + d3) * t + d2) * t + d1) * t + d0
            return (torque(omega) - (b * omega + c) * omega - d) / (j + fly)
        return alpha


def equation_of_motion(mech: Mechanism) -> EquationOfMotion:
    """The equation of motion of ``mech`` (its spec's ``dynamics``: motor and flywheel),
    from its reference method's driver torque at the rate states ``STATES`` over the grid.
    Raises ``AnalysisError`` where the crank cannot turn fully (a grid angle unreachable
    or singular: the motion could not continue there)."""
    spec = mech.spec
    grid = np.arange(0.0, float(spec.cycle), GRID_STEP_DEG)   # the loads' period
    unit_spec = replace(spec, driver=replace(spec.driver, omega=1.0, alpha=0.0),
                        friction=(), expect=())
    friction = None
    unit = mech.with_spec(unit_spec)
    kin = solve_kinematics(unit, grid)
    if kin.n != len(grid):
        missed = [f for f in kin.flags]
        where = f" at {missed[0].angle:g}°: {missed[0].reason}" if missed else ""
        raise AnalysisError(f"{spec.file}: machine dynamics needs a crank that turns fully "
                            f"and smoothly; the motion cannot continue{where}")
    method = next(iter(METHODS))
    torque = []
    for omega, alpha in STATES:
        moving = with_rates(kin, np.full(kin.n, omega), np.full(kin.n, alpha))
        torque.append(np.asarray(solve_forces(moving, [method])[method].driver_torque, float))
    m1, m2, m3, m11 = torque
    b = (m3 - 2 * m2 + m1) / 2
    c = (m2 - m1) - 3 * b
    d = m1 - c - b
    j = m11 - m1
    values = np.stack([j, b, c, d], axis=1)
    if not np.all(np.isfinite(values)):
        raise AnalysisError(f"{spec.file}: the equation of motion is not finite at every "
                            "crank angle")
    if spec.friction:
        rubbed = mech.with_spec(replace(unit_spec, friction=spec.friction))
        friction = friction_terms(spec, replace(kin, mechanism=rubbed), STATES,
                                  method_parts_of)
    drive = spec.dynamics.motor
    # a motor's characteristic as the crank receives it; with mean_rpm a constant torque,
    # set when the steady state is found (dynamics.steady_at)
    motor = on_crank(drive) if drive is not None else constant_drive(0.0)
    return EquationOfMotion(grid, j, b, c, d, spec.dynamics.flywheel, motor,
                            _pieces(np.radians(grid), values),
                            bool(spec.friction) or any(ld.kind == "damper" for ld in spec.loads),
                            friction, spec.file, drive)


def _pieces(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The polynomial pieces (N, 4, DEGREE + 1) of J, B, C, D (``y`` (N, 4) at the equally
    spaced ``x`` (N,) over one turn), by interval, function and power of the angle from the
    interval's start (highest first): J, C and D periodic splines of degree DEGREE, B half
    the derivative of J's. Each piece is the spline's Taylor polynomial at its interval's
    start (exact: the spline is one polynomial over the interval)."""
    pieces = periodic_pieces(x, y)[..., ::-1].copy()          # (N, 4, powers t^0 ..)
    pieces[:, 1] = 0.0
    pieces[:, 1, :-1] = 0.5 * pieces[:, 0, 1:] * np.arange(1, DEGREE + 1)   # B = J' / 2
    return pieces[..., ::-1].copy()


def generalized_inertia(kin: Kinematics) -> np.ndarray:
    """The reduced moment of inertia on the crank J(phi) (n,) [kg m^2] over ``kin``'s angles,
    from the velocity coefficients: sum over the links of m |v_G / omega|^2 + I_G
    (omega_link / omega)^2 (the kinetic energy at unit crank speed, doubled)."""
    unit = at_unit_rate(kin)
    spec = kin.mechanism.spec
    out = np.zeros(kin.n)
    for link in spec.links:
        if link.mass:
            v = unit.com(link.name).v
            out += link.mass * np.einsum("ij,ij->i", v, v)
        if link.inertia:
            out += link.inertia * unit.omega[:, spec.number(link.name)] ** 2
    return out


@dataclass(frozen=True)
class InertiaTerm:
    """One link's share of the reduced inertia J(phi) at one angle: link ``number``,
    ``kind`` ``mass`` (m |v_G / omega|^2) or ``inertia`` (I_G (omega_link / omega)^2),
    ``value`` the mass [kg] or the inertia [kg m^2], ``coefficient`` |v_G / omega|^2 [m^2]
    or (omega_link / omega)^2 [-]."""

    number: int
    kind: str
    value: float
    coefficient: float


def inertia_terms(kin: Kinematics, k: int) -> list[InertiaTerm]:
    """J(phi)'s terms at angle index ``k`` of ``kin``, link by link (what
    :func:`generalized_inertia` sums), from the velocity coefficients there."""
    unit = at_unit_rate(kin.take(np.array([k]), ()))
    spec = kin.mechanism.spec
    out = []
    for link in spec.links:
        i = spec.number(link.name)
        if link.mass:
            v = unit.com(link.name).v[0]
            out.append(InertiaTerm(i, "mass", link.mass, float(v @ v)))
        if link.inertia:
            w = float(unit.omega[0, i])
            out.append(InertiaTerm(i, "inertia", link.inertia, w * w))
    return out


def spec_at_speed(spec: Spec, omega: float) -> Spec:
    """``spec`` with its driver turning at ``omega`` [rad/s] and no angular acceleration."""
    return replace(spec, driver=replace(spec.driver, omega=omega, alpha=0.0,
                                        rpm_given=omega / RPM))


__all__ = ["EquationOfMotion", "InertiaTerm", "STATES", "equation_of_motion",
           "flywheel_estimate", "generalized_inertia", "inertia_terms", "spec_at_speed"]


def flywheel_estimate(eom: EquationOfMotion, omega: float) -> tuple[float, float, float]:
    """The constant-speed estimate the design review's flywheel formula makes, at the mean
    speed ``omega`` [rad/s]: (the energy fluctuation dE [J] of the torque the mechanism takes
    at constant speed, B omega^2 + C omega + D, against its mean, over the cycle's grid by
    the design review's rule; the mean over the crank angle of the reduced inertia
    J_mean + If [kg m^2]; the speed fluctuation it predicts, dE / ((J_mean + If) omega^2))."""
    torque = eom.B * omega ** 2 + eom.C * omega + eom.D
    h = math.radians(GRID_STEP_DEG)
    # the design review's rule: the periodic trapezoid's running integral of the torque
    # less its mean, its extremes at the grid's angles
    g = torque - torque.mean()
    energy = np.concatenate([[0.0], np.cumsum(0.5 * (g + np.roll(g, -1)) * h)[:-1]])
    swing = float(np.max(energy) - np.min(energy))
    inertia = float(np.mean(eom.J)) + eom.flywheel
    return swing, inertia, swing / (inertia * omega ** 2)
