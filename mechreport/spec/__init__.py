"""Stage 1: load and validate a spec file into SI dataclasses.

The records (:mod:`.types`) load with the package; the loader and the format's models
(pydantic) load when a spec is first loaded, so that a command that loads none (``mechreport
--version``) does not pay for them."""
from .types import (GROUND, BearingSpec, Buckling, Design, Driver, Expectation, Friction, Joint,
                    Line, Link, Load, Material, Pin, Pressure, Section, Shape, Spec, Strength,
                    Study, Sweep, Vary)
from .profiles import profile_at

__all__ = ["load_spec", "parse_spec", "GROUND", "BearingSpec", "Buckling", "Design", "Driver",
           "Expectation", "Friction", "Joint", "Line", "Link", "Load", "Material", "Pin",
           "Section", "Shape", "Spec", "Strength",
           "Study", "Sweep", "Vary", "Pressure", "profile_at"]


def __getattr__(name: str):
    # PEP 562: the loader is imported on first use
    if name in ("load_spec", "parse_spec"):
        from . import loader
        return getattr(loader, name)
    raise AttributeError(f"module 'mechreport.spec' has no attribute {name!r}")
