"""cosserat._text.significance: p-values below 1e-6 as z and chi^2/dof (referee 5, request 8)."""

from __future__ import annotations

import math

import pytest
from scipy import stats

from cosserat._text import SIGNIFICANCE_P, chi2_ln_p, p_or_z, significance, z_score


def test_p_value_above_the_threshold_is_printed_as_p():
    assert significance(10.0, 10) == f"p = {stats.chi2.sf(10.0, 10):.2g}" == "p = 0.44"


def test_below_the_threshold_z_and_chi2_per_dof():
    p = stats.chi2.sf(412.0, 40)
    assert p < SIGNIFICANCE_P
    z = stats.norm.isf(p)
    assert significance(412.0, 40) == f"z = {z:.1f}, chi^2/dof = 412/40"
    z = stats.norm.isf(stats.chi2.sf(61.0, 10))
    assert significance(61.0, 10) == f"z = {z:.1f}, chi^2/dof = 61/10"


def test_threshold_is_one_in_a_million():
    # the z of p = 1e-6 (one-sided) is 4.753
    assert z_score(math.log(1e-6)) == pytest.approx(stats.norm.isf(1e-6), rel=1e-10)
    assert p_or_z(math.log(1.01e-6)).startswith("p = ")
    assert p_or_z(math.log(0.99e-6)) == "z = 4.8"
    assert z_score(math.log(0.5)) == pytest.approx(0.0, abs=1e-12)


def test_far_past_underflow_z_stays_finite_and_grows():
    # chi2.sf underflows to 0 here; z = sqrt(2 |ln p|) to leading order
    assert stats.chi2.sf(1e5, 40) == 0.0
    ln_p = chi2_ln_p(1e5, 40)
    assert math.isfinite(ln_p) and ln_p < -4e4
    z = z_score(ln_p)
    assert z == pytest.approx(math.sqrt(-2.0 * ln_p), rel=0.01)
    assert significance(1e5, 40) == f"z = {z:.1f}, chi^2/dof = 100000/40"
    assert z_score(chi2_ln_p(2e5, 40)) > z


@pytest.mark.parametrize(("chi2", "dof"), [(math.nan, 3), (-1.0, 3), (math.inf, 3), (3.0, 0)])
def test_bad_inputs_raise(chi2, dof):
    with pytest.raises(ValueError, match=r"^(chi\^2 = .*: must be finite and >= 0|dof = 0: .*)$"):
        significance(chi2, dof)
