"""The per-bin autocorrelation times of omega, u and nu in the sidecar (referee 11, point 2):
where the material barely moves, their block errors may understate the scatter between runs,
so their times are recorded beside the stresses'."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.signal import lfilter

from cosserat.dem import PlaneShearDEM, RunLength, build_deck
from cosserat.dem.analyse import FINE_BIN, RunSamples, steady_profile
from cosserat.dem.checks import profile_autocorrelation
from cosserat.dem.coarse import Grains2D, Samples, bin_sums

GAP, V = 6.0, 0.0025
FINE = np.arange(-1.0, GAP + 2.0 + 1e-9, FINE_BIN)
DECK = build_deck(PlaneShearDEM(gap=GAP, wall_speed=V, run=RunLength(settle_steps=0, steps=20_000,
                                                        dump_every=1_000)))  # fmt: skip


def _ar1(phi: float, n: int, rng: np.random.Generator) -> np.ndarray:
    """A stationary AR(1) series, integrated autocorrelation time (1 + phi) / (1 - phi)."""
    return lfilter([1.0], [1.0, -phi], rng.normal(size=n + 2000))[2000:]


def test_omega_u_nu_ar1_bins_give_their_known_tau_in_blocks():
    # blocks of 40 samples: omega's bin AR(1) with phi = 0.95 (tau = 39 samples, 0.975 blocks),
    # u independent (1/40 blocks), nu phi = 0.6 (tau = 4, 0.1 blocks)
    rng = np.random.default_rng(11)
    n, blocks = 200_000, 5_000
    rec = profile_autocorrelation(
        {
            "omega": _ar1(0.95, n, rng)[:, None],
            "u": _ar1(0.0, n, rng)[:, None],
            "nu": 0.8 + 0.01 * _ar1(0.6, n, rng)[:, None],
        },
        0,
        blocks,
    )
    assert rec["omega"]["per_bin"][0] == pytest.approx(39 / 40, rel=0.15)
    assert rec["u"]["per_bin"][0] == pytest.approx(1 / 40, rel=0.05)
    assert rec["nu"]["per_bin"][0] == pytest.approx(4 / 40, rel=0.08)
    # omega's block (40 samples) is shorter than 2 tau (78): short; the others are not
    assert (rec["omega"]["short"], rec["u"]["short"], rec["nu"]["short"]) == (True, False, False)
    assert rec["short"] is True
    assert "omega, u and nu" in rec["note"]


def _grains(shift: float) -> Grains2D:
    """Pairs of equal grains about each fine bin's centre in the gap, u = 0.13 V y + shift,
    no spin, the same places every sample (nu constant)."""
    centres = 0.5 * (FINE[1:] + FINE[:-1])
    centres = centres[(centres > 0.0) & (centres < GAP)]
    s = np.concatenate([centres - 0.06, centres + 0.06])
    k = s.size
    return Grains2D(s, 0.13 * V * s + shift, np.zeros(k), np.zeros(k), np.ones(k),
                    np.full(k, 0.2), np.zeros((k, 4)))  # fmt: skip


def test_the_sidecar_records_u_and_leaves_constant_omega_and_nu_out():
    # every bin's u is one series (the samples' common shift) plus the bin's own constant, so
    # every bin has the same tau; omega (0) and nu (fixed grains) are constant: no time
    shifts = 0.01 * V * np.sin(0.7 * np.arange(40))
    sums = np.stack([bin_sums(_grains(c), FINE) for c in shifts])
    series = np.ones(40)
    run = RunSamples(Samples(np.arange(40) * 1000, sums, FINE, np.diff(FINE) * 20.0),
                     V * series, GAP * series, series, -0.3 * series, V * series,
                     100)  # fmt: skip
    p = steady_profile(run, DECK, lammps_version="synthetic", first=0, blocks=4)
    prof = p.sidecar["block_autocorrelation"]["profiles"]
    assert "omega" not in prof and "nu" not in prof
    u = prof["u"]["per_bin"]
    known = [x for x in u if x is not None]
    assert [x is None for x in u] == [not np.isfinite(x) for x in p.columns["u"]]
    assert len(known) >= 5
    assert max(known) == min(known) == prof["u"]["max"] == prof["u"]["median"]
