"""The forward model of the spin measurement (studies/validate/forward.py): a model's u and
omega binned and differenced as the DEM analysis of a run does it."""

from __future__ import annotations

import math

import numpy as np
import pytest

from cosserat._stencil import half_vorticity
from cosserat.analysis.corpus import read_run, write_run
from cosserat.errors import ParameterError
from cosserat.studies.validate import forward as fw

H = 10.0


def plane_run(tmp_path, u, omega=None, half=None, name="r", method="np.gradient"):
    """A plane run (upper wall moving) with 1 d bins and the given columns."""
    y = np.arange(10) + 0.5
    u = np.asarray(u(y), dtype=float)
    cols = {
        "y": y,
        "u": u,
        "u_se": np.full(10, 0.01),
        "omega": np.zeros(10) if omega is None else omega,
        "omega_se": np.full(10, 0.01),
        "half_vorticity": half_vorticity(y, u) if half is None else half,
        "half_vorticity_se": np.full(10, 0.01),
    }
    meta = {"cell": "plane", "gap_d": H, "B": 0.0, "wall": {"kind": "glued-grains"},
            "half_vorticity_method": method}  # fmt: skip
    return read_run(write_run(tmp_path, name, meta, cols))


def fields(u, omega, point=None):
    return fw.ModelFields(u, omega, point or (lambda x: np.zeros_like(x)))


def test_bins_span_from_each_wall_to_twice_the_end_centre(tmp_path):
    run = plane_run(tmp_path, lambda y: y / H)
    b = fw.bin_edges(run)
    assert b.lo[0] == 0.0 and b.hi[0] == 1.0 and b.lo[-1] == 9.0 and b.hi[-1] == H
    assert np.allclose(b.hi - b.lo, 1.0)


def test_on_a_linear_velocity_every_surface_stencil_gives_the_exact_half_vorticity(tmp_path):
    run = plane_run(tmp_path, lambda y: y / H)
    f = fields(lambda x: x / H, lambda x: np.zeros_like(x))
    exact = -0.5 / H
    for stencil in ("analysis", "wall", "wall-first", "second-order"):
        out = fw.forward_fields(f, run, stencil)
        assert np.allclose(out["half_vorticity"], exact, rtol=0, atol=1e-14), stencil
        assert np.allclose(out["departure"], -exact, rtol=0, atol=1e-14)
    # the wall's velocity moved 0.5 d into the gap at the moving wall (y = 9.5): the slope
    # from it (u = 1) to the second bin (y = 8.5, u = 0.85) is 0.15 per d, not 0.1
    out = fw.forward_fields(f, run, "wall+0.5")
    assert out["half_vorticity"][-1] == pytest.approx(-0.5 * 0.15, abs=1e-14)
    assert out["half_vorticity"][0] == pytest.approx(-0.5 * 0.15, abs=1e-14)  # lower: 0.15/1
    # and 0.5 d behind the surface: (1 - 0.85)/2
    out = fw.forward_fields(f, run, "wall-0.5")
    assert out["half_vorticity"][-1] == pytest.approx(-0.5 * 0.075, abs=1e-14)
    assert np.allclose(out["half_vorticity"][1:-1], exact, atol=1e-14)


@pytest.mark.parametrize("L", [0.5, 1.0, 2.0])
def test_on_an_exponential_band_the_first_bin_differs_from_the_point_value_as_derived(tmp_path, L):
    """u = exp(-s/L), s = H - y the distance from the moving wall, omega = c u: bins of 1 d
    average u to L (1 - e^(-1/L)) and L (e^(-1/L) - e^(-2/L)) in the first two, the
    analysis' one-sided stencil gives du/dy = L (1 - e^(-1/L))^2 at the first, so the
    measured departure is c L (1 - e^(-1/L)) + L (1 - e^(-1/L))^2 / 2, against the point
    value (c + 1/(2 L)) e^(-1/(2 L)) at its centre."""
    c = -0.3
    run = plane_run(tmp_path, lambda y: np.exp(-(H - y) / L))
    f = fields(
        lambda x: np.exp(-(H - x) / L),
        lambda x: c * np.exp(-(H - x) / L),
        lambda x: (c + 0.5 / L) * np.exp(-(H - x) / L),
    )
    out = fw.forward_fields(f, run)
    q = 1.0 - math.exp(-1.0 / L)
    by_hand = c * L * q + 0.5 * L * q * q
    point = (c + 0.5 / L) * math.exp(-0.5 / L)
    assert out["departure"][-1] == pytest.approx(by_hand, rel=1e-12)
    assert out["point"][-1] == pytest.approx(point, rel=1e-12)
    assert out["departure"][-1] - out["point"][-1] == pytest.approx(by_hand - point, rel=1e-10)
    # L = 1: the point value 0.121 against 0.0102 measured: the binning and the stencil,
    # not the model, take almost all of it
    if L == 1.0:
        assert point == pytest.approx(0.12130613, rel=1e-7)
        assert by_hand == pytest.approx(0.01015203, rel=1e-6)


def test_the_data_under_the_analysis_stencil_are_the_reported_columns(tmp_path):
    rng = np.random.default_rng(1)
    omega = rng.normal(0, 0.1, 10)
    run = plane_run(tmp_path, lambda y: (y / H) ** 3, omega=omega)
    dep, se_h, se_o = fw.measured_first_layer(run, 1, "analysis", 0.5)
    assert dep == pytest.approx(omega[-1] - run.columns["half_vorticity"][-1])
    assert (se_h, se_o) == (0.01, 0.01)
    # the wall stencil at the surface: (u_wall - u of the second bin) / 1.5 d, the error of
    # u there alone over 1.5 d (the wall's velocity is exact)
    dep, se_h, _ = fw.measured_first_layer(run, 1, "wall", 0.5)
    assert dep == pytest.approx(omega[-1] + 0.5 * (1.0 - 0.85**3) / 1.5)
    assert se_h == pytest.approx(0.5 * 0.01 / 1.5)


def test_bad_stencil_and_too_few_bins_are_clean_errors(tmp_path):
    run = plane_run(tmp_path, lambda y: y / H)
    with pytest.raises(ParameterError, match="stencil must be one of analysis, wall"):
        fw.forward_fields(fields(lambda x: x, lambda x: x), run, "upwind")


def test_runs_made_otherwise_are_measured_their_way(tmp_path):
    """A run of point values at the bin centres (the default without cosserat.dem's sidecar)
    has the model's point departure; one of bin means has the bin mean of it (for u = exp(-s),
    omega = c u: c (1 - e^-1) + (1 - e^-1)/2 in the first bin)."""
    c = -0.3
    f = fields(
        lambda x: np.exp(-(H - x)),
        lambda x: c * np.exp(-(H - x)),
        lambda x: (c + 0.5) * np.exp(-(H - x)),
    )
    run = plane_run(tmp_path, lambda y: np.exp(-(H - y)), name="p", method="point")
    out = fw.forward_fields(f, run)
    assert np.allclose(out["departure"], out["point"], rtol=0, atol=1e-14)
    run = plane_run(tmp_path, lambda y: np.exp(-(H - y)), name="b", method="bin-average")
    q = 1.0 - math.exp(-1.0)
    assert fw.forward_fields(f, run)["departure"][-1] == pytest.approx((c + 0.5) * q, rel=1e-12)
    run = plane_run(tmp_path, lambda y: y, name="x", method="guess")
    with pytest.raises(ParameterError, match=r"half_vorticity_method must be one of np\.gradient"):
        fw.forward_fields(f, run)


def test_the_bins_forward_fields_keeps_are_the_runs_and_read_only(tmp_path):
    """forward._kept_bins: bin_edges of the run, made once per run (forward_fields is asked
    ~10^4 times in one validate), read-only, and made again for a run whose coordinate
    column is another."""
    from dataclasses import replace

    from cosserat.analysis.bins import bin_edges

    run = plane_run(tmp_path, lambda y: y / H)
    kept = fw._kept_bins(run)
    fresh = bin_edges(run)
    for name in ("centre", "lo", "hi", "order"):
        assert np.array_equal(getattr(kept, name), getattr(fresh, name))
        assert not getattr(kept, name).flags.writeable
    assert fw._kept_bins(run) is kept
    moved = replace(run, columns={**run.columns, "y": run.columns["y"] * 0.9})
    assert np.array_equal(fw._kept_bins(moved).centre, 0.9 * fresh.centre)
    assert fw._kept_bins(run) is kept
