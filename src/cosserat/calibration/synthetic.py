"""Synthetic runs made by a model, with the error model's noise: known answers for the tests,
the coverage benchmark and the docs.

:func:`template_runs` lays out runs like the shipped corpus (plane shear under gravity at two
gaps, a Couette cell; bins one grain diameter wide); :func:`make_runs` fills their fields with a
model's predictions at given parameter values plus AR(1)-correlated Gaussian noise of the
stated standard errors (``calibration.noise``).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import replace

import numpy as np

from .data import Field, RunData
from .engine import setup
from .models import Model
from .noise import Correlation, covariance

SE = {"u": 0.01, "omega": 0.01, "stress_ratio": 0.005}
"""Default standard errors of the synthetic fields [-]."""


def template_run(
    name: str,
    cell: str,
    gap_d: float,
    *,
    B: float = 0.0,
    Ri_d: float | None = None,
    I_w: float | None = 1e-3,
    walls: Mapping[str, str] | None = None,
    material: str = "material",
    fields: Sequence[str] = ("u", "omega", "stress_ratio"),
    se: Mapping[str, float] | None = None,
) -> RunData:
    """A run with bins at s = 0.5, 1.5, ... < H [d] and zero data (see :func:`make_runs`)."""
    s = np.arange(0.5, gap_d, 1.0)
    errors = {**SE, **(se or {})}
    values: dict[str, float] = {"eps": 1.0 / gap_d}
    if cell == "couette":
        values["Ri"] = float(Ri_d if Ri_d is not None else gap_d) / gap_d
    else:
        values.update(B=B, nu=1.0)
    out = {}
    for f in fields:
        pos = s if f != "stress_ratio" else s[(s >= 1.0) & (s <= gap_d - 1.0)]
        out[f] = Field(f, pos, np.zeros_like(pos), np.full_like(pos, errors[f]))
    walls = dict(walls or {"moving": "rough", "fixed": "rough"})
    return RunData(name, cell, gap_d, values, I_w, material, walls, out, {"synthetic": True})


def template_runs() -> list[RunData]:
    """Two plane-shear cells under gravity (B = 1, H = 20 and 40 d) and a Couette cell
    (H = 20 d, R_i = 20 d), one material, one kind of wall."""
    return [
        template_run("plane_H20", "plane", 20.0, B=1.0),
        template_run("plane_H40", "plane", 40.0, B=1.0),
        template_run("couette_H20", "couette", 20.0, Ri_d=20.0),
    ]


def make_runs(
    model: Model,
    values: Mapping[str, float],
    runs: Sequence[RunData] | None = None,
    rho: Mapping[str, float] | float = 0.0,
    seed: int | None = 0,
    noise: bool = True,
) -> list[RunData]:
    """``runs`` (default :func:`template_runs`) with their fields made by ``model``.

    Parameters
    ----------
    model : Model
    values : mapping
        Parameter name (as a calibration names it: ``phi``, ``K[rough]``) -> value; the others
        take their declared defaults.
    rho : float or mapping of field to float
        Lag-1 correlation of the noise of neighbouring bins (recorded in each field, source
        ``"given"``).
    seed : int or None
        Seed of the noise.
    noise : bool
        False: the model's exact values (the noise-free truth).
    """
    runs = list(template_runs() if runs is None else runs)
    s = setup(model, runs)
    fixed = {sl.name: sl for sl in s.slots if not sl.free}
    for sl in fixed.values():
        if sl.name in values or sl.key in values:
            raise ValueError(f"{sl.name} is fixed by default; give it through setup's fix")
    theta = np.array(
        [sl.internal(float(values.get(sl.name, values.get(sl.key, sl.value)))) for sl in s.free]
    )
    rng = np.random.default_rng(seed)
    out = []
    for run in runs:
        vals = s.run_values(run, theta)
        pred = model.predict(run, vals, [f for f in run.fields if f in model.fields()])
        fields = {}
        for name, f in run.fields.items():
            if name not in pred:
                continue
            r = float(rho.get(name, 0.0)) if isinstance(rho, Mapping) else float(rho)
            y = pred[name].copy()
            if noise:
                y = y + np.linalg.cholesky(covariance(f.se, r)) @ rng.standard_normal(f.n)
            fields[name] = Field(name, f.s, y, f.se, Correlation(r, "given"))
        out.append(replace(run, fields=fields, meta={**run.meta, "synthetic_model": model.name}))
    return out


__all__ = ["SE", "make_runs", "template_run", "template_runs"]
