"""The notebook path: a profile as a DataFrame, as an xarray Dataset, and as HTML."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from cosserat import CouetteFlow, Material, PlaneShear, Wall, shear_layer_thickness, solve


@pytest.fixture(scope="module")
def profile():
    return solve(CouetteFlow(material=Material(28.5), wall=Wall(20.0), eps=0.04, Ri=1.0))


def test_dataframe_holds_every_column_and_the_parameters(profile):
    frame = profile.to_dataframe()
    assert list(frame.columns) == list(profile.columns())
    np.testing.assert_array_equal(frame["u"].to_numpy(), profile.u)
    assert frame.attrs["parameters"]["Ri"] == 1.0
    assert frame.attrs["method"] == "numerical"
    assert isinstance(frame, pd.DataFrame)


def test_xarray_dataset_has_the_coordinate_and_units(profile):
    ds = profile.to_xarray()
    np.testing.assert_array_equal(ds["xi"].to_numpy(), profile.xi)
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
    wide = solve(PlaneShear(material=Material(28.5), upper=Wall.fully_rough(), eps=0.5))
    text = wide._repr_html_()
    assert "Delta =" in text
