"""Atomic file writes: a temporary file in the same folder, then a rename, so an interrupted
build never leaves a half-written report. Files get the permissions of an ordinary
``open(..., "w")`` (0666 less the user's umask), not the 0600 of a bare temporary file;
folders are made with ``mkdir`` (0777 less the umask)."""
from __future__ import annotations

import os
import tempfile
from pathlib import Path


def _proc_umask() -> int | None:
    try:
        with open("/proc/self/status", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError):
        pass
    return None


def _set_and_restore_umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


#: elsewhere than Linux the umask can only be read by setting it: done once, at import
_FALLBACK = None if _proc_umask() is not None else _set_and_restore_umask()


def umask() -> int:
    """The process umask now (Linux: from /proc, so never changed even for an instant)."""
    mask = _proc_umask()
    if mask is None:
        mask = _FALLBACK if _FALLBACK is not None else _set_and_restore_umask()
    return mask


def file_mode() -> int:
    """Permissions of a new file: 0666 less the umask."""
    return 0o666 & ~umask()


def atomic_write_bytes(path: Path, data: bytes) -> Path:
    """Write ``data`` to ``path`` atomically. An OSError names ``path`` (a failed write names
    no file, a failed temporary file its own name), e.g. for "no space left on device"."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    try:
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    except OSError as exc:
        raise _naming(exc, path) from exc
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            if hasattr(os, "fchmod"):
                os.fchmod(fh.fileno(), file_mode())
        os.replace(tmp, path)
    except BaseException as exc:
        Path(tmp).unlink(missing_ok=True)
        if isinstance(exc, OSError):
            raise _naming(exc, path) from exc
        raise
    return path


def _naming(exc: OSError, path: Path) -> OSError:
    """``exc`` (same errno, same class) naming the file being written, ``path``."""
    if exc.errno is None:
        return exc
    return OSError(exc.errno, exc.strerror or os.strerror(exc.errno), str(path))


def atomic_write_text(path: Path, text: str) -> Path:
    return atomic_write_bytes(path, text.encode("utf-8"))
