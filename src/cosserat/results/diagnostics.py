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

from collections.abc import Callable, Iterator, Mapping
from typing import Any

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
    x_in = nodes.ravel()
    shape = nodes.shape

    # one call of the evaluator for the grid and the quadrature nodes
    f = evaluate(np.concatenate([grid, x_in]))
    n = grid.size
    f_omega, f_m = f.spin()
    u, omega, m, kappa = f.u[:n], f_omega[:n], f_m[:n], f.kappa[:n]
    m_in = f_m[n:]
    w_in = f_omega[n:] + f.kappa[n:] * f.u[n:]

    def quad(values: FloatArray) -> FloatArray:
        return np.sum(weights * values.reshape(shape), axis=1)

    st = form.stresses(x_in, m_in)
    torque = asymmetry_source(st.sigma_xy, st.sigma_yx, form.material)
    curv = form.curvature(x_in) * m_in
    # the size of the yield-condition terms (sigma_c sin phi): max|sigma_yx| vanishes on a
    # frictionless wall and would turn round-off into a large "residual"
    stress_scale = float(np.max(np.abs(st.sigma_c * form.material.sin_phi)))
    imbalance = quad(torque) - form.eps_alpha * (m[1:] - m[:-1] + quad(curv))
    r_couple = np.abs(imbalance) / (b - a) / stress_scale

    w = omega + kappa * u
    w_a, w_b = w[:-1], w[1:]
    log_rate, source = form.spin_rates(x_in, m_in)
    log_gain = quad(log_rate)
    w_max = float(np.max(np.maximum(np.abs(w_a), np.abs(w_b))))
    ok = np.minimum(np.abs(w_a), np.abs(w_b)) > _SPIN_FLOOR * w_max
    with np.errstate(over="ignore", under="ignore"):
        predicted = np.sign(w_a[ok]) * np.exp(np.log(np.abs(w_a[ok])) + log_gain[ok])
    r_spin = np.abs(w_b[ok] - predicted) / w_max

    hu = form.velocity_weight(grid) * u
    h = form.velocity_weight(grid)
    r_vel = np.abs(hu[1:] - hu[:-1] + quad(w_in * source)) / np.maximum(h[1:], h[:-1])

    return {
        "couple_stress": float(np.max(r_couple)),
        "spin": float(np.max(r_spin)) if r_spin.size else 0.0,
        "velocity": float(np.max(r_vel)),
    }


class Deferred(Mapping[str, float]):
    """A dict of diagnostics computed when first read (then kept).

    It behaves as the dict it stands for (reading, iteration, equality, truth), pickles as
    that dict, and calls ``compute`` at most once.

    Parameters
    ----------
    compute : callable () -> dict of str to float
        Makes the values [-].
    """

    __slots__ = ("_compute", "_values")

    def __init__(self, compute: Callable[[], dict[str, float]]) -> None:
        self._compute: Callable[[], dict[str, float]] | None = compute
        self._values: dict[str, float] | None = None

    def _computed(self) -> dict[str, float]:
        if self._values is None:
            assert self._compute is not None
            self._values = self._compute()
            self._compute = None
        return self._values

    def __getitem__(self, key: str) -> float:
        return self._computed()[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self._computed())

    def __len__(self) -> int:
        return len(self._computed())

    def __repr__(self) -> str:
        return repr(self._computed())

    def __reduce__(self) -> tuple[Any, ...]:
        return (dict, (self._computed(),))


class DeferredResiduals(Deferred):
    """:func:`residuals` of a profile, computed when first read (then kept).

    The check is the same independent recomputation, on the same grid; only its moment
    changes: a caller that never reads the residuals (a fit, a sweep, a likelihood) does not
    pay for ~6,400 quadrature nodes, several times the cost of the solve itself
    (``docs/performance.md``). It behaves as the dict it stands for (:class:`Deferred`).

    Parameters
    ----------
    form : Formulation, or callable () -> Formulation
        The problem's equations (not the solver's), or what makes them when the residuals are
        read.
    evaluate : Evaluator
        The profile's dense evaluator.
    grid : callable () -> ndarray
        The check grid, made when the residuals are read.
    """

    __slots__ = ()

    def __init__(
        self,
        form: Formulation | Callable[[], Formulation],
        evaluate: Evaluator,
        grid: Callable[[], FloatArray],
    ) -> None:
        def compute() -> dict[str, float]:
            equations = form if isinstance(form, Formulation) else form()
            return residuals(equations, evaluate, grid())

        super().__init__(compute)
