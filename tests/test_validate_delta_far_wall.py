"""Delta where the fixed (far) wall slips (referee 11, point 5): Delta relative to the far
bin's velocity is reported beside the used one (relative to the wall's), with whether the
"fills its gap" call, which reads the used one, would change."""

from __future__ import annotations

import numpy as np
import pytest

from cosserat.analysis.corpus import read_run, write_run
from cosserat.studies.validate.measures import (
    FAR_SLIP_SIGMAS,
    far_wall,
    measured_thickness,
    thickness_sensitivity,
)

S = np.arange(0.5, 10.0, 1.0)  # distances from the moving wall [d], gap 10 d


def _write(folder, name, u, se):
    meta = {"cell": "plane", "gap_d": 10.0, "B": 1.0, "wall": {"kind": "smooth-frictional"}}
    write_run(folder, name, meta, {"y": 10.0 - S, "u": u, "u_se": se})
    return read_run(folder / f"{name}.csv")


def _linear(far_u: float) -> np.ndarray:
    """u falls linearly from 1.0 at s = 0.5 to 0.1 at s = 5.5 (0.18 per grain), then to
    ``far_u`` at 6.5 d and stays there."""
    return np.where(S <= 5.5, 1.0 - 0.18 * (S - 0.5), far_u)


def test_a_slipping_far_wall_gives_delta_relative_to_the_far_bin_beside(tmp_path):
    # far bin u = 0.1 +- 0.001: 100 se from the wall's 0, so it slips. Relative to u_0 = 0.1
    # the target is 0.1 + 0.05 (1 - 0.1) = 0.145, reached at s = 0.5 + 0.855/0.18 = 5.25 d;
    # relative to 0 the target is 0.05, which u (never below 0.1) does not reach: no Delta
    run = _write(tmp_path, "slip", _linear(0.1), np.full(S.size, 1e-3))
    far = far_wall(run)
    assert far.u == pytest.approx(0.1) and far.z == pytest.approx(100.0) and far.slips
    t = measured_thickness(run)
    assert t.u0 == 0.0 and t.value is None
    assert t.reason.startswith("the measured velocity does not fall to 0.05")
    assert t.value_far == pytest.approx(0.5 + 0.855 / 0.18)  # 5.25 d
    assert t.fills_gap is False and t.fills_gap_far is True  # 5.25 > H/2 = 5
    d = t.to_dict()
    assert d["value_far_u0"] == pytest.approx(5.25) and d["far_wall"]["slips"] is True
    # the sensitivity reads the used Delta (relative to the wall)
    assert thickness_sensitivity(run).value[0] is None


def test_both_deltas_are_reported_and_the_exclusion_said_to_rest_on_the_slip(tmp_path):
    # u = 1, 0.75, 0.5, 0.25, 0.07, 0.06, 0.04, then 0.03 to the far bin (0.03 +- 0.005: 6 se).
    # Relative to the wall (used): target 0.05 between 5.5 d (0.06) and 6.5 d (0.04): 6.0 d,
    # over H/2 = 5 d. Relative to the far bin: target 0.03 + 0.05 x 0.97 = 0.0785 between
    # 3.5 d (0.25) and 4.5 d (0.07): 3.5 + 0.1715/0.18 = 4.4528 d, under H/2
    u = np.array([1.0, 0.75, 0.5, 0.25, 0.07, 0.06, 0.04, 0.03, 0.03, 0.03])
    run = _write(tmp_path, "both", u, np.full(S.size, 0.005))
    t = measured_thickness(run)
    assert t.far_slip and t.far is not None and t.far.z == pytest.approx(6.0)
    assert t.value == pytest.approx(6.0)
    assert t.value_far == pytest.approx(3.5 + 0.1715 / 0.18)
    assert t.stderr is not None and t.stderr_far is not None
    assert t.fills_gap and t.fills_gap_far is False
    text = t.far_text()
    assert text.startswith(
        "the fixed wall slips (far bin u = 0.03 +- 0.005 V, 6 se): Delta = 6 +- "
    )
    assert "d relative to the wall's velocity (used), 4.45 +- " in text
    assert text.endswith("relative to the far bin it would not fill its gap (under 0.5 H = 5 d): "
                         "its exclusion rests on the slip")  # fmt: skip


def test_a_far_bin_within_two_se_of_the_wall_keeps_u0_zero(tmp_path):
    # far bin 0.02 +- 0.011: 1.8 se, not a slip; Delta is the wall's 6.125 d and nothing else
    se = np.full(S.size, 0.011)
    run = _write(tmp_path, "still", _linear(0.02), se)
    far = far_wall(run)
    assert abs(far.z) < FAR_SLIP_SIGMAS and not far.slips
    t = measured_thickness(run)
    assert t.u0 == 0.0 and t.value == pytest.approx(6.125)
    assert t.value_far is None and t.fills_gap_far is None and t.far_text() == ""


def test_plane_shear_without_gravity_has_no_slipping_far_wall(tmp_path):
    meta = {"cell": "plane", "gap_d": 10.0, "B": 0.0, "wall": {"kind": "glued-grains"}}
    u = np.linspace(0.95, 0.3, S.size)
    write_run(tmp_path, "sym", meta, {"y": 10.0 - S, "u": u, "u_se": np.full(S.size, 1e-3)})
    far = far_wall(read_run(tmp_path / "sym.csv"))
    assert far.wall_u == 0.5 and not far.slips
