"""Files the command line reads and writes, with the operating system's failures turned into
:class:`~cosserat.errors.InputError` naming the file and the reason (exit status 2, one line).

Outputs are checked before any computation (``check_*``), so that a long run does not fail at
its end for a mistyped path; the writes themselves are guarded too.

One rule for missing folders, in every command: an output's folder (``--out FILE``,
``--plot FILE``, a sweep's table, an ``--out`` folder) is created if it does not exist, as
``mkdir -p`` would, when the output is written; a path through a regular file, or below a
folder that cannot be written, is refused before any work.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from .. import _atomic as atomic
from ..errors import InputError


def reason(exc: OSError) -> str:
    """The operating system's reason, lower case ("no such file or directory")."""
    text = exc.strerror or str(exc) or type(exc).__name__
    return text[:1].lower() + text[1:]


def read_measured(path: str, what: str = "measured profile") -> Any:
    """:func:`cosserat.analysis.measurements.read_profile` of the file ``path``.

    Raises
    ------
    InputError
        The file does not exist, is a directory, cannot be read, or is not UTF-8 text.
    MeasurementError
        Its content is malformed (the message starts with the file name).
    """
    from ..analysis.measurements import MeasurementError, read_profile

    try:
        return read_profile(Path(path))
    except OSError as exc:
        raise InputError(f"cannot read the {what} {path}: {reason(exc)}") from None
    except MeasurementError as exc:
        raise MeasurementError(f"{path}: {exc}") from None


def check_output_file(path: str, option: str = "--out") -> None:
    """Raise :class:`InputError` unless ``path`` can be created or overwritten as a regular
    file (a symbolic link: its target is written, the link stays; a directory, FIFO, device
    or socket is refused, never replaced). A missing folder is fine if it can be created
    there (module docstring): the write creates it."""
    why = atomic.refusal(path)
    if why is not None:
        raise InputError(f"cannot write {option} {path}: {why}")
    target = atomic.destination(path)
    folder = target.parent
    existing = folder
    while not existing.exists() and existing != existing.parent:
        existing = existing.parent
    if not existing.is_dir():
        raise InputError(f"cannot write {option} {path}: {existing} is not a folder")
    if not os.access(existing, os.W_OK | os.X_OK) or (
        target.exists() and not os.access(target, os.W_OK)
    ):
        raise InputError(f"cannot write {option} {path}: permission denied")


def same_file_key(path: str) -> str:
    """What identifies the file a write to ``path`` lands in (links and ``..`` resolved)."""
    return os.path.realpath(path)


def write_text(text: str, path: str, option: str = "--out") -> None:
    """Write ``text`` (ending in a newline) to ``path``; failures as :class:`InputError`."""
    try:
        _make_folder(path)
        atomic.write_text(path, text if text.endswith("\n") else text + "\n")
    except InputError as exc:
        why = atomic.refusal(path)
        raise InputError(f"cannot write {option} {path}: {why}" if why else str(exc)) from None
    except OSError as exc:
        raise InputError(f"cannot write {option} {path}: {reason(exc)}") from None


def _make_folder(path: str) -> None:
    """Create the folder of the file ``path`` if it is missing (module docstring)."""
    atomic.destination(path).parent.mkdir(parents=True, exist_ok=True)


def make_folder_of(path: str, option: str = "--out") -> None:
    """Create the folder of the output file ``path`` now (for writers outside this module);
    :class:`InputError` if it cannot be."""
    try:
        _make_folder(path)
    except OSError as exc:
        raise InputError(f"cannot write {option} {path}: {reason(exc)}") from None


def check_plot_file(path: str, option: str = "--plot") -> None:
    """Raise :class:`InputError` unless matplotlib can write ``path``: a file it may write
    (:func:`check_output_file`) with a suffix naming a format it knows."""
    from matplotlib.backend_bases import FigureCanvasBase

    suffix = Path(path).suffix.lower().lstrip(".")
    formats = FigureCanvasBase.get_supported_filetypes()
    check_output_file(path, option)
    if not suffix:
        raise InputError(
            f"cannot write {option} {path}: no suffix to tell the image format; add one of "
            f"{', '.join(sorted(formats))} (e.g. {path}.png)"
        )
    if suffix not in formats:
        raise InputError(
            f"cannot write {option} {path}: unknown image format {suffix!r}; use one of "
            f"{', '.join(sorted(formats))}"
        )


def save_figure(fig: Any, path: str, option: str = "--plot") -> None:
    """``fig.savefig(path)``; failures to write as :class:`InputError`."""
    try:
        _make_folder(path)
        atomic.save_figure(fig, path)
    except InputError as exc:
        why = atomic.refusal(path)
        raise InputError(f"cannot write {option} {path}: {why}" if why else str(exc)) from None
    except OSError as exc:
        raise InputError(f"cannot write {option} {path}: {reason(exc)}") from None


def output_folder(path: str, option: str = "--out") -> Path:
    """Create the folder ``path`` if needed; :class:`InputError` if it cannot be written."""
    p = Path(path)
    try:
        p.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        why = "it is a file" if isinstance(exc, FileExistsError) else reason(exc)
        raise InputError(f"cannot use {option} {path} as the output folder: {why}") from None
    if not os.access(p, os.W_OK | os.X_OK):
        raise InputError(f"cannot use {option} {path} as the output folder: permission denied")
    return p
