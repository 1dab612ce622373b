"""``mechreport.tolerance``: samples of the spec's tolerances carried through the analysis;
the statistics checked against linear propagation, a closed-form pass fraction, seeds, the
Dask cluster and a ranking built to have one dominant tolerance."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import mechreport
from mechreport.study.tolerance import (evaluate_samples, run_samples, tolerance_base,
                                        tolerance_plan)
from mechreport.study.tolerance_stats import clopper_pearson, src_shares
from mechreport.spec.loader import parse_source

ROOT = Path(__file__).resolve().parents[2]
FOUR_BAR = (ROOT / "specs" / "four_bar.yaml").read_text(encoding="utf-8")
COARSE = FOUR_BAR.replace("sweep: {start: 0, stop: 360, step: 1}",
                          "sweep: {start: 0, stop: 360, step: 4}")


def with_tolerances(body: str, text: str = COARSE) -> str:
    return text + "\ntolerances:\n" + body


def base_of(text: str):
    return tolerance_base(parse_source(text, "four_bar.yaml"))


def quantity_of(base, key_values: dict, quantity: str) -> float:
    """The kept ``quantity`` of the spec with ``key_values`` written in, analysed as a
    sample is."""
    (s,) = evaluate_samples(base, [key_values], "newton_euler", (quantity,), ())
    assert s.status == "ok", s.reason
    return s.values[0]


# ---------------------------------------------------------------------- the estimators

def test_clopper_pearson_closed_forms():
    # no success in n: the upper end solves (1 - p)^n = alpha / 2; all: the mirror image
    for n in (10, 200):
        low, high = clopper_pearson(0, n)
        assert low == 0 and high == pytest.approx(1 - 0.025 ** (1 / n), rel=1e-9)
        low, high = clopper_pearson(n, n)
        assert high == 1 and low == pytest.approx(0.025 ** (1 / n), rel=1e-9)
    low, high = clopper_pearson(50, 100)
    assert low < 0.5 < high and low == pytest.approx(1 - high, rel=1e-9)


def test_src_shares_of_a_linear_function_are_its_variance_shares():
    rng = np.random.default_rng(3)
    x = rng.normal(size=(4000, 3)) * [1.0, 2.0, 0.5]
    y = 3.0 * x[:, 0] + 1.0 * x[:, 1] + 0.0 * x[:, 2]
    shares, r2 = src_shares(x, y)
    want = np.array([9.0, 4.0, 0.0]) / 13.0
    assert r2 == pytest.approx(1.0)
    assert shares == pytest.approx(want, abs=0.02)


# --------------------------------------------------------------- linear propagation

def test_small_tolerances_std_agrees_with_linear_propagation():
    """Standard deviation of the samples = sqrt(sum (dq/dx_i sigma_i)^2), dq/dx_i by central
    finite differences, within the sampling error of a standard deviation."""
    text = with_tolerances("""\
  vary:
    - {key: links.coupler.points.C.0, tol: 0.2}
    - {key: ground.D.0, sigma: 0.1}
    - {key: links.coupler.mass, from: 215, to: 225}
  count: 200
  seed: 4
  keep: [cycle.torque.rms, joint.B.f_max]
""")
    result = mechreport.tolerance(text, jobs=1)
    base = result.base
    assert result.counts["ok"] == 200
    for j, q in enumerate(("cycle.torque.rms", "joint.B.f_max")):
        var = 0.0
        for v in base.spec.tolerances.vary:
            h = v.std
            up = quantity_of(base, {v.key: v.nominal + h}, q)
            down = quantity_of(base, {v.key: v.nominal - h}, q)
            var += ((up - down) / (2 * h) * v.std) ** 2
        linear = math.sqrt(var)
        got = result.quantities[j].std
        n = result.quantities[j].n
        # the standard error of a sample standard deviation is about std / sqrt(2 (n - 1))
        assert abs(got - linear) <= 3 * linear / math.sqrt(2 * (n - 1)), (q, got, linear)
        assert result.quantities[j].nominal == pytest.approx(
            quantity_of(base, {}, q), rel=1e-12)


# -------------------------------------------------------------- a closed-form fraction

def test_pass_probability_is_the_fraction_of_the_interval_on_the_passing_side():
    """The frame length AD moves the smallest transmission angle (at crank angle 0, where
    cos mu = (BC^2 + DC^2 - (AD - AB)^2) / (2 BC DC)) across a 55 degree limit."""
    text = COARSE.split("\ndesign:")[0] + """
design:
  limits: {transmission_angle: 55}
tolerances:
  vary:
    - {key: ground.D.0, from: 190, to: 210}
  count: 200
  seed: 2
  keep: [cycle.transmission_angle.min]
"""
    result = mechreport.tolerance(text, jobs=1)
    ab, bc, dc = 50.0, 180.0, 120.0
    ad_star = ab + math.sqrt(bc ** 2 + dc ** 2 - 2 * bc * dc * math.cos(math.radians(55)))
    passing = (210 - ad_star) / 20
    (p,) = result.verdicts
    assert p.name == "limits.transmission_angle" and p.n == 200
    assert p.low <= passing <= p.high
    assert p.p == pytest.approx(passing, abs=2 / 200)      # a Latin hypercube: 1 per stratum
    hist = result.quantities[0]
    assert hist.limit == 55 and hist.at_least


# --------------------------------------------------------------- seeds, failures, ranking

def test_seed_reproduces_the_samples_whatever_the_chunks():
    text = with_tolerances("""\
  vary:
    - {key: links.coupler.mass, sigma: 5}
    - {key: links.rocker.points.C.0, tol: 0.3}
  count: 24
  seed: 9
  keep: [cycle.torque.max]
""")
    base = base_of(text)
    tol = base.spec.tolerances
    a, b = tolerance_plan(tol), tolerance_plan(tol)
    assert np.array_equal(a.values, b.values)
    other = tolerance_plan(type(tol)(tol.vary, tol.keep, tol.count, tol.sample, 10))
    assert not np.array_equal(a.values, other.values)
    # a Latin hypercube uses each of the 24 slices of each distribution once
    u = (a.values[:, 1] - 119.7) / 0.6
    assert sorted(np.floor(u * 24).astype(int)) == list(range(24))
    one = run_samples(base, a, "newton_euler", tol.keep, (), jobs=1, chunk=5)
    two = run_samples(base, a, "newton_euler", tol.keep, (), jobs=1, chunk=24)
    assert np.array_equal(one.values, two.values)


def test_dominant_tolerance_is_ranked_first():
    text = with_tolerances("""\
  vary:
    - {key: links.rocker.points.C.0, tol: 0.01}
    - {key: links.coupler.mass, from: 150, to: 300}
    - {key: ground.D.0, tol: 0.01}
  count: 60
  keep: [cycle.torque.rms]
""")
    result = mechreport.tolerance(text, jobs=1)
    (ranking,) = result.ranking
    key, share = ranking.shares[0]
    assert key == "links.coupler.mass" and share > 0.95
    assert ranking.r2 > 0.99


def test_samples_that_cannot_be_built_are_counted_with_their_reasons():
    """A rocker shorter than 70 mm breaks Grashof's condition (50 + 200 > 180 + DC): the
    crank locks; a coupler mass drawn negative is refused by the spec."""
    text = with_tolerances("""\
  vary:
    - {key: links.rocker.points.C.0, from: 60, to: 120}
    - {key: links.coupler.mass, sigma: 150}
  count: 60
  seed: 1
  keep: [cycle.torque.rms]
""")
    result = mechreport.tolerance(text, jobs=1)
    t = result.table
    assert sum(result.counts.values()) == t.n == 60
    locked = result.counts["no assembly"]
    assert locked > 0 and result.counts["invalid"] > 0
    rocker = t.plan.values[:, 0]
    status = np.array(t.status)
    # every sample with a short rocker that the spec accepts locks, and only those
    short = (rocker < 70) & (status != "invalid")
    assert np.all(status[short] == "no assembly")
    assert np.all(status[(rocker > 70.5) & (status != "invalid")] != "no assembly")
    assert result.assembly.k == t.n - locked - result.counts["invalid"]
    reasons = {s: why for s, why, _c, _f in result.reasons}
    assert "locks" in reasons["no assembly"]
    assert "links.coupler.mass" in reasons["invalid"]
    # they are not passing: the design review counts only ok samples
    assert result.design.k <= result.counts["ok"]
    assert all(v == -1 for v in t.design_pass[status != "ok"])


def test_tolerance_refuses_a_spec_without_the_section():
    from mechreport.errors import SpecError
    with pytest.raises(SpecError, match="no 'tolerances:' section"):
        mechreport.tolerance(COARSE, jobs=1)


@pytest.mark.slow
def test_dask_local_cluster_equals_the_local_pool():
    distributed = pytest.importorskip("distributed")
    text = with_tolerances("""\
  vary:
    - {key: links.coupler.mass, sigma: 5}
    - {key: links.rocker.points.C.0, tol: 0.3}
  count: 30
  seed: 5
  keep: [cycle.torque.max, joint.C.f_max]
""")
    base = base_of(text)
    tol = base.spec.tolerances
    plan = tolerance_plan(tol)
    items = ("limits.joint_force",)
    local = run_samples(base, plan, "newton_euler", tol.keep, items, jobs=2, chunk=4)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        from mechreport.study.cluster import close_client, connect
        client = connect(cluster.scheduler_address)
        try:
            remote = run_samples(base, plan, "newton_euler", tol.keep, items, chunk=4,
                                 client=client)
        finally:
            close_client(client)
    assert np.array_equal(local.values, remote.values)
    assert local.status == remote.status and np.array_equal(local.passes, remote.passes)


def test_files_and_report_hold_every_sample_and_every_figure(tmp_path):
    """tolerance.csv and tolerance.parquet: one row per sample, its status; tolerance.md:
    each section, the numbers of the result (figures left out: the command's test)."""
    import csv

    import pyarrow.parquet as pq

    from mechreport.report.write_markdown import markdown
    from mechreport.study.tolerance_outputs import write_csv, write_parquet
    from mechreport.study.tolerance_report import build_document
    text = with_tolerances("""\
  vary:
    - {key: links.rocker.points.C.0, from: 60, to: 120}
  count: 12
  seed: 1
  keep: [cycle.torque.rms]
""")
    result = mechreport.tolerance(text, jobs=1)
    write_csv(result.table, tmp_path / "t.csv")
    write_parquet(result.table, tmp_path / "t.parquet")
    with open(tmp_path / "t.csv", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    assert [r["status"] for r in rows] == result.table.status
    assert any(r["status"] == "no assembly" and r["reason"] and r["design_pass"] == ""
               and r["cycle.torque.rms [N·m]"] == "" for r in rows)
    assert pq.read_table(tmp_path / "t.parquet").num_rows == 12
    md = markdown(build_document(result, {}))
    locked = result.counts["no assembly"]
    assert f"| cannot be assembled over the sweep | {locked} |" in md
    assert "## Samples without a result" in md and "no assembly" in md
    assert f"{result.design.k / 12 * 100:.1f} %" in md or result.design.k in (0, 12)


def test_a_nominal_design_that_cannot_be_analysed_is_refused_before_sampling():
    from mechreport.errors import MechreportError
    locked = COARSE.replace("rocker:\n    points: {D: [0, 0], C: [120, 0]}",
                            "rocker:\n    points: {D: [0, 0], C: [60, 0]}")
    assert locked != COARSE
    text = with_tolerances("  vary: [{key: links.coupler.mass, tol: 5}]\n  keep: "
                           "[cycle.torque.max]\n", locked)
    with pytest.raises(MechreportError, match="the spec as written cannot be analysed "
                                              r"\(no assembly: .*locks"):
        mechreport.tolerance(text, jobs=1)


def test_the_limit_of_a_quantity_is_the_verdict_judged_on_it():
    from mechreport.post.verdicts import Verdict
    from mechreport.study.tolerance_stats import limit_of
    verdicts = [Verdict("limits.joint_force", "joint.*.f_max", 90.0, 100.0, "N"),
                Verdict("limits.fatigue_safety", "member.*.fatigue_safety", 2.0, 1.5, "",
                        True),
                Verdict("motor.rated_torque", "cycle.torque.rms", 3.0, 4.0, "N·m")]
    assert limit_of("joint.B.f_max", verdicts) == (100.0, False, "limits.joint_force")
    assert limit_of("member.rod.fatigue_safety", verdicts) == (1.5, True,
                                                               "limits.fatigue_safety")
    assert limit_of("cycle.torque.rms", verdicts) == (4.0, False, "motor.rated_torque")
    assert limit_of("cycle.torque.max", verdicts) == (None, False, "")


def test_one_ok_sample_has_no_spread_to_report():
    """Only one sample assembles (a rocker below 70 mm locks the crank): its standard
    deviation is undefined, not 0, and the histogram does not say that the tolerances do not
    move the quantity (the nominal 2.28 N·m is far from that sample's value)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from mechreport.report.write_markdown import markdown
    from mechreport.study.tolerance_report import build_document, draw_histogram, hist_data
    text = with_tolerances("""\
  vary:
    - {key: links.rocker.points.C.0, from: 55, to: 78}
  count: 2
  seed: 1
  keep: [cycle.torque.rms]
""")
    result = mechreport.tolerance(text, jobs=1)
    assert result.counts["ok"] == 1, result.table.status
    s = result.quantities[0]
    assert s.n == 1 and math.isnan(s.std)
    assert "tolerance.cycle.torque.rms.std" not in result.summary()
    assert "tolerance.cycle.torque.rms.mean" in result.summary()
    row = [line for line in markdown(build_document(result, {})).splitlines()
           if line.startswith("| cycle.torque.rms")][0]
    assert row.split("|")[4].strip() == "—"
    fig, ax = plt.subplots()
    draw_histogram(ax, hist_data(result, 0))
    said = " ".join(t.get_text() for t in ax.texts)
    plt.close(fig)
    assert "one ok sample only" in said and "do not move" not in said


def test_a_sample_whose_analysis_failed_is_not_known_to_assemble(monkeypatch):
    """Samples whose analysis stops with an error (not an assembly error: a solver's, or a
    worker lost with them) were counted as assembling (every sample but 'no assembly' and
    'invalid'): the probability of assembly was 100 % with no sample analysed."""
    from dataclasses import replace

    import mechreport.pipeline.batch as batch
    real = batch.analyse_variants
    calls = {"n": 0}

    def failing(specs, method):
        calls["n"] += 1
        out = real(specs, method)
        if calls["n"] == 1:             # the nominal design, analysed first
            return out
        return [replace(o, exception=RuntimeError("the solver gave up")) for o in out]

    monkeypatch.setattr(batch, "analyse_variants", failing)
    text = with_tolerances("""\
  vary:
    - {key: links.coupler.mass, tol: 5}
  count: 4
  keep: [cycle.torque.rms]
""")
    result = mechreport.tolerance(text, jobs=1)
    assert result.counts["failed"] == 4 and calls["n"] > 1
    assert result.assembly.k == 0 and result.assembly.p == 0
    assert result.summary()["tolerance.assembly.p"]["value"] == 0


@pytest.mark.parametrize("nominal, drawn", [(3.841, False), (2.9905, True)])
def test_the_histogram_shows_the_nominal_value_wherever_it_lies(nominal, drawn):
    """A range beside the spec's value (tolerances.vary from/to need not hold it): the
    legend named a nominal line that lay outside the axes. Near the samples the axes take
    it in; far from them an arrow at the edge says where it is."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from mechreport.study.tolerance_report import HistData, draw_histogram
    values = np.linspace(2.976, 2.988, 200)
    fig, ax = plt.subplots()
    draw_histogram(ax, HistData("cycle.torque.max", "N·m", values, nominal, 2.9766, 2.9874))
    left, right = ax.get_xlim()
    said = " ".join(t.get_text() for t in ax.texts)
    lines = [ln.get_xdata()[0] for ln in ax.get_lines()]
    plt.close(fig)
    if drawn:
        assert nominal in lines and left < nominal < right
    else:
        assert nominal not in lines and "nominal 3.841 N·m →" in said


def test_a_failed_sample_has_no_verdicts_in_the_files(monkeypatch, tmp_path):
    """A sample analysed but with a kept quantity undefined is 'failed': the report does not
    count its verdicts, and tolerance.csv's verdict columns must be empty for it as well
    (they said true, so counting them gave a higher probability than the report's)."""
    import csv
    from dataclasses import replace

    import mechreport.study.tolerance as tol
    from mechreport.study.tolerance_outputs import write_csv
    from mechreport.study.tolerance import SampleTable
    real = tol.row_of
    monkeypatch.setattr(tol, "row_of", lambda outcome, keep: replace(
        real(outcome, keep), reason="cycle.efficiency is undefined here"))
    base = base_of(with_tolerances("""\
  vary:
    - {key: links.coupler.mass, tol: 5}
  count: 2
  keep: [cycle.torque.rms]
"""))
    items = ("motor.rated_torque", "limits.joint_force")
    (s,) = evaluate_samples(base, [{"links.coupler.mass": 221.0}], "newton_euler",
                            ("cycle.torque.rms",), items)
    assert s.status == "failed" and s.passes == (-1, -1)
    table = SampleTable(tolerance_plan(base.spec.tolerances), ("cycle.torque.rms",), items)
    table.put(0, [s, s])
    write_csv(table, tmp_path / "t.csv")
    with open(tmp_path / "t.csv", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    assert all(r["verdict.motor.rated_torque"] == "" and r["design_pass"] == "" for r in rows)


def test_a_sample_that_locks_does_not_assemble_whatever_its_member_quantities():
    """Kept member quantities and member verdicts are defined over the angles a mechanism
    reaches: a sample whose crank cannot turn (longer than the 400 mm rod) was 'ok' and
    could pass, and the probability of assembly was 100 %."""
    from optimize_specs import crank_press
    text = crank_press(380, """
design:
  limits:
    static_safety: 0.01
tolerances:
  vary:
    - {key: links.crank.points.B.0, from: 370, to: 430}
  count: 6
  seed: 2
  keep: [member.rod.stress_max]
""")
    result = mechreport.tolerance(text, jobs=1)
    crank = result.table.plan.values[:, 0]
    status = np.array(result.table.status)
    assert np.all(status[crank > 400.5] == "no assembly")
    assert np.all(status[crank < 399.5] == "ok")
    n_turn = int(np.count_nonzero(crank < 400))
    assert 0 < n_turn < 6
    assert result.assembly.k == n_turn and result.design.k <= n_turn


def test_the_nonlinear_note_reads_as_words():
    """'**Nonlinear:**the linear fit ...': the space was inside the bold, which the
    Markdown writer trims."""
    from dataclasses import replace

    from mechreport.report.write_markdown import markdown
    from mechreport.study.tolerance_report import build_document
    result = mechreport.tolerance(with_tolerances("""\
  vary:
    - {key: links.coupler.mass, tol: 5}
  count: 4
  keep: [cycle.torque.rms]
"""), jobs=1)
    result.ranking[0] = replace(result.ranking[0], r2=0.5)
    assert "**Nonlinear:** the linear fit explains" in markdown(build_document(result, {}))
