"""The Airy-function inner layer of fully rough walls (Appendix, ``docs/derivation_plane.md``).

At a fully rough slipping wall m0 = 0, the outer couple stress vanishes like sqrt(distance),
and the expansion fails in a layer of thickness eps^(2/3): there the rescaled couple stress
obeys the Riccati equation ``eqn-asymp_eta_inner``, solved by m_hat = -Ai'/Ai, and

    omega = omega_1 (Ai(x)/Ai(0))^2,    u = u_w (1 - I(x)/I(inf))      (eqn-vel_g_unif),

with x the inner variable and ``I(x) = Ai(0)^-2 int_0^x Ai(z)^2 dz`` (``eqn-defn_I``).
Since d/dz [z Ai^2 - Ai'^2] = Ai^2, the integral is elementary::

    I(x) = (x Ai(x)^2 - Ai'(x)^2 + Ai'(0)^2) / Ai(0)^2,   I(inf) = (Ai'(0)/Ai(0))^2,
    1 - I(x)/I(inf) = (Ai'(x)^2 - x Ai(x)^2) / Ai'(0)^2,

evaluated with the exponentially scaled Airy functions so that nothing underflows.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import brentq
from scipy.special import airy, airye

from ..errors import ParameterError
from ..model.constitutive import FloatArray

_AI0, _AIP0, _, _ = (float(v) for v in airy(0.0))
I_INFINITY = (_AIP0 / _AI0) ** 2
"""I(inf) of ``eqn-defn_I`` = (Ai'(0)/Ai(0))^2 [-]."""


def _log_scale(x: FloatArray) -> FloatArray:
    """-2 zeta(x) = -(4/3) x^(3/2): log of the scaling of Ai^2 for x >= 0."""
    return -(4.0 / 3.0) * np.power(np.maximum(x, 0.0), 1.5)


def velocity_fraction(x: FloatArray) -> FloatArray:
    """1 - I(x)/I(inf) = (Ai'(x)^2 - x Ai(x)^2)/Ai'(0)^2, for x >= 0 [-]."""
    x = np.asarray(x, dtype=float)
    eai, eaip, _, _ = airye(x)
    with np.errstate(under="ignore"):
        return (eaip**2 - x * eai**2) / _AIP0**2 * np.exp(_log_scale(x))


def spin_fraction(x: FloatArray) -> FloatArray:
    """(Ai(x)/Ai(0))^2, for x >= 0 [-]."""
    x = np.asarray(x, dtype=float)
    eai = airye(x)[0]
    with np.errstate(under="ignore"):
        return (eai / _AI0) ** 2 * np.exp(_log_scale(x))


def inner_couple_stress(x: FloatArray) -> FloatArray:
    """m_hat = -Ai'(x)/Ai(x), the decaying solution of ``eqn-asymp_eta_inner`` [-]."""
    eai, eaip, _, _ = airye(np.asarray(x, dtype=float))
    return -eaip / eai


def xi_hat_at_fraction(f: float) -> float:
    """The inner coordinate at which u/u_w = f (1.2748 for f = 0.05; paper: 1.275) [-]."""
    if not 0.0 < f < 1.0:
        raise ParameterError(f"f must satisfy 0 < f < 1; got {f:g}")
    hi = 1.0
    while velocity_fraction(np.array(hi)) > f:
        hi *= 2.0
    return float(
        brentq(lambda x: float(velocity_fraction(np.array(x))) - f, 0.0, hi, xtol=1e-15, rtol=1e-15)
    )


def airy_layer(
    x_hat: FloatArray, *, eps: float, scale: float, u_wall: float, slip_sign: float
) -> tuple[FloatArray, FloatArray]:
    """(u, omega) of the Airy layer with u -> 0 far from the wall (``eqn-vel_g_unif``,
    ``eqn-asymp_soln_vels_g__fr_consts``, ``eqn-asymp_soln_vels_cyl_fr``) [-].

    ``omega_1 = -s u_w eps^(-2/3) / (2 scale I(inf))`` at leading order (the wall slip is
    O(eps^(1/3)) and dropped), ``u = u_w (1 - I/I(inf))``.
    """
    omega_1 = -slip_sign * u_wall * eps ** (-2.0 / 3.0) / (2.0 * scale * I_INFINITY)
    return u_wall * velocity_fraction(x_hat), omega_1 * spin_fraction(x_hat)
