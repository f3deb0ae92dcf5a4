"""The notebook path: a profile as a DataFrame, as an xarray Dataset, as HTML, and as a plain
CSV with a JSON sidecar, in the cell's own coordinates (y in plane shear, r in Couette flow)."""

from __future__ import annotations

import io
import json

import numpy as np
import pandas as pd
import pytest

from cosserat import (
    Cosserat,
    Couette,
    Material,
    MuI,
    Plane,
    Problem,
    Wall,
    shear_layer_thickness,
    solve,
    wall_omega,
    wall_slip,
)


@pytest.fixture(scope="module")
def profile():
    return solve(
        Problem(Couette(eps=0.04, Ri=1.0), Cosserat(material=Material(28.5), wall=Wall(20.0)))
    )


def test_dataframe_holds_every_column_and_the_parameters(profile):
    frame = profile.to_dataframe()
    assert list(frame.columns) == list(profile.columns())
    np.testing.assert_array_equal(frame["u"].to_numpy(), profile.u)
    assert frame.attrs["parameters"]["Ri"] == 1.0
    assert frame.attrs["method"] == "numerical"
    assert isinstance(frame, pd.DataFrame)


def test_xarray_dataset_has_the_coordinate_and_units(profile):
    ds = profile.to_xarray()
    assert list(ds.coords) == ["r"]
    np.testing.assert_array_equal(ds["r"].to_numpy(), profile.problem.cell.Ri + profile.xi)
    assert "radius" in ds["r"].attrs["long_name"]
    assert set(ds.data_vars) >= {"sigma_theta_r", "sigma_r_theta", "sigma_rr"}
    np.testing.assert_array_equal(ds["omega"].to_numpy(), profile.omega)
    assert ds["u"].attrs["units"] == "1"
    assert "velocity" in ds["u"].attrs["long_name"]
    assert json.loads(ds.attrs["parameters"])["geometry"] == "couette"


def test_html_summary_is_short_and_states_delta(profile):
    text = profile._repr_html_()
    assert f"{shear_layer_thickness(profile):.6g}" in text
    assert text.count("<tr>") <= 8
    assert len(text) < 3000


def test_html_summary_of_a_layer_that_fills_the_gap_says_so():
    wide = solve(
        Problem(Plane(eps=0.5), Cosserat(material=Material(28.5), wall=Wall.fully_rough()))
    )
    text = wide._repr_html_()
    assert "Delta =" in text


# --------------------------------------------------------------------------- CSV and sidecar
def test_couette_csv_reads_with_pandas_defaults_in_r(profile, tmp_path):
    target = tmp_path / "profile.csv"
    text = profile.to_csv(target)
    assert target.read_text() == text
    frame = pd.read_csv(target)  # no options: one header row, then numbers
    assert list(frame.columns) == [
        "r",
        "u",
        "omega",
        "m",
        "sigma_theta_r",
        "sigma_r_theta",
        "sigma_rr",
        "asymmetry",
        "spin_minus_half_vorticity",
    ]
    assert all(dtype == np.float64 for dtype in frame.dtypes)
    assert len(frame) == profile.xi.size
    np.testing.assert_array_equal(frame["r"].to_numpy(), 1.0 + profile.xi)
    np.testing.assert_array_equal(frame["u"].to_numpy(), profile.u)  # repr: exact round trip
    np.testing.assert_array_equal(frame["sigma_r_theta"].to_numpy(), profile.sigma_yx)
    assert "$" not in text and "#" not in text


def test_the_sidecar_holds_parameters_delta_slip_units_and_diagnostics(profile, tmp_path):
    profile.to_csv(tmp_path / "profile.csv")
    meta = json.loads((tmp_path / "profile.json").read_text())
    assert meta["file"] == "profile.csv"
    assert meta["cell"] == "couette" and meta["rheology"] == "cosserat"
    assert meta["method"] == "numerical" and meta["coordinate"] == "r"
    assert meta["parameters"]["Ri"] == 1.0 and meta["parameters"]["eps"] == 0.04
    assert meta["Delta"] == shear_layer_thickness(profile)
    assert meta["wall_slip"] == wall_slip(profile)
    assert meta["wall_omega"] == wall_omega(profile)
    header = pd.read_csv(tmp_path / "profile.csv", nrows=0).columns
    assert list(meta["columns"]) == list(header)
    assert all(c["unit"] == "1" and c["meaning"] for c in meta["columns"].values())
    assert meta["diagnostics"]["residuals"] and "bc_errors" in meta["diagnostics"]
    assert "$" not in json.dumps(meta)


def test_plane_shear_exports_in_y(tmp_path):
    prof = solve(Problem(Plane(eps=0.04), Cosserat(material=Material(), wall=Wall())), points=21)
    frame = pd.read_csv(io.StringIO(prof.to_csv()))
    assert list(frame.columns[:7]) == ["y", "u", "omega", "m", "sigma_xy", "sigma_yx", "sigma_yy"]
    np.testing.assert_array_equal(frame["y"].to_numpy(), prof.xi)
    assert list(prof.to_dataframe().columns) == list(frame.columns)
    record = json.loads(prof.to_json())
    assert record["y"] == prof.xi.tolist() and "xi" not in record
    assert record["columns"]["y"].startswith("height above the fixed lower wall")
    prof.to_csv(tmp_path / "p.csv")
    assert not (tmp_path / "p.csv").read_text().startswith("#")
    assert json.loads((tmp_path / "p.json").read_text())["coordinate"] == "y"


def test_stdout_csv_writes_no_sidecar(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    prof = solve(Problem(Plane(eps=0.04), Cosserat(material=Material(), wall=Wall())), points=5)
    prof.to_csv()
    assert list(tmp_path.iterdir()) == []


def test_a_local_rheology_exports_no_cosserat_only_columns(tmp_path):
    """No grain spin or couple stress of its own: omega, m and the asymmetry are absent."""
    couette = solve(Problem(Couette(eps=0.01, Ri=2.0), MuI()), points=9)
    frame = pd.read_csv(io.StringIO(couette.to_csv()))
    assert list(frame.columns) == ["r", "u", "sigma_theta_r", "sigma_r_theta", "sigma_rr"]
    np.testing.assert_allclose(frame["r"].to_numpy(), 2.0 + couette.xi, rtol=0, atol=1e-15)
    plane = solve(Problem(Plane(eps=0.01), MuI()), points=9)
    plane.to_csv(tmp_path / "mui.csv")
    meta = json.loads((tmp_path / "mui.json").read_text())
    assert meta["rheology"] == "mui" and next(iter(meta["columns"])) == "y"
    assert "omega" not in meta["columns"] and "m" not in meta["columns"]
    assert meta["wall_omega"] is None


def test_a_sidecar_never_overwrites_its_csv(tmp_path):
    from cosserat.results.profile import sidecar_path

    assert sidecar_path(tmp_path / "a.csv") == tmp_path / "a.json"
    assert sidecar_path(tmp_path / "a.json") == tmp_path / "a.json.json"
    assert sidecar_path(tmp_path / "a") == tmp_path / "a.json"
