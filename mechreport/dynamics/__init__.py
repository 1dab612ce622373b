"""Machine dynamics (format 1.1 ``dynamics:``): the equation of motion of the mechanism on its
crank, from its own kinematics and reference method, and the motion it gives in time."""
from .equation import (EquationOfMotion, equation_of_motion, flywheel_estimate,
                       generalized_inertia, spec_at_speed)
from .mean_speed import motion
from .motor import motor_torque
from .simulate import Simulation, SteadyCycle, simulate

__all__ = ["EquationOfMotion", "Simulation", "SteadyCycle", "equation_of_motion",
           "flywheel_estimate",
           "generalized_inertia", "motion", "motor_torque", "simulate", "spec_at_speed"]
