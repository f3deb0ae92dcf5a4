"""Text files the package reads (measured profiles, corpus runs, sweep specs): UTF-8.

A leading byte-order mark (as spreadsheet programs write "UTF-8 with BOM") is accepted and
dropped. Another encoding (Latin-1, UTF-16, a binary file) is refused with
:class:`~cosserat.errors.InputError` saying the expected encoding and where the first byte that
is not UTF-8 sits (line, column and its value), never guessed: a guess could read a number
wrongly without a word.

It also holds the one formatter of statistical significance (:func:`significance`): p-values
below :data:`SIGNIFICANCE_P` are printed as a z-score and chi^2/dof.
"""

from __future__ import annotations

import math
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


# --- significance of a chi^2, as a referee can read it -------------------------------------

SIGNIFICANCE_P = 1e-6
"""A p-value below this is printed as a z-score and chi^2/dof (:func:`significance`), never
as a number such as 1e-41 or 10^-631 that only says "far in the tail"."""


def chi2_ln_p(chi2: float, dof: int) -> float:
    """ln P(X >= chi2) for X ~ chi^2(dof) [-], finite where the p-value underflows.

    Raises
    ------
    ValueError
        ``chi2`` is not finite or negative, or ``dof`` < 1.
    """
    if not (math.isfinite(chi2) and chi2 >= 0.0):
        raise ValueError(f"chi^2 = {chi2}: must be finite and >= 0")
    if dof < 1:
        raise ValueError(f"dof = {dof}: a p-value needs at least one degree of freedom")
    from scipy import stats

    ln_p = float(stats.chi2.logsf(chi2, dof))
    if not math.isfinite(ln_p):  # far in the tail: the leading term of Q(k/2, x/2)
        a, x = 0.5 * dof, 0.5 * chi2
        ln_p = -x + (a - 1.0) * math.log(x) - math.lgamma(a)
    return ln_p


def z_score(ln_p: float) -> float:
    """The one-sided normal z whose upper tail is exp(``ln_p``) [-] (p = 0.5: z = 0;
    p = 1e-6: z = 4.75), finite for any ``ln_p`` <= 0 however far in the tail."""
    from scipy.special import ndtri_exp

    return float(-ndtri_exp(min(float(ln_p), 0.0)))


def p_or_z(ln_p: float) -> str:
    """``p = 0.0012`` or, below :data:`SIGNIFICANCE_P`, ``z = 12.3`` (:func:`z_score`)."""
    if ln_p >= math.log(SIGNIFICANCE_P):
        return f"p = {math.exp(ln_p):.2g}"
    return f"z = {z_score(ln_p):.1f}"


def significance(chi2: float, dof: int) -> str:
    """How improbable a chi^2 on ``dof`` degrees of freedom is, as a referee can read it.

    ``p = 0.034`` while p >= :data:`SIGNIFICANCE_P`; below it,
    ``z = 13.2, chi^2/dof = 412/40`` (z: the one-sided normal deviate with the same tail
    probability, :func:`z_score`). The one formatter of significances in the package.

    Parameters
    ----------
    chi2 : float
        The chi^2 [-], finite and >= 0.
    dof : int
        Degrees of freedom, >= 1.

    Raises
    ------
    ValueError
        As :func:`chi2_ln_p`.
    """
    ln_p = chi2_ln_p(chi2, dof)
    if ln_p >= math.log(SIGNIFICANCE_P):
        return f"p = {math.exp(ln_p):.2g}"
    shown = f"{chi2:.0f}" if chi2 >= 100.0 else f"{chi2:.3g}"
    return f"z = {z_score(ln_p):.1f}, chi^2/dof = {shown}/{dof}"
