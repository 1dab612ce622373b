"""Stage 6: post-processing. Pure functions of the solved kinematics and forces: what the
mechanism does to its frame, bearing loads, transmission angles, balancing, and the cycle
quantities and verdicts of a design review. Nothing here draws or formats."""
from .balance import Counterweight, counterweight
from .bearings import BearingLoad, bearing_carrier, bearing_load, bearing_trace, rating_life_h
from .cycle import Cycle, CycleUndefined, cycle_of
from .frame import FrameLoad, frame_load, inertia_force, joint_point, reference_method
from ..quantities import CYCLE_UNITS as UNITS, JOINT_CYCLE_UNITS as JOINT_UNITS, unit_of
from .review import (Review, Traces, design_review, design_review_from, review, review_from,
                     review_of, traces_of)
from .verdicts import Verdict, verdicts
from .torque import Peak, TorqueStats, peak, torque_stats
from .transmission import transmission_angles

__all__ = ["Counterweight", "counterweight", "BearingLoad", "bearing_carrier", "bearing_load",
           "bearing_trace", "rating_life_h", "Cycle", "CycleUndefined", "cycle_of", "FrameLoad", "frame_load", "inertia_force", "joint_point",
           "reference_method", "JOINT_UNITS", "UNITS", "Review", "Traces", "design_review",
           "design_review_from", "review", "review_from", "review_of", "traces_of", "unit_of", "Verdict", "verdicts",
           "transmission_angles", "Peak", "TorqueStats", "peak", "torque_stats"]
