"""The output folder of ``mechreport build``: folder names, the lock, whole-folder swaps.

- **Names.** Each spec's folder is named after its file name without ``.yaml``/``.yml``:
  letters, digits, ``-``, ``_`` and ``.`` are kept, anything else becomes ``_``, leading dots
  become ``_``, the name is cut to 100 characters, and an empty or dot-only name becomes
  ``spec``. Two specs of one batch whose names match (ignoring case, so that ``A.yaml`` and
  ``a.yaml`` cannot meet on a case-insensitive disk) are told apart in argument order: the
  first keeps the name, the next get ``-2``, ``-3``, ... (skipping names already taken). The
  same spec paths in the same order always give the same names. A spec named twice in one
  batch (the same resolved file) is built once.
- **Lock.** ``OUT/.mechreport.lock`` is held (``flock``) for the whole build and holds the
  builder's pid. A second build into the same folder says who holds it and waits (``--wait``
  seconds, default 120), then fails with exit 1 if it is still held.
- **Swap.** A spec is written into ``OUT/.tmp-<name>-<pid>/``; when complete, the old
  ``OUT/<name>`` is renamed to ``OUT/.old-<name>-<pid>``, the new folder renamed in, the old
  one deleted: a folder only ever holds one run's files. A spec that fails keeps its previous
  folder untouched. Only a report folder (holding summary.json) or an empty folder is ever
  replaced; any other file or folder of that name makes the spec fail, untouched. Leftover
  ``.tmp-<name>-<pid>``/``.old-<name>-<pid>`` folders of an interrupted build are deleted by
  the next build (under the lock).
- **Out of date.** When a spec fails to build and its folder holds an earlier report, the
  build writes ``OUT/<name>/FAILED.json`` beside that report (the spec, the reason, the date):
  the folder says that its report no longer matches its spec. The index lists it as FAIL,
  ``diff`` as "no longer builds", and the next build rebuilds it (never "unchanged"); a
  successful build replaces the folder, marker and all.
- Nothing is written outside ``OUT``: every path is checked to resolve inside it.

Every command that writes into ``OUT`` (``build``, ``study``, ``dynamics``) does so through
:func:`writing` (the folder, its lock, the leftovers) and :func:`swap_in` (directly or through
:func:`write_folder`): one set of rules for every command's outputs.
"""
from __future__ import annotations

import errno
import json
import os
import re
import shutil
import stat
import sys
import time
from contextlib import contextmanager
from pathlib import Path

from ..errors import MechreportError
from .process import check_stop, held_stops

LOCK_NAME = ".mechreport.lock"
MAX_NAME = 100
SPEC_SUFFIXES = (".yaml", ".yml")
_UNSAFE = re.compile(r"[^A-Za-z0-9._-]")


class OutputError(MechreportError):
    """The output folder cannot be used (not a folder, locked, not writable)."""


# --------------------------------------------------------------------------------- names

def safe_stem(path) -> str:
    """The folder name of one spec file, before disambiguation (see the module docstring)."""
    name = Path(path).name
    for suffix in SPEC_SUFFIXES:
        if name.lower().endswith(suffix):
            name = name[: -len(suffix)]
            break
    else:
        name = Path(name).stem if not name.startswith(".") else name
    name = _UNSAFE.sub("_", name)
    if name.strip(".") == "":
        return "spec"
    stripped = name.lstrip(".")
    name = "_" * (len(name) - len(stripped)) + stripped
    return name[:MAX_NAME]


def folder_names(paths: list[Path]) -> list[str]:
    """One distinct folder name per path, in order (see the module docstring)."""
    names: list[str | None] = [None] * len(paths)
    taken: set[str] = set()
    bases = [safe_stem(p) for p in paths]
    for i, base in enumerate(bases):                       # first come keeps its name
        if base.casefold() not in taken:
            names[i] = base
            taken.add(base.casefold())
    reserved = {b.casefold() for b in bases}
    for i, base in enumerate(bases):                       # the others: -2, -3, ...
        if names[i] is not None:
            continue
        n = 2
        while (f"{base}-{n}".casefold() in taken or f"{base}-{n}".casefold() in reserved):
            n += 1
        names[i] = f"{base}-{n}"
        taken.add(names[i].casefold())
    return names  # type: ignore[return-value]


def unique_specs(paths: list[Path]) -> list[Path]:
    """``paths`` without repeats of the same file (first mention kept)."""
    seen: set[str] = set()
    out = []
    for p in paths:
        try:
            key = str(Path(p).resolve())
        except (OSError, RuntimeError):
            key = os.path.abspath(p)
        if key not in seen:
            seen.add(key)
            out.append(Path(p))
    return out


def inside(out: Path, path: Path) -> Path:
    """``path`` if it resolves to a direct or deeper child of ``out``; raises otherwise."""
    root = Path(out).resolve()
    target = Path(path).resolve()
    if target == root or root not in target.parents:
        raise OutputError(f"refusing to write {path}: it is not inside the output folder {out}")
    return Path(path)


# ------------------------------------------------------------------------ output folder

def prepare(out: Path) -> Path:
    """Create ``out`` (and its parents) if needed; a clear error if it cannot be a folder."""
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise OutputError(f"{out}: the output folder (-o) is an existing file, not a folder")
    try:
        out.mkdir(parents=True, exist_ok=True)
    except FileExistsError:
        raise OutputError(f"{out}: cannot create the output folder: it, or a folder above "
                          "it, exists and is not a folder") from None
    except OSError as exc:
        raise OutputError(f"{out}: cannot create the output folder: "
                          f"{exc.strerror or exc}") from None
    if not os.access(out, os.W_OK | os.X_OK):
        raise OutputError(f"{out}: the output folder is not writable")
    return out


class OutputLock:
    """``OUT/.mechreport.lock`` held with ``flock`` while a build writes to ``OUT``.

    ``acquire(timeout)`` waits at most ``timeout`` seconds for another holder (telling the
    user once who it is), then raises :class:`OutputError`."""

    def __init__(self, out: Path, stream=None):
        self.out = Path(out)
        self.path = self.out / LOCK_NAME
        self.stream = stream or sys.stderr
        self.fd: int | None = None

    def holder(self) -> str:
        """The pid the holder wrote into the lock file ("" if unknown)."""
        try:
            fd = os.open(self.path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
        except OSError:
            return ""
        try:
            pid = os.read(fd, 32).decode("ascii").strip()
        except (OSError, ValueError):
            return ""
        finally:
            os.close(fd)
        return pid if pid.isdigit() else ""

    def _open(self) -> int:
        """The lock file, opened for writing without following a symbolic link, and only if
        it is a regular file with no other name (a hard link to a file elsewhere would be
        emptied by the lock): nothing outside ``OUT`` is ever written through it."""
        try:
            fd = os.open(self.path, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW | os.O_NONBLOCK
                         | getattr(os, "O_CLOEXEC", 0), 0o666)
        except OSError as exc:
            if exc.errno == errno.ELOOP:
                raise OutputError(f"{self.path}: the lock file is a symbolic link; refusing to "
                                  "follow it (remove it, or use another -o folder)") from None
            raise OutputError(f"{self.path}: cannot create the lock file: "
                              f"{exc.strerror or exc}") from None
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode) or st.st_nlink != 1:
            os.close(fd)
            what = "not a regular file" if not stat.S_ISREG(st.st_mode) else \
                "a hard link to another file"
            raise OutputError(f"{self.path}: the lock file is {what}; refusing to write to it "
                              "(remove it, or use another -o folder)")
        return fd

    def acquire(self, timeout: float = 120.0, poll: float = 0.2) -> "OutputLock":
        try:
            import fcntl
        except ImportError:                                 # pragma: no cover - not POSIX
            return self
        fd = self._open()
        deadline = time.monotonic() + max(timeout, 0.0)
        told = False
        try:
            while True:
                try:
                    fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
                    break
                except BlockingIOError:
                    pid = self.holder()
                    who = f"another build (pid {pid})" if pid else "another build"
                    if time.monotonic() >= deadline:
                        raise OutputError(
                            f"{who} is still writing to {self.out} after {timeout:g} s; "
                            "try again when it has finished, or use another -o folder") from None
                    if not told:
                        print(f"{who} is writing to {self.out}; waiting up to {timeout:g} s...",
                              file=self.stream)
                        told = True
                    time.sleep(poll)
            try:
                os.ftruncate(fd, 0)
                os.pwrite(fd, f"{os.getpid()}\n".encode("ascii"), 0)
            except OSError:
                pass        # a full disk: the lock holds all the same, its holder unnamed
        except BaseException:
            os.close(fd)
            raise
        self.fd = fd
        return self

    def release(self) -> None:
        if self.fd is not None:
            try:
                os.ftruncate(self.fd, 0)
            except OSError:
                pass
            os.close(self.fd)                               # closing drops the flock
            self.fd = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.release()


def tmp_dir(out: Path, name: str, pid: int | None = None) -> Path:
    """The private folder a spec is written into before it is swapped in."""
    return Path(out) / f".tmp-{name}-{pid or os.getpid()}"


def make_tmp_dir(out: Path, name: str, pid: int | None = None) -> Path:
    """Create (fresh) the private folder of ``name``; returns it."""
    tmp = inside(out, tmp_dir(out, name, pid))
    remove(tmp)
    tmp.mkdir()                                    # 0777 less the umask, like mkdir(1)
    return tmp


def as_in_place(exc: BaseException, tmp: Path, final: Path) -> BaseException:
    """``exc`` naming the file it was about as it would be in place: ``final/x`` for
    ``tmp/x`` (a private folder means nothing to a user reading "no space left on device
    writing ...")."""
    name = getattr(exc, "filename", None)
    prefix = str(tmp) + os.sep
    if isinstance(exc, OSError) and isinstance(name, str) and name.startswith(prefix):
        exc.filename = str(Path(final) / name[len(prefix):])
    return exc


def remove(path: Path) -> None:
    """Delete a file, symlink or folder tree if it is there (never follows a symlink)."""
    path = Path(path)
    try:
        if path.is_symlink() or not path.is_dir():
            path.unlink(missing_ok=True)
        else:
            shutil.rmtree(path, ignore_errors=True)
    except OSError:
        pass


STUDY_ENTRIES = ("study.parquet", "study.csv", "study.md", "study.pdf", "study-figures",
                 "study-reports")   # what `mechreport study` writes beside a spec's report
DYNAMICS_ENTRIES = ("dynamics.csv", "dynamics.parquet")   # what `mechreport dynamics` writes
#: what `mechreport tolerance` writes beside a spec's report (it also adds to summary.json)
TOLERANCE_ENTRIES = ("tolerance.parquet", "tolerance.csv", "tolerance.md", "tolerance.pdf",
                     "tolerance.json", "tolerance-figures")
OPTIMIZE_ENTRIES = ("optimum.yaml", "history.csv", "optimize.md", "optimize.pdf",
                    "optimize-figures", "optimum")   # what `mechreport optimize` writes
#: the entries that make a folder one of mechreport's (besides an empty one): one each of
#: ``build``, ``study``, ``dynamics``, ``tolerance`` and ``optimize``
OWN_ENTRIES = {"summary.json", "study.parquet", "dynamics.parquet", "tolerance.parquet",
               "optimize.md"}


def occupied(out: Path, name: str) -> str | None:
    """Why ``OUT/name`` must not be replaced, or None. Only a report folder (one holding
    summary.json), a study folder (study.parquet), a dynamics folder (dynamics.parquet) or an
    empty folder is replaced: a build into ``-o .`` must never delete a folder of the user's
    that happens to share a spec's name."""
    path = Path(out) / name
    if not os.path.lexists(path):
        return None
    advice = "move it away or use another -o folder"
    if path.is_symlink() or not path.is_dir():
        return f"{path} exists and is not a report folder; {advice}"
    try:
        entries = {e.name for e in path.iterdir()}
    except OSError as exc:
        return f"{path}: {exc.strerror or exc}"
    if entries and not entries & OWN_ENTRIES:
        return (f"{path} exists and is neither a mechreport report nor a study or dynamics "
                f"folder (no summary.json, study.parquet or dynamics.parquet); {advice}")
    return None


def link_tree(src: Path, dst: Path) -> None:
    """Copy ``src`` (a file or folder) to ``dst`` as hard links (a copy where linking fails)."""
    def link(a, b):
        try:
            os.link(a, b)
        except OSError:
            shutil.copy2(a, b)
    if src.is_symlink():
        os.symlink(os.readlink(src), dst)
    elif src.is_dir():
        shutil.copytree(src, dst, symlinks=True, copy_function=link)
    else:
        link(src, dst)


def swap_in(out: Path, tmp: Path, name: str,
            carry=lambda entry: entry in STUDY_ENTRIES + TOLERANCE_ENTRIES + OPTIMIZE_ENTRIES
            ) -> Path:
    """Replace ``OUT/name`` by the complete folder ``tmp`` (two renames; the old folder, if
    any, is deleted afterwards). Entries of the old folder for which ``carry(name)`` holds and
    that ``tmp`` lacks are carried over as hard links (a report keeps the study and the
    optimisation beside it, and they the report). Once a stop (Ctrl-C, SIGTERM) is requested, it raises it instead;
    one that comes during the renames is raised after them. Returns the final folder."""
    out = Path(out)
    if _UNSAFE.search(name) is not None or name.strip(".") == "" or name.startswith("."):
        raise OutputError(f"refusing to write {out / name}: {name!r} is not a folder name "
                          "mechreport makes")
    why = occupied(out, name)
    if why:
        raise OutputError(why)
    final = out / name
    inside(out, tmp)
    if os.path.lexists(final):
        for entry in final.iterdir():
            if carry(entry.name) and not os.path.lexists(tmp / entry.name):
                link_tree(entry, tmp / entry.name)
    old = out / f".old-{name}-{os.getpid()}"
    remove(old)
    check_stop()                       # once a stop is requested, no folder is replaced
    with held_stops():                 # both renames, or neither
        had_old = os.path.lexists(final)
        if had_old:
            os.rename(final, old)
        try:
            os.rename(tmp, final)
        except BaseException:
            if had_old:
                os.rename(old, final)
            raise
        if had_old:
            remove(old)
    return final


def all_but(entries):
    """The ``carry`` of a command that writes ``entries`` into a folder: every other entry of
    the old folder is kept (a study's folder keeps a report, ...)."""
    return lambda entry: entry not in entries


def write_folder(out: Path, name: str, write, carry) -> Path:
    """Write ``OUT/name`` whole: ``write(tmp)`` fills a fresh private folder
    (:func:`make_tmp_dir`), which is checked (nothing in it leads outside) and swapped in
    (:func:`swap_in`, carrying over the old entries for which ``carry(entry)`` holds); if
    anything fails or is interrupted, the private folder is deleted and ``OUT/name`` is left as
    it was. Call with the lock held (:func:`writing`). Returns the final folder."""
    why = occupied(out, name)
    if why:
        raise OutputError(why)
    tmp = make_tmp_dir(out, name)
    try:
        write(tmp)
        for written in tmp.rglob("*"):                  # nothing escaped the folder
            inside(tmp, written)
        return swap_in(out, tmp, name, carry)
    except OSError as exc:
        raise as_in_place(exc, tmp, Path(out) / name)
    finally:
        remove(tmp)                                     # gone already once swapped in


@contextmanager
def writing(out: Path, wait: float = 120.0, stream=None):
    """``with writing(OUT, wait) as out:`` the output folder made ready (:func:`prepare`) and
    locked for the block (:class:`OutputLock`, waiting up to ``wait`` seconds for another
    command writing there), an interrupted command's leftovers deleted
    (:func:`clean_leftovers`). Raises :class:`OutputError` if ``out`` cannot be used."""
    out = prepare(Path(out))
    with OutputLock(out, stream).acquire(wait):
        clean_leftovers(out)
        yield out


_LEFTOVER = re.compile(r"\.(?:tmp|old)-[A-Za-z0-9_][A-Za-z0-9._-]*-\d+")


def clean_leftovers(out: Path) -> list[str]:
    """Delete the ``.tmp-<name>-<pid>`` and ``.old-<name>-<pid>`` folders an interrupted
    build left in ``out`` (call with the lock held). Returns their names."""
    gone = []
    for entry in Path(out).iterdir():
        if _LEFTOVER.fullmatch(entry.name):
            remove(entry)
            gone.append(entry.name)
    return gone


# ------------------------------------------------------------------------- out of date

FAILED = "FAILED.json"
MAX_FAILED_BYTES = 1 << 20          # a FAILED.json holds one message: a few kB at most


def mark_failed(out: Path, name: str, spec: str, message: str) -> bool:
    """Write ``OUT/name/FAILED.json`` (see the module docstring) when ``OUT/name`` is a report
    folder; whether it was written. Never through a symbolic link. Raises OSError if it
    cannot be written."""
    from ..report.files import atomic_write_text
    from ..report.provenance import build_time
    from ..version import __version__
    folder = Path(out) / name
    if occupied(out, name) is not None or not (folder / "summary.json").is_file():
        return False                    # no report there (or not ours): nothing out of date
    record = {"status": "FAIL", "spec": spec, "message": message,
              "date": build_time().strftime("%Y-%m-%d %H:%M UTC"),
              "mechreport_version": __version__}
    # a new file renamed into place: a link of that name is replaced, never followed
    atomic_write_text(inside(out, folder) / FAILED, json.dumps(record, indent=2) + "\n")
    return True


def failure_of(folder: Path) -> str | None:
    """Why the report in ``folder`` is out of date (the message of its FAILED.json, on one
    line), or None when it has no FAILED.json. A FAILED.json that cannot be read still marks
    the folder (the message then says so). Only a regular file is read, at most
    ``MAX_FAILED_BYTES``."""
    path = Path(folder) / FAILED
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0)
                     | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0))
    except OSError as exc:
        if not os.path.lexists(path):
            return None
        return f"{FAILED} could not be read: {exc.strerror or exc}"
    try:
        st = os.fstat(fd)
        data = os.read(fd, MAX_FAILED_BYTES + 1) if stat.S_ISREG(st.st_mode) else b""
    except OSError as exc:
        return f"{FAILED} could not be read: {exc.strerror or exc}"
    finally:
        os.close(fd)
    try:
        message = json.loads(data.decode("utf-8"))["message"]
        if not isinstance(message, str) or len(data) > MAX_FAILED_BYTES:
            raise ValueError
    except (ValueError, TypeError, KeyError, RecursionError):
        return f"{FAILED} could not be read (not a mechreport {FAILED})"
    lines = (" ".join(line.split()) for line in message.splitlines())
    return "; ".join(line for line in lines if line) or "no reason given"


# ------------------------------------------------------------------------------ index

def report_folders(out: Path) -> dict[str, dict | str]:
    """Every report folder in ``out``: name -> its summary.json (a dict), or a message saying
    why it could not be read. Folders without summary.json are not reports and are skipped."""
    found: dict[str, dict | str] = {}
    for entry in sorted(Path(out).iterdir(), key=lambda p: p.name.casefold()):
        if entry.name.startswith(".") or entry.is_symlink() or not entry.is_dir():
            continue
        summary = entry / "summary.json"
        if not summary.is_file():
            continue
        try:
            data = json.loads(summary.read_text(encoding="utf-8"))
            if not isinstance(data, dict):
                raise ValueError("not a JSON object")
            found[entry.name] = data
        except (OSError, ValueError) as exc:
            found[entry.name] = f"{entry.name}/summary.json could not be read: {exc}"
    return found
