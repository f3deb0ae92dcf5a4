"""The constitutive law, written once and used by every geometry.

Notation (dimensionless, ``docs/model.md``): ``sigma_yx`` is the shear stress on the plane
parallel to the walls (``sigma_r_theta`` in Couette flow), ``sigma_xy`` the other one
(``sigma_theta_r``), ``sigma_c`` the mean (= normal) stress, and ``m`` the scaled couple stress of
``dimlessvar``. All stresses are compressive-positive and scaled as in the paper.

* Yield condition ``eqn-nd_yc``::

      sxy^2 + syx^2 + 2 A sxy syx + 4 (A+1)^2 m^2 = 2 (A+1) (sigma_c sin phi)^2

* Its solution for ``sigma_xy`` with the paper's root (``eqn-nd_sigxy``, negative sign)::

      sxy = -A syx - sqrt(S),   S = (A^2 - 1) syx^2 + 2 (A+1) sigma_c^2 sin^2 phi - 4 (A+1)^2 m^2

  so that ``sigma_xy + A sigma_yx = -sqrt(S)`` and ``sigma_yx - sigma_xy >= 0`` wherever
  ``sigma_yx <= 0`` (the asymmetry the paper shows in figures 2, 6, 10).

* Flow-rule ratios (``eqn-nd_fr1``, ``eqn-nd_fr2``)::

      du/dxi = -F1 omega,    eps alpha domega/dxi = -F2 omega,
      F1 = (A+1)(sxy + syx)/(sxy + A syx),   F2 = 2 (A+1) m / (sxy + A syx).

Each formula is written once, as a compiled function of plain numbers ``k_*(syx, sigma_c, m, A,
sin_phi)`` that the solver kernels (:mod:`cosserat.numerics`) call inside their step loops. The
NumPy ufuncs ``v_*`` apply them to arrays, and the functions below, which take a
:class:`Material`, call those.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numba import njit, vectorize
from numpy.typing import ArrayLike, NDArray

from ..errors import NoSolutionError
from .parameters import Material

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]

# Relative round-off allowance on the radicand S before "no real solution" is declared.
RADICAND_ROUNDOFF = 1e-12
# Floor on sqrt(S), the denominator of the flow-rule ratios; S = 0 only on the yield bound.
SQRT_S_FLOOR = 1e-150


_KERNEL: dict[str, Any] = {"cache": True, "nogil": True}


@njit(**_KERNEL)
def k_radicand(syx: float, sc: float, m: float, A: float, sin_phi: float) -> float:
    """S of ``eqn-nd_sigxy`` (module docstring) [-]."""
    sc_sin = sc * sin_phi
    return (
        (A * A - 1.0) * syx * syx + 2.0 * (A + 1.0) * sc_sin * sc_sin - 4.0 * (A + 1.0) ** 2 * m * m
    )


@njit(**_KERNEL)
def k_torque(syx: float, sc: float, m: float, A: float, sin_phi: float) -> float:
    """(syx - sxy)/(2(A+1)) on the paper's root, free of cancellation [-].

    The right side of the couple-stress balance (``eqn-nd_zangmom``). On the paper's root
    ``syx - sxy = (1+A) syx + sqrt(S)``, which for tau = -syx > 0 subtracts two nearly equal
    numbers near a fully rough wall (both are (1+A) sin phi there). With the conjugate,
    ``S - (1+A)^2 tau^2 = 2(A+1)[(sc sin phi - tau)(sc sin phi + tau) - 2(A+1) m^2]``
    (``docs/derivation_plane.md`` section 3)::

        (syx - sxy)/(2(A+1)) = [(sc sin phi - tau)(sc sin phi + tau) - 2(A+1) m^2]
                               / (sqrt(S) + (1+A) tau)

    S is clipped at 0 (callers check the real domain).
    """
    S = k_radicand(syx, sc, m, A, sin_phi)
    root = math.sqrt(S) if S > 0.0 else 0.0
    tau = -syx
    if tau > 0.0:
        sc_sin = sc * sin_phi
        return ((sc_sin - tau) * (sc_sin + tau) - 2.0 * (A + 1.0) * m * m) / (
            root + (1.0 + A) * tau
        )
    return (root - (1.0 + A) * tau) / (2.0 * (A + 1.0))


@njit(**_KERNEL)
def k_torque_dm(syx: float, sc: float, m: float, A: float, sin_phi: float, floor: float) -> float:
    """d/dm of :func:`k_torque` at fixed syx: ``-2(A+1) m / sqrt(S)`` [-].

    From ``k_torque = ((1+A) syx + sqrt(S))/(2(A+1))`` and ``dS/dm = -8(A+1)^2 m``. sqrt(S) is
    floored at ``floor`` (S = 0 on the yield bound, where the derivative is infinite).
    """
    S = k_radicand(syx, sc, m, A, sin_phi)
    return -2.0 * (A + 1.0) * m / max(math.sqrt(S) if S > 0.0 else 0.0, floor)


@njit(**_KERNEL)
def k_torque_dsyx(syx: float, sc: float, m: float, A: float, sin_phi: float, floor: float) -> float:
    """d/dsyx of :func:`k_torque` at fixed m: ``1/2 + (A-1) syx / (2 sqrt(S))`` [-].

    From ``dS/dsyx = 2(A^2-1) syx``; used where the shear stress depends on m (Couette flow).
    sqrt(S) floored at ``floor`` as in :func:`k_torque_dm`.
    """
    S = k_radicand(syx, sc, m, A, sin_phi)
    return 0.5 + (A - 1.0) * syx / (2.0 * max(math.sqrt(S) if S > 0.0 else 0.0, floor))


@njit(**_KERNEL)
def k_torque_gradient(
    syx: float, sc: float, m: float, A: float, sin_phi: float, floor: float
) -> tuple[float, float]:
    """(:func:`k_torque_dm`, :func:`k_torque_dsyx`) together, with one square root [-]."""
    S = k_radicand(syx, sc, m, A, sin_phi)
    root = max(math.sqrt(S) if S > 0.0 else 0.0, floor)
    return -2.0 * (A + 1.0) * m / root, 0.5 + (A - 1.0) * syx / (2.0 * root)


@njit(**_KERNEL)
def k_velocity_ratio(syx: float, sc: float, m: float, A: float, sin_phi: float) -> float:
    """F1 = (A+1)(sxy + syx)/(sxy + A syx) of ``eqn-nd_fr1`` on the paper's root [-].

    There ``sxy + A syx = -sqrt(S)``, used as the denominator directly, floored away from 0.
    """
    S = k_radicand(syx, sc, m, A, sin_phi)
    denom = -max(math.sqrt(S) if S > 0.0 else 0.0, SQRT_S_FLOOR)
    sxy = denom - A * syx
    return (A + 1.0) * (sxy + syx) / denom


@njit(**_KERNEL)
def k_spin_ratio(syx: float, sc: float, m: float, A: float, sin_phi: float) -> float:
    """F2 = 2(A+1) m/(sxy + A syx) of ``eqn-nd_fr2`` on the paper's root [-]."""
    S = k_radicand(syx, sc, m, A, sin_phi)
    return -2.0 * (A + 1.0) * m / max(math.sqrt(S) if S > 0.0 else 0.0, SQRT_S_FLOOR)


@vectorize(cache=True)
def v_radicand(syx: float, sc: float, m: float, A: float, sin_phi: float) -> float:
    """:func:`k_radicand` on arrays (a NumPy ufunc)."""
    return k_radicand(syx, sc, m, A, sin_phi)


@vectorize(cache=True)
def v_torque(syx: float, sc: float, m: float, A: float, sin_phi: float) -> float:
    """:func:`k_torque` on arrays (a NumPy ufunc)."""
    return k_torque(syx, sc, m, A, sin_phi)


@vectorize(cache=True)
def v_torque_dm(syx: float, sc: float, m: float, A: float, sin_phi: float, floor: float) -> float:
    """:func:`k_torque_dm` on arrays (a NumPy ufunc)."""
    return k_torque_dm(syx, sc, m, A, sin_phi, floor)


@vectorize(cache=True)
def v_torque_dsyx(syx: float, sc: float, m: float, A: float, sin_phi: float, floor: float) -> float:
    """:func:`k_torque_dsyx` on arrays (a NumPy ufunc)."""
    return k_torque_dsyx(syx, sc, m, A, sin_phi, floor)


@vectorize(cache=True)
def v_velocity_ratio(syx: float, sc: float, m: float, A: float, sin_phi: float) -> float:
    """:func:`k_velocity_ratio` on arrays (a NumPy ufunc)."""
    return k_velocity_ratio(syx, sc, m, A, sin_phi)


@vectorize(cache=True)
def v_spin_ratio(syx: float, sc: float, m: float, A: float, sin_phi: float) -> float:
    """:func:`k_spin_ratio` on arrays (a NumPy ufunc)."""
    return k_spin_ratio(syx, sc, m, A, sin_phi)


def radicand(
    sigma_yx: ArrayLike, sigma_c: ArrayLike, m: ArrayLike, material: Material
) -> FloatArray:
    """S of ``eqn-nd_sigxy``: the yield condition has a real ``sigma_xy`` iff ``S >= 0`` [-]."""
    return v_radicand(sigma_yx, sigma_c, m, material.A, material.sin_phi)


def radicand_scale(sigma_c: ArrayLike, material: Material) -> FloatArray:
    """The size of the terms of S, for round-off comparisons [-]."""
    return 2.0 * (material.A + 1.0) * (np.asarray(sigma_c) * material.sin_phi) ** 2


def check_radicand(
    S: ArrayLike, sigma_c: ArrayLike, m: ArrayLike, material: Material, xi: ArrayLike | None = None
) -> FloatArray:
    """Return ``max(S, 0)``; raise :class:`NoSolutionError` where S is negative beyond round-off."""
    S = np.asarray(S, dtype=float)
    bad = -RADICAND_ROUNDOFF * radicand_scale(sigma_c, material) > S
    if np.any(bad):
        i = int(np.flatnonzero(np.ravel(bad))[0])
        where = "" if xi is None else f" at xi = {np.ravel(np.broadcast_to(xi, S.shape))[i]:.6g}"
        mi = float(np.ravel(np.broadcast_to(m, S.shape))[i])
        raise NoSolutionError(
            f"no real solution{where}: the yield condition (eqn-nd_yc) has no real root for "
            f"sigma_xy because the couple stress |m| = {abs(mi):.6g} exceeds its yield bound "
            f"(the radicand of eqn-nd_sigxy is {np.ravel(S)[i]:.3g} < 0)"
        )
    return np.maximum(S, 0.0)


def torque(sigma_yx: Any, sigma_c: Any, m: Any, material: Material) -> Any:
    """(syx - sxy)/(2(A+1)) on the paper's root, free of cancellation (:func:`k_torque`) [-]."""
    return v_torque(sigma_yx, sigma_c, m, material.A, material.sin_phi)


def flow_ratios(sigma_yx: Any, sigma_c: Any, m: Any, material: Material) -> tuple[Any, Any]:
    """(F1, F2) of ``eqn-nd_fr1``, ``eqn-nd_fr2`` on the paper's root [-]."""
    args = (sigma_yx, sigma_c, m, material.A, material.sin_phi)
    return v_velocity_ratio(*args), v_spin_ratio(*args)


def yield_margin(sigma_yx: Any, sigma_c: Any, m: Any, material: Any) -> Any:
    """S over the size of its terms: >= 0 iff ``eqn-nd_sigxy`` is real (the solvers' event)."""
    return radicand(sigma_yx, sigma_c, m, material) / radicand_scale(sigma_c, material)


def second_shear_stress(
    sigma_yx: ArrayLike,
    sigma_c: ArrayLike,
    m: ArrayLike,
    material: Material,
    xi: ArrayLike | None = None,
) -> FloatArray:
    """sigma_xy from the yield condition with the paper's root, ``eqn-nd_sigxy`` [-].

    Raises :class:`NoSolutionError` (saying where) if the root is complex.
    """
    check_radicand(radicand(sigma_yx, sigma_c, m, material), sigma_c, m, material, xi)
    syx = np.asarray(sigma_yx, dtype=float)
    return syx - 2.0 * (material.A + 1.0) * torque(
        syx, np.asarray(sigma_c, float), np.asarray(m, float), material
    )


def velocity_ratio(
    sigma_xy: ArrayLike, sigma_yx: ArrayLike, material: Material, denom: ArrayLike | None = None
) -> FloatArray:
    """F1 = (A+1)(sxy + syx)/(sxy + A syx) of ``eqn-nd_fr1``: du/dxi = -F1 omega [-].

    ``denom`` may supply sxy + A syx (= -sqrt(S) on the paper's root) where forming the sum
    would lose it to round-off.
    """
    A = material.A
    # ignores: ArrayLike admits str and bytes, which these operators refuse; callers pass floats
    # or float arrays, and a float in gives a float out (np.asarray would make it a 0-d array)
    d = sigma_xy + A * sigma_yx if denom is None else denom  # type: ignore[operator]
    return (A + 1.0) * (sigma_xy + sigma_yx) / d  # type: ignore[operator,return-value]


def spin_ratio(
    sigma_xy: ArrayLike,
    sigma_yx: ArrayLike,
    m: ArrayLike,
    material: Material,
    denom: ArrayLike | None = None,
) -> FloatArray:
    """F2 = 2(A+1) m/(sxy + A syx) of ``eqn-nd_fr2``: eps alpha domega/dxi = -F2 omega [-]."""
    A = material.A
    # ignores as in velocity_ratio: ArrayLike admits str and bytes; a float in gives a float out
    d = sigma_xy + A * sigma_yx if denom is None else denom  # type: ignore[operator]
    return 2.0 * (A + 1.0) * m / d  # type: ignore[operator,return-value]


def asymmetry_source(sigma_xy: ArrayLike, sigma_yx: ArrayLike, material: Material) -> FloatArray:
    """(syx - sxy)/(2(A+1)): the right side of the couple-stress balance ``eqn-nd_zangmom`` [-].

    ``eps alpha (dm/dxi + kappa m) = (syx - sxy)/(2(A+1))`` with curvature kappa = 0 in plane
    shear and 1/(Ri + xi) in Couette flow (``docs/derivation_couette.md``).
    """
    return (np.asarray(sigma_yx, dtype=float) - np.asarray(sigma_xy, dtype=float)) / (
        2.0 * (material.A + 1.0)
    )


def symmetric_couple_stress(sigma_yx: float, sigma_c: float, material: Material) -> float:
    """|m| at which sigma_xy = sigma_yx (``eqn-nd_bc4`` with ``eqn-nd_yc``) [-].

    From ``eqn-nd_yc`` with sxy = syx: ``syx^2 + 2(A+1) m^2 = (sigma_c sin phi)^2``.
    """
    arg = ((sigma_c * material.sin_phi) ** 2 - sigma_yx**2) / (2.0 * (material.A + 1.0))
    if arg < -RADICAND_ROUNDOFF * (sigma_c * material.sin_phi) ** 2:
        raise NoSolutionError(
            f"no real solution: the wall condition sigma_xy = sigma_yx (eqn-nd_bc4) needs "
            f"|sigma_yx| <= sigma_c sin(phi), but |sigma_yx| = {abs(sigma_yx):.6g} > "
            f"{sigma_c * material.sin_phi:.6g}"
        )
    return float(np.sqrt(max(arg, 0.0)))
