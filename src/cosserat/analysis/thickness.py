"""Derived wall quantities of a profile: shear-layer thickness, wall slip, wall spin."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np
from scipy.optimize import brentq

from ..errors import NoSolutionError
from ..profile import Profile

if TYPE_CHECKING:
    from ..problems import Problem

DEFAULT_F = 0.05


def shear_layer_thickness(profile: Profile, f: float = DEFAULT_F) -> float:
    """Delta of ``eqn-delta_defn``, in grain diameters [-].

    The distance from the slipping wall xi_w, over eps, at which the velocity relative to the
    reference u_0 has fallen to a fraction ``f`` of its value at the wall::

        u(xi_w -+ eps Delta) - u_0 = f (u(xi_w) - u_0)

    u_0 is 1/2 between identical walls without gravity, the velocity of the non-slipping wall
    otherwise (0, or 1 for a layer at the lower wall). Solved with Brent's method on the
    profile's dense evaluator, so it does not depend on the output grid.
    """
    if not 0.0 < f < 1.0:
        raise ValueError(f"f must satisfy 0 < f < 1; got {f:g}")
    xw = profile.slip_wall
    direction = -1.0 if xw == 1.0 else 1.0
    u0 = profile.reference_velocity
    u_w = float(profile.velocity_at([xw])[0])
    target = f * (u_w - u0)
    span = 1.0
    eps = profile.problem.eps

    def g(d: float) -> float:
        return float(profile.velocity_at([xw + direction * d])[0] - u0 - target)

    g0, g1 = g(0.0), g(span)
    if g0 == 0.0:
        return 0.0
    if np.sign(g0) == np.sign(g1):
        raise ValueError("the velocity does not decay to the fraction f within the gap")
    d = brentq(g, 0.0, span, xtol=1e-15 * eps, rtol=4 * np.finfo(float).eps, maxiter=400)
    return float(d) / eps


def wall_slip(profile: Profile) -> float:
    """|u - u_wall| at the slipping wall: slip velocity over the wall speed [-]."""
    xw = profile.slip_wall
    u = float(profile.velocity_at([xw])[0])
    return abs(u - profile.problem.wall_velocity(xw))


def wall_omega(profile: Profile) -> float:
    """omega at the slipping wall (paper's sign; negative for the cases shown) [-]."""
    value = float(profile.evaluate([profile.slip_wall]).omega[0])
    if not math.isfinite(value):
        raise ValueError("non-finite wall spin")
    return value


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
    from ..solvers import solve

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
