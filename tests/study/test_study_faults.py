"""A study survives what goes wrong around it: a worker process or a Dask task lost, a lost
Dask scheduler or workers, a bad scheduler address, names that look like numbers in the
variants' spec files, a report that cannot be written, and a --jobs beyond the machine.

Faults are injected into the task functions from FAULTS_* environment variables (read in the
worker, so the same module-level wrappers work in spawned pool processes and in Dask
workers): FAULTS_DIR (a folder where each try of a chunk appends a line to ``tries-START``),
FAULTS_AT (chunk starts, comma-separated, or ``all``), FAULTS_TIMES (how many tries fail)
and FAULTS_HOW (``exit``: os._exit(1); ``comm``: CommClosedError; ``killed``: KilledWorker;
``bug``: ValueError; ``kill-scheduler``: SIGKILL the pid in FAULTS_DIR/scheduler.pid;
``close-worker``: the Dask worker closes). Hangs are bounded by the counted tries, and by
subprocess timeouts only as a guard."""
from __future__ import annotations

import dataclasses
import json
import math
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import mechreport.study.cluster as cl
import mechreport.study.executor as ex
import mechreport.study.run as sr
from mechreport.spec import parse_spec
from mechreport.spec.loader import parse_source, spec_from_data
from mechreport.study import plan_of
from mechreport.study.variants import base_of, dump_yaml, variant_data, variant_spec, variant_yaml

pytestmark = pytest.mark.slow      # starts processes and clusters

ROOT = Path(__file__).resolve().parents[2]
FOUR_BAR = (ROOT / "specs" / "four_bar.yaml").read_text(encoding="utf-8")
COARSE = FOUR_BAR.replace("sweep: {start: 0, stop: 360, step: 1}",
                          "sweep: {start: 0, stop: 360, step: 10}")
SMALL = """
study:
  vary:
    - {key: links.coupler.points.C.0, values: [175, 185]}
    - {key: links.coupler.mass, values: [200, 240]}
    - {key: driver.rpm, values: [250, 300]}
  keep: [cycle.torque.rms, joint.C.f_max]
"""
_TASK = sr.chunk_task          # the real task (in a worker too: imported afresh there)


# ------------------------------------------------------------------------ fault injection

def _fault(start: int) -> None:
    where = os.environ.get("FAULTS_DIR")
    if not where:
        return
    at = os.environ.get("FAULTS_AT", "all")
    if at != "all" and start not in {int(x) for x in at.split(",")}:
        return
    log = Path(where) / f"tries-{start}"
    with open(log, "a", encoding="utf-8") as fh:
        fh.write("try\n")
    if len(log.read_text(encoding="utf-8").splitlines()) > int(os.environ.get("FAULTS_TIMES",
                                                                              "1000")):
        return
    how = os.environ.get("FAULTS_HOW", "exit")
    if how == "exit":
        os._exit(1)
    if how == "comm":
        from distributed.comm import CommClosedError
        raise CommClosedError("injected: connection closed")
    if how == "killed":
        from distributed import KilledWorker
        from types import SimpleNamespace
        raise KilledWorker("injected", SimpleNamespace(address="tcp://127.0.0.1:1"), 3)
    if how == "bug":
        raise ValueError("injected bug")
    if how == "kill-scheduler":
        pid = int((Path(where) / "scheduler.pid").read_text())
        os.kill(pid, signal.SIGKILL)
        time.sleep(1.0)
        return
    if how == "close-worker":
        from distributed import get_worker
        worker = get_worker()
        # the chunks done before this one reach the client first (their results travel on the
        # worker's event loop while this task sleeps; on a busy machine, closing at once could
        # also lose the first chunk's rows, which the test counts as kept)
        time.sleep(1.0)
        worker.loop.add_callback(worker.close)
        time.sleep(2.0)
        return
    raise AssertionError(how)


def _faulty_task(base, start, keys, values, method, keep):
    _fault(start)
    return _TASK(base, start, keys, values, method, keep)


def _faults(monkeypatch, tmp_path: Path, at="all", times=1000, how="exit") -> Path:
    where = tmp_path / "faults"
    where.mkdir(parents=True, exist_ok=True)
    monkeypatch.setenv("FAULTS_DIR", str(where))
    monkeypatch.setenv("FAULTS_AT", str(at))
    monkeypatch.setenv("FAULTS_TIMES", str(times))
    monkeypatch.setenv("FAULTS_HOW", how)
    monkeypatch.setattr(sr, "chunk_task", _faulty_task)
    monkeypatch.setattr(sr, "usable_cores", lambda: 2)     # a pool even on one core
    return where


def _tries(where: Path) -> dict[int, int]:
    return {int(p.name.split("-")[1]): len(p.read_text(encoding="utf-8").splitlines())
            for p in where.glob("tries-*")}


def _base(text: str = COARSE + SMALL, filename: str = "four_bar.yaml"):
    src = parse_source(text, filename)
    return base_of(spec_from_data(src.data, src), src)


def _serial(base):
    plan = plan_of(base.spec.study)
    return sr.run_variants(base, plan, "dalembert", base.spec.study.keep, jobs=1)


def _run(base, **kw):
    plan = plan_of(base.spec.study)
    lost, said = [], []
    table = sr.run_variants(base, plan, "dalembert", base.spec.study.keep, lost=lost,
                            notify=said.append, **kw)
    return table, lost, said


def _same_rows(a, b, rows):
    for i in rows:
        assert np.array_equal(a.values[i], b.values[i], equal_nan=True), i
        assert a.passed[i] == b.passed[i] and a.reason[i] == b.reason[i], i


# ------------------------------------------------------------- item 6: the local pool

def test_a_worker_process_that_dies_once_costs_only_a_retry_of_its_chunk(tmp_path,
                                                                         monkeypatch):
    base = _base()
    serial = _serial(base)
    where = _faults(monkeypatch, tmp_path, at=2, times=1)
    table, lost, said = _run(base, jobs=2, chunk=2)
    assert lost == []
    _same_rows(table, serial, range(table.n))
    assert table.done.all()
    assert _tries(where) == {2: 2}                   # died once, done the second time
    assert len(said) == 1 and re.search(r"a worker process died .*while computing variant\(s\) "
                                        r"3-4; computing them again \(try 2 of 3\)", said[0])


def test_a_chunk_whose_worker_always_dies_fails_its_rows_after_three_tries(tmp_path,
                                                                           monkeypatch):
    base = _base()
    serial = _serial(base)
    where = _faults(monkeypatch, tmp_path, at=4)
    table, lost, said = _run(base, jobs=2, chunk=2)
    assert _tries(where) == {4: ex.MAX_TRIES}
    assert lost == [ex.Lost(4, 6, "a worker process died while computing this variant "
                                  "(after 3 tries)")]
    for i in (4, 5):
        assert not table.ok[i] and table.reason[i] == lost[0].reason
        assert np.isnan(table.values[i]).all() and table.passed[i] == -1
    _same_rows(table, serial, [0, 1, 2, 3, 6, 7])     # the other chunks are kept
    assert table.done.all()
    assert sum("try" in s for s in said) == 2


def test_workers_dying_on_every_chunk_stop_the_study_after_three_chunks(tmp_path,
                                                                         monkeypatch):
    base = _base()
    where = _faults(monkeypatch, tmp_path)                 # every chunk, every try
    table, lost, said = _run(base, jobs=2, chunk=1)
    tries = _tries(where)
    # at most GIVE_UP_AFTER chunks lost for good, plus the one on the other process
    assert len(tries) <= ex.GIVE_UP_AFTER + 1
    assert sum(tries.values()) <= (ex.GIVE_UP_AFTER + 1) * ex.MAX_TRIES
    assert table.done.all() and not table.ok.any()
    assert sum(x.count for x in lost) == 8
    assert any(r.startswith("not computed: the study stopped after 3 chunks in a row")
               for r in table.reason)
    assert any("the study stops here" in s for s in said)


def test_without_a_lost_list_a_lost_chunk_still_fails_the_run(tmp_path, monkeypatch):
    from mechreport.errors import MechreportError
    base = _base()
    plan = plan_of(base.spec.study)
    _faults(monkeypatch, tmp_path, at=0)
    with pytest.raises(MechreportError, match="a worker process died"):
        sr.run_variants(base, plan, "dalembert", base.spec.study.keep, jobs=2, chunk=4)


def _write(tmp_path: Path, text: str, name: str = "four_bar.yaml") -> Path:
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


def test_cli_study_with_a_lost_chunk_writes_the_rest_and_exits_1(tmp_path, monkeypatch,
                                                                 capsys):
    import pyarrow.parquet as pq
    from mechreport.app.cli import main
    spec = _write(tmp_path, COARSE + SMALL)
    _faults(monkeypatch, tmp_path, at=3)
    code = main(["study", str(spec), "-o", str(tmp_path / "out"), "--jobs", "2",
                 "--chunk", "1"])
    err = capsys.readouterr().err
    assert code == 1, err
    assert "Traceback" not in err and "internal error" not in err
    assert "error: 1 of 8 variant(s) could not be computed (1 variant(s): a worker process " \
           "died while computing this variant (after 3 tries)); the study was written" in err
    table = pq.read_table(tmp_path / "out" / "four_bar" / "study.parquet").to_pydict()
    assert table["status"].count("failed") == 1 and table["status"][3] == "failed"
    assert "a worker process died" in table["reason"][3]
    assert (tmp_path / "out" / "four_bar" / "study.pdf").is_file()


# ---------------------------------------------------------------------- item 6: Dask

@pytest.fixture(scope="module")
def cluster():
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                                  protocol="tcp://", host="127.0.0.1",
                                  dashboard_address="127.0.0.1:0") as c:
        yield c


@pytest.fixture
def client(cluster):
    client = cl.connect(cluster.scheduler_address, timeout=5)
    try:
        yield client
    finally:
        assert cl.close_client(client) == ""


def test_a_lost_dask_task_is_submitted_again(tmp_path, monkeypatch, client):
    base = _base()
    serial = _serial(base)
    where = _faults(monkeypatch, tmp_path, at=2, times=2, how="comm")
    table, lost, said = _run(base, client=client, chunk=2)
    assert lost == [] and table.done.all()
    _same_rows(table, serial, range(table.n))
    assert _tries(where) == {2: 3}
    assert [re.sub(r"\(CommClosedError.*?\)", "(...)", s) for s in said] == [
        f"warning: a Dask task was lost (...) while computing variant(s) 3-4; computing them "
        f"again (try {k} of 3)" for k in (2, 3)]


def test_a_dask_chunk_lost_three_times_is_failed_rows(tmp_path, monkeypatch, client):
    base = _base()
    serial = _serial(base)
    where = _faults(monkeypatch, tmp_path, at=6, how="comm")
    table, lost, _said = _run(base, client=client, chunk=2)
    assert _tries(where) == {6: 3}
    assert lost == [ex.Lost(6, 8, "the Dask task computing this variant was lost: "
                                  "CommClosedError (after 3 tries)")]
    _same_rows(table, serial, range(6))


def test_a_killed_worker_is_final_and_a_task_bug_is_failed_rows(tmp_path, monkeypatch,
                                                                  client):
    base = _base()
    where = _faults(monkeypatch, tmp_path, at=0, how="killed")
    _table, lost, _ = _run(base, client=client, chunk=4)
    assert _tries(where) == {0: 1}                       # the scheduler tried it already
    assert [(x.start, x.stop) for x in lost] == [(0, 4)] and "KilledWorker" in lost[0].reason
    where = _faults(monkeypatch, tmp_path / "b", at=4, how="bug")
    table, lost, _ = _run(base, client=client, chunk=4)
    assert _tries(where) == {4: 1}                       # a bug is not retried
    assert [(x.start, x.stop) for x in lost] == [(4, 8)]
    assert lost[0].reason.startswith("internal error: ValueError: injected bug")
    assert table.ok[:4].all()


def test_a_dask_cluster_that_loses_its_last_worker_keeps_the_rows_done(tmp_path,
                                                                       monkeypatch):
    distributed = pytest.importorskip("distributed")
    monkeypatch.setattr(cl, "NO_WORKERS_WAIT", 1.0)
    monkeypatch.setattr(cl, "POLL", 0.2)
    base = _base()
    serial = _serial(base)
    where = _faults(monkeypatch, tmp_path, at=4, how="close-worker")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                  protocol="tcp://", host="127.0.0.1",
                                  dashboard_address="127.0.0.1:0") as cluster:
        client = cl.connect(cluster.scheduler_address, timeout=5)
        try:
            table, lost, said = _run(base, client=client, chunk=2)
        finally:
            cl.close_client(client)
    assert _tries(where) == {4: 1}
    assert table.done.all() and table.ok[:2].all() and not table.ok[4:].any()
    ok = np.flatnonzero(table.ok)
    _same_rows(table, serial, ok)                        # done before the worker went: kept
    # the chunk done just before may have been lost with the worker holding its rows
    assert sum(x.count for x in lost) == table.n - len(ok) in (4, 6)
    for i in np.flatnonzero(~table.ok):
        assert table.reason[i] == "not computed: the Dask cluster had no workers for 1 s"
    assert any("no workers" in s for s in said)


def _dask(*args: str) -> list[str]:
    return [sys.executable, "-m", "distributed.cli." + args[0], *args[1:]]


def test_a_killed_scheduler_keeps_the_rows_done_with_one_clean_error(tmp_path):
    """The CLI against a real scheduler and worker (processes of their own); the worker's
    task for variant 5 SIGKILLs the scheduler."""
    pytest.importorskip("distributed")
    where = tmp_path / "faults"
    where.mkdir()
    env = dict(os.environ, FAULTS_DIR=str(where), FAULTS_AT="4", FAULTS_HOW="kill-scheduler",
               PYTHONPATH=os.pathsep.join([str(Path(__file__).parent), str(ROOT)]))
    preload = tmp_path / "inject_faults.py"
    preload.write_text(
        "def dask_setup(worker):\n"
        "    import mechreport.study.run as sr\n"
        "    import test_study_faults as t\n"
        "    task = sr.chunk_task\n"
        "    def faulty(base, start, *rest):\n"
        "        t._fault(start)\n"
        "        return task(base, start, *rest)\n"
        "    sr.chunk_task = faulty\n", encoding="utf-8")
    sched_file = tmp_path / "scheduler.json"
    procs = []
    try:
        scheduler = subprocess.Popen(
            _dask("dask_scheduler", "--host", "127.0.0.1", "--port", "0",
                  "--dashboard-address", "127.0.0.1:0", "--scheduler-file", str(sched_file)),
            env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        procs.append(scheduler)
        (where / "scheduler.pid").write_text(str(scheduler.pid))
        deadline = time.monotonic() + 60
        while not sched_file.is_file() and time.monotonic() < deadline:
            time.sleep(0.1)
        address = json.loads(sched_file.read_text())["address"]
        procs.append(subprocess.Popen(
            _dask("dask_worker", address, "--host", "127.0.0.1", "--no-nanny", "--nthreads",
                  "1", "--no-dashboard", "--preload", str(preload)),
            env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        spec = _write(tmp_path, COARSE + SMALL)
        run = subprocess.run([sys.executable, "-m", "mechreport", "study", str(spec), "-o",
                              str(tmp_path / "out"), "--scheduler", address, "--chunk", "1"],
                             env=env, cwd=tmp_path, capture_output=True, text=True,
                             timeout=240)
    finally:
        for p in procs:
            p.kill()
            p.wait(10)
    err = run.stderr
    assert run.returncode == 1, err
    assert "Traceback" not in err and "Exception ignored" not in err, err
    assert "internal error" not in err, err
    assert re.search(r"^error: lost the connection to the Dask scheduler at tcp://127\.0\.0\.1:"
                     r"\d+ \(it did not come back\); the \d variant\(s\) not computed yet are "
                     r"marked 'not computed'$", err, re.M), err
    assert _tries(where) == {4: 1}
    import pyarrow.parquet as pq
    table = pq.read_table(tmp_path / "out" / "four_bar" / "study.parquet").to_pydict()
    ok = [s == "ok" for s in table["status"]]
    assert ok[0] and not ok[4]                          # the rows done are kept
    assert all(r == cl.SCHEDULER_LOST for r, good in zip(table["reason"], ok) if not good)


# ------------------------------------------------------------ item 8: bad addresses

@pytest.mark.parametrize("address", ["localhost", "garbage", "http://127.0.0.1:8786",
                                     "tls://127.0.0.1:8786", "inproc://x", "tcp://host:0",
                                     "tcp://host:99999", ""])
def test_a_bad_scheduler_address_fails_fast_without_a_traceback(tmp_path, address):
    pytest.importorskip("distributed")
    spec = _write(tmp_path, COARSE + SMALL)
    run = subprocess.run([sys.executable, "-m", "mechreport", "study", str(spec), "-o",
                          str(tmp_path / "out"), "--scheduler", address],
                         cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert run.returncode == 1, run.stderr
    assert "Traceback" not in run.stderr and "Exception ignored" not in run.stderr
    assert run.stderr.count("\n") == 1, run.stderr             # one line
    assert "is not a Dask scheduler address" in run.stderr or "is empty" in run.stderr
    assert "expected tcp://HOST:PORT or HOST:PORT" in run.stderr
    assert not (tmp_path / "out" / "four_bar").exists()


def test_an_unreachable_scheduler_is_one_line_within_the_stated_timeout(tmp_path):
    pytest.importorskip("distributed")
    code = ("import sys; from mechreport.study.cluster import connect, SchedulerError\n"
            "try:\n    connect('127.0.0.1:9', timeout=1)\n"
            "except SchedulerError as e:\n    print(e, file=sys.stderr)\n")
    run = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True,
                         text=True, timeout=120)
    assert run.returncode == 0
    assert run.stderr == ("cannot reach the Dask scheduler at tcp://127.0.0.1:9: no answer "
                          "within 1 s (is a scheduler running there? `dask scheduler` prints "
                          "its address)\n")


@pytest.mark.parametrize("address, normal", [
    ("tcp://127.0.0.1:8786", "tcp://127.0.0.1:8786"), ("127.0.0.1:8786", "tcp://127.0.0.1:8786"),
    ("sched-1.example.org:8786", "tcp://sched-1.example.org:8786"),
    (" [::1]:8786 ", "tcp://[::1]:8786"), ("tcp://node_7:01234", "tcp://node_7:1234")])
def test_scheduler_addresses_of_the_right_form_are_accepted(address, normal):
    assert cl.check_address(address) == normal


# ---------------------------------------------------- item 7: names that look like numbers

def _names_spec() -> str:
    """The coarse four-bar (without its expect entries) with a link '1e5', joints (and their
    points) 'true' and 'null', loads '.inf' and '0x10': all valid names, quoted in the spec,
    that YAML 1.2 would read as something else unquoted."""
    text = COARSE[:COARSE.index("expect:")]
    for old, new in (("  coupler:\n", "  '1e5':\n"), ("[crank, coupler]", "[crank, '1e5']"),
                     ("[coupler, rocker]", "['1e5', rocker]"), ("link: coupler", "link: '1e5'"),
                     ("  B: {type: R", "  'true': {type: R"),
                     ("  C: {type: R", "  'null': {type: R"),
                     ("{A: [0, 0], B: [50, 0]}", "{A: [0, 0], 'true': [50, 0]}"),
                     ("{B: [0, 0], C: [180, 0], E:", "{'true': [0, 0], 'null': [180, 0], E:"),
                     ("{D: [0, 0], C: [120, 0]}", "{D: [0, 0], 'null': [120, 0]}"),
                     ("assembly: {C:", "assembly: {'null':"),
                     ("name: process load", "name: '.inf'"),
                     ("name: rocker damper", "name: '0x10'")):
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    return text


def test_names_spec_is_valid():
    spec = parse_spec(_names_spec())
    assert "1e5" in [x.name for x in spec.links]
    assert {"true", "null"} <= {j.name for j in spec.joints}
    assert {".inf", "0x10"} <= {x.name for x in spec.loads}


def test_variant_yaml_reads_back_as_the_same_spec_for_names_that_look_like_numbers():
    text = _names_spec() + """
study:
  vary:
    - {key: links.1e5.mass, values: [200, 240.5, 1e20]}
    - {key: driver.rpm, values: [300.1, 0.1]}
  keep: [cycle.torque.rms]
"""
    base = _base(text)
    plan = plan_of(base.spec.study)
    for i in range(plan.n):
        values = plan.variant(i)
        yaml_text = variant_yaml(base, values, "a header\n\nwith: a colon",
                                 name="true", description="1e5\n0x10: .inf\n")
        back = parse_source(yaml_text, "v.yaml")
        assert back.problems == []
        want = dict(variant_data(base, values), name="true", description="1e5\n0x10: .inf\n")
        assert back.data == want
        got = spec_from_data(back.data, back)
        ref = variant_spec(base, values)
        assert dataclasses.replace(got, file=ref.file, name=ref.name,
                                   description=ref.description) == ref


@pytest.mark.parametrize("value", [
    "1e5", "1E5", "true", "True", "FALSE", "null", "Null", "~", "", "0x10", "0o17", "010",
    ".inf", "-.Inf", ".nan", ".NaN", "+1", "-1.5", ".5", "1.", "1.5e5", "1_000", "yes", "no",
    "10:00", "2001-01-01", "a: b", "#x", "- x", "'q'", '"q"', "x\ny", "  lead", "trail  ",
    "ünïcode", 0, -1, 2**62, 1e20, 1e-20, 0.1, 3.0, -0.0, 5e-324, 1.7976931348623157e308,
    math.inf, -math.inf, True, False, None])
def test_dump_yaml_writes_what_reads_back_identically(value):
    from mechreport.study.variants import _same_tree
    data = {"k": value, str(value): [value], "nested": {"list": [value, {"x": value}]}}
    back = parse_source(dump_yaml(data), "x.yaml")
    assert back.problems == []
    assert _same_tree(back.data, data)


def test_dump_yaml_keeps_nan_and_types():
    back = parse_source(dump_yaml({"a": math.nan, "b": 1, "c": 1.0, "d": True}), "x")
    assert math.isnan(back.data["a"]) and type(back.data["b"]) is int
    assert type(back.data["c"]) is float and back.data["d"] is True


def test_cli_study_reports_for_names_that_look_like_numbers(tmp_path, capsys):
    from mechreport.app.cli import main
    spec = _write(tmp_path, _names_spec() + """
study:
  vary:
    - {key: links.1e5.mass, values: [200, 240]}
  keep: [cycle.torque.rms]
""")
    code = main(["study", str(spec), "-o", str(tmp_path / "out"), "--jobs", "1",
                 "--reports", "1"])
    err = capsys.readouterr().err
    assert code == 0, err
    [folder] = [p for p in (tmp_path / "out" / "four_bar" / "study-reports").iterdir()
                if p.name != ".mechreport-html"]                 # report.html's script
    assert (folder / "report.pdf").is_file()
    variant = parse_spec((folder / f"{folder.name[3:]}.yaml").read_text(encoding="utf-8"))
    assert "1e5" in [x.name for x in variant.links]
    assert "no report" not in err


def test_a_report_that_cannot_be_written_makes_the_exit_status_1(tmp_path, capsys,
                                                                 monkeypatch):
    import mechreport.report.build as build
    from mechreport.app.cli import main

    def fail(*a, **k):
        raise OSError(28, "No space left on device")
    monkeypatch.setattr(build, "write_report_folder", fail)
    spec = _write(tmp_path, COARSE + SMALL)
    code = main(["study", str(spec), "-o", str(tmp_path / "out"), "--jobs", "1",
                 "--reports", "1"])
    err = capsys.readouterr().err
    assert code == 1, err
    assert re.search(r"^error: no report for rank 1 \(variant \d+\): no space left on device; "
                     r"free some space and run it again$", err, re.M), err
    assert (tmp_path / "out" / "four_bar" / "study.parquet").is_file()   # the study is kept


# ------------------------------------------------------------------ item 11: --jobs

def test_jobs_are_bounded_by_the_cores_and_the_chunks(monkeypatch):
    monkeypatch.setattr(sr, "usable_cores", lambda: 2)
    workers, size, why = sr.local_jobs(63, 1000, None)
    assert workers == 2 and size == 4 and "2 usable core(s)" in why
    assert sr.local_jobs(63, 2, None) == (2, 4, "")
    assert sr.local_jobs(63, None, None) == (2, 4, "")
    workers, size, why = sr.local_jobs(63, 2, 40)
    assert workers == 2 and why == ""
    workers, size, why = sr.local_jobs(3, 1000, 3)
    assert workers == 1 and "1 chunk(s)" in why and "2 usable core(s)" in why


def test_cli_jobs_1000_starts_at_most_a_process_per_core_and_says_so(tmp_path, monkeypatch,
                                                                   capsys):
    from concurrent.futures import ProcessPoolExecutor
    from mechreport.app.cli import main
    monkeypatch.setattr(sr, "usable_cores", lambda: 2)
    started = []

    class Counted(ProcessPoolExecutor):
        def __init__(self, *a, **k):
            started.append(k.get("max_workers", a[0] if a else None))
            super().__init__(*a, **k)
    monkeypatch.setattr(ex, "ProcessPoolExecutor", Counted)
    spec = _write(tmp_path, COARSE + SMALL)
    code = main(["study", str(spec), "-o", str(tmp_path / "out"), "--jobs", "1000"])
    err = capsys.readouterr().err
    assert code == 0, err
    assert started == [1, 1]                         # two one-process pools
    assert ("--jobs 1000: using 2 process(es), because this machine has 2 usable core(s), "
            "and more processes than cores only cost memory and time") in err
    assert "on 2 local processes" in err
