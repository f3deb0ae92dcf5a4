"""Measured-profile files: the minimal format, richer forms, and errors that name line and
column."""

from __future__ import annotations

from types import MappingProxyType

import numpy as np
import pytest

from cosserat.analysis.measurements import MeasurementError, read_profile, write_profile

MINIMAL = "distance_d,u_over_uw,u_err\n0.5,0.81,0.02\n1.5,0.52,0.02\n3.0,0.2,0.01\n"


def test_minimal_format():
    prof = read_profile(MINIMAL)
    np.testing.assert_array_equal(prof.distance_d, [0.5, 1.5, 3.0])
    np.testing.assert_array_equal(prof.u_over_uw, [0.81, 0.52, 0.2])
    np.testing.assert_array_equal(prof.u_err, [0.02, 0.02, 0.01])
    no_err = read_profile("distance_d,u_over_uw\n0,1\n2,0.5\n")
    assert no_err.u_err is None and no_err.n == 2


def test_header_block_and_unit_conversions(tmp_path):
    text = (
        "# geometry: couette\n# eps: 0.05\n# Ri = 2\n# d_p: 0.002\n# wall_speed: 0.1\n"
        "# label: MRI run 3\ndistance_m,u_m_s,u_err_m_s\n0.001,0.09,0.002\n0.004,0.05,0.002\n"
    )
    path = tmp_path / "p.csv"
    path.write_text(text)
    prof = read_profile(path)
    assert prof.meta["geometry"] == "couette" and prof.meta["eps"] == 0.05
    assert prof.meta["ri"] == 2.0 and prof.label == "MRI run 3"
    np.testing.assert_allclose(prof.distance_d, [0.5, 2.0])
    np.testing.assert_allclose(prof.u_over_uw, [0.9, 0.5])
    np.testing.assert_allclose(prof.u_err, [0.02, 0.02])
    xi = read_profile("# eps: 0.1\ndistance_xi,u_over_uw\n0.1,0.5\n0.2,0.25\n")
    np.testing.assert_allclose(xi.distance_d, [1.0, 2.0])


@pytest.mark.parametrize(
    ("text", "needle"),
    [
        ("distance_d,u_over_uw\n0.5,abc\n", "line 2, column 'u_over_uw': 'abc' is not a number"),
        ("distance_d,u_over_uw\n0.5,0.3\n1.0\n", "line 3: 1 values for 2 columns"),
        ("distance_d,u_over_uw,u_err\n0.5,0.3,-1\n", "line 2, column 'u_err'"),
        ("distance_d,u_over_uw\n0.5,0.3\n\n1,0.2\n", "line 3: empty row"),
        ("distance_d,u_over_uw\n-0.5,0.3\n", "line 2, column 'distance_d'"),
        ("distance_d,u_over_uw\n0.5,nan\n", "line 2, column 'u_over_uw': 'nan' is not finite"),
        ("distance_d,velocity\n0.5,0.3\n", "velocity column"),
        ("distance_d,u_over_uw,extra\n0.5,0.3,1\n", "unknown column(s) extra"),
        ("distance_m,u_over_uw\n0.5,0.3\n", "needs 'd_p'"),
        ("# only a comment\n", "no column header found"),
    ],
)
def test_malformed_input_names_line_and_column(text, needle):
    with pytest.raises(MeasurementError) as info:
        read_profile(text)
    assert needle in str(info.value)


def test_dataframe_like_input():
    class Frame:  # the part of a pandas DataFrame that read_profile uses
        columns = ("distance_d", "u_over_uw")
        attrs = MappingProxyType({"eps": 0.05})

        def __getitem__(self, key):
            return {"distance_d": [0.0, 1.0], "u_over_uw": [0.9, 0.4]}[key]

    prof = read_profile(Frame())
    np.testing.assert_array_equal(prof.u_over_uw, [0.9, 0.4])
    assert prof.meta["eps"] == 0.05


def test_round_trip(tmp_path):
    prof = read_profile("# synthetic: true\n# label: demo\n" + MINIMAL)
    assert prof.is_synthetic and "synthetic" in prof.label
    again = read_profile(write_profile(prof, tmp_path / "x.csv"))
    np.testing.assert_array_equal(again.u_over_uw, prof.u_over_uw)
    assert again.meta["label"] == "demo"


def test_points_outside_the_gap_are_reported():
    prof = read_profile("distance_d,u_over_uw\n0,1\n30,0\n")
    with pytest.raises(MeasurementError, match="beyond the gap of 20 grain diameters"):
        prof.xi(0.05)
