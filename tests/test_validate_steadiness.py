"""Every verdict's regime line says which runs the DEM analysis found steady (referee 9,
point 5: the rough run at H = 20 d fails its own test on the wall shear, and the report did
not say so)."""

from __future__ import annotations

import json
import shutil
from pathlib import Path
from types import SimpleNamespace

from cosserat.analysis.corpus import read_run
from cosserat.studies.validate.study import steadiness_text

V2 = Path(__file__).resolve().parents[1] / "data" / "dem_v2"


def _runs(tmp_path, names, edit=None):
    out = []
    for name in names:
        for ext in ("csv", "json"):
            shutil.copy(V2 / name / f"profile.{ext}", tmp_path / f"{name}.{ext}")
        if edit is not None:
            meta = json.loads((tmp_path / f"{name}.json").read_text())
            edit(meta)
            (tmp_path / f"{name}.json").write_text(json.dumps(meta))
        out.append(SimpleNamespace(run=read_run(tmp_path / f"{name}.csv")))
    return out


def test_the_unsteady_run_and_its_observable_are_named(tmp_path):
    # with the window from 20 d of wall travel (referee 9, point 5) the rough H = 20 d run is
    # steady; the layer run's gap is not, and its blocks are shorter than the gap's
    # autocorrelation time, which the line says (the smooth H = 10 d run, unsteady in its gap at
    # 16M steps, is steady continued to 32M)
    runs = _runs(tmp_path, ["plane_rough_H20_qs", "plane_layer_H10_qs"])
    assert runs[0].run.meta["steadiness"]["steady"] is True
    dilation = runs[1].run.meta["steadiness"]["observables"]["dilation"]
    assert dilation["steady"] is False  # the stored run fails its own test
    text = steadiness_text(runs)
    assert "shown in 1 of 2 runs; NOT shown in plane_layer_H10_qs (dilation: halves " in text
    assert f"z = {dilation['z']:+.3g})." in text
    # beside it, the gap's autocorrelation time (referee 10, point 8): 1 / 0.45 blocks per tau,
    # 10 / 2.2 = 4.5 independent samples, a lower bound (Sokal's window not closed)
    assert (
        "plane_layer_H10_qs (not steady): dilation (gap) at least 2.2 blocks, about 4.5 "
        "independent samples of 10, block se too small by 1.8; under one block in every "
        "steadiness series of the other 1 run(s)." in text
    )
    assert "dilation, mean_velocity, spin_profile, u_profile, wall_shear" in text
    assert text.endswith(
        "Window rule (at least 20 d of wall travel discarded before averaging): met in 2 of 2 runs."
    )


def test_steady_runs_and_runs_without_the_record(tmp_path):
    steady = _runs(tmp_path, ["plane_rough_H20_qs"])
    assert "shown in 1 of 1 runs." in steadiness_text(steady)

    def strip(meta):
        meta.pop("steadiness")
        meta.pop("block_autocorrelation")

    bare = _runs(tmp_path, ["plane_layer_H10_qs"], edit=strip)
    assert steadiness_text(bare).startswith(
        "Steady state: not recorded for plane_layer_H10_qs. Autocorrelation times not recorded "
        "for plane_layer_H10_qs. Window rule"
    )
    assert steadiness_text([]) == ""
