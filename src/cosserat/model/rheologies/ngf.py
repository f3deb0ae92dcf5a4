"""The nonlocal granular fluidity (NGF) model on the package's cells (``docs/derivation_ngf.md``).

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

Scalings are the cell's (``docs/derivation_mui.md`` section 2): xi across the gap, velocities
over a reference speed V, stresses over N. The rate scale is the inertial number of V,
``I_w = V d / (H sqrt(N / rho_s))`` (the cell's drive); the unknown solved for is
``F = I_w g H / V`` (the fluidity in units of ``sqrt(N/rho_s)/d``), which obeys a linear
equation independent of I_w:

    (1/r) d/dxi (r dF/dxi) = k(xi) (F - F_loc(xi)),   k = |mu - mu_s| / (A eps)^2,
    F_loc = sqrt(p/N) I_loc(mu) / mu,

with r the cell's radius (1 between plane walls, ``Ri + xi`` in Couette flow). The stress level
T (the largest stress ratio in the cell) is fixed by the reference speed (a scalar root-find)
or imposed. The compiled kernel (:mod:`cosserat.numerics.ngf`) has one branch per cell, which
calls the cell's compiled statics (:func:`statics`): NGF is defined on the cells in
:data:`KINDS`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
from numba import njit

from ... import config
from ...errors import NoSolutionError, ParameterError
from ..cells.channel import shear_stress as channel_shear_stress
from ..cells.couette import torque_decay
from ..cells.plane import mean_stress
from ..constitutive import BoolArray, FloatArray
from ..declare import Constraint, param, validate
from .base import Equations, Rheology
from .mui import MU_MAX, MuI, friction_spread

# ----------------------------------------------------------------- the source's values
NGF_MU_S = 0.3819
"""Static friction coefficient of glass beads (Henann & Kamrin 2013) [-]."""
NGF_B = 0.9377
"""Slope b of the local law mu = mu_s + b I for glass beads (Henann & Kamrin 2013) [-]."""
NGF_A = 0.48
"""Nonlocal amplitude A of the cooperativity length for glass beads (Henann & Kamrin 2013) [-]."""
NGF_RHO_S = 2450.0
"""Grain density of glass beads [kg/m^3] (dimensional conversions only)."""
NGF_I_W = config.MUI_I_W
"""Default inertial number of the reference speed: the cells' one default [-]."""
A_MIN = 1e-4
"""Smallest nonlocal amplitude A [-]: at 1e-4 plane shear solves (boundary error 6e-12, eps =
0.01); at 1e-6 the grid that resolves the cooperativity length needs 2.7e6 points, and near
1e-300 the kernels divided by zero. Smaller A is the local law: the 'mui' rheology."""
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
REFERENCE = (
    "Kamrin & Koval, Nonlocal constitutive relation for steady granular flow, Phys. Rev. Lett. "
    "108 (2012) 178301; Henann & Kamrin, A predictive, size-dependent continuum model for dense "
    "granular flows, Proc. Natl. Acad. Sci. USA 110 (2013) 6730-6735"
)
_HK = "glass beads, Henann & Kamrin, PNAS 110 (2013)"


# ----------------------------------------------------------------- compiled statics and law
PLANE, COUETTE, CHANNEL = 0, 1, 2
"""The cells' codes (``kind``) in the compiled functions below and in the kernel."""
KINDS = {"plane": PLANE, "couette": COUETTE, "channel": CHANNEL}
"""Cell name -> kernel code: the cells NGF's kernel has a branch for."""


@njit(cache=True, nogil=True)
def statics(kind: int, shape: float, T: float, x: float) -> tuple[float, float, float]:
    """(mu, p/N, r) at xi = x for the stress level T, from the cells' compiled statics
    (``shape``: B nu for plane shear, Ri for Couette flow, unused for the channel).

    Plane shear ``mu = T/s``, ``s`` the cell's :func:`~cosserat.model.cells.plane.mean_stress`,
    r = 1; Couette flow ``mu = T`` times :func:`~cosserat.model.cells.couette.torque_decay`, p
    uniform, ``r = Ri + xi``; the channel ``mu = |sigma_yx|`` of
    :func:`~cosserat.model.cells.channel.shear_stress` at B nu = 2T, p uniform, r = 1 [-].
    """
    if kind == PLANE:
        s = mean_stress(x, shape)
        return T / s, s, 1.0
    if kind == COUETTE:
        return T * torque_decay(x, shape), 1.0, shape + x
    return abs(channel_shear_stress(x, 2.0 * T)), 1.0, 1.0


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


class NGFFlow(Equations):
    """NGF on one of the cells of :data:`KINDS`: ``problem.equations`` of
    ``Problem(cell, NGF(...))``. The stress ratio, pressure and radius come from the cell's
    compiled statics (:func:`statics`), the drive from the cell (I_w, or the imposed level).
    """

    def validate(self) -> None:
        law = self.rheology
        I_w = self.I_w
        if I_w is not None and I_w < law.I_w_min:
            raise ParameterError(
                f"I_w must satisfy I_w >= {NGF_EXCESS_RTOL:g} mu_s/b = {law.I_w_min:.3g}; got "
                f"{I_w:g}: a slower wall puts the stress level within {NGF_EXCESS_RTOL:g} mu_s "
                "of mu_s (T - mu_s >= b I_w), where the excess that drives the flow has too few "
                "significant digits in double precision and the flow cannot be told from rest"
            )
        T = self.imposed_level
        mu_s = law.mu_s
        if T is not None and mu_s < T < mu_s * (1.0 + NGF_EXCESS_RTOL):
            name = self.cell.level_name
            value = getattr(self.cell, name)
            bound = mu_s * (1.0 + NGF_EXCESS_RTOL) * (T / float(value))
            raise ParameterError(
                f"{name} must satisfy {name} >= {bound!r} (a stress ratio at the "
                f"{self.wall_name} of at least mu_s (1 + {NGF_EXCESS_RTOL:g})) or make the "
                f"stress ratio <= mu_s; got {name} = {value!r}, a stress ratio {T!r} within "
                f"{NGF_EXCESS_RTOL:g} mu_s of mu_s = {mu_s!r}: the excess that drives the flow "
                "has too few significant digits in double precision and the flow cannot be told "
                "from rest"
            )

    # ----------------------------------------------------------------- the cell
    @property
    def rheology(self) -> NGF:
        return self.law

    @property
    def kind(self) -> int:
        """The cell's code in the compiled kernel."""
        return KINDS[self.cell.name]

    @property
    def shape(self) -> float:
        """The one number the statics need besides T: B nu (plane), Ri (Couette), 0."""
        if self.kind == PLANE:
            return float(self.cell.B_nu)
        if self.kind == COUETTE:
            return float(self.cell.Ri)
        return 0.0

    @property
    def fluidity_bc(self) -> str:
        return str(self.rheology.fluidity_bc)

    @property
    def I_w(self) -> float | None:
        """The reference speed's inertial number that drives the flow; None when the stress
        level is imposed."""
        return self.cell.wall_inertial_number

    @property
    def imposed_level(self) -> float | None:
        """The imposed stress level T (an imposed stress ratio, the channel's B nu/2) [-]."""
        return self.cell.imposed_level()

    @property
    def moving_wall(self) -> float:
        """xi of the wall the shear layer is measured from (the peak wall) [-]."""
        return float(self.cell.peak_wall)

    @property
    def wall_name(self) -> str:
        return str(self.cell.peak_wall_name)

    # ----------------------------------------------------------------- statics
    def _statics(self, xi: FloatArray, T: float, which: int) -> FloatArray:
        x = np.array(xi, dtype=float)  # a writeable copy (numba types read-only arrays apart)
        return _statics_on(self.kind, float(self.shape), float(T), x.ravel(), which).reshape(
            x.shape
        )

    def friction_ratio(self, xi: FloatArray, T: float) -> FloatArray:
        """mu = |tau|/p for the stress level T, from :func:`statics` [-]."""
        return self._statics(xi, T, 0)

    def pressure(self, xi: FloatArray) -> FloatArray:
        """p/N from :func:`statics` [-]."""
        return self._statics(xi, 1.0, 1)

    def radius(self, xi: FloatArray) -> FloatArray:
        """r/H of the Laplacian (1/r) d/dxi (r d/dxi), from :func:`statics` [-]."""
        return self._statics(xi, 1.0, 2)

    def k(self, xi: FloatArray, T: float) -> FloatArray:
        """1/(xi_c/H)^2 = |mu - mu_s|/(A eps)^2 [-]."""
        law = self.rheology
        return np.abs(self.friction_ratio(xi, T) - law.mu_s) / (law.A * self.eps) ** 2

    def local_fluidity(self, xi: FloatArray, T: float) -> FloatArray:
        """F_loc(xi) for the stress level T [-]."""
        return self.rheology.local_fluidity(self.friction_ratio(xi, T), self.pressure(xi))

    def creep(self, xi: FloatArray, T: float) -> BoolArray:
        """True where mu <= mu_s: g_loc = 0 there, and the material only creeps."""
        return self.friction_ratio(xi, T) <= self.rheology.mu_s

    def creep_extent(self, T: float) -> tuple[float, float] | None:
        """The interval of xi where mu <= mu_s (creeping), or None [-]."""
        return self.cell.region_below(T, self.rheology.mu_s)

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

    # ----------------------------------------------------------------- records
    def _driving(self) -> str:
        if self.I_w is None:
            if self.cell.level_name == "B":
                return f"B = {self.cell.B:g}, nu = {self.cell.nu:g}"
            return f"stress ratio {self.imposed_level:g} at the {self.wall_name}"
        return f"I_w = {self.I_w:g}"

    def describe(self) -> str:
        cell = self.cell
        keys = tuple(
            k for k, p in cell.declared().items() if p.role == "cell" and k != cell.level_name
        )
        scale = "; velocity scaled by the centre line" if cell.moving_wall is None else ""
        return (
            f"{cell.title}, NGF: {self.rheology.describe()}, {cell.describe(keys)}; "
            f"{self._driving()}; no slip, wall fluidity {self.fluidity_bc}{scale}"
        )

    def parameters(self) -> dict[str, Any]:
        out: dict[str, Any] = {"geometry": self.cell.name, "rheology": "ngf"}
        out.update(self.rheology.values())
        out.update(self.problem.cell_values())
        if self.cell.moving_wall is None:
            xs, us = self.cell.velocity_scale
            out["velocity_scale"] = f"u({xs:g}) = {us:g}"
        return out


@dataclass(frozen=True)
class NGF(Rheology):
    """The nonlocal granular fluidity model; ``NGF()`` is glass beads.

    Parameters
    ----------
    mu_s : float, default 0.3819
        Static friction coefficient, ``mu_s > 0`` [-] (Henann & Kamrin 2013).
    b : float, default 0.9377
        Slope of the local law at mu_s, ``mu = mu_s + b I`` near I = 0, ``b > 0`` [-]
        (Henann & Kamrin 2013; it equals (mu_2 - mu_s)/I_0 of Jop et al.'s glass beads).
    A : float, default 0.48
        Nonlocal amplitude of the cooperativity length xi_c = A d / sqrt(|mu - mu_s|),
        ``A >= 1e-4`` (:data:`A_MIN`) [-] (Henann & Kamrin 2013); the limit A -> 0 is the local law.
    mu_2 : float or None, default None
        None: the linear local law of Henann & Kamrin (2013), ``I_loc = (mu - mu_s)/b``.
        A number with ``mu_2 - mu_s >= 1e-4``: the saturating law of Jop et al. (2006), as used
        by Kamrin & Koval (2012), ``I_loc = I_0 (mu - mu_s)/(mu_2 - mu)`` with
        ``I_0 = (mu_2 - mu_s)/b`` [-].
    rho_s : float, default 2450
        Grain density [kg/m^3]; the dimensionless cells do not use it (it is inside I_w),
        only :meth:`wall_inertial_number` does.
    fluidity_bc : {"neumann", "local"}
        Wall condition on g: ``n . grad g = 0`` (default) or ``g = g_loc``.

    Raises
    ------
    ParameterError
        A value out of its bounds or not a finite number (the message names it).
    """

    name: ClassVar[str] = "ngf"
    title: ClassVar[str] = "nonlocal granular fluidity"
    reference: ClassVar[str] = REFERENCE
    default_free: ClassVar[tuple[str, ...]] = ("A", "I_w")
    equations: ClassVar[dict[str, type[Equations]]] = {name: NGFFlow for name in KINDS}
    constraints: ClassVar[tuple[Constraint, ...]] = friction_spread()

    mu_s: float = param(
        NGF_MU_S,
        "static friction coefficient",
        bounds=(0.0, MU_MAX),
        reason=f"a friction angle below {math.degrees(math.atan(MU_MAX)):.0f} deg",
        fit_range=(0.05, 1.2),
        role="material",
        source=_HK,
    )
    b: float = param(
        NGF_B,
        "slope of the local law at mu_s, mu = mu_s + b I near I = 0",
        bounds=(0.0, math.inf),
        fit_range=(1e-4, 10.0),  # down to a rate-independent local law (b -> 0)
        scale="log",
        role="material",
        source=_HK,
    )
    A: float = param(
        NGF_A,
        "nonlocal amplitude of the cooperativity length xi_c = A d / sqrt(|mu - mu_s|)",
        bounds=(A_MIN, math.inf),
        closed=(True, False),
        fit_range=(0.03, 5.0),
        scale="log",
        role="material",
        reason=(
            "A -> 0 is local mu(I): use the 'mui' rheology; below, the grid cannot resolve the "
            "cooperativity length"
        ),
        source=_HK,
    )
    mu_2: float | None = param(
        None,
        "limiting friction coefficient of the saturating local law of Jop et al. (2006), above "
        "mu_s; None: the linear local law of Henann & Kamrin (2013)",
        bounds=(0.0, MU_MAX),
        reason=f"a friction angle below {math.degrees(math.atan(MU_MAX)):.0f} deg",
        fit_range=(0.06, 2.0),
        optional=True,
        role="material",
        source="Kamrin & Koval, PRL 108 (2012)",
    )
    rho_s: float = param(
        NGF_RHO_S,
        "grain density (dimensional conversions only)",
        "kg/m^3",
        bounds=(0.0, math.inf),
        role="material",
        source=_HK,
    )
    fluidity_bc: str = param(
        "neumann",
        "wall condition on the fluidity: neumann, n . grad g = 0; local, g = g_loc",
        "",
        choices=FLUIDITY_BCS,
        numeric=False,
        role="option",
        source="Henann & Kamrin (2013) use neumann",
    )

    def __post_init__(self) -> None:
        validate(self)

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

    def _local(self, mu: FloatArray, pressure: FloatArray | float, fluidity: bool) -> FloatArray:
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

    def local_fluidity(self, mu: FloatArray, pressure: FloatArray | float = 1.0) -> FloatArray:
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
        values: dict[str, float] = {}
        for k, v in {"V": V, "H": H, "d": d, "N": N}.items():
            try:
                x = float(v)
            except (TypeError, ValueError):
                raise ParameterError(f"{k} must be a number; got {v!r}") from None
            if not math.isfinite(x):
                raise ParameterError(f"{k} must be finite; got {v!r}")
            values[k] = x
        for k in ("H", "d", "N"):
            if values[k] <= 0.0:
                raise ParameterError(f"{k} must be > 0; got {values[k]:g}")
        return values["V"] * values["d"] / (values["H"] * math.sqrt(values["N"] / self.rho_s))

    def describe(self) -> str:
        law = "linear local law" if self.mu_2 is None else f"mu_2 = {self.mu_2:.6g}"
        return f"mu_s = {self.mu_s:.6g}, b = {self.b:.6g}, A = {self.A:g}, {law}"


__all__ = [
    "A_MIN",
    "CHANNEL",
    "COUETTE",
    "FLUIDITY_BCS",
    "KINDS",
    "NGF",
    "NGF_A",
    "NGF_B",
    "NGF_EXCESS_RTOL",
    "NGF_MU_S",
    "NGF_RHO_S",
    "PLANE",
    "NGFFlow",
    "local_fluidity",
    "local_inertial_number",
    "statics",
]
