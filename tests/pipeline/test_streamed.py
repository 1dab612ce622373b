"""A long sweep checked chunk by chunk (mechreport.pipeline.streamed) finds what the in-memory analysis
finds: the same kinematics angle by angle (branch labels carried across chunks), flags,
agreement, residuals, expectations, cycle quantities and notes. Chunks here are tiny, so that
every spec crosses many chunk boundaries, touch points and locks included."""
from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from mechreport.pipeline.analysis import analyse
from mechreport.app import check as check_run
from mechreport.report.check_text import summary_line
from mechreport.kinematics import solve_kinematics
from mechreport.kinematics import stream
from mechreport.kinematics.stream import kinematic_chunks, streamable
from mechreport.model import build_mechanism
from mechreport.spec import Sweep, load_spec
from mechreport.spec.loader import parse_spec
from mechreport.pipeline.streamed import SweepCheck, check_sweep

ROOT = Path(__file__).resolve().parents[2]
EDGE = ROOT / "tests" / "data" / "edge"


def _short_rod() -> object:
    """The slider-crank with a rod shorter than the crank: it locks at +-53.13 deg."""
    text = (ROOT / "specs" / "slider_crank.yaml").read_text().split("expect:")[0]
    text = text.replace("points: {B: [0, 0], C: [1, 0]}", "points: {B: [0, 0], C: [0.8, 0]}")
    text = text.replace("assembly: {C: [1.4, 0]}", "assembly: {C: [1.2, 0]}")
    return parse_spec(text.replace("at: [45]", "at: [0]"), "short_rod.yaml")


def _partial_four_bar() -> object:
    """Not a whole turn, a reference angle and expectations off the sweep's grid."""
    spec = load_spec(ROOT / "specs" / "four_bar.yaml")
    return dataclasses.replace(spec, sweep=Sweep(10.0, 200.0, 1.0), at=(30.0, 215.5, 77.25),
                               expect=spec.expect)


def _clockwise() -> object:
    return load_spec(ROOT / "tests" / "data" / "slotted_crank_slider.yaml")


SPECS = {p.stem: (lambda p=p: load_spec(p)) for p in sorted((ROOT / "specs").glob("*.yaml"))}
SPECS.update({p.stem: (lambda p=p: load_spec(p)) for p in sorted(EDGE.glob("*.yaml"))})
SPECS.update({"short_rod": _short_rod, "partial_four_bar": _partial_four_bar,
              "clockwise_slotted_crank": _clockwise})


@pytest.fixture
def tiny_chunks(monkeypatch):
    monkeypatch.setattr(stream, "TRACK_CHUNK", 7)   # the tracking pass: 7 samples at a time


@pytest.mark.parametrize("name", sorted(SPECS))
def test_chunked_kinematics_equal_one_solve(name, tiny_chunks):
    spec = SPECS[name]()
    mech = build_mechanism(spec)
    if not streamable(mech):
        pytest.skip("a Newton group: analysed in memory")
    whole = solve_kinematics(mech)
    chunks = kinematic_chunks(mech, 11)
    parts = list(chunks)
    angles = np.concatenate([p.angles for p in parts])
    np.testing.assert_array_equal(angles, whole.angles)
    for what in ("r", "theta", "v", "omega", "a", "alpha"):
        got = np.concatenate([getattr(p, what) for p in parts])
        np.testing.assert_allclose(got, getattr(whole, what), rtol=1e-12, atol=1e-12)
    flags = [f for p in parts for f in p.flags]
    assert flags == list(whole.flags)
    assert chunks.branches == whole.branches
    assert chunks.motion == whole.motion
    assert chunks.notes() == whole.notes()


@pytest.mark.parametrize("name", sorted(SPECS))
def test_streamed_check_equals_the_analysis(name, tiny_chunks):
    spec = SPECS[name]()
    a = analyse(spec)
    s = check_sweep(spec, chunk=13)
    if not streamable(build_mechanism(spec)):
        assert s.__class__.__name__ == "Analysis"
        return
    assert isinstance(s, SweepCheck)
    assert s.n == a.n and s.flags == a.flags and s.passed == a.passed
    assert s.notes() == a.notes()
    assert [g.quantity for g in s.agreement][:1] == [g.quantity for g in a.agreement][:1] \
        or s.worst.relative < 1e-12
    assert {g.quantity for g in s.agreement} == {g.quantity for g in a.agreement}
    for g in s.agreement:
        ref = next(x for x in a.agreement if x.quantity == g.quantity)
        assert g.relative == pytest.approx(ref.relative, rel=1e-3, abs=1e-13)
    assert [r.method for r in s.residuals] == [r.method for r in a.residuals]
    for r, ref in zip(s.residuals, a.residuals):
        assert r.force == pytest.approx(ref.force, rel=1e-3, abs=1e-10)
        assert r.moment == pytest.approx(ref.moment, rel=1e-3, abs=1e-10)
    assert len(s.expectations) == len(a.expectations)
    for e, ref in zip(s.expectations, a.expectations):
        assert (e.expect, e.source, e.ok) == (ref.expect, ref.source, ref.ok)
        assert (e.got is None) == (ref.got is None)
        if e.got is not None:
            assert e.got == pytest.approx(ref.got, rel=1e-12, abs=1e-12)
    assert s.review_problem == a.review_problem
    if a.review is None:
        assert s.values is None
    else:
        assert s.values.keys() == a.review.values.keys()
        for k, v in a.review.values.items():
            assert s.values[k] == pytest.approx(v, rel=1e-10, abs=1e-10), k
    assert [(v.item, v.passed) for v in s.verdicts] == [(v.item, v.passed) for v in a.verdicts]
    if a.strength is None:                 # the members' quantities, merged chunk by chunk
        assert s.members is None
    else:
        assert s.members.keys() == a.strength.values.keys()
        for k, v in a.strength.values.items():
            assert s.members[k] == pytest.approx(v, rel=1e-10), k
    assert summary_line("x", s) == summary_line("x", a) \
        or "worst disagreement" in summary_line("x", s)


def test_check_streams_long_sweeps(monkeypatch, capsys):
    """`check` switches to the streamed path above ``STREAM_ANGLES`` analysed angles, with the
    same PASS line as in memory (the worst disagreement aside, which is rounding)."""
    import mechreport.pipeline.streamed as streamed
    path = ROOT / "specs" / "slider_crank.yaml"
    assert check_run.check_files([path], 1e-6) == 0
    in_memory = capsys.readouterr().out
    monkeypatch.setattr(streamed, "STREAM_ANGLES", 100)
    calls = []
    real = streamed.check_sweep
    monkeypatch.setattr(streamed, "check_sweep",
                        lambda *a, **k: calls.append(1) or real(*a, **k))
    assert check_run.check_files([path], 1e-6) == 0
    out = capsys.readouterr().out
    assert calls and out.split(", worst")[0] == in_memory.split(", worst")[0]
    assert out.split("largest residual")[1][:4] == in_memory.split("largest residual")[1][:4]


@pytest.mark.parametrize("size", range(3, 10))
def test_touch_points_at_every_offset_from_a_chunk_boundary(size, monkeypatch):
    """The textbook slider-crank's branches touch at 90 and 270 deg: with tracking chunks of
    3 to 9 samples, the swaps there fall at every place relative to a chunk's start, and the
    labels carried across must still follow the whole-sweep tracking."""
    monkeypatch.setattr(stream, "TRACK_CHUNK", size)
    spec = load_spec(ROOT / "specs" / "slider_crank.yaml")
    mech = build_mechanism(spec)
    whole = solve_kinematics(mech)
    parts = list(kinematic_chunks(mech, 50))
    np.testing.assert_allclose(np.concatenate([p.theta for p in parts]), whole.theta,
                               rtol=0, atol=1e-12)


@pytest.mark.parametrize("seed", range(5))
def test_flips_continue_across_windows_from_the_carried_swaps(seed):
    """position.label_swaps over windows (three samples of history and the last two swaps carried)
    equals label_swaps over the whole run, on erratic candidates that touch all the time (where the
    history's labels decide the votes)."""
    from mechreport.kinematics.position import label_swaps
    rng = np.random.default_rng(seed)
    n = 300
    xp = np.cumsum(rng.standard_normal((n, 2)), axis=0)
    xm = xp + rng.standard_normal((n, 2)) * 0.5
    t = np.cumsum(rng.uniform(0.5, 1.5, n))
    whole = label_swaps(xp, xm, t)
    assert 10 < whole.sum() < n - 10
    for size in (3, 4, 7, 16):
        got = list(label_swaps(xp[:size], xm[:size], t[:size]))
        for s in range(size, n, size):
            e = min(s + size, n)
            w = slice(s - 3, e)
            got += list(label_swaps(xp[w], xm[w], t[w], carried=(got[s - 3], got[s - 2]))[2:])
        np.testing.assert_array_equal(got, whole)


@pytest.mark.parametrize("step", [180, 120, 90, 60])
def test_whole_turn_closure_on_sweeps_of_a_few_angles(step, monkeypatch):
    """A change-point four-bar comes back on its other branch after a turn, however few the
    sweep's angles: with 2 to 6 samples the tracking's history is shorter than the three
    samples a window carries, and the step home must still be judged from the run's start."""
    monkeypatch.setattr(stream, "TRACK_CHUNK", 4)
    text = (EDGE / "change_point_four_bar.yaml").read_text()
    text = text.replace("step: 1}", f"step: {step}}}").replace("at: [90]", "at: [180]")
    spec = parse_spec(text, "few_angles.yaml")
    whole = solve_kinematics(build_mechanism(spec))
    chunks = kinematic_chunks(build_mechanism(spec), 3)
    assert chunks.branches == whole.branches
    if step == 180:    # (coarser sweeps may step over the change point unseen, either way)
        assert not all(b.closes for b in whole.branches)
    assert check_sweep(spec, chunk=3).review_problem == analyse(spec).review_problem


def test_slider_point_is_judged_against_the_whole_sweeps_largest_force():
    """A press load of 1e9 N acts only from 0 to 20 deg; at 200 deg the slider's force is
    below 1e-12 of the sweep's largest, so its point of application is undefined, in memory and
    streamed alike (a chunk's own largest force would have defined it)."""
    text = """mechreport: 1
name: slider-crank with a short, huge press load
gravity: [0, 0]
ground: {A: [0, 0], O: [0, 0]}
links:
  crank: {points: {A: [0, 0], B: [1, 0]}, mass: 0.001, com: [0.5, 0], inertia: 1e-4}
  rod: {points: {B: [0, 0], C: [2, 0]}, mass: 0.001, com: [1, 0], inertia: 1e-4}
  slider: {points: {C: [0, 0]}, mass: 0.001, com: [0, 0], inertia: 1e-4}
joints:
  A: {type: R, links: [ground, crank]}
  B: {type: R, links: [crank, rod]}
  C: {type: R, links: [rod, slider]}
  C_T: {type: T, links: [ground, slider], point: C, line: {through: O, direction: 0}}
driver: {joint: A, omega: 1}
sweep: {start: 0, stop: 360, step: 1}
at: [45]
assembly: {C: [2.5, 0]}
loads:
  - {type: force, name: press, link: slider, point: C, direction: [-1, 0],
     profile: [[0, 1e9], [20, 1e9], [21, 0], [359, 0]]}
expect:
  - {angle: 200, quantity: joint.C_T.px, value: 1.1, tol: 1e-6}
"""
    spec = parse_spec(text, "press.yaml")
    a, s = analyse(spec), check_sweep(spec, chunk=13)
    assert [e.message for e in a.expectations] == [e.message for e in s.expectations]
    assert s.expectations and all(e.got is None and "undefined" in e.message
                                  for e in s.expectations)
