"""Wall quantities of many problems, any rheology on any cell: the one batch entry point of
sweeps and thickness studies.

The Cosserat model on plane shear and Couette flow goes to the compiled batch kernel
(:func:`cosserat.routes.numerical.wall_quantities`), on the channel to its kernel
(:func:`cosserat.routes.channel.wall_quantities`); every other problem is solved one by one by
its numerical route and its wall quantities read from the profile. A failure is a status and its
message, never NaN, and the results come back in the order of the problems.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from .. import config
from ..errors import ConvergenceError, NoSolutionError, ParameterError
from ..model import Problem
from ..results.wall import shear_layer_thickness, wall_omega, wall_slip
from . import channel, numerical
from .numerical import WallResult, is_batched


def _is_cosserat_channel(problem: Problem) -> bool:
    return problem.model == "cosserat" and problem.cell_name == "channel"


def _one(problem: Problem, f: float) -> WallResult:
    """One problem by its numerical route: Delta, slip, spin and stress from the profile."""
    from . import solve

    try:
        profile = solve(problem, check=False, points=3)
        delta = shear_layer_thickness(profile, f)
    except NoSolutionError as exc:
        return WallResult("no-solution", None, None, None, None, str(exc))
    except (ConvergenceError, ParameterError) as exc:
        return WallResult("error", None, None, None, None, str(exc))
    stress = float(profile.evaluate([profile.slip_wall]).sigma_yx[0])
    return WallResult("ok", delta, wall_slip(profile), wall_omega(profile), stress)


def wall_quantities(
    problems: Sequence[Any], rtol: float = config.RTOL, f: float = config.DEFAULT_F
) -> list[WallResult]:
    """Delta, wall slip, wall spin and wall stress of every problem (module docstring).

    ``rtol`` is the tolerance of the Cosserat model's compiled kernels; the other routes use
    their own defaults.

    Raises
    ------
    ParameterError
        ``f`` out of (0, 1), or something that is not a problem.
    """
    if not 0.0 < f < 1.0:
        raise ParameterError(f"f must satisfy 0 < f < 1; got {f:g}")
    for pr in problems:
        if not isinstance(pr, Problem):
            raise ParameterError(f"expected a Problem(cell, rheology); got {type(pr).__name__}")
    out: list[WallResult | None] = [None] * len(problems)
    batch = [i for i, p in enumerate(problems) if is_batched(p)]
    for i, res in zip(
        batch, numerical.wall_quantities([problems[i] for i in batch], rtol, f), strict=True
    ):
        out[i] = res
    chan = [i for i, p in enumerate(problems) if _is_cosserat_channel(p)]
    for i, res in zip(
        chan, channel.wall_quantities([problems[i] for i in chan], rtol, f), strict=True
    ):
        out[i] = res
    for i, p in enumerate(problems):
        if out[i] is None:
            out[i] = _one(p, f)
    return [r for r in out if r is not None]


__all__ = ["WallResult", "wall_quantities"]
