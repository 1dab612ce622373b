"""`mechreport diff` on hostile build folders: non-finite values are changes; a malformed,
oversized, linked or unreadable summary.json is a one-line error naming the file (exit 2),
never an "internal error" or a traceback; a summary.json is read only up to a size cap."""
from __future__ import annotations

import copy
import errno
import json
import os
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from mechreport.app import diff as diff_module
from mechreport.app.cli import main

from helpers import tiny_spec

ROOT = Path(__file__).resolve().parents[2]
RMS = "cycle.torque.rms"            # a quantity with a value and a unit
PEAK = "driver.torque.peak"         # ... and the angle of its peak


@pytest.fixture(scope="module")
def real_summary(tmp_path_factory) -> dict:
    """The summary.json of a real (tiny) build."""
    d = tmp_path_factory.mktemp("diff_hostile")
    spec = tiny_spec(d / "tiny.yaml")
    r = subprocess.run([sys.executable, "-m", "mechreport", "build", str(spec), "-o",
                        str(d / "out"), "-q", "--jobs", "1"], cwd=ROOT, capture_output=True,
                       text=True, timeout=300)
    assert r.returncode == 0, r.stdout + r.stderr
    data = json.loads((d / "out" / "tiny" / "summary.json").read_text(encoding="utf-8"))
    assert {RMS, PEAK} <= set(data["quantities"])
    assert data["quantities"][PEAK]["angle_deg"] is not None
    return data


@pytest.fixture
def summary(real_summary) -> dict:
    """A fresh copy of the real summary, for a test to edit."""
    return copy.deepcopy(real_summary)


def build(root: Path, **folders) -> Path:
    """A build folder ``root`` with one report folder per keyword: its summary.json is the
    dict given (written as json.dumps writes it: NaN, Infinity) or the text/bytes given."""
    root.mkdir(parents=True, exist_ok=True)
    for name, content in folders.items():
        (root / name).mkdir()
        f = root / name / "summary.json"
        if isinstance(content, bytes):
            f.write_bytes(content)
        elif isinstance(content, str):
            f.write_text(content, encoding="utf-8")
        else:
            f.write_text(json.dumps(content, indent=2) + "\n", encoding="utf-8")
    return root


def run_diff(capsys, old: Path, new: Path, *args: str) -> tuple[int, str, str]:
    code = main(["diff", str(old), str(new), *args])
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def rows(out: str, name: str) -> list[list[str]]:
    """The table rows of quantity ``name``, as cells."""
    found = []
    for line in out.splitlines():
        if line.startswith("| "):
            cells = [c.strip() for c in line.strip("|").split(" | ")]
            if len(cells) == 5 and cells[1] == name:
                found.append(cells)
    return found


def assert_clean_error(code: int, out: str, err: str, f: Path, *words: str) -> None:
    """Exit 2, nothing on stdout, one line on stderr naming ``f`` and saying ``words``."""
    assert code == 2, (code, out, err)
    assert out == ""
    lines = err.splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("error: ") and str(f) in lines[0], err
    assert "internal error" not in err and "Traceback" not in err
    for w in words:
        assert w in lines[0], (w, err)


# ----------------------------------------------------------------- non-finite values

def test_diff_sees_a_change_to_nan(tmp_path, capsys, summary):
    new = copy.deepcopy(summary)
    new["quantities"][RMS]["value"] = float("nan")
    code, out, err = run_diff(capsys, build(tmp_path / "a", s=summary),
                              build(tmp_path / "b", s=new))
    assert code == 1, out + err
    [[spec, _, old_text, new_text, change]] = rows(out, RMS)
    assert spec == "s" and new_text == "NaN N·m" and change == "now NaN"
    assert old_text.endswith(" N·m") and old_text != "— N·m"


def test_diff_sees_a_change_from_nan(tmp_path, capsys, summary):
    old = copy.deepcopy(summary)
    old["quantities"][RMS]["value"] = float("nan")
    code, out, _ = run_diff(capsys, build(tmp_path / "a", s=old),
                            build(tmp_path / "b", s=summary))
    assert code == 1
    [[_, _, old_text, new_text, change]] = rows(out, RMS)
    assert old_text == "NaN N·m" and change == "now finite" and new_text[0].isdigit()


@pytest.mark.parametrize("literal, shown", [("Infinity", "inf"), ("-Infinity", "-inf"),
                                            ("1e400", "inf"), ("-1e400", "-inf")])
def test_diff_sees_a_change_to_infinity(tmp_path, capsys, summary, literal, shown):
    text = json.dumps(summary).replace(
        f'"{RMS}": {{"value": {json.dumps(summary["quantities"][RMS]["value"])}',
        f'"{RMS}": {{"value": {literal}')
    assert literal in text
    code, out, _ = run_diff(capsys, build(tmp_path / "a", s=summary),
                            build(tmp_path / "b", s=text))
    assert code == 1
    [[_, _, _, new_text, change]] = rows(out, RMS)
    assert new_text == f"{shown} N·m" and change == f"now {shown}"


def test_diff_sees_a_change_between_infinities(tmp_path, capsys, summary):
    old, new = copy.deepcopy(summary), copy.deepcopy(summary)
    old["quantities"][RMS]["value"] = float("inf")
    new["quantities"][RMS]["value"] = float("-inf")
    code, out, _ = run_diff(capsys, build(tmp_path / "a", s=old), build(tmp_path / "b", s=new))
    assert code == 1
    assert rows(out, RMS) == [["s", RMS, "inf N·m", "-inf N·m", "now -inf"]]


def test_diff_of_nan_to_nan_is_no_change_but_a_finite_value_to_nan_is(tmp_path, capsys,
                                                                       summary):
    old, new = copy.deepcopy(summary), copy.deepcopy(summary)
    old["quantities"][RMS]["value"] = new["quantities"][RMS]["value"] = float("nan")
    old["quantities"]["x.same"] = new["quantities"]["x.same"] = {
        "value": float("inf"), "unit": "N"}
    new["quantities"][PEAK]["value"] = float("nan")
    code, out, _ = run_diff(capsys, build(tmp_path / "a", s=old), build(tmp_path / "b", s=new))
    assert code == 1
    assert rows(out, RMS) == [] and rows(out, "x.same") == []
    [[_, _, _, new_text, change]] = rows(out, PEAK)
    assert new_text == "NaN N·m" and change == "now NaN"
    assert "1 change(s) in 1 spec(s)" in out


def test_diff_shows_an_added_nan_quantity_as_nan(tmp_path, capsys, summary):
    new = copy.deepcopy(summary)
    new["quantities"]["x.new"] = {"value": float("nan"), "unit": "N"}
    new["quantities"]["x.defined"] = {"value": float("inf"), "unit": "N"}
    old = copy.deepcopy(summary)
    old["quantities"]["x.defined"] = {"value": None, "unit": "N"}
    code, out, _ = run_diff(capsys, build(tmp_path / "a", s=old), build(tmp_path / "b", s=new))
    assert code == 1
    assert rows(out, "x.new") == [["s", "x.new", "—", "NaN N", "added"]]
    assert rows(out, "x.defined") == [["s", "x.defined", "— N", "inf N", "now defined"]]


def test_diff_sees_a_change_to_an_integer_too_large_for_a_float(tmp_path, capsys, summary):
    text = json.dumps(summary).replace(
        f'"{RMS}": {{"value": {json.dumps(summary["quantities"][RMS]["value"])}',
        f'"{RMS}": {{"value": 1{"0" * 400}')
    code, out, err = run_diff(capsys, build(tmp_path / "a", s=summary),
                              build(tmp_path / "b", s=text))
    assert code == 1, err
    [[_, _, _, new_text, change]] = rows(out, RMS)
    assert new_text == "inf N·m" and change == "now inf"


def test_diff_of_a_peak_at_nan_is_no_crash(tmp_path, capsys, summary):
    """Two NaN peaks whose angles moved: the angle is a change, the NaN values print."""
    old, new = copy.deepcopy(summary), copy.deepcopy(summary)
    old["quantities"][PEAK]["value"] = new["quantities"][PEAK]["value"] = float("nan")
    new["quantities"][PEAK]["angle_deg"] = old["quantities"][PEAK]["angle_deg"] + 30
    code, out, err = run_diff(capsys, build(tmp_path / "a", s=old),
                              build(tmp_path / "b", s=new))
    assert code == 1, err
    [[_, _, old_text, new_text, change]] = rows(out, PEAK)
    assert old_text.startswith("NaN N·m at ") and new_text.startswith("NaN N·m at ")
    assert change == "peak moved"


def test_diff_of_values_whose_difference_overflows_is_no_crash(tmp_path, capsys, summary):
    old, new = copy.deepcopy(summary), copy.deepcopy(summary)
    old["quantities"][RMS]["value"] = 1e308
    new["quantities"][RMS]["value"] = -1e308
    code, out, err = run_diff(capsys, build(tmp_path / "a", s=old), build(tmp_path / "b", s=new))
    assert code == 1 and err == "", err
    [[_, _, old_text, new_text, _]] = rows(out, RMS)
    assert (old_text, new_text) == ("1e+308 N·m", "-1e+308 N·m")


# ------------------------------------------------------------------ malformed files

def _set(path: tuple, value):
    def edit(root):
        *head, last = path
        d = root
        for k in head:
            d = d[k]
        d[last] = value
        return root
    return edit


def _drop(path: tuple):
    def edit(root):
        *head, last = path
        d = root
        for k in head:
            d = d[k]
        del d[last]
        return root
    return edit


def _with_verdict(entry):
    def edit(d):
        d["design"]["verdicts"] = [entry]
        return d
    return edit


GOOD_VERDICT = {"item": "motor.rated_torque", "passed": True}

# (id, edit of the summary dict or the file's text/bytes, words the message must hold)
MALFORMED = [
    ("not-json", "{not json", ["not JSON"]),
    ("empty-file", "", ["not JSON"]),
    ("truncated", '{"status": "PASS", "quantities": {', ["not JSON"]),
    ("not-utf8", b'{"status": "\xff"}', ["not UTF-8"]),
    ("too-deep", "[" * 200_000 + "]" * 200_000, ["nested too deeply"]),
    ("int-too-long", '{"status": 1' + "0" * 5000 + "}", ["not JSON"]),
    ("top-level-list", "[1, 2]", ["top level", "a list, not an object"]),
    ("top-level-string", '"PASS"', ["top level", "a string, not an object"]),
    ("top-level-null", "null", ["top level", "null, not an object"]),
    ("status-missing", _drop(("status",)), ['"status" is missing']),
    ("status-number", _set(("status",), 1), ["status is a number, not a string"]),
    ("status-null", _set(("status",), None), ["status is null, not a string"]),
    ("failures-missing", _drop(("failures",)), ['"failures" is missing']),
    ("failures-dict", _set(("failures",), {}), ["failures is an object, not a list"]),
    ("failures-string", _set(("failures",), "none"), ["failures is a string, not a list"]),
    ("failures-number", _set(("failures",), 3), ["failures is a number, not a list"]),
    ("quantities-missing", _drop(("quantities",)), ['"quantities" is missing']),
    ("quantities-list", _set(("quantities",), []), ["quantities is a list, not an object"]),
    ("quantities-null", _set(("quantities",), None), ["quantities is null, not an object"]),
    ("quantity-number", _set(("quantities", RMS), 4.2),
     [f'quantities["{RMS}"] is a number, not an object']),
    ("quantity-list", _set(("quantities", RMS), [4.2, "N·m"]),
     [f'quantities["{RMS}"] is a list, not an object']),
    ("quantity-null", _set(("quantities", RMS), None),
     [f'quantities["{RMS}"] is null, not an object']),
    ("value-missing", _drop(("quantities", RMS, "value")),
     [f'quantities["{RMS}"]: "value" is missing']),
    ("value-string", _set(("quantities", RMS, "value"), "4.2"),
     [f'quantities["{RMS}"].value is a string, not a number or null']),
    ("value-bool", _set(("quantities", RMS, "value"), True),
     [f'quantities["{RMS}"].value is true/false, not a number or null']),
    ("value-dict", _set(("quantities", RMS, "value"), {"value": 1}),
     [f'quantities["{RMS}"].value is an object, not a number or null']),
    ("value-list", _set(("quantities", RMS, "value"), [1]),
     [f'quantities["{RMS}"].value is a list, not a number or null']),
    ("unit-missing", _drop(("quantities", RMS, "unit")),
     [f'quantities["{RMS}"]: "unit" is missing']),
    ("unit-number", _set(("quantities", RMS, "unit"), 1),
     [f'quantities["{RMS}"].unit is a number, not a string']),
    ("unit-null", _set(("quantities", RMS, "unit"), None),
     [f'quantities["{RMS}"].unit is null, not a string']),
    ("angle-string", _set(("quantities", PEAK, "angle_deg"), "90"),
     [f'quantities["{PEAK}"].angle_deg is a string, not a number or null']),
    ("angle-bool", _set(("quantities", PEAK, "angle_deg"), False),
     [f'quantities["{PEAK}"].angle_deg is true/false, not a number or null']),
    ("angle-nan", _set(("quantities", PEAK, "angle_deg"), float("nan")),
     [f'quantities["{PEAK}"].angle_deg is NaN, not a finite angle']),
    ("angle-inf", _set(("quantities", PEAK, "angle_deg"), float("inf")),
     [f'quantities["{PEAK}"].angle_deg is inf, not a finite angle']),
    ("design-missing", _drop(("design",)), ['"design" is missing']),
    ("design-list", _set(("design",), []), ["design is a list, not an object"]),
    ("design-string", _set(("design",), "ok"), ["design is a string, not an object"]),
    ("verdicts-missing", _drop(("design", "verdicts")), ['design: "verdicts" is missing']),
    ("verdicts-dict", _set(("design", "verdicts"), {}),
     ["design.verdicts is an object, not a list"]),
    ("verdict-string", _with_verdict("motor.rated_torque"),
     ["design.verdicts[0] is a string, not an object"]),
    ("verdict-null", _with_verdict(None), ["design.verdicts[0] is null, not an object"]),
    ("verdict-item-missing", _with_verdict({"passed": True}),
     ['design.verdicts[0]: "item" is missing']),
    ("verdict-item-number", _with_verdict({"item": 3, "passed": True}),
     ["design.verdicts[0].item is a number, not a string"]),
    ("verdict-passed-missing", _with_verdict({"item": "x"}),
     ['design.verdicts[0]: "passed" is missing']),
    ("verdict-passed-string", _with_verdict({"item": "x", "passed": "false"}),
     ["design.verdicts[0].passed is a string, not true/false"]),
    ("verdict-passed-number", _with_verdict({"item": "x", "passed": 0}),
     ["design.verdicts[0].passed is a number, not true/false"]),
    ("verdict-passed-null", _with_verdict({"item": "x", "passed": None}),
     ["design.verdicts[0].passed is null, not true/false"]),
]


def _content(summary: dict, how):
    return how(copy.deepcopy(summary)) if callable(how) else how


@pytest.mark.parametrize("how, words", [m[1:] for m in MALFORMED], ids=[m[0] for m in MALFORMED])
def test_diff_of_a_malformed_summary_exits_2_naming_the_file(tmp_path, capsys, summary, how,
                                                             words):
    old = build(tmp_path / "a", p=summary, q=summary)
    new = build(tmp_path / "b", p=summary, q=_content(summary, how))
    code, out, err = run_diff(capsys, old, new)
    assert_clean_error(code, out, err, new / "q" / "summary.json", *words)


def test_diff_of_a_malformed_old_summary_exits_2_before_printing(tmp_path, capsys, summary):
    bad = _set(("quantities", RMS, "value"), "4.2")(copy.deepcopy(summary))
    old = build(tmp_path / "a", p=bad)
    new = build(tmp_path / "b", p=summary)
    code, out, err = run_diff(capsys, old, new)
    assert_clean_error(code, out, err, old / "p" / "summary.json", "value is a string")


def test_diff_message_of_a_hostile_quantity_name_stays_one_short_line(tmp_path, capsys,
                                                                       summary):
    bad = copy.deepcopy(summary)
    name = "line\nbreak" + "x" * 10_000
    bad["quantities"][name] = {"value": "1", "unit": "N"}
    new = build(tmp_path / "b", p=bad)
    code, out, err = run_diff(capsys, build(tmp_path / "a", p=summary), new)
    assert_clean_error(code, out, err, new / "p" / "summary.json", r'quantities["line\nbreak')
    assert len(err) < 400


# --------------------------------------------------------------- the size cap

#: the least a summary must hold for diff
MINIMAL = {"status": "PASS", "failures": [], "design": {"verdicts": []}, "quantities": {}}


def _count_reads(monkeypatch) -> dict[Path, int]:
    """Bytes os.read returns, by the path os.open opened, while the test runs."""
    counts: dict[Path, int] = {}
    opened: dict[int, Path] = {}
    real_open, real_read = os.open, os.read

    def open_(path, *args, **kwargs):
        fd = real_open(path, *args, **kwargs)
        opened[fd] = Path(path)
        return fd

    def read(fd, n):
        data = real_read(fd, n)
        where = opened.get(fd)
        counts[where] = counts.get(where, 0) + len(data)
        return data
    monkeypatch.setattr(os, "open", open_)
    monkeypatch.setattr(os, "read", read)
    return counts


def test_diff_has_a_documented_generous_size_cap(real_summary):
    cap = diff_module.MAX_SUMMARY_BYTES
    assert cap == 16 * 1024 * 1024
    assert "MAX_SUMMARY_BYTES" in (diff_module.__doc__ or "") and "16 MiB" in diff_module.__doc__
    assert len(json.dumps(real_summary, indent=2)) * 100 < cap     # far above a real one


def test_diff_refuses_an_oversized_summary_without_reading_it(tmp_path, capsys, summary,
                                                              monkeypatch):
    cap = diff_module.MAX_SUMMARY_BYTES
    new = build(tmp_path / "b", p=summary)
    f = new / "p" / "summary.json"
    with open(f, "r+b") as fh:          # sparse: cap + 1 bytes on disk costs nothing
        fh.truncate(cap + 1)
    old = build(tmp_path / "a", p=summary)
    counts = _count_reads(monkeypatch)
    for name in ("read_text", "read_bytes", "open"):     # no other way in either
        monkeypatch.setattr(Path, name, lambda self, *a, **k: pytest.fail(f"Path.{name}"))
    code, out, err = run_diff(capsys, old, new)
    assert_clean_error(code, out, err, f, "too large", f"{cap + 1} bytes", "16 MiB")
    assert counts.get(f, 0) == 0
    assert counts[old / "p" / "summary.json"] > 0          # the count does count


def test_diff_reads_at_most_the_cap_plus_one_bytes_of_a_growing_summary(tmp_path, capsys,
                                                                         summary, monkeypatch):
    """A file that grows between fstat and read (fstat is made to lie) is still cut at the
    cap: at most cap + 1 bytes are read."""
    monkeypatch.setattr(diff_module, "MAX_SUMMARY_BYTES", 1000)
    new = build(tmp_path / "b", p=summary)
    f = new / "p" / "summary.json"
    assert f.stat().st_size > 5000
    real_fstat = os.fstat
    grown = f.stat().st_ino

    def small_fstat(fd):
        st = real_fstat(fd)
        if st.st_ino != grown:
            return st
        return os.stat_result((*st[:6], 10, *st[7:10]))     # st_size = 10
    monkeypatch.setattr(os, "fstat", small_fstat)
    old = build(tmp_path / "a", p=MINIMAL)
    counts = _count_reads(monkeypatch)
    code, out, err = run_diff(capsys, old, new)
    assert_clean_error(code, out, err, f, "too large")
    assert counts[f] == 1001


def test_diff_accepts_a_summary_of_exactly_the_cap_and_refuses_one_byte_more(
        tmp_path, capsys, summary, monkeypatch):
    new = build(tmp_path / "b", p=summary)
    size = (new / "p" / "summary.json").stat().st_size
    old = build(tmp_path / "a", p=summary)
    (new / "study").mkdir()             # not a report (no summary.json): skipped, as before
    (new / "study" / "study.parquet").write_bytes(b"PAR1")
    (new / ".hidden" / "summary.json").mkdir(parents=True)      # hidden: skipped
    monkeypatch.setattr(diff_module, "MAX_SUMMARY_BYTES", size)
    code, out, err = run_diff(capsys, old, new)
    assert code == 0 and "nothing changed" in out, err
    monkeypatch.setattr(diff_module, "MAX_SUMMARY_BYTES", size - 1)
    code, out, err = run_diff(capsys, old, new)
    assert_clean_error(code, out, err, old / "p" / "summary.json", "too large")


# ------------------------------------------------- links, folders, unreadable files

def test_diff_refuses_a_symlinked_summary(tmp_path, capsys, summary):
    elsewhere = build(tmp_path / "elsewhere", p=summary) / "p" / "summary.json"
    new = build(tmp_path / "b")
    (new / "p").mkdir()
    (new / "p" / "summary.json").symlink_to(elsewhere)
    code, out, err = run_diff(capsys, build(tmp_path / "a", p=summary), new)
    assert_clean_error(code, out, err, new / "p" / "summary.json", "symbolic link")


def test_diff_refuses_a_dangling_symlinked_summary(tmp_path, capsys, summary):
    new = build(tmp_path / "b", p=summary)
    (new / "q").mkdir()
    (new / "q" / "summary.json").symlink_to(tmp_path / "nowhere.json")
    code, out, err = run_diff(capsys, build(tmp_path / "a", p=summary, q=summary), new)
    assert_clean_error(code, out, err, new / "q" / "summary.json", "symbolic link")


def test_diff_refuses_a_folder_named_summary_json(tmp_path, capsys, summary):
    new = build(tmp_path / "b", p=summary)
    (new / "q" / "summary.json").mkdir(parents=True)
    code, out, err = run_diff(capsys, build(tmp_path / "a", p=summary, q=summary), new)
    assert_clean_error(code, out, err, new / "q" / "summary.json", "a folder, not a file")


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes here")
def test_diff_refuses_a_named_pipe_as_summary_without_blocking(tmp_path, capsys, summary):
    new = build(tmp_path / "b", p=summary)
    (new / "q").mkdir()
    fifo = new / "q" / "summary.json"
    os.mkfifo(fifo)
    done = threading.Event()

    def unblock():        # were the pipe opened for reading, give it a writer (then EOF)
        while not done.is_set():
            try:
                os.close(os.open(fifo, os.O_WRONLY | os.O_NONBLOCK))
            except OSError as exc:
                if exc.errno != errno.ENXIO:        # ENXIO: nobody is reading
                    return
            time.sleep(0.05)
    t = threading.Thread(target=unblock, daemon=True)
    t.start()
    try:
        code, out, err = run_diff(capsys, build(tmp_path / "a", p=summary, q=summary), new)
    finally:
        done.set()
        t.join()
    assert_clean_error(code, out, err, fifo, "not a regular file")


def test_diff_reports_an_unreadable_summary_exit_2(tmp_path, capsys, summary, monkeypatch):
    new = build(tmp_path / "b", p=summary)
    f = new / "p" / "summary.json"
    f.chmod(0)
    real_open = os.open

    def refuse(path, *args, **kwargs):   # what chmod 0 does, also when running as root
        if Path(path) == f:
            raise PermissionError(errno.EACCES, os.strerror(errno.EACCES), str(path))
        return real_open(path, *args, **kwargs)
    monkeypatch.setattr(os, "open", refuse)
    try:
        code, out, err = run_diff(capsys, build(tmp_path / "a", p=summary), new)
    finally:
        f.chmod(0o644)
    assert_clean_error(code, out, err, f, "cannot read", "Permission denied")
    assert err.count(str(f)) == 1


def test_diff_reports_an_unlistable_build_folder_exit_2(tmp_path, capsys, summary,
                                                       monkeypatch):
    new = build(tmp_path / "b", p=summary)
    real_iterdir = Path.iterdir

    def refuse(self):
        if self == new:
            raise PermissionError(errno.EACCES, os.strerror(errno.EACCES), str(self))
        return real_iterdir(self)
    monkeypatch.setattr(Path, "iterdir", refuse)
    code, out, err = run_diff(capsys, build(tmp_path / "a", p=summary), new)
    assert_clean_error(code, out, err, new, "cannot list", "Permission denied")

