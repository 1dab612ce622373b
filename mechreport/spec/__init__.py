"""Stage 1: load and validate a spec file into SI dataclasses."""
from .loader import load_spec, parse_spec
from .types import (GROUND, BearingSpec, Design, Driver, Expectation, Friction, Joint, Line,
                    Link, Load, Material, Pin, Section, Shape, Spec, Strength,
                    Study, Sweep, Vary)

__all__ = ["load_spec", "parse_spec", "GROUND", "BearingSpec", "Design", "Driver",
           "Expectation", "Friction", "Joint", "Line", "Link", "Load", "Material", "Pin",
           "Section", "Shape", "Spec", "Strength",
           "Study", "Sweep", "Vary"]
