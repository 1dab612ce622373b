"""A stop request always stops (issue 40, point 9): SIGTERM ends a command with exit status
143 and Ctrl-C with 130, even when the signal's exception lands where Python can only print
"Exception ignored" (a finaliser, a weak-reference callback) and carries on; the previous
report is left as it was, or the new one is complete."""
from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from mechreport.report.html_page import ASSETS

from mechreport.app import outdir as od
from mechreport.app.build import build_files
from mechreport.app.cli import EXIT_INTERRUPTED, EXIT_TERMINATED, main
from mechreport.app.process import Terminated, check_stop, stop_requested, stop_requests

from helpers import tiny_spec

ROOT = Path(__file__).resolve().parents[2]


class _LosesItsSignal:
    """An object whose finaliser receives ``signum``: the handler's exception is raised
    inside ``__del__``, where Python ignores it."""

    def __init__(self, signum: int):
        self.signum = signum

    def __del__(self):
        os.kill(os.getpid(), self.signum)
        for _ in range(1000):               # the handler runs at one of these steps
            pass


def _lose(signum: int) -> None:
    if threading.current_thread() is not threading.main_thread():
        pytest.skip("signal handlers live in the main thread only")   # or the signal kills us
    _LosesItsSignal(signum)                 # collected at once: the stop is lost here


@pytest.mark.parametrize("signum, code", [(signal.SIGTERM, EXIT_TERMINATED),
                                          (signal.SIGINT, EXIT_INTERRUPTED)])
def test_a_stop_lost_in_a_finaliser_still_ends_the_command_with_its_status(
        signum, code, monkeypatch, capsys):
    from mechreport.app import validate

    def command(args):
        _lose(signum)
        return 0                            # it carried on and "succeeded"
    monkeypatch.setattr(validate, "validate_command", command)
    assert main(["validate", "x.yaml"]) == code
    err = capsys.readouterr().err
    assert err == ("terminated\n" if signum == signal.SIGTERM else "interrupted\n")
    assert signal.getsignal(signal.SIGTERM) is not None and stop_requested() is None


def test_no_folder_is_replaced_once_a_stop_was_requested(tmp_path, capsys):
    out = tmp_path / "out"
    (out / "x").mkdir(parents=True)
    (out / "x" / "summary.json").write_text("old")
    tmp = od.make_tmp_dir(out, "x")
    (tmp / "summary.json").write_text("new")
    with stop_requests():
        _lose(signal.SIGTERM)
        with pytest.raises(Terminated):
            od.swap_in(out, tmp, "x")
        with pytest.raises(Terminated):
            check_stop()
    assert (out / "x" / "summary.json").read_text() == "old"
    assert "Exception ignored" not in capsys.readouterr().err


# ------------------------------------------------------------------ real builds, real signals

def _files(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*"))
            if p.is_file()}


class _Builds:
    """`mechreport build` of one spec into a copy of a folder holding its earlier report,
    stopped by a signal ``delay`` seconds after it took the output lock."""

    def __init__(self, root: Path):
        old = tiny_spec(root / "old" / "tiny.yaml", "old")
        self.pristine = root / "pristine"
        assert build_files([old], self.pristine, jobs=1, quiet=True, animation=False) == 0
        self.before = _files(self.pristine / "tiny")
        self.spec = tiny_spec(root / "tiny.yaml", "new")      # a new report if it finishes
        self.out = root / "out"
        self.seconds = self._run(None)[1]                  # lock to exit, not stopped

    def _run(self, signum: int | None, delay: float = 0.0):
        shutil.rmtree(self.out, ignore_errors=True)
        shutil.copytree(self.pristine, self.out, symlinks=True)
        lock = self.out / od.LOCK_NAME
        proc = subprocess.Popen(
            [sys.executable, "-m", "mechreport", "build", str(self.spec), "-o", str(self.out),
             "--no-animation", "-q", "--jobs", "1"], cwd=ROOT, stderr=subprocess.PIPE,
            text=True, preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
        err: list[str] = []
        reader = threading.Thread(target=lambda: err.append(proc.stderr.read()))
        reader.start()
        deadline = time.monotonic() + 120
        while lock.read_text().strip() != str(proc.pid):     # its handlers are in place
            assert proc.poll() is None and time.monotonic() < deadline, err
            time.sleep(0.002)
        start = time.monotonic()
        time.sleep(delay)
        sent = signum is not None and proc.poll() is None
        if sent:
            proc.send_signal(signum)
        proc.wait(timeout=120)
        reader.join()
        return proc.returncode, time.monotonic() - start, sent, "".join(err)

    def stop(self, signum: int, delay: float) -> None:
        code, _, sent, err = self._run(signum, delay)
        assert "Traceback" not in err and "Exception ignored" not in err, err
        folder = self.out / "tiny"
        if not sent:                                     # it had ended: nothing to stop
            assert code == 0, err
        else:
            # 128 + the signal, as the shell reports it: the exit status, or the process
            # ended by the signal once the command had done its work
            assert code in (128 + signum, -signum), (code, delay, err)
        now = _files(folder)
        if now != self.before:                           # only ever a complete new report
            assert sorted(now) == sorted(self.before), (delay, sorted(now))
            assert json.loads(now["summary.json"])["name"] == "new"
        assert [p.name for p in self.out.iterdir() if p.name.startswith(".")
                and p.name != ASSETS] == [od.LOCK_NAME]  # no .tmp-* / .old-* left


@pytest.fixture(scope="module")
def builds(tmp_path_factory) -> _Builds:
    return _Builds(tmp_path_factory.mktemp("stops"))


@pytest.mark.slow                   # ten builds in subprocesses
@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
def test_sigterm_and_ctrl_c_stop_a_build_at_any_moment(builds):
    """Ten moments spread over the build, from taking the lock to its end."""
    moments = [builds.seconds * (k + 0.5) / 10 for k in range(10)]
    for k, delay in enumerate(moments):
        builds.stop(signal.SIGTERM if k % 3 else signal.SIGINT, delay)


@pytest.mark.slow
@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
def test_sigterm_and_ctrl_c_stop_a_build_at_many_random_moments(builds):
    """Twenty more moments at random (a lost stop was about 1 in 21 before the fix; the
    in-process test of a signal swallowed by a finaliser guards the mechanism itself)."""
    import random
    rng = random.Random(40)
    for _ in range(20):
        builds.stop(rng.choice([signal.SIGTERM, signal.SIGINT]),
                    rng.uniform(0, builds.seconds))
