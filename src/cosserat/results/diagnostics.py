"""Residuals of the governing ODEs, recomputed on a returned profile.

The check is independent of the route that made the profile: it takes only the profile's dense
evaluator and the equations of :class:`~cosserat.problems.base.Formulation`, and measures, over
each interval [a, b] of a layer-resolving grid, the defect of the integral form of each ODE
(8-point Gauss-Legendre quadrature):

* couple stress: the angular-momentum balance averaged over the interval,
  ``[int (syx - sxy)/(2(A+1)) - eps alpha (m(b) - m(a) + int kappa m)] / (b - a)``, over the
  stress scale max(sigma_c sin phi): the unbalanced torque relative to the yield stress. (The
  defect of ``m' = F(m)/eps`` itself would amplify an O(rtol) error in m by the stiffness
  k/eps.)
* spin: ``w(b) - w(a) exp(int dln w/dxi)``, w = omega + kappa u, over the largest |w| (the wall
  spin): deep in the plug, where w is exp(-100s) smaller, its relative error is irrelevant.
* velocity: ``(h u)(b) - (h u)(a) + int w G``, over h and the wall speed (1).

A profile that solves its equations to tolerance ``rtol`` has residuals of order ``rtol``;
the asymptotic route has residuals of the order of its neglected terms.
"""

from __future__ import annotations

import numpy as np

from ..model.constitutive import FloatArray, asymmetry_source
from ..model.formulation import Formulation
from .profile import Evaluator

_GL_NODES, _GL_WEIGHTS = np.polynomial.legendre.leggauss(8)
# Spins below this fraction of the largest are underflow territory: not checked.
_SPIN_FLOOR = 1e-250


def residuals(form: Formulation, evaluate: Evaluator, grid: FloatArray) -> dict[str, float]:
    """Largest scaled defect of each ODE over the intervals of ``grid`` (module docstring)."""
    a, b = grid[:-1], grid[1:]
    half = 0.5 * (b - a)
    nodes = (0.5 * (a + b))[:, None] + half[:, None] * _GL_NODES[None, :]
    weights = half[:, None] * _GL_WEIGHTS[None, :]

    ends_a, ends_b = evaluate(a), evaluate(b)
    inner = evaluate(nodes.ravel())
    shape = nodes.shape

    def quad(values: FloatArray) -> FloatArray:
        return np.sum(weights * values.reshape(shape), axis=1)

    m_in = inner.m
    st = form.stresses(nodes.ravel(), m_in)
    torque = asymmetry_source(st.sigma_xy, st.sigma_yx, form.material)
    curv = form.curvature(nodes.ravel()) * m_in
    # the size of the yield-condition terms (sigma_c sin phi): max|sigma_yx| vanishes on a
    # frictionless wall and would turn round-off into a large "residual"
    stress_scale = float(np.max(np.abs(st.sigma_c * form.material.sin_phi)))
    imbalance = quad(torque) - form.eps_alpha * (ends_b.m - ends_a.m + quad(curv))
    r_couple = np.abs(imbalance) / (b - a) / stress_scale

    w_a = ends_a.omega + ends_a.kappa * ends_a.u
    w_b = ends_b.omega + ends_b.kappa * ends_b.u
    w_in = inner.omega + inner.kappa * inner.u
    log_gain = quad(form.log_spin_rate(nodes.ravel(), m_in))
    w_max = float(np.max(np.maximum(np.abs(w_a), np.abs(w_b))))
    ok = np.minimum(np.abs(w_a), np.abs(w_b)) > _SPIN_FLOOR * w_max
    with np.errstate(over="ignore", under="ignore"):
        predicted = np.sign(w_a[ok]) * np.exp(np.log(np.abs(w_a[ok])) + log_gain[ok])
    r_spin = np.abs(w_b[ok] - predicted) / w_max

    h_a, h_b = form.velocity_weight(a), form.velocity_weight(b)
    source = w_in * form.velocity_source(nodes.ravel(), m_in)
    r_vel = np.abs(h_b * ends_b.u - h_a * ends_a.u + quad(source)) / np.maximum(h_b, h_a)

    return {
        "couple_stress": float(np.max(r_couple)),
        "spin": float(np.max(r_spin)) if r_spin.size else 0.0,
        "velocity": float(np.max(r_vel)),
    }
