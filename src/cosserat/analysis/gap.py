"""Shear-layer thickness against the gap, H/d, for every model on one cell.

The paper's distinguishing prediction (section "Shear layer thickness"): for walls smoother
than the material (tan delta < sin phi) the frictional Cosserat model's Delta tends to a
constant, ``-ln f / k``, independent of the gap; for fully rough walls under gravity (and in
Couette flow) it grows as ``(H/d)^(1/3)``; without gravity between fully rough walls the shear
is uniform and Delta grows like H/d. What the other registered rheologies predict on the same
cell is computed here the same way: Delta (:func:`cosserat.results.wall.shear_layer_thickness`,
the distance from the moving wall where the velocity has fallen to a fraction f of its wall
value, in grain diameters) at each gap, and the slope of log Delta against log(H/d).

What is held fixed as the gap changes is a choice: by default every other dimensionless
parameter (B, Ri, I_w, ...), as in the paper's figure 14. ``scale_with_gap`` makes a
parameter vary as a power of the gap instead, e.g. ``{"Ri": -1}`` for a fixed inner radius
R_i/d, ``{"B": 1}`` for a fixed normal stress N, ``{"I_w": -1}`` for a fixed wall speed.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .. import config
from ..config import DEFAULT_F
from ..errors import ConvergenceError, MethodNotAvailableError, NoSolutionError, ParameterError
from ..model import make_problem
from ..model.constitutive import FloatArray
from ..model.parameters import FULLY_ROUGH
from ..results.wall import shear_layer_thickness
from ..routes import models_for
from .ranking import get_parameter, model_solve, parameter_names

DEFAULT_GAPS = (10.0, 20.0, 40.0, 80.0, 160.0, 320.0)
"""Gaps H/d of :func:`thickness_vs_gap` by default [-]."""

DEFAULT_CELL = {"plane": {"B": 1.0}, "couette": {"Ri": config.RI}, "channel": {}}
"""Cell parameters by default: plane shear under gravity (B = 1, where the fully rough law
(H/d)^(1/3) holds) and the paper's Couette cell."""

PAPER_SLOPES = {"smoother walls": 0.0, "fully rough walls": 1.0 / 3.0}
"""The paper's exponents of Delta against H/d as H/d -> infinity (eqn-delta_soln,
eqn-delta_soln_fr)."""


@dataclass(frozen=True)
class SlopeFit:
    """A power law Delta = C (H/d)^slope fitted by least squares in log-log [-].

    ``stderr`` is None with fewer than three points and no uncertainties (nothing to
    estimate it from). With uncertainties it is the weighted fit's, scaled up by
    sqrt(reduced chi^2) when that exceeds 1 (the scatter is then larger than the errors say).
    """

    slope: float
    stderr: float | None
    prefactor: float
    n: int
    reduced_chi2: float | None = None

    def to_dict(self) -> dict[str, Any]:
        return {
            "slope": self.slope,
            "stderr": self.stderr,
            "prefactor": self.prefactor,
            "n": self.n,
            "reduced_chi2": self.reduced_chi2,
        }

    def text(self) -> str:
        err = "" if self.stderr is None else f" +- {self.stderr:.2g}"
        return f"{self.slope:.3f}{err}"


def power_law_slope(
    gaps: Sequence[float] | FloatArray,
    values: Sequence[float] | FloatArray,
    errors: Sequence[float] | FloatArray | None = None,
) -> SlopeFit:
    """Fit ``values = C gaps^slope`` in log-log (weighted by ``errors`` when given).

    Raises
    ------
    ParameterError
        Fewer than two points, or a value or gap that is not positive and finite.
    """
    x = np.asarray(gaps, dtype=float)
    y = np.asarray(values, dtype=float)
    if x.size < 2 or x.shape != y.shape or np.unique(x).size < 2:
        raise ParameterError("a power law needs at least two distinct gaps with a value each")
    if np.any(~np.isfinite(x) | (x <= 0)) or np.any(~np.isfinite(y) | (y <= 0)):
        raise ParameterError("gaps and thicknesses must be positive and finite for a power law")
    lx, ly = np.log(x), np.log(y)
    A = np.column_stack([np.ones_like(lx), lx])
    if errors is not None:
        e = np.asarray(errors, dtype=float)
        if e.shape != y.shape or np.any(~np.isfinite(e) | (e <= 0)):
            raise ParameterError("errors must be positive and finite, one per value")
        w = y / e  # 1/sigma of ln y
        coef, *_ = np.linalg.lstsq(A * w[:, None], ly * w, rcond=None)
        cov = np.linalg.inv((A * w[:, None]).T @ (A * w[:, None]))
        r = (ly - A @ coef) * w
        dof = x.size - 2
        red = float(r @ r / dof) if dof > 0 else None
        se = math.sqrt(cov[1, 1]) * math.sqrt(max(1.0, red or 1.0))
        return SlopeFit(float(coef[1]), se, float(math.exp(coef[0])), int(x.size), red)
    coef, *_ = np.linalg.lstsq(A, ly, rcond=None)
    dof = x.size - 2
    stderr: float | None = None
    if dof > 0:
        r = ly - A @ coef
        cov = np.linalg.inv(A.T @ A) * float(r @ r) / dof
        stderr = math.sqrt(cov[1, 1])
    return SlopeFit(float(coef[1]), stderr, float(math.exp(coef[0])), int(x.size))


@dataclass
class GapSeries:
    """Delta against H/d for one model (and wall) on the cell."""

    model: str
    label: str
    parameters: dict[str, Any]
    gaps: list[float]
    Delta: list[float | None]
    failures: dict[float, str] = field(default_factory=dict)

    def _ok(self) -> tuple[FloatArray, FloatArray]:
        ok = [(g, d) for g, d in zip(self.gaps, self.Delta, strict=True) if d is not None]
        return np.array([g for g, _ in ok]), np.array([d for _, d in ok])

    @property
    def slope(self) -> SlopeFit | None:
        """The power law over every gap with a solution (None with fewer than two)."""
        g, d = self._ok()
        return power_law_slope(g, d) if g.size >= 2 and np.all(d > 0) else None

    @property
    def slope_large_gap(self) -> float | None:
        """d ln Delta / d ln(H/d) between the two largest gaps: the asymptotic exponent."""
        g, d = self._ok()
        if g.size < 2 or np.any(d[-2:] <= 0):
            return None
        return float(math.log(d[-1] / d[-2]) / math.log(g[-1] / g[-2]))

    def to_dict(self) -> dict[str, Any]:
        s = self.slope
        return {
            "model": self.model,
            "label": self.label,
            "parameters": self.parameters,
            "gaps": self.gaps,
            "Delta": self.Delta,
            "failures": {str(k): v for k, v in self.failures.items()},
            "slope": None if s is None else s.to_dict(),
            "slope_large_gap": self.slope_large_gap,
        }


@dataclass
class GapStudy:
    """Delta against H/d for several models on one cell (:func:`thickness_vs_gap`)."""

    cell: str
    f: float
    series: list[GapSeries]
    scale_with_gap: dict[str, float]
    reference_gap: float

    def to_dict(self) -> dict[str, Any]:
        return {
            "cell": self.cell,
            "f": self.f,
            "scale_with_gap": self.scale_with_gap,
            "reference_gap": self.reference_gap,
            "paper_slopes": PAPER_SLOPES,
            "series": [s.to_dict() for s in self.series],
        }

    def to_text(self) -> str:
        held = (
            "every other dimensionless parameter held fixed"
            if not self.scale_with_gap
            else "scaled with the gap: "
            + ", ".join(
                f"{k} ~ (H/d)^{v:g} (given at H/d = {self.reference_gap:g})"
                for k, v in self.scale_with_gap.items()
            )
        )
        lines = [
            f"Delta [d] (u falls to f = {self.f:g} of its wall value) against H/d, "
            f"{self.cell} cell; {held}",
            "paper: Delta -> constant (slope 0) for walls smoother than the material, "
            "~ (H/d)^(1/3) for fully rough walls under gravity",
        ]
        gaps = sorted({g for s in self.series for g in s.gaps})
        width = max(len(s.label) for s in self.series) + 2
        lines.append(
            f"{'H/d':<{width}}"
            + "".join(f"{g:>10g}" for g in gaps)
            + f"  {'slope (all)':>14}  {'last':>6}"
        )
        for s in self.series:
            row = dict(zip(s.gaps, s.Delta, strict=True))
            cells = "".join(
                f"{row[g]:>10.4g}" if row.get(g) is not None else f"{'-':>10}" for g in gaps
            )
            sl, last = s.slope, s.slope_large_gap
            slope = "" if sl is None else sl.text()
            last_text = "" if last is None else f"{last:.3f}"
            lines.append(f"{s.label:<{width}}{cells}  {slope:>14}  {last_text:>6}")
        for s in self.series:
            for g, why in s.failures.items():
                lines.append(f"  {s.label}, H/d = {g:g}: {why}")
        return "\n".join(lines) + "\n"

    def plot(self, ax: Any = None):
        """Delta against H/d on log axes, one line per series, with the slopes 0 and 1/3."""
        from ..viz.plotting import new_figure, style

        fig = None
        if ax is None:
            fig, axes = new_figure(1, 1, width=4.6, height=3.4)
            ax = axes[0, 0]
        with style():
            markers = ["o", "s", "D", "^", "v", "*", "x"]
            all_g, all_d = [], []
            for i, s in enumerate(self.series):
                g, d = s._ok()
                if g.size == 0:
                    continue
                ax.plot(g, d, marker=markers[i % len(markers)], label=s.label)
                all_g += list(g)
                all_d += list(d)
            if all_g:
                g0, g1 = min(all_g), max(all_g)
                d0 = float(np.exp(np.mean(np.log(all_d))))
                gg = np.geomspace(g0, g1, 20)
                gm = math.sqrt(g0 * g1)
                ax.plot(gg, d0 * (gg / gm) ** (1 / 3), "k:", linewidth=0.8, label="slope 1/3")
                ax.plot(
                    gg,
                    np.full_like(gg, d0),
                    color="0.6",
                    linestyle=":",
                    linewidth=0.8,
                    label="slope 0",
                )
            ax.set_xscale("log")
            ax.set_yscale("log")
            from matplotlib.ticker import NullFormatter, ScalarFormatter

            ax.yaxis.set_major_formatter(ScalarFormatter())  # 2, 5, 10, not 2 x 10^0
            ax.yaxis.set_minor_formatter(NullFormatter())
            ax.set_xlabel(r"$H/d$")
            ax.set_ylabel(r"$\Delta$ [$d$]")
            ax.legend(fontsize=7)
            if fig is not None:
                fig.tight_layout()
        return fig if fig is not None else ax.figure


def _default_series(
    models: Sequence[str], model_parameters: Mapping[str, Mapping[str, Any]]
) -> list[tuple[str, str, dict[str, Any]]]:
    """(model, label, parameters): the Cosserat model twice (a wall smoother than the material
    and a fully rough one) unless its delta is given; every other model once."""
    out = []
    for m in models:
        params = dict(model_parameters.get(m, {}))
        if m == "cosserat" and "delta" not in params:
            out.append(
                (
                    m,
                    f"cosserat, delta = {config.text(config.DELTA)} deg",
                    {**params, "delta": config.DELTA},
                )
            )
            out.append((m, "cosserat, fully rough", {**params, "delta": FULLY_ROUGH}))
        else:
            given = ", ".join(f"{k} = {v}" for k, v in params.items())
            label = f"{m}, {given}" if given else m
            out.append((m, label, params))
    return out


def thickness_vs_gap(
    cell: str,
    models: Sequence[str] | None = None,
    gaps: Sequence[float] = DEFAULT_GAPS,
    *,
    cell_parameters: Mapping[str, Any] | None = None,
    model_parameters: Mapping[str, Mapping[str, Any]] | None = None,
    scale_with_gap: Mapping[str, float] | None = None,
    reference_gap: float | None = None,
    f: float = DEFAULT_F,
) -> GapStudy:
    """Delta against H/d for each model on one cell.

    Parameters
    ----------
    cell : str
        ``plane``, ``couette`` (``channel`` where registered).
    models : sequence of str, optional
        Registered rheologies; default every one defined on ``cell``. The Cosserat model gives
        two series, a wall with delta = :data:`cosserat.config.DELTA` and a fully rough one,
        unless ``model_parameters["cosserat"]`` sets delta.
    gaps : sequence of float
        H/d, each > 2 [-].
    cell_parameters : mapping, optional
        Parameters of the cell for every model (``B``, ``nu`` plane; ``Ri`` Couette) [-];
        default :data:`DEFAULT_CELL`.
    model_parameters : mapping of model name to mapping, optional
        Each model's own parameters (``{"cosserat": {"K": 0.5}, "mui": {"I_w": 1e-3}}``).
    scale_with_gap : mapping of str to float, optional
        Parameters that vary as (H/d / reference_gap)^exponent instead of staying fixed.
    reference_gap : float, optional
        The H/d at which scaled parameters have their given value (default the first gap).
    f : float
        Fraction of the wall velocity defining Delta, 0 < f < 1 (default 0.05) [-].

    Returns
    -------
    GapStudy
        A gap at which a model has no solution gives None and the reason.

    Raises
    ------
    ParameterError
        Unknown model or parameter, a gap <= 2, f out of (0, 1).
    MethodNotAvailableError
        A model named in ``models`` that is not defined on ``cell``.
    """
    if not 0.0 < f < 1.0:
        raise ParameterError(f"f must satisfy 0 < f < 1; got {f:g}")
    gap_list = [float(g) for g in gaps]
    if not gap_list or any(not math.isfinite(g) or g < 2.0 for g in gap_list):
        raise ParameterError(f"gaps H/d must be finite and >= 2 (eps = d/H <= 0.5); got {gaps}")
    gap_list = sorted(set(gap_list))
    names = models_for(cell) if models is None else models
    if not names:
        raise MethodNotAvailableError(f"no registered model is defined on the {cell!r} cell")
    cp = dict(DEFAULT_CELL.get(cell, {}) if cell_parameters is None else cell_parameters)
    scale = {k: float(v) for k, v in (scale_with_gap or {}).items()}
    g_ref = float(reference_gap) if reference_gap is not None else gap_list[0]
    series = []
    for model, label, own in _default_series(list(names), model_parameters or {}):
        base = {**cp, **own}
        try:
            template = make_problem(model, cell, {**base, "eps": 1.0 / g_ref})
        except (ParameterError, MethodNotAvailableError, NoSolutionError) as exc:
            # this model cannot be set up on the cell with these parameters: a row saying why,
            # not the end of the whole study
            why = " ".join(str(exc).split())
            series.append(
                GapSeries(model, label, {**base}, gap_list, [None] * len(gap_list),
                          dict.fromkeys(gap_list, why))
            )  # fmt: skip
            continue
        own_scale = {k: v for k, v in scale.items() if k in parameter_names(template)}
        deltas: list[float | None] = []
        failures: dict[float, str] = {}
        for g in gap_list:
            params = {**base, "eps": 1.0 / g}
            for k, expo in own_scale.items():
                params[k] = float(get_parameter(template, k)) * (g / g_ref) ** expo
            try:
                prof = model_solve(make_problem(model, cell, params))
                deltas.append(shear_layer_thickness(prof, f))
            except (NoSolutionError, ConvergenceError) as exc:
                deltas.append(None)
                failures[g] = " ".join(str(exc).split())
            except ParameterError as exc:
                if "is not defined" not in str(exc) and "f = " not in str(exc):
                    raise
                deltas.append(None)
                failures[g] = " ".join(str(exc).split())
        series.append(GapSeries(model, label, {**base}, gap_list, deltas, failures))
    return GapStudy(cell, f, series, scale, g_ref)


__all__ = [
    "DEFAULT_GAPS",
    "PAPER_SLOPES",
    "GapSeries",
    "GapStudy",
    "SlopeFit",
    "power_law_slope",
    "thickness_vs_gap",
]
