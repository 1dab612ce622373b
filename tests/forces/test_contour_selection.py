"""The contour method's search and what keeps its fixed cost down change no equation: the
one-row rank and the determinant independence test agree with the SVD; the structural
selection equals the candidate-by-candidate numerical one (and falls back to it where the
structure misleads, falls short or is near rank); a plan kept per structure is replayed bit
for bit as searched (a bridge's too), and kept only when the structure decided; a topology's
structure is found once; terms shared between equations are those built for each; forces at
the moment centre are left out as the plain rule does."""
from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from mechreport.forces import METHODS, ForceContext
from mechreport.kinematics import solve_kinematics
from mechreport.model import build_mechanism
from mechreport.pipeline.analysis import analyse
from mechreport.spec import load_spec

ROOT = Path(__file__).resolve().parents[2]


def test_contour_rank_of_one_row_equals_the_svd():
    """The contour search's rank of a single row (a zero test, where no entry is near the
    SVD's floor or overflow) is the SVD's count: zero rows, -0 and large entries; with
    subnormal rows, or a row whose length overflows, the SVD itself decides."""
    from mechreport.forces import contour

    def svd_rank(rows):
        s = np.linalg.svd(rows, compute_uv=False)
        return np.sum(s > contour.RANK_RTOL * np.maximum(s[:, :1], 1e-300), axis=1)
    rng = np.random.default_rng(3)
    rows = rng.standard_normal((400, 1, 3)) * 10.0 ** rng.uniform(-280, 300, (400, 1, 1))
    rows[:50] = 0.0
    rows[50:60, 0, 1:] = 0.0
    rows[70:80, 0, 0] = -0.0
    tiny = rows.copy()
    tiny[60:70] = 5e-324
    tiny[80:90] = 1e-305
    huge = rows.copy()
    huge[90:95] = 1.5e308                 # the row's length overflows: the SVD counts none
    for case in (rows, tiny, huge):
        np.testing.assert_array_equal(contour._rank(case), svd_rank(case))
    assert contour._rank(tiny)[60:70].sum() == 0      # below the floor: no rank


def test_contour_independence_by_determinant_implies_the_svd_rank():
    """The contour search's check of a chosen set by its determinants: wherever it says the
    square matrices are independent with the margin, the SVD says so too (random matrices
    of 1 to 8 unknowns over many scales and conditions, near-singular and singular ones and
    out-of-range scales among them; NaN is never independent); and it does say so for
    well-conditioned sets, which is what makes it worth having."""
    from mechreport.forces import contour
    rng = np.random.default_rng(11)
    rtol = 2 * contour.RANK_RTOL
    certified = 0
    for trial in range(600):
        k = int(rng.integers(1, 9))
        U = np.linalg.qr(rng.standard_normal((16, k, k)))[0]
        V = np.linalg.qr(rng.standard_normal((16, k, k)))[0]
        s = 10.0 ** rng.uniform(-12 if trial % 3 else -1, 0, (16, k))
        s[:, 0] = 1.0
        rows = (U * s[:, None, :]) @ V * 10.0 ** rng.uniform(-40, 40)
        if trial % 40 == 1 and k > 1:
            rows[5, -1] = rows[5, 0]                  # two equal rows: singular
        surely = contour._surely_independent(rows, rtol)
        assert bool((contour._rank(rows, rtol) == k).all()) or not surely, (trial, k)
        certified += surely
        if trial % 50 == 0:                           # (the SVD itself fails on NaN)
            rows[3, 0, 0] = np.nan
            assert not contour._surely_independent(rows, rtol)
    assert certified > 100
    assert not contour._surely_independent(np.ones((4, 2, 3)), rtol)    # not square
    # numbers whose k-th power of the norm could underflow or overflow: left to the SVD
    for scale in (1e-40, 1e40):
        assert not contour._surely_independent(np.eye(8)[None] * scale, rtol)
    assert contour._surely_independent(np.eye(8)[None], rtol)


def _both_selections(monkeypatch):
    """Make the contour search run the structural and the numerical selection side by side
    and record whether they chose the same equation objects."""
    from mechreport.forces import contour
    numeric = contour._select_numeric
    compared = []

    def select(unknowns, chosen, candidates, build, probes, needs, record=None):
        by_structure = contour_select(unknowns, chosen, candidates, build, probes, needs,
                                      record)
        by_numbers = numeric(unknowns, chosen, candidates, build, probes)
        compared.append((by_structure is None and by_numbers is None)
                        or (by_structure is not None and by_numbers is not None
                            and list(map(id, by_structure)) == list(map(id, by_numbers))))
        return by_structure
    contour_select = contour._select
    monkeypatch.setattr(contour, "_select", select)     # (no ContourPlans: none replayed)
    return compared


@pytest.mark.parametrize("path", sorted((ROOT / "specs").glob("*.yaml"))
                         + sorted((ROOT / "tests" / "data").rglob("*.yaml")),
                         ids=lambda p: p.stem)
def test_contour_structural_selection_equals_the_numerical_one(path, monkeypatch):
    """The contour search picks its equations by structural rank and checks them with one
    rank test: on every spec (short sweeps searched in place, and the probe context of a
    long one), every selection, failed ones included, is the one the candidate-by-candidate
    numerical selection makes."""
    from mechreport.forces import contour
    compared = _both_selections(monkeypatch)
    spec = load_spec(path)
    for step in (spec.sweep.step, (spec.sweep.stop - spec.sweep.start) / 30):
        kin = solve_kinematics(build_mechanism(dataclasses.replace(
            spec, sweep=dataclasses.replace(spec.sweep, step=step))))
        if kin.n == 0:
            continue
        contour.plan(ForceContext(kin))
    assert compared and all(compared)
    # the unknowns the structure reads from the actions are those of the equation built
    ctx = ForceContext(kin)
    cuts = [r for p in contour.plan(ctx) for r in p.recipes if r[0] == "cut"]
    assert cuts
    for _, w, body in cuts:
        joint = spec.joint(w)
        eq = contour._equation(ctx, joint, list(body))
        assert contour._needs(ctx, joint, list(body)) == set(eq.unknown_names()), (w, body)


def _fake_equation(label, row):
    """An equation over unknowns a, b, c whose coefficients are ``row`` (P, 3) at P probes."""
    from mechreport.forces.equations import Action, Equation, Term
    act = Action(label, "force", "reaction", "link", unknowns=("a", "b", "c"))
    return Equation(label, "force", ("link",), [Term(act, np.asarray(row, float),
                                                     np.zeros(len(row)))])


def test_contour_selection_falls_back_to_the_numbers_where_structure_misleads():
    """Where the structure promises rank the numbers do not have (a multiple of a row taken;
    a row that vanishes at one probe angle), the numerical selection decides: the result is
    the candidate-by-candidate one."""
    from mechreport.forces import contour
    P = 4
    probes = np.arange(P)
    one = np.ones(P)
    rows = {
        "e1": np.stack([one, one, 0 * one], axis=1),
        "twice": np.stack([2 * one, 2 * one, 0 * one], axis=1),    # 2 e1: dependent
        "gap": np.stack([one, -one, 0 * one], axis=1) * np.array([1, 1, 0, 1])[:, None],
        "b": np.stack([0 * one, one, 0 * one], axis=1),
        "c": np.stack([0 * one, 0 * one, one], axis=1),
    }
    eqs = {k: _fake_equation(k, v) for k, v in rows.items()}
    needs = {k: frozenset({"a", "b", "c"}) for k in rows}
    needs["b"], needs["c"] = frozenset({"b"}), frozenset({"c"})
    for order in (["e1", "twice", "b", "c"], ["e1", "gap", "c", "b"], ["gap", "c", "e1"],
                  ["c", "twice"], ["e1", "twice"]):
        got = contour._select(["a", "b", "c"], [], order, eqs.__getitem__, probes, needs)
        want = contour._select_numeric(["a", "b", "c"], [], order, eqs.__getitem__, probes)
        assert (got is None) == (want is None), order
        if got is not None:
            assert [e.label for e in got] == [e.label for e in want], order
    assert [e.label for e in contour._select(["a", "b", "c"], [], ["e1", "twice", "b", "c"],
                                             eqs.__getitem__, probes, needs)] == ["e1", "b", "c"]


def test_contour_selection_where_structure_falls_short_or_is_near_rank():
    """Two cases an adversarial review found. Too few equations by structure: the numerical
    selection's second pass still takes two rows of one unknown that add rank at different
    angles, a set singular at every angle (no row names b); the selection refuses it, as
    it refuses any set the structure cannot make independent. And a set whose smallest
    singular value is within rounding of the rank threshold, where a subset falls below
    it: the numerical selection decides, and says so."""
    from mechreport.forces import contour
    from mechreport.forces.equations import Action, Equation, Term

    def eq(label, row, unknowns):
        act = Action(label, "force", "reaction", "link", unknowns=unknowns)
        return Equation(label, "force", ("link",), [Term(act, np.asarray(row, float),
                                                         np.zeros(len(row)))])
    eqs = {"r1": eq("r1", [[1.0, 0.0], [0.0, 0.0]], ("a", "b")),
           "r2": eq("r2", [[0.0, 0.0], [1.0, 0.0]], ("a", "b"))}
    needs = {"r1": frozenset({"a"}), "r2": frozenset({"a"})}
    by_numbers = contour._select_numeric(["a", "b"], [], ["r1", "r2"], eqs.__getitem__,
                                         np.arange(2))
    assert [e.label for e in by_numbers] == ["r1", "r2"]
    both = np.stack([eqs["r1"].terms[0].coeffs, eqs["r2"].terms[0].coeffs], axis=1)
    assert (np.linalg.det(both) == 0).all()                # singular at every angle
    record: list = []
    assert contour._select(["a", "b"], [], ["r1", "r2"], eqs.__getitem__, np.arange(2),
                           needs, record) is None
    assert not record                   # decided by the structure alone
    M = np.array([[2.136261400290193e-10, -9.127772506153829e-10, 3.481401140932097e-10],
                  [-0.8337553361356009, -0.35607590279527473, -0.4219739220780606],
                  [-0.5091325079640706, 0.20011902008450655, 0.8371000341265268]])
    assert contour._rank(M[None]) == 3 and contour._rank(M[None, :2]) == 1
    u = ("a", "b", "c")
    eqs = {f"k{i}": eq(f"k{i}", M[i][None, :], u) for i in range(3)}
    needs = {k: frozenset(u) for k in eqs}
    # the numbers drop k1 (the first two rows are below the threshold): too few, None
    assert contour._select_numeric(list(u), [], list(eqs), eqs.__getitem__, np.arange(1)) \
        is None
    assert contour._select(list(u), [], list(eqs), eqs.__getitem__, np.arange(1), needs,
                           record) is None
    assert record == [True]             # not independent enough: the numbers decided


def test_terms_shared_between_equations_are_those_built_for_each():
    """An action's projection on a direction, and its moment about a point, are built once
    per context and shared by every equation that holds them: each equation's terms, in
    every method of three specs, are bit for bit those built afresh for it (its direction;
    its centre, a joint's point, a centre of mass or a ground point, named as the equation
    says), and some are shared."""
    from mechreport.forces.builders import force_term, moment_term
    for name in ("r_rtr_rtr", "hydraulic_boom", "stephenson3_six_bar"):
        ctx = ForceContext(solve_kinematics(build_mechanism(load_spec(
            ROOT / "specs" / f"{name}.yaml"))))
        seen: dict[int, int] = {}
        centre_arrays = ([s.r for s in ctx.links.values()] + list(ctx.joint_points.values())
                         + [ctx.point_of(p) for p in ctx.spec.ground])
        for module in METHODS.values():
            for step in module.build_steps(ctx):
                for eq in step.equations:
                    for t in eq.terms:
                        seen[id(t)] = seen.get(id(t), 0) + 1
                        if t.kind == "projection" and t.side == "rhs" and eq.kind != "constraint":
                            d = ctx.axis(eq.axis) if eq.axis in ("x", "y") else \
                                ctx.line_direction(ctx.spec.joint(eq.axis[len("Delta_"):]))
                            fresh = force_term(t.action, d)
                        elif t.kind == "moment":
                            assert t.factor("about") == eq.about, (name, eq.label)
                            centres = [c for c in centre_arrays
                                       if np.array_equal(t.action.at - c, t.lever)]
                            assert centres, (name, eq.label)
                            fresh = moment_term(t.action, centres[0], ctx.n,
                                                about_name=t.factor("about"))
                        else:
                            continue
                        for a, b in ((t.coeffs, fresh.coeffs), (t.const, fresh.const)):
                            assert np.array_equal(np.asarray(a).view(np.uint64),
                                                  np.asarray(b).view(np.uint64)), eq.label
        assert max(seen.values()) > 1, name


def test_forces_at_the_moment_centre_are_those_at_it_at_every_angle():
    """builders.with_moment leaves out the forces applied at the moment centre: a force
    apart from it at the first angle is kept without a look at the others; otherwise the
    whole sweep decides, as the plain rule does (within 1e-12 of 1 m + the centre's largest
    coordinate at every angle; NaN is never at the centre)."""
    from mechreport.forces.builders import with_moment
    from mechreport.forces.equations import Action
    ctx = ForceContext(solve_kinematics(build_mechanism(load_spec(
        ROOT / "specs" / "four_bar.yaml"))))
    n = ctx.n
    rng = np.random.default_rng(7)
    p = rng.normal(size=(n, 2)) * 1e3
    tol = 1e-12 * (1.0 + np.abs(p).max())

    def near(offset):
        return p + offset

    late = np.zeros((n, 2))
    late[-1, 1] = 10 * tol                              # apart at the last angle only
    first = np.zeros((n, 2))
    first[0, 0] = 10 * tol                              # apart at the first angle only
    nan = np.zeros((n, 2))
    nan[n // 2, 0] = np.nan
    cases = {"same": near(0.0), "within": near(0.5 * tol), "late": near(late),
             "first": near(first), "nan": near(nan), "far": near(1.0),
             "nan first": near(np.where(np.arange(n)[:, None] == 0, np.nan, 0.0))}
    acts = [Action(name, "force", "load", "x", at, value=np.zeros((n, 2)))
            for name, at in cases.items()]
    acts.append(Action("M", "couple", "load", "x", value=np.zeros(n)))
    kept = [a.symbol for a in with_moment(ctx, acts, p)]
    plain = [a.symbol for a in acts
             if a.kind != "force" or not (np.abs(a.at - p) <= tol).all()]
    assert kept == plain == ["late", "first", "nan", "far", "nan first", "M"]
    assert [a.symbol for a in with_moment(ctx, acts, p)] == kept     # from the memo


def _shape(mech):
    """A mechanism's structure by name, every joint checked to be its own spec's."""
    own = {j.name: j for j in mech.spec.joints}

    def names(joints):
        assert all(j is own[j.name] for j in joints)
        return tuple(j.name for j in joints)
    groups = [(g.links, names(g.joints), g.driver, g.dyad and (g.dyad.links,
               names(g.dyad.outer), names([g.dyad.inner]))) for g in mech.groups]
    loops = [[(l.links, names(l.joints)) for l in ls] for ls in (mech.loops, mech.cycles)]
    return groups, loops


def test_structure_found_once_per_topology_equals_a_fresh_one(monkeypatch):
    """build_mechanism keeps each topology's structure: another spec of the same topology
    (other numbers) gets it bound to its own joints, equal to one found afresh; another
    order of the joints is another topology."""
    import mechreport.model as model
    from mechreport.spec.loader import parse_spec
    text = (ROOT / "specs" / "r_rtr_rtr.yaml").read_text()
    moved = text.replace("C: [0, 0.06]", "C: [0, 0.07]")
    joints = text.index("  A:   {type: R"), text.index("\ndriver:")
    lines = text[joints[0]:joints[1]].splitlines(keepends=True)
    reordered = text[:joints[0]] + "".join(lines[::-1]) + text[joints[1]:]
    assert moved != text and reordered != text
    specs = [parse_spec(t, "r_rtr_rtr.yaml") for t in (text, text, moved, reordered)]
    monkeypatch.setattr(model, "_STRUCTURES", {})
    kept = [build_mechanism(s) for s in specs]
    assert len(model._STRUCTURES) == 2                  # the reordered joints: another key
    for spec, mech in zip(specs, kept):
        assert mech.spec is spec
        monkeypatch.setattr(model, "_STRUCTURES", {})
        assert _shape(mech) == _shape(build_mechanism(spec))
    assert [g.links for g in kept[0].groups] == [g.links for g in kept[3].groups]


def _contour_context(spec, step=None, plans=None):
    if step is not None:
        spec = dataclasses.replace(spec, sweep=dataclasses.replace(spec.sweep, step=step))
    ctx = ForceContext(solve_kinematics(build_mechanism(spec)))
    ctx.plans = plans
    return ctx


def _steps_as_numbers(steps):
    """Each step's title, unknowns and equations (labels, and every term's numbers)."""
    return [(s.title, list(s.unknowns), [(e.label, [(t.action.symbol, t.coeffs.tobytes(),
                                                      t.const.tobytes()) for t in e.terms])
                                         for e in s.equations]) for s in steps]


def test_contour_plan_replayed_for_a_structure_is_the_search_s_own(monkeypatch):
    """The contour method's plan is kept per structure and replayed for the next spec of
    it (issue 14, the fixed cost): for every spec, replayed from a spec of the same topology
    (itself over another sweep, and the other specs of its topology in the repository), the
    plan and every equation of its steps are bit for bit those a fresh search gives."""
    from mechreport.forces import contour
    from mechreport.model import topology
    paths = sorted((ROOT / "specs").glob("*.yaml")) + sorted((ROOT / "tests" / "data").rglob("*.yaml"))
    specs = [load_spec(p) for p in paths]
    by_topology: dict = {}
    for spec in specs:
        by_topology.setdefault(topology(spec), []).append(spec)
    assert any(len(v) > 1 for v in by_topology.values())   # replays across specs are tried
    replayed = []
    real_replay = contour._replay

    def replay(ctx, plans):
        out = real_replay(ctx, plans)
        replayed.append(out is not None)
        return out
    monkeypatch.setattr(contour, "_replay", replay)
    for spec in specs:
        for step in (spec.sweep.step, (spec.sweep.stop - spec.sweep.start) / 30):
            fresh = _contour_context(spec, step)
            want = contour.plan(fresh), _steps_as_numbers(contour.build_steps(fresh))
            for source in by_topology[topology(spec)]:
                book = contour.ContourPlans()
                contour.plan(_contour_context(source, source.sweep.step / 2, book))   # kept
                if not len(book):
                    continue
                replayed.clear()
                ctx = _contour_context(spec, step, book)
                got = contour.plan(ctx), _steps_as_numbers(contour.build_steps(ctx))
                assert got == want, (spec.file, source.file)
                assert replayed in ([True], [False]), replayed
                if source is spec:
                    assert replayed == [True]
    # a plan that fails its test at the replay falls back to the search
    spec = load_spec(ROOT / "specs" / "r_rtr_rtr.yaml")
    book = contour.ContourPlans()
    good = contour.plan(_contour_context(spec, plans=book))
    [structure] = book.structures()
    twice = dataclasses.replace(good[0], recipes=(good[0].recipes[0],) * 2)   # dependent
    book.keep(structure, (twice,) + good[1:])
    replayed.clear()
    assert contour.plan(_contour_context(spec, plans=book)) == good and replayed == [False]
    assert book.get(structure) == good


def test_contour_plan_is_kept_only_when_the_structure_decided(monkeypatch):
    """A search in which the numerical selection decided anything is not kept: its choice
    hangs on the numbers of its spec. The structure key tells apart two specs of one
    topology whose reactions act at different pins (which changes what a cut names)."""
    from mechreport.forces import contour
    from mechreport.spec.loader import parse_spec
    text = (ROOT / "specs" / "r_rtr_rtr.yaml").read_text()
    spec = parse_spec(text, "r_rtr_rtr.yaml")
    real = contour._verified
    calls = []

    def once_not(unknowns, equations, probes):
        calls.append(1)
        return len(calls) > 1 and real(unknowns, equations, probes)
    book = contour.ContourPlans()
    monkeypatch.setattr(contour, "_verified", once_not)
    contour.plan(_contour_context(spec, plans=book))
    assert calls and not len(book)
    monkeypatch.setattr(contour, "_verified", real)
    contour.plan(_contour_context(spec, plans=book))
    assert len(book) == 1
    # B_T's slider point moved off the pin B: B_T's reaction has a moment about B
    moved = parse_spec(text.replace("points: {B: [0, 0]}", "points: {B: [0, 0], S: [0.02, 0]}")
                       .replace("point: B, line", "point: S, line"), "moved.yaml")
    book = contour.ContourPlans()
    ctx, ctx_moved = _contour_context(spec, plans=book), _contour_context(moved, plans=book)
    assert contour._structure(ctx)[0] == contour._structure(ctx_moved)[0]
    assert contour._structure(ctx) != contour._structure(ctx_moved)
    want = _steps_as_numbers(contour.build_steps(_contour_context(moved)))
    contour.plan(ctx)                                       # r_rtr_rtr's plan kept
    assert _steps_as_numbers(contour.build_steps(ctx_moved)) == want


LONE_CRANK = """
mechreport: 1
name: lone crank
units: {length: m, mass: kg}
gravity: [0, -9.807]
ground: {A: [0, 0]}
links:
  crank: {points: {A: [0, 0], B: [0.1, 0]}, mass: 1.0, inertia: 0.001, com: [0.05, 0]}
joints:
  A: {type: R, links: [ground, crank]}
driver: {joint: A, rpm: 100}
sweep: {start: 0, stop: 360, step: 10}
"""


def test_contour_plan_with_a_bridge_is_replayed_as_searched(monkeypatch):
    """A joint on no loop (a lone crank) is solved as a bridge: the whole part beyond it as
    one free body. Its plan is kept and replayed like any other, bit for bit the search's."""
    from mechreport.forces import contour
    from mechreport.spec.loader import parse_spec
    spec = parse_spec(LONE_CRANK, "lone_crank.yaml")
    book = contour.ContourPlans()
    fresh = _contour_context(spec, plans=book)
    plans = contour.plan(fresh)
    assert [p.recipes[0][0] for p in plans] == ["bridge"] and len(book) == 1
    search = contour._search

    def no_search(ctx):
        raise AssertionError("searched, not replayed")
    monkeypatch.setattr(contour, "_search", no_search)
    got = _steps_as_numbers(contour.build_steps(_contour_context(spec, 5.0, book)))
    monkeypatch.setattr(contour, "_search", search)
    assert got == _steps_as_numbers(contour.build_steps(_contour_context(spec, 5.0)))
    result = analyse(spec)
    assert result.agreement[0].relative < 1e-12
