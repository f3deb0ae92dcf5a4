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
    runs = _runs(tmp_path, ["plane_rough_H10_qs", "plane_rough_H20_qs"])
    shear = runs[1].run.meta["steadiness"]["observables"]["wall_shear"]
    assert shear["steady"] is False  # the stored run fails its own test
    text = steadiness_text(runs)
    assert "shown in 1 of 2 runs; NOT shown in plane_rough_H20_qs (wall_shear: halves " in text
    assert f"z = {shear['z']:+.3g})." in text
    assert "dilation, mean_velocity, spin_profile, u_profile, wall_shear" in text


def test_steady_runs_and_runs_without_the_record(tmp_path):
    steady = _runs(tmp_path, ["plane_smooth_H10_qs"])
    assert steadiness_text(steady).endswith("shown in 1 of 1 runs.")
    bare = _runs(tmp_path, ["plane_layer_H10_qs"], edit=lambda m: m.pop("steadiness"))
    assert steadiness_text(bare) == "Steady state: not recorded for plane_layer_H10_qs."
    assert steadiness_text([]) == ""
