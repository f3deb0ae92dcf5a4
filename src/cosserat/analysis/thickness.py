"""Thickness curves: Delta against eps for one problem (the other parameters fixed)."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

from ..config import DEFAULT_F
from ..errors import NoSolutionError
from ..results.wall import shear_layer_thickness
from ..routes import solve

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
    its reason in ``failures``; other errors propagate. ``progress(i, n)`` is called after each
    solve. Residual checks are skipped: only the dense velocity near the wall is needed.
    """
    deltas: list[float | None] = []
    failures: dict[float, str] = {}
    guess: dict[str, float] = {}
    for i, eps in enumerate(eps_values):
        try:
            profile = solve(
                replace(problem, eps=eps),
                method=method,
                check=False,
                points=3,
                **options,
                **guess,
            )
        except NoSolutionError as exc:
            deltas.append(None)
            failures[float(eps)] = str(exc)
        else:
            deltas.append(shear_layer_thickness(profile, f))
            if "m_inner" in profile.diagnostics.stats:  # continuation in eps (Couette)
                guess = {"m_inner_guess": profile.diagnostics.stats["m_inner"]}
        if progress is not None:
            progress(i + 1, len(eps_values))
    return ThicknessCurve([float(e) for e in eps_values], deltas, failures)
