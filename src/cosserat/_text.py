"""Text files the package reads (measured profiles, corpus runs, sweep specs): UTF-8.

A leading byte-order mark (as spreadsheet programs write "UTF-8 with BOM") is accepted and
dropped. Another encoding (Latin-1, UTF-16, a binary file) is refused with
:class:`~cosserat.errors.InputError` saying the expected encoding and where the first byte that
is not UTF-8 sits (line, column and its value), never guessed: a guess could read a number
wrongly without a word.
"""

from __future__ import annotations

from pathlib import Path

from .errors import InputError

ENCODING = "UTF-8"
"""The encoding of every text file the package reads."""


def decode(data: bytes, name: str | Path) -> str:
    """``data`` as UTF-8 text (a leading byte-order mark dropped).

    Raises
    ------
    InputError
        ``data`` is not UTF-8; the message names ``name``, the line, the column and the byte.
    """
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise InputError(f"{name}: {not_utf8(data, exc)}") from None


def not_utf8(data: bytes, exc: UnicodeDecodeError) -> str:
    """What :func:`decode` says of ``data``: the first byte that is not UTF-8 and where."""
    before = data[: exc.start]
    line = before.count(b"\n") + 1
    column = exc.start - (before.rfind(b"\n") + 1) + 1
    if b"\x00" in data[:4096]:
        kind = "not a text file (it holds NUL bytes: binary, or UTF-16)"
    else:
        kind = f"not {ENCODING} text"
    return (
        f"{kind}: byte 0x{data[exc.start]:02x} at line {line}, column {column} is not valid "
        f"{ENCODING}; save the file as {ENCODING} (with or without a byte-order mark)"
    )


def read_text(path: str | Path, name: str | None = None) -> str:
    """The text of the file ``path`` (:func:`decode`; ``name``: how the message names it,
    default the path).

    Raises
    ------
    OSError
        As :func:`open` (no such file, a directory, no permission).
    InputError
        Not UTF-8 (:func:`decode`).
    """
    return decode(Path(path).read_bytes(), path if name is None else name)
