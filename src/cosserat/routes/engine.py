"""The numerical engine: two well-conditioned passes over a :class:`Formulation`.

Why two passes (``docs/numerics.md``):

1. **Couple stress.** ``dm/dxi`` is stiff (rate ~ k/eps) and stable only when integrated from
   the wall that does not slip (or the centre) towards the slipping wall: along that direction
   perturbations decay like exp(-k |xi - xi0| / eps). It is integrated with an implicit
   Runge-Kutta method (Radau IIA, order 5) with dense output, and stopped with a
   :class:`~cosserat.errors.NoSolutionError` if the yield radicand S of ``eqn-nd_sigxy``
   reaches zero (the solution leaves the real domain).
2. **Spin and velocity.** With m known, the spin relative to rigid rotation is
   ``w = w_s exp(l(xi))`` and ``h u = (h u)_s - w_s P(xi)``, where ``l`` and ``P`` are
   quadratures started at the slipping wall: ``l' = dln w/dxi``, ``P' = exp(l) G``,
   ``l(xi_s) = P(xi_s) = 0``. Started there, ``l <= 0`` and ``P`` stay bounded for any eps, the
   error control is relative to the spin where the spin matters, and nothing over- or
   underflows: the integration stops where exp(l) underflows (l < -745), beyond which the
   spin is exactly 0 in double precision and P is constant. This pass is not stiff (pure
   quadratures) and uses the explicit DOP853 method.

The two constants (u_s, w_s) then follow from the two linear velocity conditions.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import ConvergenceError, NoSolutionError
from ..model.constitutive import FloatArray, radicand_scale
from ..model.formulation import Formulation
from .dop853_small import SmallSolution, dop853_small
from .radau_scalar import ScalarSolution, StepFailedError, radau_scalar

# exp(l) underflows below this; the spin is then exactly zero in double precision.
LOG_UNDERFLOW = -745.0


@dataclass(frozen=True)
class CoupleStress:
    """Dense couple stress m(xi) on [min(start, end), max(start, end)]."""

    sol: ScalarSolution
    xi_start: float
    xi_end: float
    nfev: int
    njev: int
    steps: int

    def __call__(self, xi: FloatArray) -> FloatArray:
        x = np.asarray(xi, dtype=float)
        return np.asarray(self.sol(x), dtype=float) if x.ndim else float(self.sol(x))

    def scalar(self, xi: float) -> float:
        return self.sol.at(xi)


def integrate_couple_stress(
    form: Formulation,
    xi_start: float,
    xi_end: float,
    m_start: float,
    rtol: float,
    atol: float,
) -> CoupleStress:
    """Pass 1: the couple-stress balance from ``xi_start`` to ``xi_end`` (stable direction).

    Radau IIA (order 5) specialised to a scalar equation (:mod:`.radau_scalar`); a terminal
    event on the yield radicand S stops it where the solution leaves the real domain.
    """
    try:
        sol = radau_scalar(
            form.dm_dxi, xi_start, xi_end, m_start, rtol, atol, event=form.yield_margin
        )
    except StepFailedError as exc:
        margin = float(form.yield_margin(exc.t, exc.y))
        why = (
            f"; the couple stress is within {margin:.1e} (relative) of its yield bound there, "
            f"where the couple-stress equation is singular (dF/dm ~ 1/sqrt(S)): the problem is "
            f"at the edge of the model's real domain (e.g. a nearly frictionless wall, or a very "
            f"small inner cylinder with a small eps)"
            if margin < 1e-6
            else ""
        )
        raise ConvergenceError(
            f"couple-stress integration stalled at xi = {exc.t:.6g} (m = {exc.y:.6g}): {exc}{why}"
        ) from None
    if sol.status == 1:
        xi_r = float(sol.t_event)  # type: ignore[arg-type]
        m_r = float(sol.y[-1])
        raise NoSolutionError(
            f"no real solution: the couple stress reaches the yield bound at xi = {xi_r:.6g} "
            f"(m = {m_r:.6g}), beyond which the second shear stress of eqn-nd_sigxy is complex; "
            f"the couple-stress balance cannot be continued to the wall at xi = {xi_end:g}"
        )
    return CoupleStress(sol, xi_start, xi_end, sol.nfev, sol.njev, sol.steps)


@dataclass(frozen=True)
class SpinQuadrature:
    """Dense (l, P) of pass 2 from the slipping wall ``xi_slip`` towards ``xi_far``."""

    sol: SmallSolution  # in tau: xi = xi_slip + span * tau (or the square-root map)
    xi_slip: float
    xi_cut: float  # where the integration stopped (xi_far, or where exp(l) underflows)
    l_cut: float
    P_cut: float
    nfev: int
    span: float
    singular: bool

    def __call__(self, xi: FloatArray) -> tuple[FloatArray, FloatArray]:
        x = np.asarray(xi, dtype=float)
        inside = np.abs(x - self.xi_slip) <= abs(self.xi_cut - self.xi_slip)
        ell = np.full(x.shape, -np.inf)
        P = np.full(x.shape, self.P_cut)
        if np.any(inside):
            frac = np.clip((x[inside] - self.xi_slip) / self.span, 0.0, 1.0)
            tau = 1.0 - np.sqrt(1.0 - frac) if self.singular else frac
            y = self.sol(tau)
            ell[inside] = y[:, 0]
            P[inside] = y[:, 1]
        return ell, P


def integrate_spin(
    form: Formulation,
    m: Callable[[FloatArray], FloatArray],
    xi_slip: float,
    xi_far: float,
    rtol: float,
    atol: float,
) -> SpinQuadrature:
    """Pass 2: l = ln(w / w_s) and P = int exp(l) G from the slipping wall inwards.

    DOP853 (:mod:`.dop853_small`). If the couple stress at the far end sits on the yield bound
    (S = 0, e.g. a prescribed m = b at the fixed wall), the spin rate has an integrable
    1/sqrt singularity there; the quadrature is then carried out in tau with
    xi = xi_slip + (xi_far - xi_slip)(2 tau - tau^2), whose Jacobian vanishes like the square
    root.
    """
    st = form.stresses(xi_far, m(xi_far))
    singular = float(st.radicand) <= 1e-8 * float(radicand_scale(st.sigma_c, form.material))
    span = xi_far - xi_slip
    m_scalar = m.scalar if hasattr(m, "scalar") else (lambda x: float(m(x)))

    def rhs(tau: float, y: list[float]) -> list[float]:
        if singular:
            xi, jac = xi_slip + span * (2.0 * tau - tau * tau), span * 2.0 * (1.0 - tau)
        else:
            xi, jac = xi_slip + span * tau, span
        rate, source = form.spin_rates(xi, m_scalar(xi))
        ell = y[0]
        # a trial stage may overshoot; l <= 0 on the solution (w is largest at the wall)
        gain = math.exp(min(ell, 700.0)) if ell > LOG_UNDERFLOW else 0.0
        return [jac * rate, jac * gain * source]

    def underflow(tau: float, y: list[float]) -> float:
        return y[0] - LOG_UNDERFLOW

    # P ~ eps G and G carries the velocity weight h (1/(Ri + xi) in Couette flow): its absolute
    # tolerance must scale with h, or at large Ri the velocity u = (u_s h_s - w_s P)/h, a
    # difference of O(h) terms divided by h, loses the digits atol did not ask for.
    h_min = min(float(form.velocity_weight(xi_slip)), float(form.velocity_weight(xi_far)))
    try:
        sol = dop853_small(
            rhs, 0.0, 1.0, [0.0, 0.0], rtol, [rtol, atol * form.eps * h_min], event=underflow
        )
    except RuntimeError as exc:
        raise ConvergenceError(f"spin/velocity quadrature failed: {exc}") from None
    tau_cut = float(sol.t[-1])
    xi_cut = xi_slip + span * (2.0 * tau_cut - tau_cut**2) if singular else xi_slip + span * tau_cut
    return SpinQuadrature(
        sol, xi_slip, xi_cut, float(sol.y[-1, 0]), float(sol.y[-1, 1]), sol.nfev, span, singular
    )


def wall_constants_from_conditions(
    *,
    h_slip: Any,
    kappa_slip: Any,
    P_fixed: Any,
    h_fixed: Any,
    u_fixed: Any,
    u_wall_slip: Any,
    slip_sign: Any,
    eps_K: Any,
) -> tuple[Any, Any]:
    """(u_s, w_s) at the slipping wall from the two velocity conditions (floats or arrays).

    With ``h u = (h u)_s - w_s P``: no slip at the fixed wall, ``h_f u_f = h_s u_s - w_s P_f``;
    slip ``u_s = u_wall + s eps K omega_s`` with ``omega_s = w_s - kappa_s u_s``. Cramer's rule
    on the 2x2 system.
    """
    a11, a12 = h_slip, -P_fixed
    a21, a22 = 1.0 + slip_sign * eps_K * kappa_slip, -slip_sign * eps_K
    b1, b2 = h_fixed * u_fixed, u_wall_slip
    det = _checked_det(a11 * a22 - a12 * a21)
    return (b1 * a22 - a12 * b2) / det, (a11 * b2 - a21 * b1) / det


def symmetric_wall_constants(
    P_centre: Any, eps: Any, K_upper: Any, K_lower: Any
) -> tuple[Any, Any, Any]:
    """(u_s, w_s, u_c) between identical walls that both slip (floats or arrays).

    Upper half: ``u = u_s - w_s P``; u - u_c is odd and omega even about xi = 1/2, so with
    ``u_c = u_s - w_s P_c``: ``u_s = 1 + eps K_u w_s`` (``eqn-nd_bc3u``) and
    ``u(0) = 2 u_c - u_s = -eps K_l w_s`` (``eqn-nd_bc3l``).
    """
    det = _checked_det(eps * (K_upper + K_lower) - 2.0 * P_centre)
    u_s = (eps * K_lower - 2.0 * P_centre) / det
    w_s = -1.0 / det
    return u_s, w_s, u_s - w_s * P_centre


def _checked_det(det: Any) -> Any:
    """A singular velocity system is reported, not propagated as inf/NaN."""
    bad = ~np.isfinite(det) | (np.abs(det) < 1e-300)
    if np.any(bad) and np.ndim(det) == 0:
        raise ConvergenceError("the velocity boundary conditions are singular")
    return np.where(bad, np.nan, det) if np.ndim(det) else det
