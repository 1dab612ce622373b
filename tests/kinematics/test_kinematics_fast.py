"""The fast kinematics paths give the numbers of the general ones: a dyad's rate systems
solved through their block structure (``DyadSystem``) against LAPACK on the full equilibrated
6x6 matrices (``linalg.Equilibrated``), condition numbers (which the singular and
near-singular flags are calibrated on) included; the branch tracking's shared whole-turn
flips against the run's own; cached rotations against ``rotate``."""
from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from mechreport.kinematics import _positions, driver_pose
from mechreport.kinematics.dyadsolve import DyadSystem
from mechreport.kinematics.frames import LinkFrames, Trig, rotate
from mechreport.kinematics.groups import RateEquations
from mechreport.kinematics.path import sweep_path
from mechreport.kinematics.position import label_swaps, ring_swaps, dyad_candidates, signature
from mechreport.linalg import SINGULAR_COND, Equilibrated
from mechreport.model import build_mechanism
from mechreport.spec import GROUND, Sweep, load_spec

ROOT = Path(__file__).resolve().parents[2]
SPECS = sorted((ROOT / "specs").glob("*.yaml")) + sorted((ROOT / "tests" / "data").rglob("*.yaml"))


def _fine(path: Path, step: float = 0.1):
    spec = load_spec(path)
    return dataclasses.replace(spec, sweep=Sweep(spec.sweep.start, spec.sweep.stop, step))


def _frames(mech) -> LinkFrames:
    """Every link's poses over the spec's tracking path (angles later flagged singular or
    near-singular included; those not reached set to zero, as the rate solve does)."""
    spec = mech.spec
    r, th, _, _ = _positions(mech, sweep_path(spec, spec.analysed_angles(), spec.at[0]))
    ok = np.all([np.isfinite(x[:, 0]) for x in r.values()], axis=0)
    return LinkFrames({k: np.where(ok[:, None], x, 0.0) for k, x in r.items()},
                      {k: np.where(ok, t, 0.0) for k, t in th.items()})


def _rhs(n: int) -> np.ndarray:
    return np.sin(np.arange(6 * n).reshape(n, 6) * 0.7) + 0.1


def _dyad_systems():
    """(spec name, group, rate equations) for every dyad of every spec, over a 0.1 deg
    sweep."""
    for path in SPECS:
        mech = build_mechanism(_fine(path))
        frames = _frames(mech)
        for group in mech.groups:
            if group.dyad is not None:
                yield path.stem, group, RateEquations(mech.spec, group, frames)


CASES = list(_dyad_systems())


@pytest.mark.parametrize("case", CASES, ids=[f"{c[0]}-{c[1].label}" for c in CASES])
def test_dyad_system_gives_equilibrated_lapack_numbers(case):
    _, group, eqs = case
    b = _rhs(eqs.frames.n)
    fast, full = DyadSystem(eqs), Equilibrated(eqs.matrix())
    with np.errstate(all="ignore"):
        x, cond = fast.solve_cond(b)
        x_ref, cond_ref = full.solve_cond(b)
        xa, xa_ref = fast.solve(b), full.solve(b)
    np.testing.assert_array_equal(cond < SINGULAR_COND, cond_ref < SINGULAR_COND)
    ok = cond_ref < SINGULAR_COND
    np.testing.assert_allclose(cond[ok], cond_ref[ok], rtol=1e-14 * np.max(cond_ref[ok]) + 1e-12)
    scale = np.max(np.abs(x_ref[ok]), axis=1) * cond_ref[ok]
    assert np.all(np.max(np.abs(x[ok] - x_ref[ok]), axis=1) <= 1e-14 * scale)
    assert np.all(np.max(np.abs(xa[ok] - xa_ref[ok]), axis=1) <= 1e-14 * scale)


def test_dyads_prepared_together_equal_each_alone():
    """DyadSystem.joined prepares a mechanism's dyads in one pass: each dyad's solutions and
    condition numbers are bit for bit those it gets alone, over every spec's dyads joined
    (different dyad kinds and row orders together), with a pose that could not be solved
    (NaN), a right-hand side that is not finite and an exactly singular dyad among them."""
    by_spec: dict[str, list] = {}
    for name, _, eqs in CASES:
        by_spec.setdefault(name, []).append(eqs)
    eqs_all = [e for name in ("slider_crank", "four_bar", "r_rtr_rtr") for e in by_spec[name]]
    n = min(e.frames.n for e in eqs_all)
    frames = [LinkFrames({k: x[:n].copy() for k, x in e.frames.r.items()},
                         {k: x[:n].copy() for k, x in e.frames.th.items()}) for e in eqs_all]
    frames[0].th[eqs_all[0].group.links[0]][3] = np.nan
    eqs_all = [RateEquations(e.spec, e.group, f) for e, f in zip(eqs_all, frames)]
    inner = next(i for i, j in enumerate(eqs_all[1].group.joints)
                 if set(j.links) == set(eqs_all[1].group.links))
    eqs_all[1].geometry[inner] = _NoBlocks()                  # exactly singular
    b = _rhs(n)
    b[5, 0] = np.inf
    for joined, eqs in zip(DyadSystem.joined(eqs_all), eqs_all):
        alone = DyadSystem(eqs)
        with np.errstate(all="ignore"):
            got = [*joined.solve_cond(b), joined.solve(b)]
            want = [*alone.solve_cond(b), alone.solve(b)]
        for g, w in zip(got, want):
            assert np.array_equal(g.view(np.uint64), w.view(np.uint64)), eqs.group.label


def test_near_singular_dyad_keeps_its_condition_number():
    """The slider-crank with AB = BC near 90 deg: condition numbers up to the singular
    threshold, the same as LAPACK's to round-off times the condition number."""
    spec = load_spec(ROOT / "specs" / "slider_crank.yaml")
    spec = dataclasses.replace(spec, sweep=Sweep(89.0, 91.0, 0.0005), at=(89.0,), expect=())
    mech = build_mechanism(spec)
    frames = _frames(mech)
    group = next(g for g in mech.groups if g.dyad is not None)
    eqs = RateEquations(spec, group, frames)
    b = _rhs(frames.n)
    cond = DyadSystem(eqs).solve_cond(b)[1]
    cond_ref = Equilibrated(eqs.matrix()).solve_cond(b)[1]
    ok = cond_ref < SINGULAR_COND
    assert np.max(cond_ref[ok]) > 1e5 and not ok.all()
    np.testing.assert_array_equal(cond < SINGULAR_COND, ok)
    rel = np.abs(cond[ok] - cond_ref[ok]) / cond_ref[ok]
    assert np.all(rel <= 1e-15 * cond_ref[ok] + 1e-13), np.max(rel / cond_ref[ok])


def test_dyad_system_not_finite_and_exactly_singular_as_equilibrated():
    """A pose that could not be solved (NaN) gives NaN solutions and condition numbers; a
    right-hand side that is not finite a NaN condition number; an exactly singular system
    (here the inner joint's rows zeroed) an infinite one."""
    spec = load_spec(ROOT / "specs" / "four_bar.yaml")
    mech = build_mechanism(spec)
    frames = _frames(mech)
    th = {k: x.copy() for k, x in frames.th.items()}
    group = next(g for g in mech.groups if g.dyad is not None)
    th[group.links[0]][3] = np.nan
    eqs = RateEquations(spec, group, LinkFrames(frames.r, th))
    b = _rhs(frames.n)
    b[5, 0] = np.inf
    for system in (DyadSystem(eqs), Equilibrated(eqs.matrix())):
        with np.errstate(invalid="ignore"):
            x, cond = system.solve_cond(b)
        assert np.isnan(cond[[3, 5]]).all() and np.isnan(x[[3, 5]]).all()
        assert np.isfinite(cond[[0, 1, 2, 4]]).all()
    inner = next(i for i, j in enumerate(group.joints) if set(j.links) == set(group.links))
    eqs.geometry[inner] = _NoBlocks()
    for system in (DyadSystem(eqs), Equilibrated(eqs.matrix())):
        with np.errstate(all="ignore"):
            x, cond = system.solve_cond(b)
        assert np.isinf(cond[[0, 1, 2, 4]]).all() and np.isnan(x).all()


class _NoBlocks:
    """A joint whose Jacobian blocks are all zero."""

    def write_blocks(self, out):
        pass


@pytest.mark.parametrize("name", ["slider_crank", "four_bar"])
def test_whole_turn_flips_are_the_runs_own(name):
    """The swaps decided along a whole turn and back to its start, but the last, are those
    decided along the turn alone (the closing check and the forward run share them), touch
    points included."""
    spec = _fine(ROOT / "specs" / f"{name}.yaml")
    if name == "four_bar":
        spec = load_spec(ROOT / "tests" / "data" / "edge" / "change_point_four_bar.yaml")
        spec = dataclasses.replace(spec, sweep=Sweep(spec.sweep.start, spec.sweep.stop, 0.1))
    mech = build_mechanism(spec)
    path = sweep_path(spec, spec.analysed_angles(), spec.at[0])
    kin_r = {GROUND: np.zeros((len(path.angles), 2))}
    kin_th = {GROUND: np.zeros(len(path.angles))}
    for link, (rr, tt) in driver_pose(spec, path.angles * spec.driver.unit).items():
        kin_r[link], kin_th[link] = rr, tt
    dyad = next(g.dyad for g in mech.groups if g.dyad is not None)
    cands = dyad_candidates(spec, dyad, {k: (kin_r[k], kin_th[k]) for k in kin_r})
    sig = [signature(spec, dyad.links, c) for c in cands]
    run, travel = path.runs[0], path.travel[0]
    ring = ring_swaps(sig, run, travel)
    own = label_swaps(sig[0][run], sig[1][run], travel[:len(run)])
    np.testing.assert_array_equal(ring[:-1], own)
    if name == "slider_crank":
        assert own.any()          # a touch: the labels swap


def test_cached_rotations_are_rotate():
    rng = np.random.default_rng(7)
    th = rng.uniform(-4, 4, 50)
    frames = LinkFrames({"a": np.zeros((50, 2)), GROUND: np.zeros((50, 2))},
                        {"a": th, GROUND: np.zeros(50)})
    trig = Trig()
    for v in ((0.3, -1.2), rng.normal(size=(50, 2))):
        np.testing.assert_array_equal(frames.rotate("a", v), rotate(v, th))
        np.testing.assert_array_equal(trig.rotate(v, th), rotate(v, th))
        np.testing.assert_array_equal(frames.rotate(GROUND, v), rotate(v, np.zeros(50)))
    assert trig(th)[0] is trig(th)[0]


@pytest.mark.parametrize("path", SPECS, ids=lambda p: p.stem)
def test_points_prepared_together_equal_each_alone(path):
    """Kinematics.prepare_points computes many points' states in one pass: each is bit for
    bit the state Kinematics.point computes alone, contiguous and read-only (every named
    point and centre of mass of the spec, ground points included)."""
    from mechreport.kinematics import solve_kinematics
    mech = build_mechanism(load_spec(path))
    kin = solve_kinematics(mech)
    if kin.n == 0:
        pytest.skip("no angle solved")
    spec = mech.spec
    wanted = [(link.name, link.com) for link in spec.links]
    wanted += [(link.name, p) for link in spec.links for p in link.points.values()]
    wanted += [(GROUND, p) for p in spec.ground.values()]
    alone = dataclasses.replace(kin)
    together = dataclasses.replace(kin)
    together.prepare_points(wanted)
    for link, local in wanted:
        a, b = alone.point(link, local), together.point(link, local)
        for x, y in ((a.r, b.r), (a.v, b.v), (a.a, b.a)):
            assert np.array_equal(x.view(np.uint64), y.view(np.uint64)), (link, local)
            assert y.flags.c_contiguous and not y.flags.writeable
