"""The nonlocal granular fluidity (NGF) model on three cells (``docs/derivation_ngf.md``).

Kamrin & Koval, Phys. Rev. Lett. 108, 178301 (2012); Henann & Kamrin, Proc. Natl. Acad. Sci.
USA 110, 6730 (2013). The shear rate is the granular fluidity times the stress ratio,
``gamma_dot = g mu``, and g obeys the steady fluidity equation

    nabla^2 g = (g - g_loc(mu, p)) / xi_c(mu)^2,
    g_loc = sqrt(p / (rho_s d^2)) I_loc(mu) / mu   (0 for mu <= mu_s),
    xi_c = A d / sqrt(|mu - mu_s|),

where ``I_loc(mu)`` inverts the local law: Henann & Kamrin's linear one, ``mu = mu_s + b I``
(the default, ``mu_2=None``), or the saturating one of Jop et al. (2006),
``mu = mu_s + (mu_2 - mu_s)/(I_0/I + 1)`` with ``I_0 = (mu_2 - mu_s)/b`` so that both start
from mu_s with the slope b. Where mu <= mu_s the material *creeps*: g_loc = 0, but g > 0
because the fluidity diffuses in from the flowing region, decaying over xi_c.

Scalings as for the Cosserat and mu(I) cells (``docs/derivation_mui.md`` section 2): xi across
the gap, velocities over a reference speed V, stresses over N. The rate scale is the inertial
number of V, ``I_w = V d / (H sqrt(N / rho_s))``; the unknown solved for is
``F = I_w g H / V`` (the fluidity in units of ``sqrt(N/rho_s)/d``), which obeys a linear
equation independent of I_w:

    (1/r) d/dxi (r dF/dxi) = k(xi) (F - F_loc(xi)),   k = |mu - mu_s| / (A eps)^2,
    F_loc = sqrt(p/N) I_loc(mu) / mu,

with r = 1 (plane, channel) or ``Ri + xi`` (Couette). The stress level T (the largest stress
ratio in the cell) is fixed by the reference speed (a scalar root-find) or imposed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numba import njit

from ..errors import NoSolutionError, ParameterError, shown
from .constitutive import FloatArray
from .couette import validate_Ri
from .mui import MuI
from .parameters import require_finite
from .plane import B_MAX, validate_B, validate_eps, validate_nu

# ----------------------------------------------------------------- the source's values
NGF_MU_S = 0.3819
"""Static friction coefficient of glass beads (Henann & Kamrin 2013) [-]."""
NGF_B = 0.9377
"""Slope b of the local law mu = mu_s + b I for glass beads (Henann & Kamrin 2013) [-]."""
NGF_A = 0.48
"""Nonlocal amplitude A of the cooperativity length for glass beads (Henann & Kamrin 2013) [-]."""
NGF_RHO_S = 2450.0
"""Grain density of glass beads [kg/m^3] (dimensional conversions only)."""
NGF_I_W = 0.01
"""Default inertial number of the reference speed, as for mu(I) [-]."""
NGF_I_W_MAX = 1.0
"""Largest admissible I_w [-] (dense flow, the range of the local law)."""
NGF_EXCESS_RTOL = 1e-7
"""Smallest relative excess (T - mu_s)/mu_s of the stress level T over mu_s [-].

The excess drives the flow (g_loc and k are proportional to it), but the stress level is found
to about 1e-15 (Brent's tolerance) and mu, mu_s are rounded to 1e-16 mu_s: an excess of
1e-7 mu_s keeps about 7 significant digits, and the profile about 1e-9 (measured, uniform
shear at the bound). Closer to mu_s the flow cannot be told from rest at double precision.
Through ``T - mu_s >= b I_w`` (every cell, the maximum principle) it bounds the wall speed:
:attr:`NGF.I_w_min`."""
FLUIDITY_BCS = ("neumann", "local")
"""Wall conditions on g: ``n . grad g = 0`` (default) or ``g = g_loc``."""


# ----------------------------------------------------------------- compiled statics and law
PLANE, COUETTE, CHANNEL = 0, 1, 2
"""The cells' codes (``kind``) in the compiled functions below and in the kernel."""


@njit(cache=True, nogil=True)
def statics(kind: int, shape: float, T: float, x: float) -> tuple[float, float, float]:
    """(mu, p/N, r) at xi = x for the stress level T, the one statement of the three cells'
    statics (``shape``: B nu for plane shear, Ri for Couette flow, unused for the channel).

    Plane shear ``mu = T/s``, ``s = 1 + B nu (1 - xi)``, r = 1; Couette flow
    ``mu = T (Ri/(Ri + xi))^2``, p uniform, ``r = Ri + xi``; the channel ``mu = 2 T |xi - 1/2|``,
    p uniform, r = 1 [-].
    """
    if kind == PLANE:
        s = 1.0 + shape * (1.0 - x)
        return T / s, s, 1.0
    if kind == COUETTE:
        q = shape / (shape + x)
        return T * q * q, 1.0, shape + x
    return 2.0 * T * abs(x - 0.5), 1.0, 1.0


@njit(cache=True, nogil=True)
def local_inertial_number(mu: float, mu_s: float, b: float, mu_2: float) -> float:
    """I_loc(mu), 0 for mu <= mu_s: ``(mu - mu_s)/b`` (mu_2 = 0, the linear law) or
    ``I_0 (mu - mu_s)/(mu_2 - mu)``, ``I_0 = (mu_2 - mu_s)/b`` (for mu < mu_2) [-]."""
    excess = mu - mu_s
    if excess <= 0.0:
        return 0.0
    return excess / b if mu_2 == 0.0 else (mu_2 - mu_s) / b * excess / (mu_2 - mu)


@njit(cache=True, nogil=True)
def local_fluidity(mu: float, s: float, mu_s: float, b: float, mu_2: float) -> float:
    """F_loc = sqrt(p/N) I_loc(mu)/mu, 0 for mu <= mu_s (mu_2 = 0: the linear law) [-]."""
    i = local_inertial_number(mu, mu_s, b, mu_2)
    if i <= 0.0:
        return 0.0
    return math.sqrt(s) * i / mu


@njit(cache=True, nogil=True)
def _statics_on(kind: int, shape: float, T: float, xs: np.ndarray, which: int) -> np.ndarray:
    """Component ``which`` (0 mu, 1 p/N, 2 r) of :func:`statics` on the 1-D array xs."""
    out = np.empty_like(xs)
    for i in range(xs.size):
        out[i] = statics(kind, shape, T, xs[i])[which]
    return out


@njit(cache=True, nogil=True)
def _local_on(
    mu: np.ndarray, s: np.ndarray, mu_s: float, b: float, mu_2: float, fluidity: bool
) -> np.ndarray:
    """:func:`local_fluidity` (or :func:`local_inertial_number`) on 1-D arrays."""
    out = np.empty_like(mu)
    for i in range(mu.size):
        if fluidity:
            out[i] = local_fluidity(mu[i], s[i], mu_s, b, mu_2)
        else:
            out[i] = local_inertial_number(mu[i], mu_s, b, mu_2)
    return out


@dataclass(frozen=True)
class NGF:
    """The constants of the nonlocal granular fluidity model; ``NGF()`` is glass beads.

    Parameters
    ----------
    mu_s : float, default 0.3819
        Static friction coefficient, ``mu_s > 0`` [-] (Henann & Kamrin 2013).
    b : float, default 0.9377
        Slope of the local law at mu_s, ``mu = mu_s + b I`` near I = 0, ``b > 0`` [-]
        (Henann & Kamrin 2013; it equals (mu_2 - mu_s)/I_0 of Jop et al.'s glass beads).
    A : float, default 0.48
        Nonlocal amplitude of the cooperativity length xi_c = A d / sqrt(|mu - mu_s|),
        ``A > 0`` [-] (Henann & Kamrin 2013); the limit A -> 0 is the local law.
    mu_2 : float or None, default None
        None: the linear local law of Henann & Kamrin (2013), ``I_loc = (mu - mu_s)/b``.
        A number ``mu_2 > mu_s``: the saturating law of Jop et al. (2006), as used by Kamrin &
        Koval (2012), ``I_loc = I_0 (mu - mu_s)/(mu_2 - mu)`` with ``I_0 = (mu_2 - mu_s)/b`` [-].
    rho_s : float, default 2450
        Grain density [kg/m^3]; the dimensionless cells do not use it (it is inside I_w),
        only :meth:`wall_inertial_number` does.

    Raises
    ------
    ParameterError
        A value out of its bounds or not a finite number (the message names it).
    """

    mu_s: float = NGF_MU_S
    b: float = NGF_B
    A: float = NGF_A
    mu_2: float | None = None
    rho_s: float = NGF_RHO_S

    def __post_init__(self) -> None:
        mu_s = require_finite("mu_s", self.mu_s)
        b = require_finite("b", self.b)
        A = require_finite("A", self.A)
        rho_s = require_finite("rho_s", self.rho_s)
        if mu_s <= 0.0:
            raise ParameterError(f"mu_s must satisfy mu_s > 0; got {mu_s:g}")
        if b <= 0.0:
            raise ParameterError(f"b must satisfy b > 0; got {b:g}")
        if A <= 0.0:
            raise ParameterError(
                f"A must satisfy A > 0 (A -> 0 is local mu(I): use the 'mui' rheology); got {A:g}"
            )
        if rho_s <= 0.0:
            raise ParameterError(f"rho_s must satisfy rho_s > 0 [kg/m^3]; got {rho_s:g}")
        if self.mu_2 is not None:
            mu_2 = require_finite("mu_2", self.mu_2)
            if mu_2 <= mu_s:
                raise ParameterError(f"mu_2 must satisfy mu_2 > mu_s = {mu_s:g}; got {mu_2:g}")
            object.__setattr__(self, "mu_2", mu_2)
        for name, value in (("mu_s", mu_s), ("b", b), ("A", A), ("rho_s", rho_s)):
            object.__setattr__(self, name, value)

    @property
    def saturating(self) -> bool:
        """True for the Jop et al. local law (mu_2 given), False for the linear one."""
        return self.mu_2 is not None

    @property
    def I_w_min(self) -> float:
        """Smallest admissible I_w, ``NGF_EXCESS_RTOL mu_s / b`` (4.07e-8 for glass beads) [-].

        Since g <= max g_loc (the maximum principle of the fluidity equation), the wall speed
        satisfies ``b I_w <= T - mu_s`` in every cell (equality in uniform shear, to first
        order in the excess with the saturating law): a slower wall would put the stress level
        within :data:`NGF_EXCESS_RTOL` of mu_s.
        """
        return NGF_EXCESS_RTOL * self.mu_s / self.b

    @property
    def I_0(self) -> float | None:
        """I_0 = (mu_2 - mu_s)/b of the saturating local law, None for the linear one [-]."""
        return None if self.mu_2 is None else (self.mu_2 - self.mu_s) / self.b

    def _local(self, mu: FloatArray, pressure: FloatArray, fluidity: bool) -> FloatArray:
        m, p = np.broadcast_arrays(np.asarray(mu, dtype=float), np.asarray(pressure, dtype=float))
        if self.mu_2 is not None and np.any(m >= self.mu_2):
            raise NoSolutionError(
                f"stress ratio {float(np.max(m)):.6g} >= mu_2 = {self.mu_2:.6g}: the local law "
                "of Jop et al. has no steady rate there, so g_loc is undefined"
            )
        mu_2 = 0.0 if self.mu_2 is None else self.mu_2
        shape = m.shape
        m, p = np.array(m, dtype=float).ravel(), np.array(p, dtype=float).ravel()
        flat = _local_on(m, p, self.mu_s, self.b, mu_2, fluidity)
        return flat.reshape(shape)

    def local_inertial_number(self, mu: FloatArray) -> FloatArray:
        """I_loc(mu): the local law inverted, 0 where mu <= mu_s [-]
        (:func:`local_inertial_number`).

        Raises
        ------
        NoSolutionError
            The saturating law and some mu >= mu_2 (no local steady rate carries it).
        """
        return self._local(mu, 1.0, False)

    def local_fluidity(self, mu: FloatArray, pressure: FloatArray = 1.0) -> FloatArray:
        """F_loc = sqrt(p/N) I_loc(mu)/mu: g_loc in units of sqrt(N/rho_s)/d [-]
        (:func:`local_fluidity`)."""
        return self._local(mu, pressure, True)

    def cooperativity_length(self, mu: FloatArray, eps: float) -> FloatArray:
        """xi_c / H = A eps / sqrt(|mu - mu_s|) (inf at mu = mu_s) [-]."""
        gap = np.abs(np.asarray(mu, dtype=float) - self.mu_s)
        with np.errstate(divide="ignore"):
            return np.where(gap > 0.0, self.A * eps / np.sqrt(gap), np.inf)

    def matching_mui(self) -> MuI:
        """The local mu(I) law NGF reduces to as A -> 0 (saturating form only).

        Raises
        ------
        ParameterError
            The linear local law (mu_2 is None): :class:`MuI` has the saturating form only.
        """
        if self.mu_2 is None or self.I_0 is None:
            raise ParameterError(
                "matching_mui: the linear local law (mu_2=None) is not of MuI's form; give mu_2"
            )
        return MuI(mu_s=self.mu_s, mu_2=self.mu_2, I_0=self.I_0)

    def wall_inertial_number(self, V: float, H: float, d: float, N: float) -> float:
        """I_w = V d / (H sqrt(N / rho_s)) from a speed V [m/s], a gap H [m], a grain diameter
        d [m] and a normal stress N [Pa] [-]."""
        values = {k: require_finite(k, v) for k, v in {"V": V, "H": H, "d": d, "N": N}.items()}
        for k in ("H", "d", "N"):
            if values[k] <= 0.0:
                raise ParameterError(f"{k} must be > 0; got {values[k]:g}")
        return values["V"] * values["d"] / (values["H"] * math.sqrt(values["N"] / self.rho_s))

    def describe(self) -> str:
        law = "linear local law" if self.mu_2 is None else f"mu_2 = {self.mu_2:.6g}"
        return f"mu_s = {self.mu_s:.6g}, b = {self.b:.6g}, A = {self.A:g}, {law}"

    def parameters(self) -> dict[str, Any]:
        return {"mu_s": self.mu_s, "b": self.b, "A": self.A, "mu_2": self.mu_2}


def _validate_driving(
    I_w: float | None, level: float | None, level_name: str, law: NGF
) -> tuple[float | None, float | None]:
    """Exactly one of the reference speed (I_w) and the stress level drives the cell."""
    if I_w is not None and level is not None:
        raise ParameterError(
            f"give either I_w (imposed speed) or {level_name} (imposed stress), not both"
        )
    if level is not None:
        x = require_finite(level_name, level)
        if x <= 0.0:
            raise ParameterError(f"{level_name} must be > 0; got {x:g}")
        return None, x
    x = require_finite("I_w", NGF_I_W if I_w is None else I_w)
    if not 0.0 < x <= NGF_I_W_MAX:
        raise ParameterError(
            f"I_w = V d / (H sqrt(N/rho_s)) must satisfy 0 < I_w <= {NGF_I_W_MAX:g} "
            f"(dense flow, the range of the local law); got {x:g}"
        )
    if x < law.I_w_min:
        raise ParameterError(
            f"I_w must satisfy I_w >= {NGF_EXCESS_RTOL:g} mu_s/b = {law.I_w_min:.3g}; got "
            f"{x:g}: a slower wall puts the stress level within {NGF_EXCESS_RTOL:g} mu_s of "
            "mu_s (T - mu_s >= b I_w), where the excess that drives the flow has too few "
            "significant digits in double precision and the flow cannot be told from rest"
        )
    return x, None


def _validate_bc(bc: str) -> str:
    if bc not in FLUIDITY_BCS:
        raise ParameterError(
            f"fluidity_bc must be one of {', '.join(repr(b) for b in FLUIDITY_BCS)} "
            f"('neumann': n . grad g = 0; 'local': g = g_loc); got {bc!r}"
        )
    return bc


class _NGFCell:
    """What the three NGF cells share: the law, eps, the driving and the wall condition.

    ``kind`` is the kernel's cell code (0 plane, 1 Couette, 2 channel) and ``shape`` the one
    number the statics need besides the stress level T (B nu, Ri, or 0).
    """

    rheology: NGF
    eps: float
    I_w: float | None
    fluidity_bc: str
    kind: int
    moving_wall: float
    wall_name: str
    reference_velocity: float

    @property
    def shape(self) -> float:  # pragma: no cover - overridden
        raise NotImplementedError

    @property
    def imposed_level(self) -> float | None:  # pragma: no cover - overridden
        raise NotImplementedError

    @property
    def slip_wall(self) -> float:
        """xi of the wall the shear layer is measured from (NGF has no wall slip) [-]."""
        return self.moving_wall

    def _statics(self, xi: FloatArray, T: float, which: int) -> FloatArray:
        x = np.array(xi, dtype=float)  # a writeable copy (numba types read-only arrays apart)
        return _statics_on(self.kind, float(self.shape), float(T), x.ravel(), which).reshape(
            x.shape
        )

    def friction_ratio(self, xi: FloatArray, T: float) -> FloatArray:
        """mu = |tau|/p for the stress level T, from :func:`statics` [-]: ``T/(1 + B nu
        (1 - xi))`` (plane), ``T (Ri/(Ri + xi))^2`` (Couette), ``2 T |xi - 1/2|`` (channel)."""
        return self._statics(xi, T, 0)

    def pressure(self, xi: FloatArray) -> FloatArray:
        """p/N from :func:`statics`: ``1 + B nu (1 - xi)`` (plane), 1 otherwise [-]."""
        return self._statics(xi, 1.0, 1)

    def radius(self, xi: FloatArray) -> FloatArray:
        """r/H of the Laplacian (1/r) d/dxi (r d/dxi), from :func:`statics`: ``Ri + xi`` in
        Couette flow, 1 otherwise [-]."""
        return self._statics(xi, 1.0, 2)

    def sigma_c(self, xi: FloatArray) -> FloatArray:
        """Normal stress over its scale (the Cell protocol's name for :meth:`pressure`)."""
        return self.pressure(xi)

    def curvature(self, xi: FloatArray) -> FloatArray:
        return np.zeros_like(np.asarray(xi, dtype=float))

    def k(self, xi: FloatArray, T: float) -> FloatArray:
        """1/(xi_c/H)^2 = |mu - mu_s|/(A eps)^2 [-]."""
        law = self.rheology
        return np.abs(self.friction_ratio(xi, T) - law.mu_s) / (law.A * self.eps) ** 2

    def local_fluidity(self, xi: FloatArray, T: float) -> FloatArray:
        """F_loc(xi) for the stress level T [-]."""
        return self.rheology.local_fluidity(self.friction_ratio(xi, T), self.pressure(xi))

    def creep(self, xi: FloatArray, T: float) -> FloatArray:
        """True where mu <= mu_s: g_loc = 0 there, and the material only creeps."""
        return self.friction_ratio(xi, T) <= self.rheology.mu_s

    def level_bounds(self) -> tuple[float, float]:
        """The open interval of stress levels T with a flowing, steady solution [-].

        T <= mu_s: g_loc = 0 everywhere, so g = 0 and nothing moves; with the saturating law
        T < mu_2 (no local rate beyond).
        """
        law = self.rheology
        return law.mu_s, (math.inf if law.mu_2 is None else law.mu_2)

    def check_imposed_level(self) -> float:
        """The imposed stress level T, or NoSolutionError saying why it has none."""
        T = self.imposed_level
        assert T is not None
        lo, hi = self.level_bounds()
        where = f"at the {self.wall_name}, where it is largest"
        if T <= lo:
            raise NoSolutionError(
                f"stress ratio {T:.6g} <= mu_s = {lo:.6g} {where}: g_loc = 0 everywhere, the "
                "only solution of the fluidity equation is g = 0, nothing flows, and u = v/V "
                "is undefined"
            )
        if T >= hi:
            raise NoSolutionError(
                f"stress ratio {T:.6g} >= mu_2 = {hi:.6g} {where}: the local law has no steady "
                "rate there (the material accelerates)"
            )
        return T

    def _check_level_excess(self, name: str, bound: float) -> None:
        """ParameterError if the imposed stress level exceeds mu_s by less than
        :data:`NGF_EXCESS_RTOL` mu_s (``name`` >= ``bound`` is the same condition on the
        parameter given). A level <= mu_s passes: it is NoSolutionError at solve time."""
        T = self.imposed_level
        mu_s = self.rheology.mu_s
        if T is not None and mu_s < T < mu_s * (1.0 + NGF_EXCESS_RTOL):
            raise ParameterError(
                f"{name} must satisfy {name} >= {shown(bound)} (a stress ratio at the "
                f"{self.wall_name} of at least mu_s (1 + {NGF_EXCESS_RTOL:g})) or make the "
                f"stress ratio <= mu_s; got {name} = {shown(getattr(self, name))}, a stress "
                f"ratio {shown(T)} within {NGF_EXCESS_RTOL:g} mu_s of mu_s = {shown(mu_s)}: the "
                "excess that drives the flow has too few significant digits in double "
                "precision and the flow cannot be told from rest"
            )

    def _driving(self) -> str:
        if self.I_w is None:
            return f"stress ratio {self.imposed_level:g} at the {self.wall_name}"
        return f"I_w = {self.I_w:g}"

    def _common(self) -> dict[str, Any]:
        out: dict[str, Any] = {"rheology": "ngf"}
        out.update(self.rheology.parameters())
        out.update({"eps": self.eps, "I_w": self.I_w, "fluidity_bc": self.fluidity_bc})
        return out

    def _validate_common(self) -> None:
        if not isinstance(self.rheology, NGF):
            raise ParameterError(f"rheology must be an NGF; got {type(self.rheology).__name__}")
        object.__setattr__(self, "eps", validate_eps(self.eps))
        object.__setattr__(self, "fluidity_bc", _validate_bc(self.fluidity_bc))


@dataclass(frozen=True, kw_only=True)
class NGFPlaneShear(_NGFCell):
    """Plane shear of an NGF material between walls; the upper wall (xi = 1) moves.

    Statics of :class:`~cosserat.model.mui.MuIPlaneShear`: ``tau/N = T`` uniform,
    ``p/N = 1 + B nu (1 - xi)``, ``mu = T/(1 + B nu (1 - xi))``; no slip at either wall.
    With gravity the region below the yield depth (mu <= mu_s) creeps.

    Parameters
    ----------
    rheology : NGF
    eps : float
        Grain diameter over gap d/H, ``0 < eps <= 0.5`` [-] (sets the cooperativity length).
    B : float
        Gravity parameter rho_p g H / N, ``0 <= B <= 1e6`` [-].
    nu : float
        Solids fraction, ``0 < nu <= 1`` [-]; only B nu enters.
    I_w : float, default 0.01
        Inertial number of the wall speed, V d / (H sqrt(N / rho_s)),
        ``rheology.I_w_min <= I_w <= 1`` [-].
    stress_ratio : float, optional
        Instead of I_w: the imposed tau/N [-]; the wall speed is then an output. Either
        ``<= mu_s`` (NoSolutionError at solve time) or ``>= mu_s (1 + NGF_EXCESS_RTOL)``.
    fluidity_bc : {"neumann", "local"}
        Wall condition on g: ``n . grad g = 0`` (default) or ``g = g_loc``.
    """

    rheology: NGF = NGF()
    eps: float
    B: float = 0.0
    nu: float = 1.0
    I_w: float | None = None
    stress_ratio: float | None = None
    fluidity_bc: str = "neumann"

    kind = PLANE
    moving_wall = 1.0
    fixed_wall = 0.0
    wall_name = "moving upper wall"
    reference_velocity = 0.0

    def __post_init__(self) -> None:
        self._validate_common()
        object.__setattr__(self, "B", validate_B(self.B))
        nu = validate_nu(self.nu)
        object.__setattr__(self, "nu", nu)
        I_w, T = _validate_driving(self.I_w, self.stress_ratio, "stress_ratio", self.rheology)
        object.__setattr__(self, "I_w", I_w)
        object.__setattr__(self, "stress_ratio", T)
        self._check_level_excess("stress_ratio", self.rheology.mu_s * (1.0 + NGF_EXCESS_RTOL))

    @property
    def shape(self) -> float:
        return self.B * self.nu

    @property
    def imposed_level(self) -> float | None:
        return self.stress_ratio

    @staticmethod
    def wall_velocity(xi_wall: float) -> float:
        """u of the wall: 1 at the moving upper wall, 0 at the fixed lower one [-]."""
        return 1.0 if xi_wall == 1.0 else 0.0

    def creep_extent(self, T: float) -> tuple[float, float] | None:
        """[0, xi_p] where mu <= mu_s (the creeping region at the fixed wall), or None [-]."""
        bn, mu_s = self.B * self.nu, self.rheology.mu_s
        if bn == 0.0 or T / mu_s - 1.0 >= bn:
            return None if T > mu_s else (0.0, 1.0)
        return (0.0, 1.0 - (T / mu_s - 1.0) / bn)

    def describe(self) -> str:
        return (
            f"plane shear, NGF: {self.rheology.describe()}, eps = {self.eps:g}, B = {self.B:g}, "
            f"nu = {self.nu:g}; no slip, wall fluidity {self.fluidity_bc}; {self._driving()}"
        )

    def parameters(self) -> dict[str, Any]:
        out: dict[str, Any] = {"geometry": "plane"}
        out.update(self._common())
        out.update({"B": self.B, "nu": self.nu, "stress_ratio": self.stress_ratio})
        return out


@dataclass(frozen=True, kw_only=True)
class NGFCouetteFlow(_NGFCell):
    """Cylindrical Couette flow of an NGF material; the inner cylinder (xi = 0) turns.

    Variables and signs of :class:`~cosserat.model.mui.MuICouetteFlow`: ``xi = (r - R_i)/H``,
    ``u = -v_theta/V_i``, p uniform across the gap, ``mu = T (Ri/(Ri + xi))^2``; the fluidity
    equation carries the cylindrical Laplacian ``(1/r) d/dr (r dg/dr)``. Beyond
    ``xi_c = Ri (sqrt(T/mu_s) - 1)`` the material creeps.

    Parameters
    ----------
    rheology : NGF
    eps : float
        Grain diameter over gap d/H, ``0 < eps <= 0.5`` [-].
    Ri : float
        Inner radius over gap R_i/H, ``1e-3 <= Ri <= 1e6`` [-].
    I_w : float, default 0.01
        Inertial number of the inner wall's speed, V_i d / (H sqrt(p / rho_s)),
        ``rheology.I_w_min <= I_w <= 1`` [-].
    stress_ratio : float, optional
        Instead of I_w: the imposed tau_i/p at the inner cylinder (the torque) [-]; either
        ``<= mu_s`` (NoSolutionError at solve time) or ``>= mu_s (1 + NGF_EXCESS_RTOL)``.
    fluidity_bc : {"neumann", "local"}
        Wall condition on g (default ``n . grad g = 0``).
    """

    rheology: NGF = NGF()
    eps: float
    Ri: float
    I_w: float | None = None
    stress_ratio: float | None = None
    fluidity_bc: str = "neumann"

    kind = COUETTE
    moving_wall = 0.0
    fixed_wall = 1.0
    wall_name = "turning inner cylinder"
    reference_velocity = 0.0

    def __post_init__(self) -> None:
        self._validate_common()
        object.__setattr__(self, "Ri", validate_Ri(self.Ri))
        I_w, T = _validate_driving(self.I_w, self.stress_ratio, "stress_ratio", self.rheology)
        object.__setattr__(self, "I_w", I_w)
        object.__setattr__(self, "stress_ratio", T)
        self._check_level_excess("stress_ratio", self.rheology.mu_s * (1.0 + NGF_EXCESS_RTOL))

    @property
    def shape(self) -> float:
        return self.Ri

    @property
    def imposed_level(self) -> float | None:
        return self.stress_ratio

    @staticmethod
    def wall_velocity(xi_wall: float) -> float:
        """u of the wall: -1 at the turning inner cylinder, 0 at the outer one [-]."""
        return -1.0 if xi_wall == 0.0 else 0.0

    def curvature(self, xi: FloatArray) -> FloatArray:
        return 1.0 / (self.Ri + np.asarray(xi, dtype=float))

    def creep_extent(self, T: float) -> tuple[float, float] | None:
        """[xi_c, 1] where mu <= mu_s (creeping, at the outer cylinder), or None [-]."""
        xi_c = self.Ri * (math.sqrt(T / self.rheology.mu_s) - 1.0)
        return (max(xi_c, 0.0), 1.0) if xi_c < 1.0 else None

    def describe(self) -> str:
        return (
            f"Couette flow, NGF: {self.rheology.describe()}, eps = {self.eps:g}, "
            f"Ri = {self.Ri:g}; no slip, wall fluidity {self.fluidity_bc}; {self._driving()}"
        )

    def parameters(self) -> dict[str, Any]:
        out: dict[str, Any] = {"geometry": "couette"}
        out.update(self._common())
        out.update({"Ri": self.Ri, "stress_ratio": self.stress_ratio})
        return out


@dataclass(frozen=True, kw_only=True)
class NGFChannel(_NGFCell):
    """Fully developed gravity flow of an NGF material down a vertical channel.

    The conventions of :class:`~cosserat.model.channel.Channel` and
    :class:`~cosserat.model.mui.MuIChannel`: ``xi = y/H`` across, walls at rest at 0 and 1 (no
    slip), x downward along gravity, ``u >= 0`` downward, scaled by the centre-line speed V_c
    (``u(1/2) = 1``); ``p = N`` uniform; ``|tau|/N = B nu |xi - 1/2|`` with
    ``B = rho_p g H / N``, so ``mu = B nu |xi - 1/2|``, largest (B nu/2) at the walls; the core
    where mu <= mu_s creeps. Symmetric about the centre line.

    Parameters
    ----------
    rheology : NGF
    eps : float
        Grain diameter over channel width d/H, ``0 < eps <= 0.5`` [-].
    B : float, optional
        rho_p g H / N with N the wall normal stress, ``0 < B <= 1e6`` [-]: the wall stress
        ratio is B nu/2 (either <= mu_s, NoSolutionError at solve time, or
        >= mu_s (1 + NGF_EXCESS_RTOL)); the centre-line speed (its I_w) is then an output.
    nu : float
        Solids fraction, ``0 < nu <= 1`` [-]; only B nu enters.
    I_w : float, default 0.01 when B is not given
        Instead of B: the inertial number of the centre-line speed, V_c d/(H sqrt(N/rho_s))
        [-], ``rheology.I_w_min <= I_w <= 1``; B nu is then an output.
    fluidity_bc : {"neumann", "local"}
        Wall condition on g (default ``n . grad g = 0``).
    """

    rheology: NGF = NGF()
    eps: float
    B: float | None = None
    nu: float = 1.0
    I_w: float | None = None
    fluidity_bc: str = "neumann"

    kind = CHANNEL
    moving_wall = 1.0  # the layer is measured from the wall at xi = 1 (as for Channel)
    fixed_wall = 0.0
    wall_name = "walls"
    reference_velocity = 1.0  # the centre-line speed: Delta is where u = 1 - f

    def __post_init__(self) -> None:
        self._validate_common()
        nu = validate_nu(self.nu)
        object.__setattr__(self, "nu", nu)
        I_w, B = _validate_driving(self.I_w, self.B, "B", self.rheology)
        if B is not None and B > B_MAX:
            raise ParameterError(f"B = rho_p g H / N must satisfy 0 < B <= {B_MAX:g}; got {B:g}")
        object.__setattr__(self, "I_w", I_w)
        object.__setattr__(self, "B", B)
        self._check_level_excess("B", 2.0 * self.rheology.mu_s * (1.0 + NGF_EXCESS_RTOL) / nu)

    @property
    def shape(self) -> float:
        return 0.0

    @property
    def imposed_level(self) -> float | None:
        """The wall stress ratio B nu/2 when B is imposed [-]."""
        return None if self.B is None else 0.5 * self.B * self.nu

    @staticmethod
    def wall_velocity(xi_wall: float) -> float:
        """u of either wall: 0 (no slip) [-]."""
        return 0.0

    def creep_extent(self, T: float) -> tuple[float, float] | None:
        """The core [1/2 - w, 1/2 + w], w = mu_s/(2T) = mu_s/(B nu), where mu <= mu_s [-]."""
        w = min(self.rheology.mu_s / (2.0 * T), 0.5)
        return (0.5 - w, 0.5 + w)

    def describe(self) -> str:
        drive = f"B = {self.B:g}, nu = {self.nu:g}" if self.B is not None else f"I_w = {self.I_w:g}"
        return (
            f"vertical channel, NGF: {self.rheology.describe()}, eps = {self.eps:g}; {drive}; "
            f"no slip, wall fluidity {self.fluidity_bc}; velocity scaled by the centre line"
        )

    def parameters(self) -> dict[str, Any]:
        out: dict[str, Any] = {"geometry": "channel"}
        out.update(self._common())
        out.update({"B": self.B, "nu": self.nu})
        out["velocity_scale"] = "centre-line velocity, u(1/2) = 1"
        return out


NGFProblem = NGFPlaneShear | NGFCouetteFlow | NGFChannel

__all__ = [
    "CHANNEL",
    "COUETTE",
    "FLUIDITY_BCS",
    "NGF",
    "NGF_A",
    "NGF_B",
    "NGF_EXCESS_RTOL",
    "NGF_MU_S",
    "NGF_RHO_S",
    "PLANE",
    "NGFChannel",
    "NGFCouetteFlow",
    "NGFPlaneShear",
    "NGFProblem",
    "local_fluidity",
    "local_inertial_number",
    "statics",
]
