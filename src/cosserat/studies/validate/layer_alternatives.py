"""The alternatives that matter for the layer claim (issue 18; referee 5, request 3).

Plane shear without gravity (B = 0) between a smoother and a rougher wall: the momentum
balance makes ``sigma_yy = N`` and ``sigma_yx`` uniform, so the stress ratio ``mu`` is the
same in every bin (the layer run measures 0.208-0.217). Where the band sits does not tell the
models apart (a local rheology with a Coulomb wall also puts it at the smoother wall); how the
shear rate varies across the gap under that uniform stress does. Each alternative below is
written in ``y``, the distance from the smoother wall [d], and ``v``, the velocity relative to
the smoother wall over the walls' velocity difference (0 at the smoother wall's surface, 1 at
the rougher wall's), with a gap ``H`` [d]; ``slip`` is ``v`` of the grains at the smoother
wall's surface (the velocity jump there, over the walls' difference).

**(a) Local mu(I) with a Coulomb wall** (Jop, Forterre & Pouliquen 2006, Nature 441, 727: the
friction ``mu(I) = mu_s + (mu_2 - mu_s) / (I_0 / I + 1)``, rising from ``mu_s``; at the
smoother wall a Coulomb condition, sliding when ``|sigma_yx| = tan(delta) N``). Uniform
``mu`` means uniform ``I``, hence a **uniform shear rate**: ``v = slip + (1 - slip) y / H``
(:func:`local_coulomb_velocity`). Which ``slip``: with ``r`` the stress ratio the smoother
wall can carry (``tan delta``, measured 0.212 in the layer run) and ``I_H`` the inertial number
of uniform shear at the wall speed (2.5e-4 there),

* ``r < mu_s``: the material cannot yield; the block slides on the smoother wall, ``slip = 1``
  (``a = 1``), and the stress ratio is ``r`` (the rigid block);
* ``r > mu(I_H)``: the wall holds, no slip, uniform shear at ``mu(I_H)``, ``slip = 0``;
* in between: the wall slides at ``r`` and the bulk shears uniformly at ``mu(I) = r``,
  ``0 < slip < 1``, with ``1 - slip = I H sqrt(N / rho_s) / (V d)``.

As ``mu(I_H) - mu_s`` is a few thousandths at these rates, the third case needs ``r`` within
that of ``mu_s``. mu_s of these disks has not been measured independently, so the fit leaves
``slip`` free in [0, 1] (one parameter): whatever mu_s is, a local rheology gives a linear
profile. The rigid block (``slip = 1``, nothing fitted) is reported beside it.

**(b) NGF with a wall-fluidity condition** (Kamrin & Koval 2012, PRL 108, 178301; Henann &
Kamrin 2013, PNAS 110, 6730): the fluidity ``g = gamma_dot / mu`` obeys
``xi^2 g'' = g - g_loc(mu)``, with ``g_loc = 0`` below yield and the cooperativity length
``xi = A d / sqrt(|mu - mu_s|)``. Under a uniform sub-yield stress ``g'' = g / xi^2``; with
``g(0) = g_w`` at the smoother wall (a wall fluidity, the boundary condition the package's
Neumann one replaces) and ``g'(H) = 0`` at the rougher one,
``g = g_w cosh((H - y)/xi) / cosh(H/xi)``: a shear rate ``mu g`` **decaying exponentially
from the smoother wall** over ``xi``. Integrated, with ``v(H) = 1``,

    v = slip + (1 - slip) [sinh(H/xi) - sinh((H - y)/xi)] / sinh(H/xi),
    g_w = (1 - slip) / (mu xi tanh(H/xi))   [V/d]

(:func:`ngf_wall_velocity`, :func:`ngf_wall_fluidity`); ``xi -> inf`` gives the linear
profile of (a), ``xi -> 0`` the rigid block. Fitted: ``xi`` and ``slip`` (equivalently
``g_w`` and ``xi``; two parameters), and ``xi`` alone with no slip. ``A`` follows only with
a mu_s: ``A = xi sqrt(|mu - mu_s|) / d``.

**(c) The Cosserat model's layer profile** (the paper's ``eqn-soln_aw_vels``): ``phi`` =
:data:`COSSERAT_PHI`, the smoother wall's ``delta`` = its measured friction angle
``atan(r)``, the rougher wall fully rough, ``A`` and ``K`` at their defaults, at ``L`` = 4 and
5 d (nothing fitted) and at the ``L`` that fits best (one parameter).

**chi^2**: over all the run's bins, with the bins' errors an AR(1) sequence of lag-1
correlation ``rho`` (the sidecar's ``bin_correlation.u``; the covariance and whitening of
:mod:`cosserat.calibration.noise`); dof = bins - fitted parameters.

**Robustness to the covariance model** (referee 6, point 2): rho is one lag-1 coefficient from
ten blocks, and the sidecar stores no lag-2 or lag-3 correlation, so ``rho^|i - j|`` is not
checked beyond lag 1. Every alternative is therefore refitted and its chi^2 given under
:data:`COVARIANCES`: ``ar1`` (the above), ``diagonal`` (independent bins, rho = 0) and
``common-mode`` (independent bins plus one offset shared by all bins, the bulk-speed wander:
``C = diag(se^2 - s_cm^2) + s_cm^2``, with ``s_cm^2 = rho min(se^2)``, the largest shared
variance that keeps every bin's variance ``se^2`` and gives the quietest bins the measured
lag-1 correlation ``rho``). With each fit a Wald-Wolfowitz runs test of the residuals' signs
(:func:`cosserat.calibration.diagnostics.runs_test`): a fit whose curve lies on one side of
every bin has one run.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from functools import cached_property, partial
from typing import Any

import numpy as np
from scipy.optimize import least_squares, minimize_scalar
from scipy.stats import chi2 as chi2_dist

from ...calibration.diagnostics import runs_test
from ...calibration.noise import covariance as ar1_covariance
from ...calibration.noise import whiten
from ...errors import CosseratError, ParameterError

COSSERAT_PHI = 19.0
"""The Cosserat model's friction angle for the layer profile [deg] (the design's, docs/dem.md;
at B = 0 the layer's stress ratio is the wall's tan(delta) whatever phi is)."""
COSSERAT_L = (4.0, 5.0)
"""The material lengths at which the Cosserat layer profile is evaluated unfitted [d]."""
L_RANGE = (0.5, 40.0)
"""The range searched for the best-fitting L [d]."""
XI_RANGE = (0.05, 1e3)
"""The range searched for NGF's cooperativity length [d]."""
COVARIANCES = ("ar1", "diagonal", "common-mode")
"""The bins' error models each alternative is fitted under (module docstring)."""
DERIVED = ("g_w",)
"""Parameters that follow from the fitted ones (NGF's wall fluidity from xi and the slip)."""
REFERENCES = {
    "mui": "Jop, Forterre & Pouliquen 2006, Nature 441, 727",
    "ngf": "Kamrin & Koval 2012, PRL 108, 178301; Henann & Kamrin 2013, PNAS 110, 6730",
    "cosserat": "the paper's eqn-soln_aw_vels",
}
"""Where each alternative's law comes from."""


def _check(y_d: np.ndarray, gap_d: float, slip: float) -> np.ndarray:
    y = np.asarray(y_d, dtype=float)
    if not (math.isfinite(gap_d) and gap_d > 0.0):
        raise ParameterError(f"gap_d must be finite and > 0 [d]; got {gap_d}")
    if not (math.isfinite(slip) and 0.0 <= slip <= 1.0):
        raise ParameterError(f"slip must be in [0, 1] (a fraction of the walls' jump); got {slip}")
    if not np.all(np.isfinite(y)):
        raise ParameterError("y_d must be finite [d]")
    return y


def local_coulomb_velocity(y_d: np.ndarray, gap_d: float, slip: float) -> np.ndarray:
    """(a) A local rheology under uniform stress with a Coulomb smoother wall:
    ``v = slip + (1 - slip) y / H`` [-] (module docstring).

    Parameters
    ----------
    y_d : array
        Distances from the smoother wall [d].
    gap_d : float
        The gap H [d].
    slip : float
        The velocity jump at the smoother wall over the walls' difference, in [0, 1] [-].
    """
    y = _check(y_d, gap_d, slip)
    return slip + (1.0 - slip) * y / gap_d


def _decay(y: np.ndarray, gap_d: float, xi_d: float) -> np.ndarray:
    """``sinh((H - y)/xi) / sinh(H/xi)`` without overflow."""
    e = np.exp(-y / xi_d)
    return e * -np.expm1(-2.0 * (gap_d - y) / xi_d) / -math.expm1(-2.0 * gap_d / xi_d)


def ngf_wall_velocity(y_d: np.ndarray, gap_d: float, xi_d: float, slip: float = 0.0) -> np.ndarray:
    """(b) NGF under uniform sub-yield stress with ``g(0) = g_w`` at the smoother wall and
    ``g'(H) = 0`` at the rougher one:
    ``v = slip + (1 - slip) [1 - sinh((H - y)/xi) / sinh(H/xi)]`` [-].

    Parameters
    ----------
    y_d : array
        Distances from the smoother wall [d].
    gap_d : float
        The gap H [d].
    xi_d : float
        The cooperativity length xi = A d / sqrt(|mu - mu_s|), > 0 [d].
    slip : float
        The velocity jump at the smoother wall, in [0, 1] [-].
    """
    y = _check(y_d, gap_d, slip)
    if not (math.isfinite(xi_d) and xi_d > 0.0):
        raise ParameterError(f"xi_d must be finite and > 0 [d]; got {xi_d}")
    return slip + (1.0 - slip) * (1.0 - _decay(y, gap_d, xi_d))


def ngf_wall_fluidity(gap_d: float, xi_d: float, slip: float, mu: float) -> float:
    """The wall fluidity ``g_w = (1 - slip) / (mu xi tanh(H/xi))`` that makes the rougher wall's
    velocity 1 [V/d]: the shear rate at the smoother wall is ``mu g_w``.

    Raises
    ------
    ParameterError
        ``mu`` not > 0, or as :func:`ngf_wall_velocity`.
    """
    _check(np.zeros(1), gap_d, slip)
    if not (math.isfinite(xi_d) and xi_d > 0.0 and math.isfinite(mu) and mu > 0.0):
        raise ParameterError(f"xi_d and mu must be finite and > 0; got {xi_d}, {mu}")
    return (1.0 - slip) / (mu * xi_d * math.tanh(gap_d / xi_d))


def cooperativity_amplitude(xi_d: float, mu: float, mu_s: float) -> float:
    """NGF's ``A = xi sqrt(|mu - mu_s|) / d`` from a fitted ``xi`` [d] at stress ratio ``mu``
    and a static friction ``mu_s`` [-]."""
    return xi_d * math.sqrt(abs(mu - mu_s))


def profile_chi2(residual: np.ndarray, se: np.ndarray, rho: float) -> float:
    """chi^2 of residuals (bin order) under the AR(1) covariance ``se_i se_j rho^|i-j|`` [-]."""
    w = whiten(np.asarray(residual, dtype=float), np.asarray(se, dtype=float), rho)
    return float(np.sum(w * w))


def error_covariance(se: np.ndarray, rho: float, kind: str = "ar1") -> np.ndarray:
    """The bins' error covariance under one of :data:`COVARIANCES` [-]: ``ar1``
    ``se_i se_j rho^|i-j|``; ``diagonal`` ``diag(se^2)``; ``common-mode``
    ``diag(se^2 - s_cm^2) + s_cm^2`` with ``s_cm^2 = rho min(se^2)`` (module docstring).

    Raises
    ------
    ParameterError
        An unknown ``kind``, ``rho`` not in [0, 1) or ``se`` not finite and > 0.
    """
    s = np.asarray(se, dtype=float)
    if kind not in COVARIANCES:
        raise ParameterError(f"kind must be one of {', '.join(COVARIANCES)}; got {kind!r}")
    if not (math.isfinite(rho) and 0.0 <= rho < 1.0):
        raise ParameterError(f"rho must be in [0, 1) (a bin correlation); got {rho}")
    if not (s.ndim == 1 and s.size >= 1 and np.all(np.isfinite(s)) and np.all(s > 0.0)):
        raise ParameterError("se must be a 1-D array of finite values > 0")
    if kind == "ar1":
        return ar1_covariance(s, rho)
    if kind == "diagonal":
        return np.diag(s * s)
    cm = rho * float(np.min(s * s))
    return np.diag(s * s - cm) + cm


@dataclass(frozen=True)
class CovarianceFit:
    """One alternative refitted under one error model of :data:`COVARIANCES`.

    Parameters
    ----------
    kind : str
        The error model.
    chi2 : float
        chi^2 of the refit [-].
    dof : int
        Bins minus fitted parameters.
    p : float
        P(chi^2 >= this) [-].
    parameters : mapping
        The refitted parameters.
    """

    kind: str
    chi2: float
    dof: int
    p: float
    parameters: Mapping[str, float]

    def to_dict(self) -> dict[str, Any]:
        return {
            "kind": self.kind,
            "chi2": self.chi2,
            "dof": self.dof,
            "p": self.p,
            "parameters": dict(self.parameters),
        }


@dataclass(frozen=True)
class LayerAlternative:
    """One alternative's profile against a run's velocities (module docstring).

    Parameters
    ----------
    key : str
        ``mui-coulomb`` (slip fitted), ``mui-rigid``, ``ngf-wall`` (xi and slip fitted),
        ``ngf-wall-noslip`` (xi fitted), ``cosserat-L4``, ``cosserat-L5``, ``cosserat-Lfit``.
    label : str
        What it is, in words.
    parameters : mapping
        Its parameters (fitted or fixed), in the units their names say.
    fitted : tuple of str
        The names of the fitted ones.
    chi2 : float
        chi^2 over the bins with the AR(1) covariance [-].
    dof : int
        Bins minus fitted parameters.
    u : tuple of float
        Its velocity at the run's bins (u over V, the fixed wall 0, the moving wall 1) [-].
    shape : str
        The profile shape it predicts.
    decays : bool
        Whether its shear rate decays away from the smoother wall under uniform stress.
    asymmetry : float
        Its ``a = f_smoother - f_rougher`` from its velocity at the bins (as the data's) [-].
    curve : (distance_d, u)
        Its profile on a fine grid, distances from the moving wall [d] and u over V [-] (for
        the figure).
    sign_runs : (runs, expected, p)
        The runs test of the residuals' signs in bin order: the number of runs, the number
        expected for independent signs and P(this few or fewer) (None with fewer than two of
        either sign) (:func:`~cosserat.calibration.diagnostics.runs_test`).
    by_covariance : tuple of CovarianceFit
        The same alternative refitted under each error model of :data:`COVARIANCES`.
    """

    key: str
    label: str
    parameters: Mapping[str, float]
    fitted: tuple[str, ...]
    chi2: float
    dof: int
    u: tuple[float, ...]
    shape: str
    decays: bool
    asymmetry: float = math.nan
    curve: tuple[tuple[float, ...], tuple[float, ...]] = ((), ())
    sign_runs: tuple[int, float, float | None] = (0, math.nan, None)
    by_covariance: tuple[CovarianceFit, ...] = ()

    @property
    def text(self) -> str:
        pars = ", ".join(
            f"{k} = {v:.3g}"
            + ("" if k in self.fitted else " (derived)" if k in DERIVED else " (fixed)")
            for k, v in self.parameters.items()
        )
        return (
            f"{self.label} [{pars}]: chi^2 = {self.chi2:.1f} for {self.dof} dof, "
            f"a = {self.asymmetry:+.3f}; {self.shape}"
        )

    def to_dict(self) -> dict[str, Any]:
        return {
            "key": self.key,
            "label": self.label,
            "parameters": dict(self.parameters),
            "fitted": list(self.fitted),
            "chi2": self.chi2,
            "dof": self.dof,
            "asymmetry": self.asymmetry,
            "u": list(self.u),
            "shape": self.shape,
            "decays": self.decays,
            "curve": {"distance_d": list(self.curve[0]), "u": list(self.curve[1])},
            "sign_runs": {
                "runs": self.sign_runs[0],
                "expected": self.sign_runs[1],
                "p": self.sign_runs[2],
            },
            "by_covariance": [c.to_dict() for c in self.by_covariance],
        }


@dataclass(frozen=True)
class LayerData:
    """A run's velocities in the smoother wall's frame (module docstring): ``y`` from the
    smoother wall [d], ``v`` [-] and its errors [-] in bin order from that wall, the gap [d],
    the bins' lag-1 correlation, the stress ratio, which wall is smoother, and ``distance_d``
    from the moving wall [d] of each bin (for ``u``)."""

    y: np.ndarray
    v: np.ndarray
    se: np.ndarray
    gap_d: float
    rho: float
    ratio: float
    smoother: str
    extra: Mapping[str, Any] = field(default_factory=dict)
    covariance: str = "ar1"

    @cached_property
    def _cholesky(self) -> np.ndarray:
        return np.linalg.cholesky(error_covariance(self.se, self.rho, self.covariance))

    def white(self, residual: np.ndarray) -> np.ndarray:
        """Residuals (bin order) whitened under this data's error model [-] (the AR(1) one by
        :func:`~cosserat.calibration.noise.whiten`; the others by their Cholesky factor)."""
        r = np.asarray(residual, dtype=float)
        if self.covariance == "ar1":
            return whiten(r, self.se, self.rho)
        return np.linalg.solve(self._cholesky, r)

    def under(self, kind: str) -> LayerData:
        """The same data with the error model ``kind`` (:data:`COVARIANCES`)."""
        error_covariance(self.se, self.rho, kind)  # checks kind
        return replace(self, covariance=kind)

    @classmethod
    def from_run(
        cls,
        distance_d: np.ndarray,
        u: np.ndarray,
        u_se: np.ndarray,
        gap_d: float,
        smoother: str,
        rho: float,
        ratio: float,
    ) -> LayerData:
        """From a run's bins (distances from the moving wall [d], u over V and its errors)."""
        if smoother not in ("fixed", "moving"):
            raise ParameterError(f"smoother must be 'fixed' or 'moving'; got {smoother!r}")
        if not (math.isfinite(ratio) and ratio > 0.0):
            raise ParameterError(f"the stress ratio must be finite and > 0; got {ratio}")
        if not (math.isfinite(rho) and 0.0 <= rho < 1.0):
            raise ParameterError(f"rho must be in [0, 1) (a bin correlation); got {rho}")
        s, uu, se = (np.asarray(x, dtype=float) for x in (distance_d, u, u_se))
        y = gap_d - s if smoother == "fixed" else s
        v = uu if smoother == "fixed" else 1.0 - uu
        order = np.argsort(y)
        return cls(y[order], v[order], se[order], float(gap_d), float(rho), float(ratio), smoother)

    def to_u(self, v: np.ndarray) -> np.ndarray:
        """A model's ``v`` at these bins as u over V (the fixed wall 0, the moving wall 1)."""
        return np.asarray(v, dtype=float) if self.smoother == "fixed" else 1.0 - np.asarray(v)

    def chi2(self, v_model: np.ndarray) -> float:
        w = self.white(self.v - np.asarray(v_model, dtype=float))
        return float(np.sum(w * w))

    def asymmetry(self, v_model: np.ndarray, within_d: float = 3.0) -> float:
        """``a = v(within_d) - (1 - v(H - within_d))`` of a model's ``v`` at these bins."""
        f_s = float(np.interp(within_d, self.y, v_model))
        f_r = 1.0 - float(np.interp(self.gap_d - within_d, self.y, v_model))
        return f_s - f_r


CURVE_POINTS = 201
"""Points of each alternative's curve for the figure."""


def _alternative(
    data: LayerData, key: str, label: str, model: Callable[[np.ndarray], np.ndarray],
    pars: dict[str, float], fitted: tuple[str, ...], shape: str, decays: bool,
) -> LayerAlternative:  # fmt: skip
    """``model`` maps distances from the smoother wall [d] to ``v`` [-]."""
    v = model(data.y)
    y = np.linspace(0.0, data.gap_d, CURVE_POINTS)
    s = data.gap_d - y if data.smoother == "fixed" else y
    curve = (tuple(float(x) for x in s), tuple(float(x) for x in data.to_u(model(y))))
    rt = runs_test(data.v - v)
    return LayerAlternative(
        key, label, pars, fitted, data.chi2(v), data.v.size - len(fitted),
        tuple(float(x) for x in data.to_u(v)), shape, decays, data.asymmetry(v), curve,
        (rt.runs, rt.expected, rt.p_value),
    )  # fmt: skip


def fit_local(data: LayerData) -> list[LayerAlternative]:
    """(a): the linear profile with its slip fitted (generalised least squares, the slip
    clipped to [0, 1]) and the rigid block (``slip = 1``)."""
    x = 1.0 - data.y / data.gap_d  # v = y/H + slip (1 - y/H)
    wx = data.white(x)
    wr = data.white(data.v - data.y / data.gap_d)
    slip = float(np.clip(np.dot(wx, wr) / np.dot(wx, wx), 0.0, 1.0))
    linear = "a linear profile: a uniform shear rate (1 - slip)/H"
    return [
        _alternative(
            data, "mui-coulomb", "(a) local mu(I), Coulomb smoother wall, slip fitted",
            lambda y: local_coulomb_velocity(y, data.gap_d, slip), {"slip": slip}, ("slip",),
            linear + f" = {(1.0 - slip) / data.gap_d:.3g} V/d", False,
        ),
        _alternative(
            data, "mui-rigid", "(a) local mu(I), rigid block (tan delta < mu_s)",
            lambda y: local_coulomb_velocity(y, data.gap_d, 1.0), {"slip": 1.0}, (),
            "a rigid block sliding on the smoother wall: no shear in the gap", False,
        ),
    ]  # fmt: skip


def fit_ngf(data: LayerData) -> list[LayerAlternative]:
    """(b): xi and the slip fitted, and xi alone without slip (least squares on the whitened
    residuals, log xi searched over :data:`XI_RANGE` from several starts)."""
    out = []
    lo, hi = math.log(XI_RANGE[0]), math.log(XI_RANGE[1])
    for with_slip in (True, False):

        def residual(p: np.ndarray, with_slip: bool = with_slip) -> np.ndarray:
            s = float(p[1]) if with_slip else 0.0
            v = ngf_wall_velocity(data.y, data.gap_d, math.exp(float(p[0])), s)
            return data.white(data.v - v)

        best = None
        for start in np.log([0.3, 1.0, 3.0, 10.0, 100.0]):
            x0 = np.array([start, 0.3]) if with_slip else np.array([start])
            bounds = ([lo, 0.0], [hi, 1.0]) if with_slip else ([lo], [hi])
            r = least_squares(residual, x0, bounds=bounds)
            if best is None or r.cost < best.cost:
                best = r
        assert best is not None
        xi = math.exp(float(best.x[0]))
        slip = float(best.x[1]) if with_slip else 0.0
        g_w = ngf_wall_fluidity(data.gap_d, xi, slip, data.ratio)
        pars = {"xi_d": xi, "slip": slip, "g_w": g_w}
        fitted = ("xi_d", "slip") if with_slip else ("xi_d",)
        out.append(
            _alternative(
                data, "ngf-wall" if with_slip else "ngf-wall-noslip",
                "(b) NGF, wall fluidity at the smoother wall, "
                + ("xi and slip fitted" if with_slip else "no slip, xi fitted"),
                partial(ngf_wall_velocity, gap_d=data.gap_d, xi_d=xi, slip=slip), pars,
                fitted,
                f"shear rate mu g_w exp(-y/xi) from the smoother wall (mu g_w = "
                f"{data.ratio * g_w:.3g} V/d, xi = {xi:.3g} d)",
                xi < data.gap_d,
            )
        )  # fmt: skip
    return out


def cosserat_profile(data: LayerData, L_d: float, phi: float = COSSERAT_PHI) -> Any:
    """(c): the Cosserat model's solution (a :class:`~cosserat.results.profile.Profile`, the
    moving wall at xi = 1) with the smoother wall at ``delta = atan(ratio)`` and the rougher
    fully rough, friction angle ``phi`` [deg] (default :data:`COSSERAT_PHI`), material length
    ``L_d`` [d]."""
    from ...model import make_problem
    from ...routes import solve

    return solve(make_problem("cosserat", "plane", _cosserat_input(data, L_d, phi)))


def cosserat_values(data: LayerData, L_d: float, phi: float = COSSERAT_PHI) -> dict[str, Any]:
    """The parameters (c) is solved with (:func:`cosserat_profile`), defaults resolved: phi
    [deg], delta [deg] at the smoother wall ("fully-rough" at the rougher), K and A [-], L [d]
    (referee 13, point 4: the text states them)."""
    from ...model import make_problem

    return dict(make_problem("cosserat", "plane", _cosserat_input(data, L_d, phi)).values())


def _cosserat_input(data: LayerData, L_d: float, phi: float = COSSERAT_PHI) -> dict[str, Any]:
    """(c)'s given parameters (the rest at their declared defaults)."""
    delta = math.degrees(math.atan(data.ratio))
    walls = (
        {"delta_lower": delta, "delta": "fully-rough"}
        if data.smoother == "fixed"
        else {"delta": delta, "delta_lower": "fully-rough"}
    )
    return {"phi": phi, "B": 0.0, "L": L_d, "eps": 1.0 / data.gap_d, **walls}


def cosserat_velocity(
    data: LayerData, L_d: float, y_d: np.ndarray | None = None, phi: float = COSSERAT_PHI
) -> np.ndarray:
    """(c): the Cosserat model's ``v`` at ``y_d`` (distances from the smoother wall [d]; the
    bins when None), the smoother wall at ``delta = atan(ratio)`` and the rougher fully rough,
    friction angle ``phi`` [deg] (default :data:`COSSERAT_PHI`), material length ``L_d`` [d]
    (:func:`cosserat_profile`)."""
    return profile_velocity(data, cosserat_profile(data, L_d, phi), y_d)


def profile_velocity(data: LayerData, sol: Any, y_d: np.ndarray | None = None) -> np.ndarray:
    """(c)'s ``v`` at ``y_d`` (distances from the smoother wall [d]; the bins when None) from
    its solution ``sol`` (:func:`cosserat_profile`), so that one solve gives the bins and the
    figure's curve."""
    xi, u = np.asarray(sol.xi, dtype=float), np.asarray(sol.u, dtype=float)
    y = data.y if y_d is None else np.asarray(y_d, dtype=float)
    y_fixed = y if data.smoother == "fixed" else data.gap_d - y
    u_bins = np.interp(y_fixed / data.gap_d, xi, u)
    return u_bins if data.smoother == "fixed" else 1.0 - u_bins


def best_length(
    data: LayerData, phi: float = COSSERAT_PHI, near: float | None = None
) -> tuple[float, float]:
    """(c)'s best-fitting ``L`` [d] at friction angle ``phi`` [deg] and its chi^2 under
    ``data``'s error model: a bounded search of ln L, over the neighbours of the best of 13
    points of :data:`L_RANGE`, or over ``near`` / 2 to ``near`` x 2 where ``near`` [d] (a fit
    at another phi) is given (about 10 solves; the full search where the best lies at that
    range's edge)."""
    if near is None:
        grid = np.geomspace(L_RANGE[0], L_RANGE[1], 13)
        chis = [data.chi2(cosserat_velocity(data, L, phi=phi)) for L in grid]
        k = int(np.argmin(chis))
        lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)]
    else:
        lo, hi = max(near / 2.0, L_RANGE[0]), min(near * 2.0, L_RANGE[1])
    r = minimize_scalar(
        lambda lnL: data.chi2(cosserat_velocity(data, math.exp(lnL), phi=phi)),
        bounds=(math.log(lo), math.log(hi)),
        method="bounded",
        options={"xatol": 1e-3},
    )
    if near is not None and min(r.x - math.log(lo), math.log(hi) - r.x) < 1e-2:
        return best_length(data, phi)
    return math.exp(float(r.x)), float(r.fun)


def fit_cosserat(data: LayerData) -> list[LayerAlternative]:
    """(c) at L = 4 and 5 d and at the best-fitting L in :data:`L_RANGE`."""
    delta = math.degrees(math.atan(data.ratio))
    shape = "the shear rate decaying from the smoother wall over about L, slip set by K"
    out = []
    for L in COSSERAT_L:
        out.append(
            _alternative(
                data, f"cosserat-L{L:g}", f"(c) Cosserat, delta = {delta:.1f} deg, L = {L:g} d",
                partial(cosserat_velocity, data, L), {"L_d": L, "delta_deg": delta}, (),
                shape, True,
            )
        )  # fmt: skip
    L = best_length(data)[0]
    out.append(
        _alternative(
            data, "cosserat-Lfit", f"(c) Cosserat, delta = {delta:.1f} deg, L fitted",
            lambda y: cosserat_velocity(data, L, y), {"L_d": L, "delta_deg": delta}, ("L_d",),
            shape, True,
        )
    )  # fmt: skip
    return out


def _fit_all(data: LayerData) -> tuple[tuple[LayerAlternative, ...], str]:
    out = (*fit_local(data), *fit_ngf(data))
    try:
        return (*out, *fit_cosserat(data)), ""
    except CosseratError as exc:
        return out, f"the Cosserat layer profile is not computed: {exc}"


def layer_alternatives(
    data: LayerData, covariances: tuple[str, ...] = COVARIANCES
) -> tuple[tuple[LayerAlternative, ...], str]:
    """Every alternative of the module docstring on one run's data (fitted under ``data``'s
    error model), each with its refits under ``covariances`` (:data:`COVARIANCES`;
    ``by_covariance``), and a note naming any left out and why ("" when none is): the
    Cosserat profile needs the smoother wall smoother than the material,
    ``tan(delta) < sin(phi)``, which a stress ratio above ``sin(phi)`` (0.326 at
    :data:`COSSERAT_PHI`) is not."""
    alts, note = _fit_all(data)
    refits: dict[str, dict[str, LayerAlternative]] = {}
    for kind in covariances:
        again = alts if kind == data.covariance else _fit_all(data.under(kind))[0]
        refits[kind] = {x.key: x for x in again}
    out = []
    for x in alts:
        fits = tuple(
            CovarianceFit(
                kind,
                r.chi2,
                r.dof,
                float(chi2_dist.sf(r.chi2, r.dof)),
                {k: float(r.parameters[k]) for k in r.fitted},
            )
            for kind in covariances
            if (r := refits[kind].get(x.key)) is not None
        )
        out.append(replace(x, by_covariance=fits))
    return tuple(out), note


__all__ = [
    "COSSERAT_L",
    "COSSERAT_PHI",
    "COVARIANCES",
    "CURVE_POINTS",
    "DERIVED",
    "L_RANGE",
    "REFERENCES",
    "XI_RANGE",
    "CovarianceFit",
    "LayerAlternative",
    "LayerData",
    "best_length",
    "cooperativity_amplitude",
    "cosserat_profile",
    "cosserat_values",
    "cosserat_velocity",
    "error_covariance",
    "fit_cosserat",
    "fit_local",
    "fit_ngf",
    "layer_alternatives",
    "local_coulomb_velocity",
    "ngf_wall_fluidity",
    "ngf_wall_velocity",
    "profile_chi2",
    "profile_velocity",
]
