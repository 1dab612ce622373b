"""The contour method's independence test is dimensionless (issue 36, item 13): a mechanism
scaled to 1e9 m or 1e-9 m across finds the same equations as at 1 m, and agrees with the
other methods, as they did already."""
from __future__ import annotations

from pathlib import Path

import pytest
import yaml

import mechreport

ROOT = Path(__file__).resolve().parents[2]


def scaled(path: Path, factor: float) -> str:
    """The spec at ``path`` with every length times ``factor`` (expectations dropped; the
    inertias kept, within the loader's range): the same linkage, another size."""
    data = yaml.safe_load(path.read_text(encoding="utf-8"))
    data.pop("expect", None)
    data.pop("sheet", None)
    data["units"] = {"length": "m", "mass": "kg"}

    def xy(p):
        return [float(c) * factor for c in p]
    data["ground"] = {k: xy(v) for k, v in data["ground"].items()}
    for link in data["links"].values():
        link["points"] = {k: xy(v) for k, v in link["points"].items()}
        link["com"] = xy(link.get("com", next(iter(link["points"].values()))))
        link["inertia"] = float(link.get("inertia", 1e-4))
        link.pop("shape", None)
    if "assembly" in data:
        data["assembly"] = {k: xy(v) for k, v in data["assembly"].items()}
    return yaml.safe_dump(data)


@pytest.mark.parametrize("path, factor", [
    (ROOT / "specs" / "slider_crank.yaml", 1e9), (ROOT / "specs" / "slider_crank.yaml", 1e-9),
    (ROOT / "tests" / "data" / "class_iii_triad.yaml", 1e-9),
    (ROOT / "tests" / "data" / "class_iii_triad.yaml", 1e15)],
    ids=["slider-crank-1e9", "slider-crank-1e-9", "triad-1e-9", "triad-1e15"])
def test_contour_solves_a_scaled_mechanism_and_agrees(path, factor):
    a = mechreport.analyse(scaled(path, factor))
    assert "contour" in a.forces
    assert a.worst.relative < 1e-6, a.worst
    at_one = mechreport.analyse(scaled(path, 1.0))
    titles = [s.title for s in a.worked_steps("contour")]
    assert titles == [s.title for s in at_one.worked_steps("contour")]
