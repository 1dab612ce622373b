"""``mechreport optimize`` and ``mechreport.optimize``: the feasible optimum, proven; the
traps it must not fall into; reproducibility."""
from __future__ import annotations

import math

import numpy as np
import pytest

import mechreport
from mechreport.app.cli import main
from mechreport.study.optimize import optimize

from optimize_specs import CONSTRAINED, INFEASIBLE, TRAP


def test_branch_jump_trap_is_never_the_optimum():
    r = optimize(TRAP)
    assert r.feasible
    a = r.analysis                                  # every method, from optimum.yaml's text
    assert [b.sign for b in a.kinematics.branches] == [1]
    assert r.values["assembly.C.1"] > 0             # the hint keeps C above AD
    # the trap was in the box, lower than the optimum, and refused as the other branch
    trapped = [j for j in r.history.judged if j.faults and math.isfinite(j.objective)
               and j.objective < r.objective]
    assert trapped
    assert all("assembly branch" in j.faults[0] for j in trapped)


def test_seed_reproduces_the_search():
    one = optimize(TRAP, budget=60, seed=5)
    two = optimize(TRAP, budget=60, seed=5)
    other = optimize(TRAP, budget=60, seed=6)
    assert np.array_equal(np.array(one.history.values), np.array(two.history.values))
    assert one.values == two.values
    assert not np.array_equal(np.array(one.history.values), np.array(other.history.values))


def test_infeasible_box_exits_1_with_the_least_violating_design(tmp_path, capsys):
    spec = tmp_path / "infeasible.yaml"
    spec.write_text(INFEASIBLE, encoding="utf-8")
    assert main(["optimize", str(spec), "-o", str(tmp_path / "out"), "--jobs", "1"]) == 1
    err = capsys.readouterr().err
    assert "the least violating design links.coupler.points.C.0 = " in err
    assert "cycle.transmission_angle.min >= 85 deg: 59.0" in err and "missed by" in err
    folder = tmp_path / "out" / "infeasible"
    assert (folder / "history.csv").is_file() and (folder / "optimize.pdf").is_file()
    assert "No feasible design was found." in (folder / "optimize.md").read_text("utf-8")
    assert not (folder / "optimum").exists()
    # optimum.yaml holds the least violating values and says so (it said "The optimum")
    head = (folder / "optimum.yaml").read_text("utf-8").split("\nmechreport:")[0]
    assert head.startswith("# NOT an optimum: mechreport optimize found no feasible design")
    assert "The optimum" not in head and "cycle.transmission_angle.min >= 85 deg" in head


def test_optimum_yaml_is_the_users_text_and_check_passes(tmp_path, capsys):
    spec = tmp_path / "trap.yaml"
    written = TRAP.replace("budget: 120", "budget: 40")
    spec.write_text(written, encoding="utf-8")
    assert main(["optimize", str(spec), "-o", str(tmp_path / "out"), "--jobs", "1"]) == 0
    folder = tmp_path / "out" / "trap"
    text = (folder / "optimum.yaml").read_text("utf-8")
    body = [line for line in text.splitlines() if not line.startswith("#")]
    original = [line for line in written.splitlines() if not line.startswith("#")]
    changed = [(a, b) for a, b in zip(original, body) if a != b]
    # only the two varied values changed, each in place; comments kept
    assert len(body) == len(original) and len(changed) == 2
    assert changed[0][1].startswith("    points: {B: [0, 0], C: [")
    assert changed[1][1].startswith("assembly: {C: [196, ")
    assert "# open configuration: C above the frame line AD" in changed[1][1]
    assert main(["check", str(folder / "optimum.yaml")]) == 0
    assert (folder / "optimum" / "report.pdf").is_file()
    header = (folder / "history.csv").read_text("utf-8").splitlines()[0]
    assert header.startswith("evaluation,phase,generation,assembly.C.1,")


def test_expect_entries_are_taken_out_of_optimum_yaml():
    from optimize_specs import FOUR_BAR
    text = FOUR_BAR.replace("mechreport: 1\n", "mechreport: 1.2\n").replace(
        "sweep: {start: 0, stop: 360, step: 1}", "sweep: {start: 0, stop: 360, step: 6}") + """
optimize:
  vary:
    - {key: links.coupler.points.C.0, from: 175, to: 185}
  minimize: cycle.torque.rms
  budget: 20
"""
    r = optimize(text)
    assert r.feasible
    assert "expect:" not in r.text.replace("# expect: removed", "")
    assert "# expect: removed by mechreport optimize" in r.text
    assert mechreport.analyse(r.text).passed


@pytest.mark.slow
def test_constrained_optimum_lies_on_the_constraint_and_beats_a_fine_grid():
    r = optimize(CONSTRAINED)
    assert r.feasible
    (c, margin), = r.active()
    assert c.quantity == "cycle.transmission_angle.min" and 0 <= margin <= 1e-3
    # an independent brute force: every design of a fine grid analysed by itself
    from mechreport.study.run import run_study
    steps = (41, 41)
    grid = CONSTRAINED[:CONSTRAINED.index("optimize:")] + f"""
study:
  vary:
    - {{key: links.coupler.points.C.0, from: 150, to: 220, count: {steps[0]}}}
    - {{key: links.rocker.points.C.0, from: 100, to: 200, count: {steps[1]}}}
  keep: [cycle.torque.rms, cycle.transmission_angle.min]
"""
    t = run_study(grid, jobs=1)
    rms = t.values[:, 0].reshape(steps)
    mu = t.values[:, 1].reshape(steps)
    ok = t.ok.reshape(steps) & (mu >= 40)
    best = np.nanmin(np.where(ok, rms, np.nan))
    # the objective's change over one grid step, near the grid's best
    i, j = np.argwhere(ok & (rms == best))[0]
    near = rms[max(i - 1, 0):i + 2, max(j - 1, 0):j + 2]
    resolution = np.nanmax(np.abs(near - best))
    assert r.objective <= best + resolution
    assert r.objective >= best - 2 * resolution      # and no better than the grid allows


@pytest.mark.slow
def test_local_pool_and_dask_give_the_in_process_optimum():
    distributed = pytest.importorskip("distributed")
    here = optimize(TRAP, budget=80, seed=2)
    pool = optimize(TRAP, budget=80, seed=2, jobs=2)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        dask = optimize(TRAP, budget=80, seed=2, scheduler=cluster.scheduler_address)
    for other in (pool, dask):
        assert np.array_equal(np.array(here.history.values), np.array(other.history.values))
        assert other.values == here.values


def test_a_candidate_that_loses_angles_or_its_branch_is_infeasible():
    from dataclasses import replace

    from mechreport.pipeline.batch import analyse_variants
    from mechreport.study.optimize import load_optimize_base, problem_of
    from mechreport.study.optimize_eval import OTHER_BRANCH, judge_outcome, score
    from mechreport.study.variants import variant_spec
    base = load_optimize_base(TRAP)
    problem, _, _ = problem_of(base)
    spec = variant_spec(base, {"assembly.C.1": 120, "links.coupler.points.C.0": 180})
    outcome, = analyse_variants([spec], problem.method)
    good = judge_outcome(problem, outcome)
    assert good.feasible and score(problem, good) < 1
    lost = judge_outcome(problem, replace(outcome, left_out=(16.0, 24.0)))
    assert not lost.feasible and score(problem, lost) > 1
    assert lost.faults == ("leaves out 2 angle(s) that the original analyses (16, 24)",)
    other = replace(outcome, branches=tuple(replace(b, sign=-b.sign)
                                            for b in outcome.branches))
    flipped = judge_outcome(problem, other)
    assert flipped.violation == OTHER_BRANCH and "assembly branch" in flipped.faults[0]


@pytest.mark.slow
def test_a_build_and_an_optimisation_into_one_folder_keep_each_other(tmp_path, capsys):
    spec = tmp_path / "trap.yaml"
    spec.write_text(TRAP.replace("budget: 120", "budget: 20"), encoding="utf-8")
    out = tmp_path / "out"
    assert main(["optimize", str(spec), "-o", str(out), "--jobs", "1"]) == 0
    assert main(["build", str(spec), "-o", str(out), "-q"]) == 0
    folder = out / "trap"
    assert (folder / "optimize.md").is_file() and (folder / "optimum" / "report.md").is_file()
    assert main(["optimize", str(spec), "-o", str(out), "--jobs", "1"]) == 0
    assert (folder / "report.md").is_file() and (folder / "summary.json").is_file()


def test_a_design_that_fails_its_proof_is_not_the_optimum(monkeypatch):
    """The proof refuses the best design (as if its methods disagreed): the next best
    feasible design is proven and reported instead."""
    import dataclasses

    import mechreport.study.optimize as opt
    real = opt.judge_outcome
    calls = {"n": 0}

    def judge(problem, outcome):
        judged = real(problem, outcome)
        calls["n"] += 1
        if calls["n"] == 2:                  # 1: the original; 2: the first proof
            return dataclasses.replace(judged, faults=("the methods disagree",),
                                       violation=1.0)
        return judged
    monkeypatch.setattr(opt, "judge_outcome", judge)
    r = optimize(TRAP, budget=40)
    first, second = r.proofs[:2]
    assert not first.ok and "the methods disagree" in first.why
    assert second.ok and r.optimum == second.index != first.index
    assert r.objective >= r.history.judged[first.index].objective


def test_a_feasible_original_in_the_box_is_never_lost():
    """A wide box in which almost nothing assembles (the crank turns only when it is the
    shortest link) and a small budget: the first population held no feasible design and the
    search stopped there, reporting no feasible design although the spec's own design, in
    the box, is one. The original is a member of the first population."""
    from optimize_specs import four_bar
    needle = four_bar(step=8) + """
optimize:
  vary:
    - {key: links.crank.points.B.0, from: 10, to: 2000}
  minimize: cycle.torque.rms
  budget: 12
  seed: 0
"""
    r = optimize(needle)
    assert r.original.feasible
    assert r.feasible and r.objective <= r.original.objective
    assert r.history.values[0][0] == pytest.approx(50.0, rel=1e-12)   # the spec's own crank


def test_without_an_optimum_the_verdict_table_shows_the_least_violating_design():
    """optimize.md's verdict table had an 'optimum' column left blank when nothing was
    feasible, while the constraints table gave the least violating design's margins."""
    from mechreport.report.write_markdown import markdown
    from mechreport.study.optimize_report import build_document
    from optimize_specs import four_bar
    text = four_bar(step=8, design=True) + """
optimize:
  vary:
    - {key: links.coupler.points.C.0, from: 170, to: 190}
  minimize: cycle.torque.rms
  subject_to:
    - {quantity: cycle.transmission_angle.min, min: 85, unit: deg}
  budget: 10
"""
    r = optimize(text)
    assert not r.feasible and r.judged is not None
    md = markdown(build_document(r, {}))
    header = [line for line in md.splitlines() if line.startswith("| design verdict")][0]
    assert "least violating" in header and "optimum" not in header
    row = [line for line in md.splitlines() if line.startswith("| limits.joint")][0]
    assert "pass (+" in row


def test_when_every_proof_fails_the_least_violating_design_says_why(monkeypatch):
    """Every design the search found feasible fails its proof: the least violating design
    is one of them, and it was reported as missing nothing (an empty list under 'misses:')."""
    import dataclasses

    import mechreport.study.optimize as opt
    from mechreport.report.write_markdown import markdown
    from mechreport.study.optimize_report import build_document
    real = opt.judge_outcome
    calls = {"n": 0}

    def judge(problem, outcome):
        judged = real(problem, outcome)
        calls["n"] += 1
        if calls["n"] >= 2:                  # 1: the original; then every proof
            return dataclasses.replace(judged, faults=("the methods disagree",),
                                       violation=1.0)
        return judged
    monkeypatch.setattr(opt, "judge_outcome", judge)
    r = optimize(TRAP, budget=40)
    assert not r.feasible and r.proofs and not any(p.ok for p in r.proofs)
    missed = r.judged.missed(r.problem)
    assert not r.judged.feasible
    assert any("its proof failed: the methods disagree" in line for line in missed)
    assert "its proof failed: the methods disagree" in markdown(build_document(r, {}))


def test_a_candidate_that_locks_is_infeasible_even_when_the_original_locks():
    """Member quantities are defined over the angles a mechanism reaches, so a crank that
    cannot turn had a fatigue safety, and leaving out no angle the (locking) original did
    not, it was 'feasible': a proven optimum that locks over half its turn."""
    from mechreport.study.optimize import load_optimize_base, problem_of
    from mechreport.study.optimize_eval import judge_chunk
    from optimize_specs import crank_press
    base = load_optimize_base(crank_press(430, """
optimize:
  vary:
    - {key: links.crank.points.B.0, from: 300, to: 450}
  maximize: member.rod.fatigue_safety
  budget: 10
"""))
    problem, original, _ = problem_of(base)
    assert not original.kinematics.motion.full            # the original locks too
    _, (locks, turns) = judge_chunk(problem, 0, np.array([[410.0], [300.0]]))
    assert not locks.feasible and any("cannot make a full turn" in f for f in locks.faults)
    assert math.isfinite(locks.objective)                  # it had a value: the trap
    assert turns.feasible


def test_a_member_objective_is_scaled_by_the_original_value():
    """The objective is scaled by the original's value so that the search's scores resolve
    it; a member quantity's was not found (looked up among the cycle quantities only): a
    stress in Pa scaled by 1 gave scores equal to 1e-8 and the search stopped after two
    generations."""
    from mechreport.study.optimize import load_optimize_base, problem_of
    from optimize_specs import crank_press
    base = load_optimize_base(crank_press(100, """
optimize:
  vary:
    - {key: links.rod.points.C.0, from: 300, to: 600}
  minimize: member.rod.stress_max
  subject_to:
    - {quantity: member.rod.fatigue_safety, min: 0.5}
  budget: 10
"""))
    problem, a, _ = problem_of(base)
    stress = a.strength.values["member.rod.stress_max"]
    assert stress > 1e6 and problem.scale == pytest.approx(stress, rel=1e-12)
    safety = a.strength.values["member.rod.fatigue_safety"]
    assert safety > 0.5 and problem.constraints[-1].scale == pytest.approx(safety, rel=1e-12)
