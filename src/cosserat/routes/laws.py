"""Shear-layer thickness laws for eps -> 0 (section "Shear layer thickness").

* Walls that are not fully rough (k > 0), every problem: ``Delta = -ln f / k``
  (``eqn-delta_soln``), independent of eps; 17.67 for phi = 28.5 deg, delta = 20 deg, L = 10.
* Fully rough walls under gravity: ``Delta = x_f eps^(-1/3) (L^2/(2 B nu))^(1/3)``
  (``eqn-delta_soln_fr`` a), x_f the Airy inner coordinate where u = f u_w (1.2748 for f = 0.05);
  in Couette flow ``Delta = x_f eps^(-1/3) (L^2 Ri/4)^(1/3)`` (``eqn-delta_soln_fr`` b).
* Fully rough walls without gravity: uniform shear, ``Delta = (1 - u_0)(1 - f)/eps``.
"""

from __future__ import annotations

import math

from ..config import DEFAULT_F
from ..model import PlaneShearCase, Problem
from ..model.rheologies.cosserat import CosseratCouette, cosserat_equations
from .airy import xi_hat_at_fraction


def thickness_limit(problem: Problem, f: float = DEFAULT_F) -> float | None:
    """The eps -> 0 limit of Delta, ``-ln f / k`` (``eqn-delta_soln``); None if it diverges.

    Examples
    --------
    >>> from cosserat import Cosserat, Plane, Problem, Wall
    >>> from cosserat.analysis import thickness_limit
    >>> round(thickness_limit(Problem(Plane(eps=0.01), Cosserat())), 2)
    17.67
    >>> print(thickness_limit(Problem(Plane(eps=0.01), Cosserat(wall=Wall.fully_rough()))))
    None
    """
    k = cosserat_equations(problem).slip_constants.k
    return -math.log(f) / k if k > 0.0 else None


def asymptotic_thickness(problem: Problem, f: float = DEFAULT_F) -> float:
    """The leading-order small-eps law for Delta at the problem's eps [grain diameters]."""
    limit = thickness_limit(problem, f)
    if limit is not None:
        return limit
    eps, eq = problem.eps, cosserat_equations(problem)
    if isinstance(eq, CosseratCouette):  # eqn-delta_soln_fr (b)
        return xi_hat_at_fraction(f) * eps ** (-1.0 / 3.0) * eq.inner_scale()
    if eq.B > 0.0:  # eqn-delta_soln_fr (a)
        return xi_hat_at_fraction(f) * eps ** (-1.0 / 3.0) * eq.inner_scale()
    u0 = 0.5 if eq.case is PlaneShearCase.SYMMETRIC else 0.0
    return (1.0 - u0) * (1.0 - f) / eps
