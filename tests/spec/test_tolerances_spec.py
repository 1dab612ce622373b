"""The ``tolerances:`` section (format 1.2): its distributions resolved about the spec's
values, and its mistakes reported at their key paths, by the models and the key-path check a
study uses."""
from __future__ import annotations

from pathlib import Path

import pytest

from mechreport.errors import SpecError
from mechreport.spec import parse_spec

ROOT = Path(__file__).resolve().parents[2]
FOUR_BAR = (ROOT / "specs" / "four_bar.yaml").read_text(encoding="utf-8")


def spec_with(body: str):
    return parse_spec(FOUR_BAR + "\ntolerances:\n" + body, "four_bar.yaml")


def problems(body: str) -> str:
    with pytest.raises(SpecError) as info:
        spec_with(body)
    return str(info.value)


def test_each_way_of_writing_a_tolerance_is_resolved_about_the_spec_value():
    tol = spec_with("""\
  vary:
    - {key: links.coupler.points.C.0, tol: 0.1}
    - {key: links.coupler.mass, sigma: 5, dist: normal}
    - {key: links.rocker.points.C.0, from: 119, to: 121.5}
    - {key: ground.D.0, tol: 0.3, dist: normal}
    - {key: links.crank.points.B.0, sigma: 0.05}
  keep: [cycle.torque.max, joint.B.f_max]
""").tolerances
    c, m, r, d, b = tol.vary
    assert (c.nominal, c.dist, c.low, c.high, c.given) == (180, "uniform", 179.9, 180.1, "tol")
    assert c.std == pytest.approx(0.2 / 12 ** 0.5)
    assert (m.nominal, m.dist, m.mean, m.sigma, m.std) == (220, "normal", 220, 5, 5)
    assert (r.dist, r.low, r.high, r.given) == ("uniform", 119, 121.5, "range")
    assert (d.dist, d.mean, d.sigma) == ("normal", 200, pytest.approx(0.1))   # +-3 sigma
    assert b.dist == "normal" and b.sigma == 0.05                            # sigma: normal
    assert c.path == ("links", "coupler", "points", "C", 0)
    assert (tol.count, tol.sample, tol.seed) == (1000, "lhs", 0)             # the defaults
    assert tol.keep == ("cycle.torque.max", "joint.B.f_max")


def test_a_spec_with_tolerances_loads_as_before_otherwise():
    plain = parse_spec(FOUR_BAR, "four_bar.yaml")
    with_tol = spec_with("  vary: [{key: links.coupler.mass, tol: 5}]\n  keep: "
                         "[cycle.torque.max]\n")
    assert plain.tolerances is None
    assert with_tol.links == plain.links and with_tol.design == plain.design


@pytest.mark.parametrize("body, message", [
    ("  vary: [{key: links.coupler.mass, tol: 5, sigma: 2}]\n  keep: [cycle.torque.max]\n",
     "tolerances.vary[0]: give one of 'tol', 'sigma' or 'from' and 'to', got tol and sigma"),
    ("  vary: [{key: links.coupler.mass}]\n  keep: [cycle.torque.max]\n",
     "tolerances.vary[0]: give one of 'tol', 'sigma' or 'from' and 'to', got none"),
    ("  vary: [{key: links.coupler.mass, sigma: 2, dist: uniform}]\n  keep: "
     "[cycle.torque.max]\n", "'sigma' is the standard deviation of a normal distribution"),
    ("  vary: [{key: links.coupler.mass, from: 3}]\n  keep: [cycle.torque.max]\n",
     "a range needs 'from' and 'to', two different numbers"),
    ("  vary: [{key: links.coupler.mass, tol: -1}]\n  keep: [cycle.torque.max]\n",
     "tolerances.vary[0].tol: must be a positive number"),
    ("  vary: [{key: links.coupler.mas, tol: 1}]\n  keep: [cycle.torque.max]\n",
     "tolerances.vary[0].key: 'links.coupler.mas': links.coupler has no key 'mas'; did you "
     "mean 'mass'?"),
    ("  vary: [{key: links.coupler.mass, tol: 1}, {key: links.coupler.mass, sigma: 1}]\n"
     "  keep: [cycle.torque.max]\n",
     "tolerances.vary[1].key: 'links.coupler.mass' is varied by tolerances.vary[0] too"),
    ("  vary: [{key: study.seed, tol: 1}]\n  keep: [cycle.torque.max]\n",
     "a study varies the mechanism, not 'study'"),
    ("  vary: [{key: links.coupler.mass, tol: 1, dist: lognormal}]\n  keep: [cycle.torque.max]\n",
     "tolerances.vary[0].dist: must be one of uniform, normal"),
    ("  vary: [{key: links.coupler.mass, tol: 1}]\n  keep: [joint.Q.f_max]\n",
     "tolerances.keep[0]: 'joint.Q.f_max': no joint named 'Q'"),
    ("  vary: [{key: links.coupler.mass, tol: 1}]\n  keep: [cycle.torque.max]\n  count: 1\n",
     "tolerances.count: must be a whole number from 2 to 1000000"),
    ("  vary: [{key: links.coupler.mass, tol: 1}]\n  keep: [cycle.torque.max]\n"
     "  sample: grid\n", "tolerances.sample: must be one of lhs, random"),
    ("  vary: [{key: links.coupler.mass, tol: 1}]\n", "tolerances: missing required key 'keep'"),
])
def test_mistakes_are_reported_at_their_key_path(body, message):
    assert message in problems(body)


def test_the_json_schema_judges_the_spread_as_the_loader_does():
    jsonschema = pytest.importorskip("jsonschema")
    from mechreport.spec.schema import json_schema
    from mechreport.spec.yaml_source import Source
    validator = jsonschema.Draft202012Validator(json_schema())

    def ok(entry: str) -> bool:
        data = Source("four_bar.yaml", FOUR_BAR + f"\ntolerances:\n  vary: [{entry}]\n  "
                                                  "keep: [cycle.torque.max]\n").data
        return not list(validator.iter_errors(data))
    for entry in ("{key: links.coupler.mass, tol: 5}", "{key: links.coupler.mass, sigma: 5}",
                  "{key: links.coupler.mass, sigma: 5, dist: normal}",
                  "{key: links.coupler.mass, from: 1, to: 2, dist: normal}"):
        assert ok(entry), entry
    for entry in ("{key: links.coupler.mass, tol: 5, sigma: 1}", "{key: links.coupler.mass}",
                  "{key: links.coupler.mass, sigma: 5, dist: uniform}",
                  "{key: links.coupler.mass, from: 1}"):
        assert not ok(entry), entry
