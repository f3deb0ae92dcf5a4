"""Files that appear whole or not at all.

Every output of the package (profiles, tables, figures, reports) is written to a temporary file
in the destination's folder and renamed over the destination when complete (``os.replace``,
atomic on POSIX and Windows). An interrupted run (an exception, Ctrl-C, a killed process)
leaves either the old file or the new one, never half of one.

A destination that is a symbolic link is written through: its target is replaced (atomically,
in the target's folder) and the link stays. A destination that is not a regular file (a
directory, a FIFO, a device, a socket) is refused with :class:`~cosserat.errors.InputError`,
never replaced by a plain file.

Temporary files are hidden and carry the writing process's id,
``.<name>.<pid>.<random>.tmp<suffix>``. A process removes its own on an exception and, on a
signal or the loss of its parent, through :func:`remove_own_temporaries`; the ones a killed
process (SIGKILL) could not remove are found by :func:`remove_stale_temporaries`, which deletes
those whose process no longer runs.
"""

from __future__ import annotations

import contextlib
import os
import re
import stat
import tempfile
import threading
from collections.abc import Iterator
from pathlib import Path
from typing import IO, Any

from .errors import InputError

_LIVE: set[str] = set()
"""The temporary files this process is writing now (removed on success or failure)."""
_LIVE_LOCK = threading.Lock()

_TEMPORARY = re.compile(r"^\.(?P<name>.+)\.(?P<pid>\d+)\.[A-Za-z0-9_]+\.tmp[^/]*$")
"""The name of a temporary file of :func:`atomic_path`; ``pid``: the process writing it."""


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def file_kind(mode: int) -> str | None:
    """What a file of ``mode`` is if not a regular file ("a FIFO (named pipe)", ...), or None."""
    if stat.S_ISREG(mode):
        return None
    if stat.S_ISDIR(mode):
        return "a directory"
    if stat.S_ISFIFO(mode):
        return "a FIFO (named pipe)"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "not a regular file"


def _resolved(path: str | Path) -> Path:
    """``path``, or the file its symbolic link(s) point to (which need not exist yet)."""
    return Path(os.path.realpath(path)) if os.path.islink(path) else Path(path)


def refusal(path: str | Path) -> str | None:
    """Why a write to ``path`` is refused ("it is a FIFO (named pipe); ..."), or None: it
    does not exist yet, or it is a regular file or a link to one."""
    target = _resolved(path)
    try:
        mode = target.stat().st_mode
    except OSError:
        return None  # does not exist (yet), or cannot be inspected: the write will say
    kind = file_kind(mode)
    if kind is None:
        return None
    via = f" (the target {target} of the link)" if target != Path(path) else ""
    return f"it is {kind}{via}; only a regular file is replaced"


def destination(path: str | Path) -> Path:
    """The file a write to ``path`` replaces: ``path``, or the file its symbolic link(s) point
    to (which need not exist yet).

    Raises
    ------
    InputError
        ``path`` (or what it points to) exists and is not a regular file.
    """
    why = refusal(path)
    if why is not None:
        raise InputError(f"cannot write {path}: {why}")
    return _resolved(path)


@contextlib.contextmanager
def atomic_path(path: str | Path) -> Iterator[Path]:
    """A temporary path beside ``path`` (same suffix) that replaces ``path`` on success
    (through a symbolic link: its target)."""
    target = destination(path)
    fd, tmp = tempfile.mkstemp(
        prefix=f".{target.name}.{os.getpid()}.",
        suffix=f".tmp{target.suffix}",
        dir=target.parent,
    )
    os.close(fd)
    with _LIVE_LOCK:
        _LIVE.add(tmp)
    try:
        yield Path(tmp)
        os.chmod(tmp, 0o666 & ~_umask())  # mkstemp's 0600 would hide the file from others
        os.replace(tmp, target)
    except BaseException as exc:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        if isinstance(exc, OSError) and exc.errno and not exc.filename:  # say which file
            raise OSError(exc.errno, exc.strerror or str(exc), str(target)) from exc
        raise
    finally:
        with _LIVE_LOCK:
            _LIVE.discard(tmp)


def remove_own_temporaries() -> None:
    """Delete the temporary files this process is writing (before it exits at once, on a
    signal or when its parent is gone: no ``finally`` block runs then)."""
    with _LIVE_LOCK:
        live = list(_LIVE)
        _LIVE.clear()
    for tmp in live:
        with contextlib.suppress(OSError):
            os.unlink(tmp)


def destination_of(path: str | Path) -> Path:
    """The file a temporary file of :func:`atomic_path` was to become (``path`` itself if it is
    not one), for messages about a write that failed."""
    path = Path(path)
    match = _TEMPORARY.match(path.name)
    return path.with_name(match["name"]) if match else path


def _running(pid: int) -> bool:
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:  # exists, another user's
        return True
    return True


def remove_stale_temporaries(folder: str | Path) -> list[Path]:
    """Delete the temporary files in ``folder`` left by processes that no longer run (killed
    while writing); returns them. Another running process's files are left alone."""
    removed = []
    with contextlib.suppress(OSError):
        for entry in os.scandir(folder):
            match = _TEMPORARY.match(entry.name)
            stale = match is not None and not _running(int(match["pid"]))
            if stale and entry.is_file(follow_symlinks=False):
                with contextlib.suppress(OSError):
                    os.unlink(entry.path)
                    removed.append(Path(entry.path))
    return removed


@contextlib.contextmanager
def atomic_open(path: str | Path, newline: str | None = None) -> Iterator[IO[str]]:
    """``open(path, "w")`` whose content appears at ``path`` only when the block completes."""
    with atomic_path(path) as tmp, tmp.open("w", newline=newline, encoding="utf-8") as fh:
        yield fh


def write_text(path: str | Path, text: str) -> Path:
    """``Path(path).write_text(text)``, atomically."""
    with atomic_open(path) as fh:
        fh.write(text)
    return Path(path)


def save_figure(fig: Any, path: str | Path, **kwargs: Any) -> Path:
    """``fig.savefig(path)``, atomically (the format from ``path``'s suffix)."""
    target = Path(path)
    fmt = kwargs.pop("format", None) or target.suffix.lstrip(".")
    if not fmt:
        raise InputError(f"cannot write the figure {path}: no suffix to tell the image format")
    with atomic_path(target) as tmp:
        fig.savefig(tmp, format=fmt, **kwargs)
    return target
