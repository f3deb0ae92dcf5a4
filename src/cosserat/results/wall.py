"""Wall quantities of a profile: shear-layer thickness Delta, wall slip, wall spin.

Functions of a :class:`~cosserat.results.profile.Profile` only, so that every route's profile
(and the profile's own export) uses the same definitions.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
from scipy.optimize import brentq

from ..config import DEFAULT_F
from ..errors import ConvergenceError, ParameterError

if TYPE_CHECKING:
    from .profile import Profile


def shear_layer_thickness(profile: Profile, f: float = DEFAULT_F) -> float:
    """Delta of ``eqn-delta_defn``, in grain diameters [-].

    The distance from the slipping wall xi_w, over eps, at which the velocity relative to the
    reference u_0 has fallen to a fraction ``f`` of its value at the wall::

        u(xi_w -+ eps Delta) - u_0 = f (u(xi_w) - u_0)

    u_0 is 1/2 between identical walls without gravity, the velocity of the non-slipping wall
    otherwise (0, or 1 for a layer at the lower wall), the centre-line velocity in the channel.
    Solved with Brent's method on the profile's dense evaluator, so it does not depend on the
    output grid; in a cell symmetric about its centre line (the channel) over the half gap.

    Examples
    --------
    >>> from cosserat import Cosserat, Plane, Problem, Wall, shear_layer_thickness, solve
    >>> profile = solve(Problem(Plane(eps=0.01), Cosserat(wall=Wall(delta=20.0))))
    >>> round(shear_layer_thickness(profile), 2)
    18.35
    >>> round(shear_layer_thickness(profile, f=0.1), 2)
    13.93
    """
    own = getattr(profile.evaluator, "thickness", None)
    if own is not None:  # the numerical route's compiled root-finder on its dense output
        if not 0.0 < f < 1.0:
            raise ParameterError(f"f must satisfy 0 < f < 1; got {f:g}")
        return float(own(f))
    if not 0.0 < f < 1.0:
        raise ParameterError(f"f must satisfy 0 < f < 1; got {f:g}")
    xw = profile.slip_wall
    direction = -1.0 if xw == 1.0 else 1.0
    u0 = profile.reference_velocity
    u_w = float(profile.velocity_at([xw])[0])
    target = f * (u_w - u0)
    span = float(getattr(getattr(profile.problem, "cell", None), "span", 1.0))
    eps = profile.problem.eps

    def g(d: float) -> float:
        return float(profile.velocity_at([xw + direction * d])[0] - u0 - target)

    g0, g1 = g(0.0), g(span)
    if g0 == 0.0:
        return 0.0
    if np.sign(g0) == np.sign(g1):
        raise ParameterError(
            f"f = {f:g}: the velocity does not fall to this fraction of its wall value within "
            f"the gap, so Delta (eqn-delta_defn) is not defined; choose a larger f"
        )
    d = brentq(g, 0.0, span, xtol=1e-15 * eps, rtol=4 * np.finfo(float).eps, maxiter=400)
    return float(d) / eps


def wall_slip(profile: Profile) -> float:
    """|u - u_wall| at the slipping wall: slip velocity over the wall speed [-].

    Examples
    --------
    >>> from cosserat import Cosserat, Plane, Problem, Wall, solve, wall_slip
    >>> profile = solve(Problem(Plane(eps=0.01), Cosserat(wall=Wall(delta=20.0))))
    >>> round(wall_slip(profile), 4)
    0.0202
    """
    xw = profile.slip_wall
    u = float(profile.velocity_at([xw])[0])
    return abs(u - profile.problem.wall_velocity(xw))


def wall_omega(profile: Profile) -> float | None:
    """omega at the slipping wall (paper's sign; negative for the cases shown) [-]; None for a
    rheology without grain spin (local mu(I), NGF).

    Examples
    --------
    >>> from cosserat import Cosserat, Plane, Problem, Wall, solve, wall_omega
    >>> profile = solve(Problem(Plane(eps=0.01), Cosserat(wall=Wall(delta=20.0))))
    >>> round(wall_omega(profile), 3)
    -4.035
    """
    omega = profile.evaluate([profile.slip_wall]).omega
    if omega is None:
        return None
    value = float(omega[0])
    if not math.isfinite(value):
        raise ConvergenceError(f"non-finite wall spin {value!r}")
    return value
