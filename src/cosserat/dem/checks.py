"""Checks on DEM profiles: is the flow rate-independent (quasi-static)? Are the time blocks
long enough for their means to be independent (:func:`block_autocorrelation`)?"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError, ParameterError


@dataclass(frozen=True)
class RateCheck:
    """Two scaled profiles compared bin by bin.

    Attributes
    ----------
    z : ndarray
        (a - b) / sqrt(se_a^2 + se_b^2) per bin (b interpolated onto a's coordinate).
    within : float
        Fraction of bins with |z| <= ``z_limit`` [-].
    chi2_per_dof : float
        mean(z^2) [-]: about 1 when the profiles agree within their errors.
    consistent : bool
        ``within`` at least the fraction a normal law puts inside ``z_limit`` less 10 points.
    """

    column: str
    z: np.ndarray
    within: float
    chi2_per_dof: float
    z_limit: float
    consistent: bool


_NORMAL_INSIDE = {1.0: 0.6827, 2.0: 0.9545, 3.0: 0.9973}


def rate_independence(
    a: dict[str, np.ndarray], b: dict[str, np.ndarray], column: str = "u", z_limit: float = 2.0
) -> RateCheck:
    """Compare the scaled ``column`` of two runs at different wall speeds.

    Parameters
    ----------
    a, b : dict
        Profile columns (corpus format, e.g. :attr:`DEMProfile.columns` or a CSV read into a
        dict); the coordinate is ``y`` or ``r``.
    z_limit : float
        The bins' agreement threshold in combined standard errors (1, 2 or 3).
    """
    if z_limit not in _NORMAL_INSIDE:
        raise InputError(f"z_limit must be 1, 2 or 3; got {z_limit!r}")
    coord = "y" if "y" in a else "r"
    for prof, name in ((a, "a"), (b, "b")):
        for key in (coord, column, f"{column}_se"):
            if key not in prof:
                raise InputError(f"profile {name} has no column {key!r}")
    xa, xb = np.asarray(a[coord], float), np.asarray(b[coord], float)
    inside = (xa >= xb.min()) & (xa <= xb.max())
    va = np.asarray(a[column], float)[inside]
    sa = np.asarray(a[f"{column}_se"], float)[inside]
    vb = np.interp(xa[inside], xb, np.asarray(b[column], float))
    sb = np.interp(xa[inside], xb, np.asarray(b[f"{column}_se"], float))
    se = np.hypot(sa, sb)
    ok = np.isfinite(va) & np.isfinite(vb) & (se > 0)
    if not ok.any():
        raise InputError("the two profiles share no bin with a finite value and error")
    z = (va[ok] - vb[ok]) / se[ok]
    within = float(np.mean(np.abs(z) <= z_limit))
    return RateCheck(
        column,
        z,
        within,
        float(np.mean(z**2)),
        z_limit,
        within >= _NORMAL_INSIDE[z_limit] - 0.10,
    )


# --------------------------------------------------------------------------- blocks
WINDOW_C = 5.0
"""Sokal's automatic window: the autocorrelation sum stops at the first lag M >= WINDOW_C tau(M)."""
MIN_BLOCK_TAUS = 2.0
"""A block shorter than this many integrated autocorrelation times is flagged: its mean is
correlated with its neighbours', and the block standard errors are too small."""
MIN_AUTOCORRELATION_SAMPLES = 20
"""Fewest samples from which an autocorrelation time is estimated."""


def autocorrelation_time(series: np.ndarray) -> tuple[float, bool] | None:
    """The integrated autocorrelation time of a sampled series [samples], and whether its
    estimate is reliable.

    ``tau = 1 + 2 sum_{t=1}^{M} rho(t)`` (``rho`` the normalised autocovariance, by FFT), with
    Sokal's automatic window: ``M`` the first lag with ``M >= WINDOW_C tau(M)``; unreliable
    when no such lag exists below half the series (then ``tau`` at half the series, a lower
    bound). Independent samples give tau = 1; an AR(1) series with lag-1 correlation ``phi``
    gives ``(1 + phi)/(1 - phi)``. A block of ``b`` samples has a mean independent of its
    neighbours' when ``b`` is several tau.

    Returns
    -------
    (tau, reliable) or None
        None with fewer than :data:`MIN_AUTOCORRELATION_SAMPLES` finite samples, or a series
        constant up to round-off (its spread below 1e-12 of its largest magnitude).
    """
    x = np.asarray(series, dtype=float)
    x = x[np.isfinite(x)]
    n = x.size
    if n < MIN_AUTOCORRELATION_SAMPLES:
        return None
    d = x - x.mean()
    var = float(d @ d) / n
    if not var > (1e-12 * float(np.max(np.abs(x)))) ** 2:  # constant up to round-off
        return None
    size = 1 << (2 * n - 1).bit_length()
    f = np.fft.rfft(d, size)
    acov = np.fft.irfft(f * np.conj(f), size)[:n] / n
    rho = acov / acov[0]
    tau = 1.0
    for m in range(1, n // 2):
        tau += 2.0 * float(rho[m])
        if m >= WINDOW_C * tau:
            return max(tau, 1e-12), True
    return max(tau, 1.0), False


def block_autocorrelation(
    series: dict[str, np.ndarray], first: int, blocks: int, every: int
) -> dict:
    """The block length of a run's steady window against the integrated autocorrelation time
    of each per-sample series (the sidecar's ``block_autocorrelation``).

    Parameters
    ----------
    series : dict
        Name -> the whole per-sample series (the bulk velocity of the free grains, the wall's
        shear stress, the gap, ...).
    first : int
        Index of the first steady sample.
    blocks : int
        Blocks of the steady window.
    every : int
        Steps between samples.

    Returns
    -------
    dict
        ``block_samples``, ``block_steps``; per observable ``tau_samples``, ``tau_steps``,
        ``blocks_per_tau`` (the block length in autocorrelation times), ``reliable`` and
        ``short`` (the block shorter than :data:`MIN_BLOCK_TAUS` tau); ``short``: any
        observable's; ``note``: the rule.
    """
    if blocks < 1 or every < 1:
        raise InputError(f"blocks and steps between samples must be >= 1; got {blocks}, {every}")
    out: dict = {}
    n = None
    for name, values in series.items():
        x = np.asarray(values, dtype=float)[first:]
        n = x.size
        est = autocorrelation_time(x)
        if est is None:
            continue
        tau, reliable = est
        b = x.size / blocks
        out[name] = {
            "tau_samples": round(tau, 3),
            "tau_steps": round(tau * every),
            "blocks_per_tau": round(b / tau, 3),
            "reliable": reliable,
            "short": bool(b < MIN_BLOCK_TAUS * tau),
        }
    b = (n or 0) / blocks
    return {
        "block_samples": round(b, 3),
        "block_steps": round(b * every),
        "observables": out,
        "short": any(v["short"] for v in out.values()),
        "note": (
            "integrated autocorrelation time tau of each per-sample series over the steady "
            f"window (Sokal's window, c = {WINDOW_C:g}; 'reliable' false: the window did not "
            f"close within half the series, tau a lower bound); a block shorter than "
            f"{MIN_BLOCK_TAUS:g} tau is 'short': neighbouring block means are then correlated "
            "and the block standard errors too small"
        ),
    }


PROFILE_NOTE = (
    "per bin (the profile's rows), the integrated autocorrelation time of the per-sample "
    "field (the stresses; omega, u and nu) of that bin over the steady window (as for "
    "'observables'), in blocks (tau_blocks = tau_samples / block_samples): per_bin (null "
    "where a bin's series is "
    "constant or too short), its largest (max, at row max_row) and median over the bins, the "
    "bins whose estimate is a lower bound (unreliable_bins) and 'short' (any bin's block shorter "
    "than 2 tau). A series whose tau is one block or more gives about blocks / tau_blocks "
    "independent samples in the window, and its block standard errors are too small by about "
    "cosserat.dem.checks.block_se_factor (about sqrt(tau_blocks) for tau of several blocks)"
)
"""The ``note`` of the sidecar's ``block_autocorrelation.profiles`` record."""


def profile_autocorrelation(profiles: dict[str, np.ndarray], first: int, blocks: int) -> dict:
    """Per-bin integrated autocorrelation times of per-sample profiles, in blocks (the
    sidecar's ``block_autocorrelation.profiles``; referee 10, point 8: the stresses'; referee
    11, point 2: omega, u and nu).

    Parameters
    ----------
    profiles : dict
        Name (the profile's column, e.g. ``sigma_yx``) -> the whole per-sample profile, shape
        (samples, bins) [any unit: tau does not depend on it].
    first : int
        Index of the first steady sample.
    blocks : int
        Blocks of the steady window.

    Returns
    -------
    dict
        Per name: ``per_bin`` (tau in blocks to 4 significant digits, null where
        :func:`autocorrelation_time` gives none), ``max``, ``max_row``, ``median`` (over the
        bins that have one), ``bins``, ``unreliable_bins`` and ``short`` (a block shorter
        than :data:`MIN_BLOCK_TAUS` tau in any bin); ``short``: any name's; ``note``:
        :data:`PROFILE_NOTE`.

    Raises
    ------
    InputError
        Fewer than one block, a profile that is not 2-D, or fewer steady samples than blocks.
    """
    if blocks < 1:
        raise InputError(f"blocks must be >= 1; got {blocks}")
    out: dict = {}
    for name, values in profiles.items():
        x = np.asarray(values, dtype=float)
        if x.ndim != 2:
            raise InputError(f"profile {name!r} must be (samples, bins); got shape {x.shape}")
        x = x[first:]
        if x.shape[0] < blocks:
            raise InputError(f"{x.shape[0]} steady samples cannot make {blocks} blocks")
        block = x.shape[0] / blocks
        per_bin: list[float | None] = []
        unreliable = 0
        for k in range(x.shape[1]):
            est = autocorrelation_time(x[:, k])
            if est is None:
                per_bin.append(None)
                continue
            per_bin.append(float(f"{est[0] / block:.4g}"))
            unreliable += not est[1]
        known = [(v, k) for k, v in enumerate(per_bin) if v is not None]
        if not known:
            continue
        top, row = max(known)
        out[name] = {
            "per_bin": per_bin,
            "max": top,
            "max_row": row,
            "median": float(f"{float(np.median([v for v, _ in known])):.4g}"),
            "bins": len(known),
            "unreliable_bins": unreliable,
            "short": bool(top > 1.0 / MIN_BLOCK_TAUS),
        }
    return {
        **out,
        "short": any(v["short"] for v in out.values()),
        "note": PROFILE_NOTE,
    }


def block_se_factor(tau_blocks: float, blocks: int, block_samples: float = 1000.0) -> float:
    """How much too small the block standard error of a window mean is, for a series whose
    integrated autocorrelation time is ``tau_blocks`` blocks [-].

    The series is taken as AR(1) with that time (lag-1 correlation ``phi = (tau - 1) /
    (tau + 1)``, ``tau`` in samples): the factor is ``sqrt(Var(window mean) / E[s_B^2 /
    blocks])``, ``s_B^2`` the sample variance of the ``blocks`` block means, both exact for
    AR(1) (``S(m) = sum_{i,j<m} phi^|i-j| = m (1 + phi)/(1 - phi) - 2 phi (1 - phi^m) /
    (1 - phi)^2``; ``Var(mean of m) = S(m)/m^2``, ``E[s_B^2] = blocks (Var(B) - Var(M)) /
    (blocks - 1)``). 1 for independent samples; about ``sqrt(tau_blocks)`` once tau is
    several blocks (more with few blocks: ``s_B^2`` is then biased low too).

    Parameters
    ----------
    tau_blocks : float
        The autocorrelation time in blocks (> 0) [-].
    blocks : int
        Blocks of the window (>= 2).
    block_samples : float
        Samples per block [-] (the factor depends on it only through ``tau_blocks`` once a
        block holds many samples).

    Raises
    ------
    ParameterError
        tau_blocks not positive and finite, fewer than 2 blocks, or tau under one sample.
    """
    if not (math.isfinite(tau_blocks) and tau_blocks > 0.0):
        raise ParameterError(f"tau_blocks must be positive and finite; got {tau_blocks}")
    if blocks < 2:
        raise ParameterError(f"blocks must be >= 2; got {blocks}")
    tau = tau_blocks * block_samples
    if tau < 1.0:
        raise ParameterError(
            f"tau must be at least one sample (tau_blocks x block_samples = {tau:g})"
        )
    phi = (tau - 1.0) / (tau + 1.0)

    def s(m: float) -> float:
        return m * (1.0 + phi) / (1.0 - phi) - 2.0 * phi * (1.0 - phi**m) / (1.0 - phi) ** 2

    var_b = s(block_samples) / block_samples**2
    n = blocks * block_samples
    var_m = s(n) / n**2
    expected = blocks * (var_b - var_m) / (blocks - 1) / blocks
    return math.sqrt(var_m / expected)


def block_length_text(
    record: dict | None, blocks: int | None = None, steps: int | None = None
) -> str:
    """One sentence on a run's block length against its autocorrelation times (the sidecar's
    ``block_autocorrelation``, its stresses' per-bin times where recorded), or on what a
    sidecar without it lacks."""
    if not record:
        length = f" (blocks of {steps / blocks:,.0f} steps)" if blocks and steps else ""
        return (
            f"block length against the autocorrelation time: not recorded{length}; the run was "
            "analysed before cosserat.dem recorded it, and its per-sample series are not kept "
            "with the profile, so it needs the run's dumps analysed again"
        )
    parts = []
    for name, v in record.get("observables", {}).items():
        flag = " SHORT" if v.get("short") else ""
        bound = "" if v.get("reliable", True) else " (tau a lower bound)"
        parts.append(
            f"{name.replace('_', ' ')}: tau = {v['tau_steps']:,.0f} steps{bound}, block = "
            f"{v['blocks_per_tau']:.3g} tau{flag}"
        )
    head = f"blocks of {record.get('block_steps', 0):,.0f} steps"
    verdict = (
        f"; blocks shorter than {MIN_BLOCK_TAUS:g} autocorrelation times: their standard errors "
        "are too small"
        if record.get("short")
        else f"; every block is at least {MIN_BLOCK_TAUS:g} autocorrelation times long"
    )
    profiles = record.get("profiles") or {}
    stresses = [
        f"{name} up to {v['max']:.2g} blocks (median {v['median']:.2g})"
        for name, v in profiles.items()
        if isinstance(v, dict) and "max" in v
    ]
    tail = (
        "; the stresses' per-bin times: " + ", ".join(stresses)
        + (f" (some bins' blocks shorter than {MIN_BLOCK_TAUS:g} tau: their errors too "
           "small)" if profiles.get("short") else "")
        if stresses
        else ""
    )  # fmt: skip
    return (
        head
        + " against the integrated autocorrelation time ("
        + "; ".join(parts)
        + ")"
        + verdict
        + tail
    )
