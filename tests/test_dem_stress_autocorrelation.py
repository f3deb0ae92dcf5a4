"""The stresses' per-bin autocorrelation times in the sidecar (referee 10, point 8): the block
errors of sigma_yx and sigma_yy are only as good as their blocks are long against these."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.signal import lfilter

from cosserat.dem.checks import block_se_factor, profile_autocorrelation
from cosserat.dem.coarse import SUMS, Samples, block_fields, sample_fields
from cosserat.errors import InputError, ParameterError


def _ar1(phi: float, n: int, rng: np.random.Generator) -> np.ndarray:
    """A stationary AR(1) series, integrated autocorrelation time (1 + phi) / (1 - phi)."""
    burn = 2000
    x = lfilter([1.0], [1.0, -phi], rng.normal(size=n + burn))
    return x[burn:]


def test_the_per_bin_times_of_ar1_bins_are_their_known_tau_in_blocks():
    rng = np.random.default_rng(7)
    n, blocks = 200_000, 10_000  # blocks of 20 samples
    # bin 0 independent (tau = 1 sample), bin 1 phi = 0.9 (tau = 19), bin 2 constant
    profile = np.stack([_ar1(0.0, n, rng), _ar1(0.9, n, rng), np.full(n, 2.5)], axis=1)
    rec = profile_autocorrelation({"sigma_yx": profile}, 0, blocks)
    got = rec["sigma_yx"]
    assert got["per_bin"][0] == pytest.approx(1 / 20, rel=0.05)
    assert got["per_bin"][1] == pytest.approx(19 / 20, rel=0.15)
    assert got["per_bin"][2] is None  # constant: no time
    assert (got["max"], got["max_row"], got["bins"]) == (got["per_bin"][1], 1, 2)
    assert got["median"] == pytest.approx(0.5 * (got["per_bin"][0] + got["per_bin"][1]), rel=1e-3)
    # a block shorter than 2 tau is short: 20 samples < 2 x 19
    assert got["short"] is True and rec["short"] is True
    assert got["unreliable_bins"] == 0
    # the same series in blocks of 2,000 samples: 19 / 2000 blocks, not short
    long = profile_autocorrelation({"sigma_yx": profile}, 0, 100)
    assert long["sigma_yx"]["max"] == pytest.approx(19 / 2000, rel=0.15)
    assert long["short"] is False
    assert set(long) == {"sigma_yx", "short", "note"}


def test_a_constant_profile_has_no_record_and_bad_shapes_are_refused():
    rec = profile_autocorrelation({"sigma_yy": np.ones((100, 3))}, 0, 10)
    assert set(rec) == {"short", "note"} and rec["short"] is False
    with pytest.raises(InputError, match="must be \\(samples, bins\\)"):
        profile_autocorrelation({"sigma_yy": np.ones(100)}, 0, 10)
    with pytest.raises(InputError, match="5 steady samples cannot make 10 blocks"):
        profile_autocorrelation({"sigma_yy": np.ones((15, 3))}, 10, 10)


def test_block_se_factor_by_hand():
    # one sample per block, two blocks: Var(M) = (1 + phi)/2, E[s_B^2]/2 = (1 - phi)/2, so the
    # factor is sqrt((1 + phi)/(1 - phi)) = sqrt(tau); tau = 3 samples: phi = 1/2
    assert block_se_factor(3.0, 2, block_samples=1.0) == pytest.approx(math.sqrt(3.0), rel=1e-12)
    # independent samples (tau = 1 sample): the block errors are right
    assert block_se_factor(1e-3, 10, block_samples=1000.0) == pytest.approx(1.0, abs=1e-12)
    with pytest.raises(ParameterError, match="blocks must be >= 2"):
        block_se_factor(1.0, 1)
    with pytest.raises(ParameterError, match="tau_blocks must be positive"):
        block_se_factor(float("nan"), 10)


def test_block_se_factor_is_what_ar1_windows_show():
    # 4,000 windows of 10 blocks of 200 samples with tau = 1 block: the spread of the window
    # means over the root-mean-square block error
    rng = np.random.default_rng(3)
    b, nb, reps = 200, 10, 4000
    phi = (b - 1.0) / (b + 1.0)
    x = lfilter([1.0], [1.0, -phi], rng.normal(size=(reps, b * nb + 3000)), axis=1)[:, 3000:]
    means = x.mean(axis=1)
    se2 = x.reshape(reps, nb, b).mean(axis=2).var(axis=1, ddof=1) / nb
    seen = math.sqrt(means.var() / se2.mean())
    assert seen == pytest.approx(block_se_factor(1.0, nb, block_samples=b), rel=0.04)
    assert block_se_factor(1.0, nb, block_samples=b) == pytest.approx(1.345, abs=0.001)


def test_sample_fields_are_one_sample_blocks():
    rng = np.random.default_rng(1)
    sums = rng.uniform(0.5, 2.0, size=(6, 4, len(SUMS)))
    samples = Samples(np.arange(6) * 100, sums, np.arange(5.0), np.ones(4))
    per = sample_fields(samples, 2, ("sigma_nt", "sigma_nn"))
    blocks = block_fields(Samples(samples.steps[2:], sums[2:], samples.edges, samples.bin_area),
                          0, 4)  # fmt: skip
    for k, f in enumerate(blocks):
        np.testing.assert_array_equal(per["sigma_nt"][k], f["sigma_nt"])
        np.testing.assert_array_equal(per["sigma_nn"][k], f["sigma_nn"])
    with pytest.raises(InputError, match="unknown fields"):
        sample_fields(samples, 0, ("sigma_xy",))
    with pytest.raises(InputError, match="first sample 6 outside the 6 samples"):
        sample_fields(samples, 6, ("sigma_nt",))


def test_the_run_notes_quote_the_stresses_times():
    from cosserat.dem.checks import block_length_text

    rec = {
        "block_steps": 1000,
        "observables": {},
        "short": False,
        "profiles": {"sigma_yx": {"max": 0.85, "median": 0.11}, "short": True, "note": ""},
    }
    assert block_length_text(rec).endswith(
        "; the stresses' per-bin times: sigma_yx up to 0.85 blocks (median 0.11) (some bins' "
        "blocks shorter than 2 tau: their errors too small)"
    )
    rec.pop("profiles")
    assert "stresses" not in block_length_text(rec)
