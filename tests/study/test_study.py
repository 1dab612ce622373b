"""Design studies (`mechreport study`, the spec's `study:` section): plans, variants, the
evaluation seam, execution on a local pool and on a Dask cluster, outputs, the command.

Small sweeps (10-degree steps) keep the whole file fast."""
from __future__ import annotations

import copy
import math
import re
from pathlib import Path

import numpy as np
import pytest

from mechreport.pipeline.analysis import analyse
from mechreport.errors import SpecError
from mechreport.spec import parse_spec
from mechreport.spec.loader import parse_source, spec_from_data
from mechreport.study import evaluate_chunk, plan_of
from mechreport.study.run import run_variants
from mechreport.study.variants import base_of, variant_spec

pytestmark = pytest.mark.slow      # builds reports, starts processes or fuzzes: not in the fast tier

ROOT = Path(__file__).resolve().parents[2]
FOUR_BAR = (ROOT / "specs" / "four_bar.yaml").read_text(encoding="utf-8")
COARSE = FOUR_BAR.replace("sweep: {start: 0, stop: 360, step: 1}",
                          "sweep: {start: 0, stop: 360, step: 10}")
assert COARSE != FOUR_BAR

KEEP = ["cycle.torque.rms", "cycle.flywheel_inertia", "joint.B.f_max",
        "cycle.transmission_angle.min", "joint.A.life_h", "cycle.shaking.force_max"]

GRID = """
study:
  vary:
    - {key: links.coupler.points.C.0, values: [145, 180, 185]}
    - {key: links.coupler.mass, from: 200, to: 240, count: 3}
    - {key: driver.rpm, values: [200, 300, 400]}
  sample: grid
  keep: [%s]
""" % ", ".join(KEEP)


def study_text(section: str, base: str = COARSE) -> str:
    return base.rstrip("\n") + "\n" + section


def base_from(text: str, filename: str = "four_bar.yaml"):
    src = parse_source(text, filename)
    return base_of(spec_from_data(src.data, src), src)


def edited(x: float, mass: float, rpm: float) -> str:
    """The coarse four-bar with C.x, the coupler's mass and the speed edited in its text:
    a variant built independently of the study's data-tree substitution."""
    text = COARSE.replace("coupler:\n    points: {B: [0, 0], C: [180, 0], E: [90, 30]}",
                          f"coupler:\n    points: {{B: [0, 0], C: [{x!r}, 0], E: [90, 30]}}")
    text = text.replace("    mass: 220 ", f"    mass: {mass!r} ")
    text = text.replace("driver: {joint: A, rpm: 300}", f"driver: {{joint: A, rpm: {rpm!r}}}")
    assert text.count(repr(x)) == 1 and f"mass: {mass!r}" in text and f"rpm: {rpm!r}" in text
    return text


# ------------------------------------------------------------------------------ loader

def test_study_section_loads_and_plain_commands_ignore_it():
    spec = parse_spec(study_text(GRID))
    st = spec.study
    assert st.sample == "grid" and st.size == 27 and st.keep == tuple(KEEP)
    assert st.vary[0].path == ("links", "coupler", "points", "C", 0)
    assert st.vary[1].count == 3 and st.vary[1].start == 200 and st.vary[1].stop == 240
    plain = parse_spec(COARSE)
    assert plain.study is None
    # everything but the study is the same spec
    assert spec.links == plain.links and spec.driver == plain.driver


def test_contract_example_loads():
    """The spec-format contract's own example (grid with a count: count is for random/lhs)."""
    text = FOUR_BAR.replace("B: [0, 0], C: [180, 0]", "B: [0, 0], C: [1.2, 0]")
    section = """
study:
  vary:
    - {key: links.coupler.points.C.0, from: 0.9, to: 1.5, count: 25}
    - {key: driver.rpm, values: [600, 900, 1200]}
  sample: grid
  count: 10000
  seed: 1
  keep: [cycle.torque.rms, cycle.flywheel_inertia, joint.B.f_max]
"""
    st = parse_spec(study_text(section, text)).study
    assert st.size == 75 and st.count == 10000 and st.seed == 1


@pytest.mark.parametrize("section, expected", [
    ("study:\n  vary: [{key: links.rod.mass, values: [1]}]\n  keep: [cycle.torque.rms]\n",
     r"study\.vary\[0\]\.key: 'links\.rod\.mass': links has no key 'rod'"),
    ("study:\n  vary: [{key: driver.joint, values: [1]}]\n  keep: [cycle.torque.rms]\n",
     r"must lead to a number of the spec"),
    ("study:\n  vary: [{key: links.coupler.points.C.5, values: [1]}]\n"
     "  keep: [cycle.torque.rms]\n", r"is a list of 2: '5' must be an index from 0 to 1"),
    ("study:\n  vary: [{key: driver.rpm, from: 1, to: 2}]\n  keep: [cycle.torque.rms]\n",
     r"missing required key 'count'"),
    ("study:\n  vary: [{key: driver.rpm, from: 1, to: 2}]\n  sample: lhs\n"
     "  keep: [cycle.torque.rms]\n", r"study: missing required key 'count' \(how many"),
    ("study:\n  vary: [{key: driver.rpm, values: [1]}]\n  sample: sobol\n"
     "  keep: [cycle.torque.rms]\n", r"study\.sample: must be one of grid, random, lhs"),
    ("study:\n  vary: [{key: driver.rpm, values: [1]}]\n  keep: [cycle.torque.rmss]\n",
     r"did you mean 'cycle\.torque\.rms'"),
    ("study:\n  vary: [{key: driver.rpm, values: [1]}]\n  keep: [joint.X.f_max]\n",
     r"study\.keep\[0\]: 'joint\.X\.f_max': no joint named 'X'"),
    ("study:\n  vary: [{key: driver.rpm, values: [1]}]\n  keep: [joint.B.life_h]\n",
     r"needs design\.bearings\.B\.rating"),
    ("study:\n  vary: [{key: expect.0.value, values: [1]}]\n  keep: [cycle.torque.rms]\n",
     r"a study varies the mechanism, not 'expect'"),
    ("study:\n  vary: [{key: driver.rpm, values: [1]}, {key: driver.rpm, values: [2]}]\n"
     "  keep: [cycle.torque.rms]\n", r"varied by study\.vary\[0\] too"),
    ("study:\n  vary: [{key: driver.rpm, values: [1], from: 2}]\n  keep: [cycle.torque.rms]\n",
     r"give either 'values"),
    ("study:\n  vary: [{key: driver.rpm, values: [1]}]\n  seed: -3\n"
     "  keep: [cycle.torque.rms]\n", r"study\.seed: must be a whole number from 0"),
])
def test_study_section_errors_name_line_and_key_path(section, expected):
    with pytest.raises(SpecError) as err:
        parse_spec(study_text(section), "x.yaml")
    text = str(err.value)
    assert re.search(expected, text), text
    assert re.search(r"^x\.yaml:\d+: study", text, re.M), text


def test_check_and_validate_ignore_the_study_section(tmp_path, capsys):
    from mechreport.app.cli import main
    spec = tmp_path / "four_bar.yaml"
    spec.write_text(study_text(GRID), encoding="utf-8")
    assert main(["validate", str(spec)]) == 0
    assert main(["check", str(spec)]) == 0
    assert "PASS" in capsys.readouterr().out


def test_study_needs_cycle_quantities():
    text = COARSE.replace("sweep: {start: 0, stop: 360, step: 10}",
                          "sweep: {start: 0, stop: 180, step: 10}")
    with pytest.raises(SpecError, match="a study tabulates cycle quantities"):
        parse_spec(study_text("study:\n  vary: [{key: driver.rpm, values: [1]}]\n"
                              "  keep: [cycle.torque.rms]\n", text))


# ------------------------------------------------------------------------------- plans

def _lhs_study(sample: str, seed: int, count: int = 20):
    section = f"""
study:
  vary:
    - {{key: links.coupler.points.C.0, from: 170, to: 190}}
    - {{key: driver.rpm, values: [200, 300, 400, 500]}}
  sample: {sample}
  count: {count}
  seed: {seed}
  keep: [cycle.torque.rms]
"""
    return parse_spec(study_text(section)).study


def test_grid_plan_is_every_combination_first_key_slowest():
    plan = plan_of(parse_spec(study_text(GRID)).study)
    assert plan.n == 27
    assert plan.variant(0) == {"links.coupler.points.C.0": 145, "links.coupler.mass": 200,
                               "driver.rpm": 200}
    assert plan.variant(1)["driver.rpm"] == 300 and plan.variant(3)["links.coupler.mass"] == 220
    assert len({tuple(r) for r in plan.values}) == 27


@pytest.mark.parametrize("sample", ["random", "lhs"])
def test_sampled_plans_are_reproducible_from_their_seed(sample):
    a, b, c = (plan_of(_lhs_study(sample, s)) for s in (1, 1, 2))
    assert np.array_equal(a.values, b.values)
    assert not np.array_equal(a.values, c.values)
    x, rpm = a.values[:, 0], a.values[:, 1]
    assert np.all((170 <= x) & (x <= 190)) and set(rpm) <= {200, 300, 400, 500}
    if sample == "lhs":                       # one draw in each of the 20 strata
        strata = np.floor((x - 170) / 20 * 20).astype(int)
        assert sorted(strata) == list(range(20))
        assert sorted(np.bincount((rpm / 100 - 2).astype(int))) == [5, 5, 5, 5]


def test_random_study_table_is_reproducible_from_its_seed():
    runs = []
    for seed in (7, 7, 8):
        section = f"""
study:
  vary:
    - {{key: links.coupler.points.C.0, from: 175, to: 185}}
    - {{key: links.coupler.mass, from: 200, to: 240}}
  sample: random
  count: 4
  seed: {seed}
  keep: [cycle.torque.rms, joint.B.f_max]
"""
        base = base_from(study_text(section))
        plan = plan_of(base.spec.study)
        runs.append(run_variants(base, plan, "newton_euler", base.spec.study.keep, jobs=1))
    assert np.array_equal(runs[0].plan.values, runs[1].plan.values)
    assert np.array_equal(runs[0].values, runs[1].values)
    assert not np.array_equal(runs[0].values, runs[2].values)


# ---------------------------------------------------------------------- the seam, rows

def test_grid_rows_equal_single_spec_analysis_of_each_variant():
    base = base_from(study_text(GRID))
    plan = plan_of(base.spec.study)
    before = copy.deepcopy(base.data)
    table = run_variants(base, plan, "newton_euler", KEEP, jobs=1, chunk=5)
    assert base.data == before                     # variants never modify the shared tree
    assert table.n == 27 and table.done.all() and table.ok.all()
    for i in range(plan.n):
        v = plan.variant(i)
        ref = analyse(parse_spec(edited(v["links.coupler.points.C.0"],
                                        v["links.coupler.mass"], v["driver.rpm"])),
                      methods=["newton_euler"])
        want = np.array([ref.review.values[q] for q in KEEP])
        np.testing.assert_allclose(table.values[i], want, rtol=1e-12, atol=0)
        assert bool(table.passed[i]) == all(x.passed for x in ref.verdicts)
        assert table.failed[i] == "; ".join(x.item for x in ref.verdicts if not x.passed)
    assert 0 < table.passing.sum() < 27             # the grid straddles a design limit


def test_failed_variants_are_rows_with_reasons():
    section = """
study:
  vary:
    - {key: links.coupler.points.C.0, values: [20, 60, 180]}
    - {key: links.coupler.mass, values: [220, -5]}
  keep: [cycle.torque.rms, joint.B.f_max]
"""
    base = base_from(study_text(section))
    plan = plan_of(base.spec.study)
    table = run_variants(base, plan, "dyad", base.spec.study.keep, jobs=1)
    by = {(v["links.coupler.points.C.0"], v["links.coupler.mass"]): i
          for i, v in enumerate(plan.chunk(0, plan.n))}
    ok = by[(180, 220)]
    assert table.ok[ok] and table.reason[ok] == "" and np.isfinite(table.values[ok]).all()
    for x in (20, 60, 180):
        r = table.reason[by[(x, -5)]]
        assert re.fullmatch(r"line \d+: links\.coupler\.mass: must be a positive number, got "
                            r"-5", r), r
    assert "cannot close at the first reference angle" in table.reason[by[(20, 220)]]
    assert table.reason[by[(60, 220)]].startswith("no cycle quantities")   # it locks
    for i in range(plan.n):
        if i != ok:
            assert not table.ok[i] and table.passed[i] == -1
            assert np.isnan(table.values[i]).all()
            assert "four_bar.yaml" not in table.reason[i] and "\n" not in table.reason[i]


def test_evaluate_chunk_turns_any_exception_into_a_row(monkeypatch):
    """A bug in the method breaks the batch, then the variant's own analysis: a row."""
    from mechreport.forces import dyad

    def broken(*a, **k):
        raise ZeroDivisionError("boom")
    base = base_from(study_text(GRID))
    monkeypatch.setattr(dyad, "build_steps", broken)
    rows = evaluate_chunk(base, [{"driver.rpm": 300}], "dyad", ["cycle.torque.rms"])
    assert len(rows) == 1 and not rows[0].ok and rows[0].passed is None
    assert "internal error: ZeroDivisionError: boom" in rows[0].reason


def test_variant_values_are_written_in_the_specs_units():
    base = base_from(study_text(GRID))
    spec = variant_spec(base, {"links.coupler.points.C.0": 185, "links.coupler.mass": 230,
                               "driver.rpm": 600})
    coupler = spec.link("coupler")
    assert coupler.points["C"] == (pytest.approx(0.185), 0.0)       # mm
    assert coupler.mass == pytest.approx(0.230)                      # g
    assert spec.driver.omega == pytest.approx(600 * math.pi / 30)    # rpm
    assert spec.study is None and spec.expect == ()


# ---------------------------------------------------------------------------- methods

def test_default_method_is_the_fastest_that_serves_the_kept_quantities():
    from mechreport.spec import Design
    from mechreport.study.methods import FASTEST, cannot_serve, default_method
    assert default_method(["cycle.torque.rms"], Design()) == FASTEST[0] == "power"
    assert default_method(["joint.B.f_max"], Design()) == FASTEST[1]
    assert default_method(["cycle.torque.rms"], Design(limits={"joint_force": 1.0})) \
        == FASTEST[1]
    assert "cannot give joint.B.f_max" in cannot_serve("power", ["joint.B.f_max"], Design())


# -------------------------------------------------------------------------- execution

SMALL = """
study:
  vary:
    - {key: links.coupler.points.C.0, values: [175, 185]}
    - {key: links.coupler.mass, values: [200, 240]}
    - {key: driver.rpm, values: [0, 300]}
  keep: [cycle.torque.rms, joint.C.f_max, cycle.shaking.force_rms]
"""


def _same(a, b):
    assert np.array_equal(a.values, b.values, equal_nan=True)
    assert np.array_equal(a.passed, b.passed)
    assert a.failed == b.failed and a.reason == b.reason


def test_local_pool_gives_the_serial_table():
    base = base_from(study_text(SMALL))
    plan = plan_of(base.spec.study)
    serial = run_variants(base, plan, "dalembert", base.spec.study.keep, jobs=1)
    pool = run_variants(base, plan, "dalembert", base.spec.study.keep, jobs=2, chunk=1)
    _same(serial, pool)
    # rpm 0 is refused by the loader for this spec (its design sizes a flywheel and rates
    # bearings, which divide by the speed): each such variant is a row with its message
    assert sum(bool(r) for r in pool.reason) == 4
    assert all("the driver is at rest (driver.rpm: 0)" in r for r in pool.reason if r)


def test_dask_local_cluster_gives_the_local_pool_table():
    distributed = pytest.importorskip("distributed")
    base = base_from(study_text(SMALL))
    plan = plan_of(base.spec.study)
    local = run_variants(base, plan, "dalembert", base.spec.study.keep, jobs=2, chunk=3)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        # by address, as `--scheduler` does: its own client, version check, in-order rows
        remote = run_variants(base, plan, "dalembert", base.spec.study.keep, chunk=3,
                              scheduler=cluster.scheduler_address)
    _same(local, remote)


def test_unreachable_scheduler_is_a_clear_error():
    pytest.importorskip("distributed")
    from mechreport.study.cluster import SchedulerError, connect
    with pytest.raises(SchedulerError, match="cannot reach the Dask scheduler at "
                                             "tcp://127.0.0.1:9"):
        connect("tcp://127.0.0.1:9", timeout=1)


# ---------------------------------------------------------------------------- command

def _write(tmp_path: Path, text: str, name: str = "four_bar.yaml") -> Path:
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


def test_cli_study_writes_table_and_report(tmp_path, capsys):
    from mechreport.app.cli import main
    import pyarrow.parquet as pq
    spec = _write(tmp_path, study_text(SMALL))
    out = tmp_path / "out"
    # a report folder already there (as `mechreport build` leaves it) is kept
    (out / "four_bar").mkdir(parents=True)
    (out / "four_bar" / "summary.json").write_text("{}", encoding="utf-8")
    code = main(["study", str(spec), "-o", str(out), "--jobs", "1", "--cross-check", "2",
                 "--reports", "1"])
    captured = capsys.readouterr()
    assert code == 0, captured.err
    folder = out / "four_bar"
    for f in ("study.parquet", "study.csv", "study.md", "study.pdf", "summary.json"):
        assert (folder / f).is_file(), f
    assert not [p for p in out.iterdir() if p.name.startswith((".tmp-", ".old-"))]
    table = pq.read_table(folder / "study.parquet").to_pydict()
    assert table["variant"] == list(range(1, 9))
    assert "joint.C.f_max [N]" in table and "driver.rpm" in table
    assert table["status"].count("failed") == 4
    csv_lines = (folder / "study.csv").read_text(encoding="utf-8").splitlines()
    assert len(csv_lines) == 9 and csv_lines[0].startswith("variant,links.coupler")
    md = (folder / "study.md").read_text(encoding="utf-8")
    for heading in ("## Best variants", "## Pareto front", "## Failed variants",
                    "## Cross-check"):
        assert heading in md
    assert "D'Alembert" in md or "Newton-Euler" in md
    assert "all agree" in captured.out
    [best] = [p for p in (folder / "study-reports").iterdir()    # --reports 1: the best
              if p.name != ".mechreport-html"]                   # (and report.html's script)
    assert re.fullmatch(r"01-variant-\d+", best.name)
    assert (best / "report.pdf").is_file() and (best / "summary.json").is_file()
    variant = parse_spec((best / f"{best.name[3:]}.yaml").read_text(encoding="utf-8"))
    assert variant.study is None and "study variant" in variant.name
    assert f"{best.name}/report.pdf" in md
    assert "variants" in captured.err and "ETA" in captured.err or "100%" in captured.err


def test_cli_study_exit_codes(tmp_path, capsys):
    from mechreport.app.cli import main
    plain = _write(tmp_path, COARSE, "plain.yaml")
    assert main(["study", str(plain), "-o", str(tmp_path / "o")]) == 1
    assert "has no 'study:' section" in capsys.readouterr().err
    spec = _write(tmp_path, study_text(SMALL))
    assert main(["study", str(spec), "-o", str(tmp_path / "o"), "--method", "power"]) == 1
    assert "cannot give joint.C.f_max" in capsys.readouterr().err
    with pytest.raises(SystemExit) as exc:
        main(["study", str(spec), "--jobs", "0"])
    assert exc.value.code == 2
    assert not (tmp_path / "o" / "four_bar").exists()


def test_interrupted_write_leaves_the_folder_as_it_was(tmp_path, monkeypatch):
    from mechreport.app.cli import main
    import mechreport.report.pdf as pdf
    spec = _write(tmp_path, study_text(SMALL))
    out = tmp_path / "out"

    def interrupt(*a, **k):
        raise KeyboardInterrupt
    monkeypatch.setattr(pdf, "compile_typst", interrupt)
    assert main(["study", str(spec), "-o", str(out), "--jobs", "1"]) == 130
    assert sorted(p.name for p in out.iterdir()) == [".mechreport.lock"]


def test_study_refuses_a_folder_that_is_not_mechreports(tmp_path, capsys):
    from mechreport.app.cli import main
    spec = _write(tmp_path, study_text(SMALL))
    mine = tmp_path / "out" / "four_bar"
    mine.mkdir(parents=True)
    (mine / "notes.txt").write_text("mine", encoding="utf-8")
    assert main(["study", str(spec), "-o", str(tmp_path / "out"), "--jobs", "1"]) == 1
    assert "neither a mechreport report nor a study or dynamics folder" in capsys.readouterr().err
    assert sorted(p.name for p in mine.iterdir()) == ["notes.txt"]


def test_a_report_and_a_study_share_their_folder(tmp_path):
    """A build keeps the study beside its report, and a study keeps the report."""
    from mechreport.app import outdir as od
    from mechreport.app.study import install
    final = tmp_path / "four_bar"
    final.mkdir()
    (final / "summary.json").write_text("old report")
    (final / "study.parquet").write_text("study")
    report = od.make_tmp_dir(tmp_path, "four_bar")
    (report / "summary.json").write_text("new report")
    od.swap_in(tmp_path, report, "four_bar")
    assert (final / "summary.json").read_text() == "new report"
    assert (final / "study.parquet").read_text() == "study"
    study = od.make_tmp_dir(tmp_path, "four_bar")
    (study / "study.parquet").write_text("new study")
    install(tmp_path, study, "four_bar")
    assert (final / "summary.json").read_text() == "new report"
    assert (final / "study.parquet").read_text() == "new study"
    only_study = tmp_path / "other"
    only_study.mkdir()
    (only_study / "study.csv").write_text("x")
    assert od.occupied(tmp_path, "other") is not None     # neither a report nor a study
