"""Variants analysed as one batch (their numbers stacked with the angles) give exactly what
each gives analysed alone: the design study's engine."""
from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from mechreport.pipeline.analysis import analyse
from mechreport.pipeline.batch import analyse_variants
from mechreport.model import build_mechanism
from mechreport.kinematics.stacked import solve_stacked
from mechreport.spec import load_spec
from mechreport.spec.stack import stack_specs

ROOT = Path(__file__).resolve().parents[2]


def _variants(spec, count: int = 4):
    """``count`` variants: every link's mass and inertia, one point of the last link, every
    slider line (turned 2 degrees and moved 1 % of its offset) and the driver's speed
    changed."""
    out = []
    for k in range(count):
        f = 1.0 + 0.03 * k
        turn = np.radians(2.0 * k)
        joints = []
        for joint in spec.joints:
            if joint.line is not None:
                (dx, dy), (tx, ty) = joint.line.direction, joint.line.through
                line = dataclasses.replace(
                    joint.line, through=(tx * (1 + 0.01 * k), ty + 0.001 * k),
                    direction=(dx * np.cos(turn) - dy * np.sin(turn),
                               dx * np.sin(turn) + dy * np.cos(turn)))
                joint = dataclasses.replace(joint, line=line)
            joints.append(joint)
        links = []
        for i, link in enumerate(spec.links):
            points = dict(link.points)
            if i == len(spec.links) - 1:
                name, (x, y) = next(iter(points.items()))
                points[name] = (x * (1 + 0.01 * k), y)
            links.append(dataclasses.replace(link, mass=link.mass * f,
                                             inertia=link.inertia * f ** 2, points=points))
        driver = dataclasses.replace(spec.driver, omega=spec.driver.omega * (1 + 0.1 * k))
        out.append(dataclasses.replace(spec, links=tuple(links), joints=tuple(joints),
                                       driver=driver))
    return out


def _same_outcome(batched, alone):
    if alone.review is None:
        assert batched.review is None and batched.review_problem == alone.review_problem
    else:
        assert batched.review.values.keys() == alone.review.values.keys()
        for q, v in alone.review.values.items():
            assert batched.review.values[q] == pytest.approx(v, rel=1e-12, abs=1e-300), q
    assert [(v.item, v.passed) for v in batched.verdicts] == \
        [(v.item, v.passed) for v in alone.verdicts]


def test_every_variant_equals_its_single_analysis(spec_path):
    spec = load_spec(spec_path)
    specs = _variants(spec)
    outcomes = analyse_variants(specs, "newton_euler")
    stacked = solve_stacked(build_mechanism(spec), specs)
    for s, o in zip(specs, outcomes):
        try:
            a = analyse(s, methods=["newton_euler"])
        except Exception as exc:     # noqa: BLE001 - the batch must report the same failure
            assert o.error is not None and str(exc) in o.error
            continue
        assert o.error is None
        _same_outcome(o, a)
    if stacked is not None and stacked.clean.all():   # dyads only, every angle clean
        # (a spec with friction solves it with each variant's own forces, one with dynamics
        # its own motion: alone)
        alone = bool(spec.friction) or spec.dynamics is not None
        assert all(o.batched != alone for o in outcomes)


def test_mechanisms_of_dyads_with_clean_sweeps_are_solved_in_the_batch():
    """(The textbook slider-crank's sweep has near-singular angles, and the boom's driver is
    a Newton group: those variants are analysed alone, as the equality test checks.)"""
    for name in ("four_bar", "r_rtr_rtr", "spring_loaded_slider_crank", "scotch_yoke",
                 "stephenson3_six_bar"):
        outcomes = analyse_variants(_variants(load_spec(ROOT / "specs" / f"{name}.yaml")),
                                    "dyad")
        assert all(o.batched for o in outcomes), name


def test_variants_that_differ_in_structure_are_not_stacked():
    spec = load_spec(ROOT / "specs" / "four_bar.yaml")
    other = dataclasses.replace(spec, sweep=dataclasses.replace(spec.sweep, step=2.0))
    assert stack_specs([spec, other], 3) is None
    renamed = dataclasses.replace(spec, links=(dataclasses.replace(spec.links[0],
                                                                   name="arm"),)
                                  + spec.links[1:])
    assert stack_specs([spec, renamed], 3) is None
    same = stack_specs([spec, spec], 3)
    assert same.links[0].mass == spec.links[0].mass          # equal numbers stay numbers
    heavier = dataclasses.replace(spec, links=(dataclasses.replace(spec.links[0], mass=2.0),)
                                  + spec.links[1:])
    mixed = stack_specs([spec, heavier], 3)
    np.testing.assert_array_equal(mixed.links[0].mass, [spec.links[0].mass] * 3 + [2.0] * 3)


def test_a_variant_that_cannot_assemble_is_analysed_alone_and_reports_why():
    spec = load_spec(ROOT / "specs" / "four_bar.yaml")
    coupler = spec.link("coupler")
    short = dataclasses.replace(coupler, points={**coupler.points, "C": (0.02, 0.0)})
    broken = dataclasses.replace(spec, links=tuple(short if l.name == "coupler" else l
                                                   for l in spec.links))
    outcomes = analyse_variants([spec, broken, spec], "dyad")
    assert outcomes[0].batched and outcomes[2].batched
    assert not outcomes[1].batched and "cannot close" in outcomes[1].error


def test_a_method_without_reactions_reports_no_shaking_force():
    """The power balance alone gives the driver torque, not the frame's load: the review has
    no shaking quantities (rather than ones computed from no reactions)."""
    a = analyse(ROOT / "specs" / "four_bar.yaml", methods=["power"])
    assert "cycle.torque.rms" in a.review.values
    assert not any(q.startswith("cycle.shaking.") for q in a.review.values)
    full = analyse(ROOT / "specs" / "four_bar.yaml")
    assert full.review.values["cycle.shaking.force_max"] > 0


def test_a_variant_that_changes_branch_over_a_turn_is_analysed_alone():
    """A change-point four-bar comes back on its other branch: in a batch it is analysed
    alone and has no cycle quantities, for the same reason as a single analysis gives."""
    spec = load_spec(ROOT / "tests" / "data" / "edge" / "change_point_four_bar.yaml")
    alone = analyse(spec, methods=["dyad"])
    outcomes = analyse_variants(_variants(spec, 3), "dyad")
    assert not any(o.batched for o in outcomes)
    assert all(o.review is None and o.review_problem == alone.review_problem
               for o in outcomes[:1])
    assert all("repeats every two turns" in o.review_problem for o in outcomes)


def test_variants_turning_either_way_are_batched_by_sense():
    """Variants whose cranks turn clockwise and counter-clockwise follow their branches in
    opposite senses: each sense is one batch, and every outcome equals its own analysis."""
    spec = load_spec(ROOT / "specs" / "four_bar.yaml")
    both = [dataclasses.replace(spec, driver=dataclasses.replace(spec.driver, omega=w))
            for w in (spec.driver.omega, -spec.driver.omega, 0.5 * spec.driver.omega)]
    outcomes = analyse_variants(both, "dyad")
    assert all(o.batched for o in outcomes)
    for s, o in zip(both, outcomes):
        _same_outcome(o, analyse(s, methods=["dyad"]))
