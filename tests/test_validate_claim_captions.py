"""The claim figures' captions carry the numbers a reader needs beside the figure (referee
12, points 4 and 8): the one calibration's Cosserat Delta against the measured, the runs
where the model's Delta and the data's lie on opposite sides of H/2, and the spin figure's
stencil range of the raw departure against the verdict's beyond-null sign."""

from __future__ import annotations

from cosserat.studies.validate.report import level_caption
from cosserat.studies.validate.verdicts import DeltaPoint, DeltaSeries, ModelDelta


def _series(points, predicted):
    return DeltaSeries(
        "plane, glued-grains, B = 1",
        "plane",
        "fully-rough",
        True,
        tuple(points),
        curves={"cosserat": ModelDelta("cosserat", predicted)},
    )


def test_the_delta_caption_gives_the_level_miss_and_the_runs_the_model_does_not_fill():
    """The shipped rough series' numbers: H10 runs measured 6.61 and 5.15 d (over H/2 = 4.92
    and 4.89 d), the model 4.17 and 4.16 d (under); H20 measured 7.95 d, the model 6.49 d,
    both under H/2 = 9.78 d. Ratios 4.16/5.15 = 0.81, 4.17/6.61 = 0.63, 6.49/7.95 = 0.82."""
    pts = [
        DeltaPoint("h10", 9.8377, 6.61, 0.67, True, "fills"),
        DeltaPoint("h10_s2", 9.7845, 5.15, 0.53, True, "fills"),
        DeltaPoint("h20", 19.5617, 7.95, 1.1),
    ]
    s = _series(pts, {"h10": (4.17, 0.02), "h10_s2": (4.16, 0.02), "h20": (6.49, 0.33)})
    assert level_caption(s) == (
        "plane, glued-grains, B = 1: the one calibration's cosserat Delta is below the measured in "
        "all 3 runs, cosserat / measured = 0.63-0.82 (a level miss of the creep tail); the "
        "cosserat Delta lies under H/2 while the measured lies over it at h10 (cosserat 4.17 "
        "d, measured 6.61 d, H/2 = 4.92 d), h10_s2 (cosserat 4.16 d, measured 5.15 d, H/2 = "
        "4.89 d): the data fill the gap and the model does not, a discrepancy of its own "
        "(those runs are left out of the gap law for the data's filling, not the model's)."
    )


def test_the_delta_caption_the_other_way_and_without_either():
    """A model over H/2 where the data are under: said the other way; a model on the data's
    side of H/2 and of the level (one run above, one below): nothing."""
    over = _series([DeltaPoint("a", 10.0, 3.0, 0.5)], {"a": (6.0, 0.1)})
    assert level_caption(over) == (
        "plane, glued-grains, B = 1: the one calibration's cosserat Delta is above the measured in "
        "its one run, cosserat / measured = 2 (a level miss); the cosserat Delta lies over "
        "H/2 while the measured lies under it at a (cosserat 6 d, measured 3 d, H/2 = 5 d): "
        "the model fills the gap and the data do not, a discrepancy of its own."
    )
    mixed = _series(
        [DeltaPoint("a", 20.0, 3.0, 0.5), DeltaPoint("b", 20.0, 4.0, 0.5)],
        {"a": (3.5, 0.1), "b": (3.5, 0.1)},
    )
    assert level_caption(mixed) == ""
    assert level_caption(DeltaSeries("k", "plane", "fully-rough", True, ())) == ""


def _row(label, kind, lo, hi, beyond, judged=True, sheared=True):
    return {
        "label": label,
        "sheared": sheared,
        "stencil_range": (lo, hi),
        "beyond_stencils": beyond,
        "bins": {"beyond": [beyond["analysis"]], "judged": judged},
        "kind": kind,
    }


def test_the_spin_caption_sets_the_raw_stencil_range_against_the_beyond_null_sign():
    """Referee 12, point 8: the raw range crosses 0 at both sheared walls (up to +0.21 and
    +0.47); beyond the null the smooth wall keeps its sign under all 3 stencils, the rough
    one under 2 of 3 (then its first layer is left out)."""
    from cosserat.studies.validate.report import spin_caption

    rows = [
        _row("rough: moving", "glued-grains", -0.15, 0.21,
             {"analysis": -0.11, "wall": -0.05, "wall-first": 0.02}),
        _row("smooth: moving", "smooth-frictional", -0.33, 0.47,
             {"analysis": -0.29, "wall": -0.2, "wall-first": -0.1}),
        _row("smooth: fixed", "smooth-frictional", -0.01, 0.01, {"analysis": 0.0},
             judged=False, sheared=False),
    ]  # fmt: skip
    text = spin_caption(rows)
    assert (
        " At 2 of the 2 sheared walls it crosses 0 (reaching +0.21 to +0.47): the raw "
        "first-layer sign depends on the stencil there, and the verdicts do not use it. What "
        "the spin verdicts use is the departure beyond the null (right panel): its first-layer "
        "sign is the same under every stencil at 1 of the 2 judged walls (at the "
        "smooth-frictional walls: 3/3 stencil-wall pairs); where it is not, the first layer is "
        "left out of the verdict's test (open markers, right)."
    ) in text
    assert text.startswith("Left: the first layer's departure omega - half vorticity (d/V)")
    assert text.endswith("filled: the bins the verdict's test uses.")
    # no sheared wall: the panels only
    assert "crosses 0" not in spin_caption(rows[2:])


def test_a_run_figures_title_gives_the_slip_I_beside_the_bin_gradient_I():
    """Referee 12, point 8: I = V d / (H sqrt(p_w)) x H |1 - u_1| / s_1 = 0.0025 x 0.5 / 0.5
    = 0.0025 from the slip (u_1 = 0.5 at s_1 = 0.5 d), beside the bins' 5e-4."""
    from pathlib import Path
    from types import SimpleNamespace

    import numpy as np

    from cosserat.analysis.corpus import Run
    from cosserat.studies.validate.report import run_title

    y = np.arange(0.5, 10.0, 1.0)
    u = np.where(y > 9.0, 0.5, 0.0)  # the upper wall moves; its first bin at s = 0.5 d
    meta = {"cell": "plane", "gap_d": 10.0, "B": 1.0, "wall_speed": 0.0025,
            "wall": {"kind": "glued-grains"}}  # fmt: skip
    run = Run("r", Path("r.csv"), meta, {"y": y, "u": u, "u_se": np.full(y.size, 0.01)})
    title = run_title(SimpleNamespace(run=run, inertial_number=5e-4))
    assert title == (
        "r: plane, H/d = 10, I at the moving wall = 0.0005 from the bin gradient, 0.0025 from "
        "the wall's slip (0.5 V over 0.5 d)"
    )
    bare = run_title(SimpleNamespace(run=Run("r", Path("r.csv"), {**meta, "wall_speed": None},
                                             run.columns), inertial_number=None))  # fmt: skip
    assert bare == "r: plane, H/d = 10"
