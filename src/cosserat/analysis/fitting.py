"""Compare a model with a measured velocity profile: the model at the data's points.

What is not fitting: :func:`compare` (model minus data, RMS and chi-square), :func:`model_at`,
:func:`model_profile`, :func:`moving_wall`, and the Cosserat parameters' accessors
:func:`natural_value` and :func:`with_values`.

Fitting is a calibration of one run (``docs/calibration.md``):
:func:`cosserat.calibration.single.fit`. ``cosserat.analysis.fitting.fit``, ``FitResult``,
``FitParameter`` and ``FlatDirection`` are deprecated aliases of it for one release (a
:class:`DeprecationWarning` names the replacement).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from .. import config
from .._moved import moved_names
from ..errors import MethodNotAvailableError
from ..model import Cosserat, Problem
from ..model.constitutive import FloatArray
from ..model.parameters import FULLY_ROUGH, Wall
from ..results.profile import Profile
from ..routes import solve
from .measurements import MeasuredProfile

FREE_PARAMETERS = ("delta", "K", "L", "phi", "A")
"""The Cosserat model's parameters :func:`natural_value` and :func:`with_values` take (those a
fit to one profile can free)."""


def fit_range(name: str) -> tuple[float, float]:
    """The declared fit range of the Cosserat parameter ``name`` [its unit]."""
    rng = Cosserat.declared()[name].fit_range
    assert rng is not None
    return rng


def moving_wall(problem: Any) -> tuple[float, float]:
    """(xi, u) of the wall that drives the flow, read from the cell's ``wall_velocity``.

    (1, 1) for plane shear (the upper plate), (0, -1) for Couette flow (the inner cylinder),
    whatever the rheology.

    Raises
    ------
    MethodNotAvailableError
        No wall moves (a gravity-driven cell): a velocity over the wall speed is undefined.
    """
    for xi in (1.0, 0.0):
        u = float(problem.wall_velocity(xi))
        if u != 0.0:
            return xi, u
    name = getattr(problem, "cell_name", type(problem).__name__)
    raise MethodNotAvailableError(
        f"the {name} cell: no wall moves, so a profile over the wall speed cannot be "
        "compared with it (the gravity-driven cell needs its own velocity scale)"
    )


def model_profile(problem: Problem, method: str = "numerical", **options: Any) -> Profile:
    """The solution of ``problem`` by ``method`` without its residual check, on a coarse
    output grid (the dense solution is evaluated at the data's points)."""
    return solve(problem, method=method, check=False, points=3, **options)


def model_at(profile: Profile, distance_d: FloatArray) -> FloatArray:
    """u / u_wall of ``profile`` at distances from the moving wall in grain diameters [-]."""
    xw, uw = moving_wall(profile.problem)
    d = np.asarray(distance_d, dtype=float) * profile.problem.eps
    xi = d if xw == 0.0 else 1.0 - d
    return profile.velocity_at(np.clip(xi, 0.0, 1.0)) / uw


@dataclass(frozen=True)
class Comparison:
    """The model beside a measured profile."""

    measured: MeasuredProfile
    profile: Profile
    model: FloatArray
    residuals: FloatArray
    rms: float
    chi2: float | None

    def model_curve(self, distance_d: FloatArray) -> FloatArray:
        """The model's u / u_wall at distances from the moving wall [d_p] (for plots)."""
        return model_at(self.profile, distance_d)

    def to_dict(self) -> dict[str, Any]:
        return {
            "problem": self.profile.problem.parameters(),
            "distance_d": self.measured.distance_d.tolist(),
            "u_over_uw": self.measured.u_over_uw.tolist(),
            "model": self.model.tolist(),
            "residuals": self.residuals.tolist(),
            "rms": self.rms,
            "chi2": self.chi2,
            "n_points": self.measured.n,
        }


def compare(
    problem: Problem, measured: MeasuredProfile, method: str = "numerical", **options: Any
) -> Comparison:
    """Model minus data at the measured points; RMS and (with uncertainties) chi-square."""
    measured.xi(problem.eps, moving_wall(problem)[0])  # checks the points lie in the gap
    prof = model_profile(problem, method, **options)
    model = model_at(prof, measured.distance_d)
    res = measured.u_over_uw - model
    chi2 = None if measured.u_err is None else float(np.sum((res / measured.u_err) ** 2))
    return Comparison(measured, prof, model, res, float(np.sqrt(np.mean(res**2))), chi2)


# --------------------------------------------------------------------------- parameters
def _cosserat(problem: Problem) -> Cosserat:
    """The problem's law, checked to be the Cosserat model (the one these fits free)."""
    law = problem.rheology
    if not isinstance(law, Cosserat):
        raise MethodNotAvailableError(
            f"fitting delta, K, L, phi or A needs the Cosserat model; got the {law.name} rheology"
        )
    return law


def _moving(problem: Problem) -> Wall:
    return _cosserat(problem).wall


def natural_value(problem: Problem, name: str) -> float:
    """Current value of a fittable parameter of the Cosserat model (delta in degrees, fully
    rough as its angle)."""
    mat = _cosserat(problem).material
    if name == "delta":
        wall = _moving(problem)
        return mat.fully_rough_delta if wall.is_fully_rough else float(wall.delta)
    if name == "K":
        return _moving(problem).K
    return float(getattr(mat, name))


def with_values(problem: Problem, values: dict[str, float]) -> Problem:
    """``problem`` (of the Cosserat model) with the moving wall's delta, K and the material's
    L, phi, A replaced (:meth:`~cosserat.model.problem.Problem.with_values`).

    delta = "fully-rough" when tan(delta) reaches sin(phi), and a wall left rougher than fully
    rough by a lower phi is clamped to it. Between identical plane walls both walls change
    together (a plane cell's lower wall follows the moving one unless it was given).
    """
    law = _cosserat(problem)
    mat = law.material
    material = replace(
        mat, phi=values.get("phi", mat.phi), L=values.get("L", mat.L), A=values.get("A", mat.A)
    )
    old = law.wall
    delta: float | str = old.delta
    if "delta" in values:
        tan_d = math.tan(math.radians(values["delta"]))
        rough = tan_d >= material.sin_phi * (1.0 - config.FULLY_ROUGH_RTOL)
        delta = FULLY_ROUGH if rough else values["delta"]
    elif not old.is_fully_rough and math.tan(math.radians(float(old.delta))) > material.sin_phi:
        delta = FULLY_ROUGH  # phi changed below the wall's friction: clamp
    new = {"phi": material.phi, "L": material.L, "A": material.A, "delta": delta}
    new["K"] = values.get("K", old.K)
    if law.lower is not None and law.lower == law.wall:
        new["delta_lower"], new["K_lower"] = delta, new["K"]
    return problem.with_values(new)


# deprecated name -> (module, name) of its replacement, one layer up (resolved on access only)
_MOVED = {
    "fit": ("cosserat.calibration.single", "fit"),
    "FitResult": ("cosserat.calibration.single", "SingleFit"),
    "FitParameter": ("cosserat.calibration.result", "Estimate"),
    "FlatDirection": ("cosserat.calibration.diagnostics", "FlatDirection"),
}


__getattr__ = moved_names(__name__, _MOVED, "a fit to one profile is a calibration of one run")


__all__ = [
    "FREE_PARAMETERS",
    "Comparison",
    "compare",
    "fit_range",
    "model_at",
    "model_profile",
    "moving_wall",
    "natural_value",
    "with_values",
]
