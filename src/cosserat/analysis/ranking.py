"""What every model's fit to a measured profile needs that is not fitting: the models' problems,
their parameters by key, their solution at the data's points and the information criteria.

Fitting and ranking are calibrations of one run (``docs/calibration.md``):
:func:`cosserat.calibration.single.fit_model`,
:func:`~cosserat.calibration.single.rank_models` and :class:`~cosserat.calibration.single.Ranking`.
The names
``fit_model``, ``rank_models``, ``Ranking``, ``ModelFit`` and ``Estimate`` here are deprecated
aliases of them for one release (a :class:`DeprecationWarning` names the replacement).

Information criteria, k free parameters, n points (:func:`information_criteria`):

* with the points' uncertainties sigma given (taken as absolute, Gaussian): ``-2 ln L =
  chi^2`` up to a constant, so ``AIC = chi^2 + 2k`` and ``BIC = chi^2 + k ln n``;
* without them (sigma unknown, estimated by its maximum-likelihood value RSS/n):
  ``AIC = n ln(RSS/n) + 2k`` and ``BIC = n ln(RSS/n) + k ln n``.

The constant dropped is the same for every model fitted to the same data, so differences
between models are meaningful and the values themselves are not.
"""

from __future__ import annotations

import inspect
import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from .. import config
from .._moved import moved_names
from ..errors import (
    MethodNotAvailableError,
    ParameterError,
)
from ..model import Problem
from ..model.constitutive import FloatArray
from ..model.rheologies import RHEOLOGIES
from ..results.profile import Profile
from ..routes import solve
from ..routes.registry import find as find_route
from .fitting import FREE_PARAMETERS as COSSERAT_PARAMETERS
from .fitting import model_at, moving_wall, natural_value, with_values
from .measurements import MeasuredProfile

CELL_PARAMETERS = ("eps", "Ri", "B", "nu")
"""Parameters of the cell rather than of the material: d/H, R_i/H, rho_s g H/N, nu [-]."""


# --------------------------------------------------------------------------- the models
def rheology_and_cell(problem: Any) -> tuple[str, str]:
    """(model name, cell name) of a problem.

    Raises
    ------
    ParameterError
        Not a :class:`~cosserat.model.problem.Problem`.
    """
    if not isinstance(problem, Problem):
        raise ParameterError(
            f"{type(problem).__name__} is not a Problem(cell, rheology) of a registered rheology"
        )
    return problem.model, problem.cell_name


def parameter_names(problem: Any) -> list[str]:
    """Every numeric parameter name :func:`set_parameters` accepts for ``problem`` (its
    declared keys, :meth:`~cosserat.model.problem.Problem.declared`)."""
    return [k for k, p in problem.declared().items() if p.numeric]


def get_parameter(problem: Any, name: str) -> Any:
    """Value of parameter ``name`` of ``problem`` (its command-line key; I_w as it drives the
    flow, its default included).

    For the Cosserat model ``delta`` is the moving wall's friction angle [deg] (the fully rough
    wall as its angle) and ``K`` its slip coefficient.
    """
    if problem.model == "cosserat" and name in COSSERAT_PARAMETERS:
        return natural_value(problem, name)
    values = {**problem.values(), **problem.cell_values()}
    if name not in values:
        raise ParameterError(
            f"the {problem.model} rheology on the {problem.cell_name} cell has no parameter "
            f"{name!r}; it has {', '.join(parameter_names(problem))}"
        )
    return values[name]


def set_parameters(problem: Any, values: Mapping[str, Any]) -> Any:
    """``problem`` with parameters replaced by key (validated again): the problem's
    :meth:`~cosserat.model.problem.Problem.with_values`, and for the Cosserat model's
    ``delta``, ``K`` and material :func:`cosserat.analysis.fitting.with_values` (a wall made
    rougher than fully rough by a lower phi is clamped to it; both walls change together when
    the plane cell's walls are alike).

    Raises
    ------
    ParameterError
        A name the problem does not have, or a value out of its bounds.
    """
    rest = dict(values)
    if problem.model == "cosserat":
        wall = {k: float(rest.pop(k)) for k in list(rest) if k in COSSERAT_PARAMETERS}
        if wall:
            problem = with_values(problem, wall)
    if not rest:
        return problem
    return problem.with_values(rest)


model_velocity = model_at
"""u / u_wall of a profile at distances from the moving wall [d] (:func:`fitting.model_at`)."""


def model_solve(problem: Any, points: int = 3, **options: Any) -> Profile:
    """The model's profile, in closed form where its rheology has one for this problem, else
    by its numerical route at ``rtol`` = :data:`cosserat.config.RTOL` (unless given): the fit's
    finite-difference steps are far above that. A coarse output grid: the fit evaluates the
    dense solution at the data points."""
    model, cell = rheology_and_cell(problem)
    if find_route(model, cell, "closed-form") is not None and not options:
        try:
            return solve(problem, method="closed-form", check=False, points=points)
        except MethodNotAvailableError:
            pass
    route = find_route(model, cell, "numerical")
    if route is not None and "rtol" in inspect.signature(route).parameters:
        options = {"rtol": config.RTOL, **options}
    return solve(problem, method="numerical", check=False, points=points, **options)


def default_free(model: str, problem: Any) -> tuple[str, ...]:
    """The parameters fitted by default: the rheology's
    :attr:`~cosserat.model.rheologies.base.Rheology.default_free` that this problem has, or else
    every parameter of the rheology with a declared fit range."""
    names = tuple(n for n in RHEOLOGIES[model].default_free if n in parameter_names(problem))
    if names:
        return names
    own = RHEOLOGIES[model].declared(problem.cell_name)
    return tuple(k for k, p in own.items() if p.fittable and p.numeric)


# --------------------------------------------------------------------------- statistics
def information_criteria(
    residuals: FloatArray, k: int, absolute_sigma: bool
) -> tuple[float, float | None, float | None]:
    """(chi^2 or RSS, AIC, BIC) of weighted residuals for k free parameters.

    ``residuals`` are ``(model - data)/sigma`` (sigma = 1 without uncertainties). With
    ``absolute_sigma``: AIC = chi^2 + 2k, BIC = chi^2 + k ln n. Without: AIC = n ln(RSS/n) + 2k,
    BIC = n ln(RSS/n) + k ln n; None when RSS = 0 (a perfect fit has no finite likelihood
    with an estimated sigma).
    """
    r = np.asarray(residuals, dtype=float)
    n = r.size
    s = float(np.sum(r * r))
    if absolute_sigma:
        return s, s + 2.0 * k, s + k * math.log(n)
    if s == 0.0:
        return s, None, None
    base = n * math.log(s / n)
    return s, base + 2.0 * k, base + k * math.log(n)


def measured_cell(measured: MeasuredProfile, **given: Any) -> dict[str, Any]:
    """The cell parameters a measured profile's header states (``geometry``, ``eps``, ``Ri``,
    ``B``, ``nu``), with ``given`` values (not None) taking precedence: what
    :func:`rank_models` takes as ``cell_parameters``.

    Raises
    ------
    ParameterError
        No geometry or no eps in the header or ``given``.
    """
    names = {"geometry": "geometry", "eps": "eps", "ri": "Ri", "b": "B", "nu": "nu"}
    out = {names[k]: v for k, v in measured.meta.items() if k in names}
    out.update({k: v for k, v in given.items() if v is not None})
    for key in ("geometry", "eps"):
        if out.get(key) is None:
            raise ParameterError(
                f"the cell's {key} is neither in the profile's header ('# {key}: ...') nor given"
            )
    return out


# deprecated name -> (module, name) of its replacement, one layer up (resolved on access only)
_MOVED = {
    "fit_model": ("cosserat.calibration.single", "fit_model"),
    "rank_models": ("cosserat.calibration.single", "rank_models"),
    "Ranking": ("cosserat.calibration.single", "Ranking"),
    "ModelFit": ("cosserat.calibration.single", "SingleFit"),
    "Estimate": ("cosserat.calibration.result", "Estimate"),
}


__getattr__ = moved_names(__name__, _MOVED, "a fit to one profile is a calibration of one run")


__all__ = [
    "CELL_PARAMETERS",
    "default_free",
    "get_parameter",
    "information_criteria",
    "measured_cell",
    "model_solve",
    "model_velocity",
    "moving_wall",
    "parameter_names",
    "rheology_and_cell",
    "set_parameters",
]
