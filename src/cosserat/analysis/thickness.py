"""Thickness curves: Delta against eps for one problem (the other parameters fixed)."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from ..config import DEFAULT_F
from ..errors import ConvergenceError, NoSolutionError, ParameterError
from ..results.wall import shear_layer_thickness
from ..routes import solve
from ..routes.numerical import is_batched, wall_quantities

if TYPE_CHECKING:
    from ..model import Problem


@dataclass(frozen=True)
class ThicknessCurve:
    """Delta against eps; ``Delta[i]`` is None where the model has no real solution."""

    eps: list[float]
    Delta: list[float | None]
    failures: dict[float, str]


def thickness_curve(
    problem: Problem,
    eps_values: Sequence[float],
    *,
    f: float = DEFAULT_F,
    method: str = "numerical",
    progress: Callable[[int, int], None] | None = None,
    **options: Any,
) -> ThicknessCurve:
    """Delta at each eps of ``eps_values`` for ``problem`` (other parameters fixed).

    An eps at which the model has no real solution (:class:`NoSolutionError`) gives None and
    its reason in ``failures``; other errors propagate. The numerical route of the Cosserat
    model on plane shear and Couette flow (:func:`cosserat.routes.numerical.is_batched`)
    solves the whole curve in one call of the compiled batch kernel (the same kernel as a
    single solve); the other routes, cells and rheologies solve eps by eps, calling
    ``progress(i, n)`` after each.

    Examples
    --------
    >>> from cosserat import Cosserat, Plane, Problem, Wall
    >>> from cosserat.analysis import thickness_curve
    >>> problem = Problem(Plane(eps=0.01), Cosserat(wall=Wall(delta=20.0)))
    >>> curve = thickness_curve(problem, [1e-2, 1e-4, 1e-6])
    >>> [round(D, 2) for D in curve.Delta]
    [18.35, 17.67, 17.67]
    """
    problems = [problem.with_values({"eps": eps}) for eps in eps_values]
    eps_list = [float(e) for e in eps_values]
    if method == "numerical" and is_batched(problem):
        unknown = sorted(set(options) - {"rtol", "atol"})
        if unknown:
            raise ParameterError(
                f"option(s) {', '.join(unknown)} do not apply to a numerical thickness curve; "
                f"it accepts rtol, atol"
            )
        results = wall_quantities(problems, f=f, **options)
        failures = {
            e: r.message for e, r in zip(eps_list, results, strict=True) if r.status != "ok"
        }
        errors = [r.message for r in results if r.status == "error"]
        if errors:
            raise ConvergenceError(errors[0])
        if progress is not None:
            progress(len(problems), len(problems))
        return ThicknessCurve(eps_list, [r.Delta for r in results], failures)
    deltas: list[float | None] = []
    failures = {}
    for i, pr in enumerate(problems):
        try:
            profile = solve(pr, method=method, check=False, points=3, **options)
        except NoSolutionError as exc:
            deltas.append(None)
            failures[eps_list[i]] = str(exc)
        else:
            deltas.append(shear_layer_thickness(profile, f))
        if progress is not None:
            progress(i + 1, len(problems))
    return ThicknessCurve(eps_list, deltas, failures)
