"""Batches and outputs that cannot collide (issue 9): every file of a batch is reported,
unexpected failures are one-line internal errors, output folder names are safe and distinct,
builds lock their output folder, swap report folders whole, keep the index true to what is on
disk, end their workers with them, and exit 1 when a check fails."""
from __future__ import annotations

import json
import os
import signal
import stat
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from helpers import tiny_spec
from mechreport.app import cli
from mechreport.app import outdir as od
from mechreport.app.build import build_files

pytestmark = pytest.mark.slow      # builds reports, starts processes or fuzzes: not in the fast tier

ROOT = Path(__file__).resolve().parents[2]


def run_cli(*args, cwd=ROOT, env=None):
    return subprocess.run([sys.executable, "-m", "mechreport.app.cli", *map(str, args)], cwd=cwd,
                          capture_output=True, text=True, env=env, timeout=300)


@pytest.fixture(scope="module")
def unreadable_folder(tmp_path_factory):
    """A folder of specs where three cannot be read: a folder named x.yaml, invalid UTF-8, a
    broken symlink; and one good spec."""
    d = tmp_path_factory.mktemp("unreadable")
    tiny_spec(d / "a_good.yaml")
    (d / "b_folder.yaml").mkdir()
    (d / "c_bytes.yaml").write_bytes(b"mechreport: 1\nname: \xff\xfe\n")
    (d / "d_dangling.yaml").symlink_to(d / "nowhere.yaml")
    return d


# ------------------------------------------------------------------ 10: every file reported

def test_validate_reports_every_unreadable_file_and_goes_on(unreadable_folder):
    out = run_cli("validate", unreadable_folder)
    assert out.returncode == 1
    text = out.stdout + out.stderr
    assert "Traceback" not in text
    assert f"{unreadable_folder / 'a_good.yaml'}: OK" in out.stdout
    for name, why in (("b_folder.yaml", "Is a directory"), ("c_bytes.yaml", "not UTF-8"),
                      ("d_dangling.yaml", "No such file")):
        line = next(l for l in out.stderr.splitlines() if name in l)
        assert why in line


def test_check_reports_every_unreadable_file_and_goes_on(unreadable_folder):
    out = run_cli("check", unreadable_folder)
    assert out.returncode == 1
    assert "Traceback" not in out.stdout + out.stderr
    lines = out.stdout.splitlines()
    assert any(l.startswith(f"PASS {unreadable_folder / 'a_good.yaml'}") for l in lines)
    for name in ("b_folder.yaml", "c_bytes.yaml", "d_dangling.yaml"):
        assert any(l.startswith(f"FAIL {unreadable_folder / name}: ") for l in lines), name


def test_validate_empty_folder_exits_1(tmp_path):
    out = run_cli("validate", tmp_path)
    assert out.returncode == 1
    assert f"{tmp_path}: no spec files" in out.stderr


@pytest.fixture
def one_spec_crashes(monkeypatch):
    """Loading or analysing any spec whose file name starts with "crash" raises a bug."""
    import mechreport.pipeline.analysis
    import mechreport.spec

    def boom(loader):
        def wrapped(path, *a, **kw):
            if Path(str(path)).name.startswith("crash"):
                raise TypeError("'int' object is not iterable\n  (second line)")
            return loader(path, *a, **kw)
        return wrapped

    monkeypatch.setattr(mechreport.spec, "load_spec", boom(mechreport.spec.load_spec))
    monkeypatch.setattr(mechreport.pipeline.analysis, "analyse", boom(mechreport.pipeline.analysis.analyse))
    monkeypatch.delenv("MECHREPORT_DEBUG", raising=False)


INTERNAL = ("internal error: TypeError: 'int' object is not iterable (second line) — please "
            "report this with the spec file")


@pytest.mark.parametrize("command", ["validate", "check", "build"])
def test_unexpected_error_is_one_line_internal_error_and_the_batch_goes_on(
        command, tmp_path, capsys, one_spec_crashes):
    crash = tiny_spec(tmp_path / "crash.yaml")
    good = tiny_spec(tmp_path / "good.yaml")
    extra = ["-o", tmp_path / "out", "--jobs", "1"] if command == "build" else []
    code = cli.main([command, str(crash), str(good), *map(str, extra)])
    out, err = capsys.readouterr()
    assert code == 1
    text = out + err
    assert "Traceback" not in text
    lines = [l for l in text.splitlines() if "internal error" in l]
    assert len(lines) == 1 and str(crash) in lines[0] and lines[0].endswith(INTERNAL)
    assert any(str(good) in l and ("OK" in l or "PASS" in l or "built" in l)
               for l in text.splitlines())


def test_kin_unexpected_error_is_one_line(tmp_path, capsys, one_spec_crashes):
    crash = tiny_spec(tmp_path / "crash.yaml")
    assert cli.main(["kin", str(crash)]) == 1
    out, err = capsys.readouterr()
    assert out == "" and err == f"{crash}: {INTERNAL}\n"


def test_internal_error_traceback_only_with_mechreport_debug(tmp_path, capsys, monkeypatch,
                                                             one_spec_crashes):
    crash = tiny_spec(tmp_path / "crash.yaml")
    monkeypatch.setenv("MECHREPORT_DEBUG", "1")
    assert cli.main(["check", str(crash)]) == 1
    assert "Traceback" in capsys.readouterr().err


# ------------------------------------------------------------------------ argument checks

@pytest.mark.parametrize("args, message", [
    (["build", "specs", "--jobs", "0"], "argument --jobs: must be a whole number >= 1, got '0'"),
    (["build", "specs", "--jobs", "two"], "must be a whole number >= 1, got 'two'"),
    (["check", "specs", "--tol", "0"], "argument --tol: must be a finite number > 0, got '0'"),
    (["check", "specs", "--tol", "nan"], "must be a finite number > 0, got 'nan'"),
])
def test_jobs_and_tol_are_validated(args, message, capsys):
    with pytest.raises(SystemExit) as exc:
        cli.main(args)
    assert exc.value.code == 2
    assert message in capsys.readouterr().err


def test_out_naming_an_existing_file_is_a_clear_error(tmp_path, capsys):
    target = tmp_path / "report.txt"
    target.write_text("not a folder")
    spec = tiny_spec(tmp_path / "s.yaml")
    assert cli.main(["build", str(spec), "-o", str(target)]) == 1
    assert capsys.readouterr().err == (f"error: {target}: the output folder (-o) is an "
                                       "existing file, not a folder\n")
    assert target.read_text() == "not a folder"


def test_build_help_states_the_exit_status():
    out = run_cli("build", "--help")
    assert "exit status: 0 if every spec was built and passed its check" in out.stdout
    assert "failed its check" in out.stdout


# -------------------------------------------------------------------------- 11: names

@pytest.mark.parametrize("file, name", [
    ("slider_crank.yaml", "slider_crank"), ("x.yml", "x"), ("X.YAML", "X"),
    ("...yaml", "spec"), ("..yaml", "spec"), (".yaml", "spec"), ("..", "spec"),
    (".hidden.yaml", "_hidden"), ("a b|c[x](y).yaml", "a_b_c_x__y_"), ("é.yaml", "_"),
    ("v1.2.yaml", "v1.2"), ("x" * 300 + ".yaml", "x" * 100),
])
def test_folder_name_is_a_sanitised_stem(file, name):
    assert od.safe_stem(Path("some/dir") / file) == name


def test_same_stems_get_numbered_suffixes_in_argument_order():
    paths = [Path("a/x.yaml"), Path("b/x.yaml"), Path("x.yml"), Path("c/x-2.yaml"),
             Path("X.yaml"), Path("...yaml"), Path("..yaml")]
    assert od.folder_names(paths) == ["x", "x-3", "x-4", "x-2", "X-5", "spec", "spec-2"]
    assert od.folder_names(paths) == od.folder_names(list(paths))        # stable


def test_same_file_twice_is_built_once(tmp_path):
    a = tmp_path / "a.yaml"
    assert od.unique_specs([a, tmp_path / "." / "a.yaml", tmp_path / "b.yaml"]) == \
        [a, tmp_path / "b.yaml"]


@pytest.fixture(scope="module")
def batch(tmp_path_factory):
    """Build 1: c/...yaml alone. Then leftovers and a stale file are planted, and build 2
    builds a/x.yaml and b/x.yml (same stem; b fails its check) with two jobs under umask 027.
    Build 3 rebuilds a/x.yaml after it was broken."""
    root = tmp_path_factory.mktemp("batch")
    a = tiny_spec(root / "a" / "x.yaml", "from a")
    b = tiny_spec(root / "b" / "x.yml", "from b", expect_torque=1.0)
    dots = tiny_spec(root / "c" / "...yaml", "dots")
    out = root / "out"
    first = build_files([dots], out, jobs=1)
    (out / "x" / "figures").mkdir(parents=True)
    (out / "x" / "figures" / "stale.png").write_bytes(b"old")
    (out / "x" / "summary.json").write_text("{}")
    (out / ".tmp-x-999999").mkdir()
    (out / ".tmp-x-999999" / "half.md").write_text("half-written")
    old_mask = os.umask(0o027)
    try:
        second = build_files([a, b], out, jobs=2)
    finally:
        os.umask(old_mask)
    index2 = (out / "index.md").read_text(encoding="utf-8")
    a.write_text("mechreport: 1\nname: [unclosed\n", encoding="utf-8")
    third = build_files([a], out, jobs=1)
    index3 = (out / "index.md").read_text(encoding="utf-8")
    return {"root": root, "out": out, "codes": (first, second, third), "index2": index2,
            "index3": index3}


def test_same_stem_specs_get_distinct_folders(batch):
    out = batch["out"]
    assert json.loads((out / "x" / "summary.json").read_text())["name"] == "from a"
    assert json.loads((out / "x-2" / "summary.json").read_text())["name"] == "from b"
    for folder in ("x", "x-2"):
        assert (out / folder / "report.md").read_text().startswith(
            "# from a" if folder == "x" else "# from b")
    assert "[pdf](x/report.pdf)" in batch["index2"] and "[pdf](x-2/report.pdf)" in batch["index2"]


def test_dot_only_spec_names_write_inside_out(batch):
    root, out = batch["root"], batch["out"]
    assert sorted(p.name for p in root.iterdir()) == ["a", "b", "c", "out"]
    assert json.loads((out / "spec" / "summary.json").read_text())["name"] == "dots"
    for p in out.rglob("*"):
        assert out.resolve() in p.resolve().parents


def test_build_exits_1_when_a_check_fails(batch):
    first, second, _ = batch["codes"]
    assert first == 0 and second == 1
    row = next(l for l in batch["index2"].splitlines() if l.startswith("| from b"))
    assert "| FAIL" in row
    assert "3 spec(s): 2 passed their check, 1 failed it, 0 could not be built." in batch["index2"]


def test_swap_leaves_only_this_runs_files(batch):
    out = batch["out"]
    assert not (out / "x" / "figures" / "stale.png").exists()
    assert {p.name for p in (out / "x").iterdir()} == {"figures", "report.md", "report.pdf",
                                                       "results.csv", "summary.json",
                                                       "animation.gif", "report.html",
                                                       "FAILED.json"}   # build 3 failed
    assert sorted(p.name for p in out.iterdir() if p.name.startswith(".")) == \
        [".mechreport-html", ".mechreport.lock"]   # report.html's script; no .tmp-* / .old-*


def test_files_and_folders_follow_the_umask(batch):
    folder = batch["out"] / "x"
    assert stat.S_IMODE((folder / "report.md").stat().st_mode) == 0o640
    assert stat.S_IMODE((folder / "figures" / "torque.svg").stat().st_mode) == 0o640
    assert stat.S_IMODE(folder.stat().st_mode) == 0o750
    assert stat.S_IMODE((folder / "figures").stat().st_mode) == 0o750


def test_index_lists_reports_already_in_the_folder(batch):
    index = batch["index2"]                       # build 2 did not build c/...yaml
    assert next(l for l in index.splitlines() if l.startswith("| dots")).count("| PASS |") == 1


def test_failed_spec_keeps_its_previous_folder_and_the_index_says_fail(batch):
    out, index = batch["out"], batch["index3"]
    assert batch["codes"][2] == 1
    assert json.loads((out / "x" / "summary.json").read_text())["name"] == "from a"
    assert "malformed YAML" in json.loads((out / "x" / "FAILED.json").read_text())["message"]
    row = next(l for l in index.splitlines() if "x.yaml" in l)
    assert "| FAIL" in row and "earlier build is still in x/" in row
    assert "3 spec(s): 1 passed their check, 1 failed it, 1 could not be built." in index
    assert any(l.startswith("| from b") for l in index.splitlines())


def test_a_folder_that_is_not_a_report_is_never_replaced(tmp_path, capsys):
    """`-o .` beside a docs/ folder and a spec named docs.yaml: docs/ is left alone."""
    spec = tiny_spec(tmp_path / "specs" / "docs.yaml")
    (tmp_path / "docs").mkdir()
    (tmp_path / "docs" / "notes.txt").write_text("mine")
    (tmp_path / ".tmp-cache").mkdir()                  # not a leftover of ours
    assert build_files([spec], tmp_path, jobs=1) == 1
    assert (tmp_path / "docs" / "notes.txt").read_text() == "mine"
    assert (tmp_path / ".tmp-cache").is_dir()
    assert (f"FAIL {spec}: {tmp_path / 'docs'} exists and is neither a mechreport report nor "
            "a study or dynamics folder (no summary.json, study.parquet or dynamics.parquet); "
            "move it away or use another -o folder") in capsys.readouterr().err


# -------------------------------------------------------------------------- 12: locking

def test_second_build_waits_for_the_lock_then_gives_up(tmp_path, capsys):
    out = tmp_path / "out"
    out.mkdir()
    with od.OutputLock(out).acquire(0):
        start = time.monotonic()
        with pytest.raises(od.OutputError) as exc:
            build_files([tmp_path / "missing.yaml"], out, jobs=1, wait=0.5)
        assert time.monotonic() - start >= 0.5
    pid = os.getpid()
    assert str(exc.value) == (f"another build (pid {pid}) is still writing to {out} after "
                              "0.5 s; try again when it has finished, or use another -o folder")
    assert f"another build (pid {pid}) is writing to {out}; waiting up to 0.5 s..." in \
        capsys.readouterr().err
    assert not (out / "index.md").exists()


def test_second_build_proceeds_when_the_lock_is_released(tmp_path, capsys):
    out = tmp_path / "out"
    out.mkdir()
    lock = od.OutputLock(out).acquire(0)
    threading.Timer(0.5, lock.release).start()
    assert build_files([tmp_path / "missing.yaml"], out, jobs=1, wait=30) == 1
    assert "waiting up to 30 s" in capsys.readouterr().err
    assert "missing.yaml" in (out / "index.md").read_text()
    assert (out / od.LOCK_NAME).read_text() == ""             # released: no holder


# ------------------------------------------------------------------- 12: worker lifetime

def _children(pid: int) -> list[int]:
    kids = []
    for stat_file in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat_file.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[1]) == pid:
            kids.append(int(stat_file.parent.name))
    return kids


def _alive(pid: int) -> bool:
    try:
        fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    except OSError:
        return False
    return fields[0] != "Z"


def _start_build(tmp_path: Path) -> tuple[subprocess.Popen, list[int], Path]:
    specs = [tiny_spec(tmp_path / f"s{i}.yaml", f"s{i}") for i in range(3)]
    out = tmp_path / "out"
    proc = subprocess.Popen([sys.executable, "-m", "mechreport.app.cli", "build", *map(str, specs),
                             "-o", str(out), "--jobs", "2"], cwd=ROOT,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        workers = [k for k in _children(proc.pid)
                   if b"spawn_main" in Path(f"/proc/{k}/cmdline").read_bytes()]
        if len(workers) == 2 and list(out.glob(".tmp-*")):
            return proc, workers, out
        time.sleep(0.05)
    proc.kill()
    pytest.fail("the build did not start two workers")


def _wait_gone(pids: list[int], seconds: float) -> list[int]:
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline and any(_alive(p) for p in pids):
        time.sleep(0.05)
    return [p for p in pids if _alive(p)]


@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="needs /proc")
def test_sigterm_ends_the_workers_with_the_build(tmp_path):
    proc, workers, out = _start_build(tmp_path)
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=30)
    assert proc.returncode == 143
    assert _wait_gone(workers, 5) == []
    assert "terminated after " in err and "Traceback" not in err
    assert not list(out.glob(".tmp-*")) and not list(out.glob(".old-*"))
    assert (out / "index.md").exists()


@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="needs /proc")
def test_workers_exit_when_the_build_is_killed(tmp_path):
    proc, workers, out = _start_build(tmp_path)
    proc.kill()
    proc.communicate(timeout=30)
    assert _wait_gone(workers, 5) == []
    leftovers = list(out.glob(".tmp-*"))
    snapshot = {p: sorted(q.name for q in p.rglob("*")) for p in leftovers}
    time.sleep(1.5)                                   # nobody writes there any more
    assert {p: sorted(q.name for q in p.rglob("*")) for p in leftovers} == snapshot
