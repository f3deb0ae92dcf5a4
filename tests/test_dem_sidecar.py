"""The sidecar's measures of regime and steadiness (``cosserat.dem.analyse``): the steadiness
test on series with and without a trend, the lag-1 bin correlation on blocks of known AR(1)
noise, and the criterion constants shared with the calibration."""

from __future__ import annotations

import math

import numpy as np
import pytest

from cosserat.dem.analyse import (
    QUASI_STATIC_I,
    STEADY_BINS,
    STEADY_Z,
    WALL_BINS,
    bin_correlation,
    block_series,
    steadiness,
)


def test_the_quasi_static_criterion_is_the_calibrations():
    from cosserat.calibration import data

    assert (QUASI_STATIC_I, WALL_BINS) == (data.QUASI_STATIC_I, data.WALL_BINS) == (1e-3, 3)


def test_block_series_are_the_means_of_the_blocks_of_block_fields():
    x = np.arange(25.0)
    # from sample 5: 20 samples in 4 blocks of 5
    np.testing.assert_array_equal(block_series(x, 5, 4), [7.0, 12.0, 17.0, 22.0])


def test_steadiness_z_is_the_half_difference_over_its_standard_error():
    flat = np.array([1.0, 2.0, 1.0, 2.0, 1.0, 2.0, 1.0, 2.0, 1.0, 2.0])
    # halves [1,2,1,2,1] and [2,1,2,1,2]: means 1.4 and 1.6, variances 0.3 each
    z = 0.2 / math.sqrt(0.3 / 5 + 0.3 / 5)
    rising = flat + np.repeat([0.0, 3.0], 5)  # a step of 3 between the halves
    out = steadiness({"flat": flat, "rising": rising}, {})
    assert out["observables"]["flat"]["z"] == pytest.approx(round(z, 3))
    assert out["observables"]["flat"]["steady"] is True
    assert out["observables"]["rising"]["z"] == pytest.approx(round(3.2 / math.sqrt(0.12), 3))
    assert out["observables"]["rising"]["steady"] is False and out["steady"] is False
    assert f"{STEADY_Z:g} standard errors" in out["test"]


def test_steadiness_false_alarms_and_power():
    """Steady windows (10 blocks of independent noise; a u-like profile of 10 bins with
    neighbouring errors correlated at 0.9 and a spin-like one of independent bins): all five
    observables pass in about 94% of windows; a step of 4 block standard deviations between
    the halves of one scalar is caught in nearly all."""
    rng = np.random.default_rng(11)

    def ar(rho, bins=10):
        e = np.empty((10, bins))
        e[:, 0] = rng.normal(size=10)
        for i in range(1, bins):
            e[:, i] = rho * e[:, i - 1] + math.sqrt(1 - rho**2) * rng.normal(size=10)
        return e

    n = 1000
    alarms = caught = 0
    for _ in range(n):
        scalars = {k: rng.normal(size=10) for k in ("wall_shear", "dilation", "mean_velocity")}
        out = steadiness(scalars, {"u_profile": ar(0.9), "spin_profile": ar(0.0)})
        alarms += not out["steady"]
        step = rng.normal(size=10) + np.repeat([0.0, 4.0], 5)
        caught += not steadiness({"mean_velocity": step}, {})["steady"]
    assert 0.02 < alarms / n < 0.10
    assert caught / n > 0.9


def test_steadiness_of_a_profile_counts_its_bins():
    rng = np.random.default_rng(3)
    noise = rng.normal(size=(10, 40))
    steady = steadiness({}, {"u": noise})
    assert steady["observables"]["u"]["bins_within"] >= STEADY_BINS and steady["steady"]
    shifted = noise + np.where(np.arange(10) >= 5, 5.0, 0.0)[:, None]
    out = steadiness({}, {"u": shifted})["observables"]["u"]
    assert out["bins_within"] == 0.0 and out["steady"] is False and out["max_abs_z"] > 5


@pytest.mark.parametrize("rho", [0.0, 0.5, 0.8])
def test_bin_correlation_recovers_the_lag1_correlation_of_ar1_blocks(rho):
    """2000 blocks of 30 bins whose deviations are AR(1) with correlation rho: the estimate is
    within 4 of its standard errors (about 1/sqrt(2000 x 29) for the pooled pairs)."""
    rng = np.random.default_rng(7)
    e = np.empty((2000, 30))
    e[:, 0] = rng.normal(size=2000)
    for i in range(1, 30):
        e[:, i] = rho * e[:, i - 1] + math.sqrt(1 - rho**2) * rng.normal(size=2000)
    scale = np.linspace(0.5, 3.0, 30)  # unequal errors per bin: the estimate standardises
    estimate = bin_correlation(10.0 + scale * e)
    assert estimate == pytest.approx(rho, abs=4 * (1 - rho**2) / math.sqrt(2000 * 29) + 1e-3)


def test_bin_correlation_needs_two_pairs_of_varying_bins():
    assert bin_correlation(np.ones((10, 5))) is None
    x = np.ones((10, 5))
    x[:, 2] = np.arange(10.0)
    x[:, 3] = np.arange(10.0) ** 2
    assert bin_correlation(x) is None  # one usable pair only
