"""Wall quantities for many problems at once: the two passes of :mod:`.engine`, vectorised.

Sweeps and thickness curves need, per parameter set, only the shear-layer thickness, the wall
slip, spin and stress. Here every problem of a batch advances by one step per iteration of one
Python loop (:mod:`.batch_ode`: Radau IIA for the couple stress, DOP853 for the spin and
velocity quadratures), the equations evaluated on parameter arrays by the same formulas as the
scalar path (``constitutive.radicand``, the cancellation-free torque, the flow ratios); the
velocity constants and Delta (a vectorised bisection on the dense output) follow in closed form.

Couette problems share a lock-step secant on m(0). A problem the batch cannot finish the
standard way (a prescribed m on the yield bound, a secant that does not converge, a trial that
leaves the real domain during shooting) is handed to the scalar solver, so results and error
messages are the same as :func:`cosserat.solve` with ``check=False``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np

from ..config import DEFAULT_F
from ..errors import CosseratError, NoSolutionError
from ..model import CouetteFlow, PlaneShear, PlaneShearCase, Problem
from ..model.constitutive import FloatArray
from ..model.couette import outer_wall_couple_stress
from ..model.couette import shear_stress as couette_shear_stress
from ..model.formulation import Formulation
from ..model.plane import mean_stress
from ..results.wall import shear_layer_thickness, wall_omega, wall_slip
from .batch_ode import FINISHED, STOPPED, dop853_batch, radau_scalar_batch
from .engine import LOG_UNDERFLOW, symmetric_wall_constants, wall_constants_from_conditions


@dataclass(frozen=True)
class WallResult:
    """Wall quantities of one problem (dimensionless; ``None`` where there is no solution)."""

    status: str  # "ok", "no-solution", or "error" (the solver could not finish; see message)
    Delta: float | None
    wall_slip: float | None
    wall_omega: float | None
    wall_stress: float | None  # sigma_yx (sigma_r_theta) at the slipping wall
    message: str = ""


class _Mat(NamedTuple):
    """Array-valued stand-in for Material: what the formulas of Formulation read."""

    A: FloatArray
    sin_phi: FloatArray
    alpha: FloatArray


def _scalar(problem: Problem, rtol: float, f: float) -> WallResult:
    from . import solve

    try:
        prof = solve(problem, check=False, points=3, rtol=rtol)
    except NoSolutionError as exc:
        return WallResult("no-solution", None, None, None, None, str(exc))
    except CosseratError as exc:  # e.g. a stalled integration: recorded with its reason
        return WallResult("error", None, None, None, None, str(exc))
    stress = float(prof.evaluate([prof.slip_wall]).sigma_yx[0])
    return WallResult(
        "ok", shear_layer_thickness(prof, f), wall_slip(prof), wall_omega(prof), stress
    )


def wall_quantities(
    problems: Sequence[Problem], rtol: float = 1e-8, f: float = DEFAULT_F
) -> list[WallResult]:
    """Delta, wall slip, wall spin and wall stress for every problem (batched)."""
    results: list[WallResult | None] = [None] * len(problems)
    plane = [i for i, p in enumerate(problems) if isinstance(p, PlaneShear)]
    couette = [i for i, p in enumerate(problems) if isinstance(p, CouetteFlow)]
    for group, solver in ((plane, _plane_batch), (couette, _couette_batch)):
        if group:
            for i, r in zip(group, solver([problems[i] for i in group], rtol, f), strict=True):
                results[i] = r
    for i, r in enumerate(results):
        if r is None:  # anything the batch left over
            results[i] = _scalar(problems[i], rtol, f)
    return results  # type: ignore[return-value]


# ---------------------------------------------------------------------- shared pieces
def _spin_pass(
    form_of,
    m_of,
    xi_slip: FloatArray,
    span: FloatArray,
    eps: FloatArray,  # type: ignore[no-untyped-def]
    rtol: float,
    h_min: FloatArray | float = 1.0,
):
    """Batched pass 2 in t in [0, 1], xi = xi_slip + span t (as engine.integrate_spin, whose
    comment explains the velocity weight ``h_min`` in the absolute tolerance of P)."""
    n = xi_slip.size

    def fun(t: FloatArray, y: FloatArray, idx: FloatArray) -> FloatArray:
        xi = xi_slip[idx] + span[idx] * t
        rate, source = form_of(idx).spin_rates(xi, m_of(xi, idx))
        ell = y[:, 0]
        gain = np.where(ell > LOG_UNDERFLOW, np.exp(np.minimum(ell, 700.0)), 0.0)
        return np.stack([span[idx] * rate, span[idx] * gain * source], axis=1)

    def stop(t: FloatArray, y: FloatArray, idx: FloatArray) -> FloatArray:
        return y[:, 0] - LOG_UNDERFLOW

    atol = np.stack([np.full(n, rtol), rtol * 1e-2 * eps * h_min], axis=1)
    res = dop853_batch(fun, np.zeros(n), np.ones(n), np.zeros((n, 2)), rtol, atol, stop=stop)
    return res, res.y_final[:, 1], res.t_final


def _bisect_distance(g, upper: FloatArray, iterations: int = 64) -> FloatArray:  # type: ignore[no-untyped-def]
    """Vectorised bisection for g(d) = 0 on [0, upper], g(0) > 0 > g(upper)."""
    lo, hi = np.zeros_like(upper), upper.copy()
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        pos = g(mid) > 0.0
        lo, hi = np.where(pos, mid, lo), np.where(pos, hi, mid)
    return 0.5 * (lo + hi)


def _materials(problems: Sequence[Problem]) -> _Mat:
    return _Mat(
        np.array([p.material.A for p in problems]),
        np.array([p.material.sin_phi for p in problems]),
        np.array([p.material.alpha for p in problems]),
    )


def _sub(mat: _Mat, idx: FloatArray) -> _Mat:
    return _Mat(mat.A[idx], mat.sin_phi[idx], mat.alpha[idx])


# ---------------------------------------------------------------------- plane shear
def _plane_batch(problems: list[PlaneShear], rtol: float, f: float) -> list[WallResult | None]:
    out: list[WallResult | None] = [None] * len(problems)
    # a prescribed m on the yield bound makes pass 2 singular: the scalar path maps it
    ok = [
        i
        for i, p in enumerate(problems)
        if p.m_fixed_wall is None
        or abs(p.m_fixed_wall) < p.couple_stress_bound(p.fixed_wall or 0.0) * (1 - 1e-6)
    ]
    if not ok:
        return out
    ps = [problems[i] for i in ok]
    arr = _plane_arrays(ps)
    mat = _materials(ps)

    def form_of(idx: FloatArray) -> Formulation:
        tau, B_nu = arr["tau"][idx], arr["Bnu"][idx]
        return Formulation(
            material=_sub(mat, idx),
            eps=arr["eps"][idx],
            sigma_yx=lambda xi, m: -tau + 0.0 * m,
            sigma_c=lambda xi: mean_stress(xi, B_nu),
        )

    r1 = radau_scalar_batch(
        lambda t, m, idx: form_of(idx).dm_dxi(t, m),
        None,
        arr["xi0"],
        arr["xi1"],
        arr["m0"],
        rtol,
        rtol * 1e-2,
        stop=lambda t, m, idx: form_of(idx).yield_margin(t, m),
    )
    # pass 2 only for the problems whose couple stress reached the slipping wall; the others
    # (no real solution, or a stalled step) go to the scalar path, which words the reason
    fin = np.flatnonzero(r1.status == FINISHED)
    if fin.size == 0:
        return out
    a2 = {key: value[fin] for key, value in arr.items()}
    span = a2["xi0"] - a2["xi1"]
    r2, P_far, t_far = _spin_pass(
        lambda j: form_of(fin[j]),
        lambda xi, j: r1.evaluate(xi, fin[j]),
        a2["xi1"],
        span,
        a2["eps"],
        rtol,
    )
    sym = a2["sym"]
    us_sym, ws_sym, uc_sym = symmetric_wall_constants(P_far, a2["eps"], a2["K_up"], a2["K_low"])
    us_one, ws_one = wall_constants_from_conditions(
        h_slip=1.0,
        kappa_slip=0.0,
        P_fixed=P_far,
        h_fixed=1.0,
        u_fixed=a2["U_n"],
        u_wall_slip=a2["U_s"],
        slip_sign=a2["s"],
        eps_K=a2["eps"] * a2["K"],
    )
    u_s, w_s = np.where(sym, us_sym, us_one), np.where(sym, ws_sym, ws_one)
    u0 = np.where(sym, uc_sym, a2["U_n"])
    j_all = np.arange(fin.size)

    def g(d: FloatArray) -> FloatArray:
        P = r2.evaluate(np.minimum(d / np.abs(span), t_far), j_all)[:, 1]
        return (u_s - w_s * P - u0) / (u_s - u0) - f  # 1 - f at the wall, -f far away

    d = _bisect_distance(g, np.abs(span))
    for j, k in enumerate(fin):
        if r2.status[j] in (FINISHED, STOPPED) and math.isfinite(d[j]):
            out[ok[k]] = WallResult(
                "ok",
                float(d[j] / a2["eps"][j]),
                float(abs(u_s[j] - a2["U_s"][j])),
                float(w_s[j]),
                float(-a2["tau"][j]),
            )
    return out


def _plane_arrays(ps: list[PlaneShear]) -> dict[str, FloatArray]:
    cols: dict[str, list[Any]] = {
        k: []
        for k in (
            "eps",
            "tau",
            "Bnu",
            "xi0",
            "xi1",
            "m0",
            "sym",
            "K",
            "K_up",
            "K_low",
            "s",
            "U_s",
            "U_n",
        )
    }
    for p in ps:
        sym = p.case is PlaneShearCase.SYMMETRIC
        xs = p.slip_wall
        cols["eps"].append(p.eps)
        cols["tau"].append(-p.sigma_yx)
        cols["Bnu"].append(p.B * p.nu)
        cols["xi0"].append(0.5 if sym else p.fixed_wall)
        cols["xi1"].append(xs)
        cols["m0"].append(0.0 if sym else p.m_at_fixed_wall)
        cols["sym"].append(sym)
        cols["K"].append(p.slipping.K)
        cols["K_up"].append(p.upper.K)
        cols["K_low"].append(p.lower_wall.K)
        cols["s"].append(p.slip_sign(xs))
        cols["U_s"].append(p.wall_velocity(xs))
        cols["U_n"].append(0.0 if sym else p.wall_velocity(p.fixed_wall))  # type: ignore[arg-type]
    return {k: np.asarray(v, dtype=bool if k == "sym" else float) for k, v in cols.items()}


# ---------------------------------------------------------------------- Couette flow
def _couette_batch(problems: list[CouetteFlow], rtol: float, f: float) -> list[WallResult | None]:
    n = len(problems)
    mat = _materials(problems)
    eps = np.array([p.eps for p in problems])
    tan_d = np.array([p.tan_delta for p in problems])
    Ri = np.array([p.Ri for p in problems])
    K = np.array([p.wall.K for p in problems])
    factor = np.array([p.couple_factor for p in problems])

    def form_of(idx: FloatArray, mu: FloatArray) -> Formulation:
        td, ri, cf = tan_d[idx], Ri[idx], factor[idx]
        return Formulation(
            material=_sub(mat, idx),
            eps=eps[idx],
            sigma_yx=lambda xi, m: couette_shear_stress(
                xi, m, mu, tan_delta=td, Ri=ri, couple_factor=cf
            ),
            sigma_c=lambda xi: 1.0 + 0.0 * xi,
            kappa=lambda xi: 1.0 / (ri + xi),
        )

    def pass1(mu: FloatArray, idx: FloatArray):  # type: ignore[no-untyped-def]
        m1, disc = outer_wall_couple_stress(
            mu,
            tan_delta=tan_d[idx],
            Ri=Ri[idx],
            couple_factor=factor[idx],
            A=mat.A[idx],
            sin_phi=mat.sin_phi[idx],
        )
        res = radau_scalar_batch(
            lambda t, m, j: form_of(idx[j], mu[j]).dm_dxi(t, m),
            None,
            np.ones(idx.size),
            np.zeros(idx.size),
            m1,
            rtol * 0.1,
            rtol * 1e-3,
            stop=lambda t, m, j: form_of(idx[j], mu[j]).yield_margin(t, m),
        )
        return res, disc >= 0.0

    # lock-step secant on m(0) (as the scalar _couette_shooting, without its bracketing)
    mu = np.array([float(p.outer_couple_stress(np.array([0.0]))[0]) for p in problems])
    tol = np.maximum(rtol * 1e-2, rtol * np.abs(mu))
    alive = np.ones(n, bool)
    done = np.zeros(n, bool)
    mu_prev = np.full(n, np.nan)
    g_prev = np.full(n, np.nan)
    final: dict[int, tuple[Any, int]] = {}
    for _ in range(12):
        act = np.flatnonzero(alive & ~done)
        if act.size == 0:
            break
        r, real = pass1(mu[act], act)
        ok_run = (r.status == FINISHED) & real
        alive[act[~ok_run]] = False
        g = r.y_final - mu[act]
        for j, k in enumerate(act):
            if not ok_run[j]:
                continue
            if abs(g[j]) <= tol[k]:
                done[k] = True
                final[k] = (r, j)
                continue
            if np.isnan(mu_prev[k]):
                new = mu[k] + g[j]
            else:
                slope = (g[j] - g_prev[k]) / (mu[k] - mu_prev[k]) if mu[k] != mu_prev[k] else -1.0
                new = mu[k] - g[j] / (slope if slope < 0.0 else -1.0)
            mu_prev[k], g_prev[k], mu[k] = mu[k], g[j], new
    c = np.flatnonzero(done)
    out: list[WallResult | None] = [None] * n
    if c.size == 0:
        return out
    # each converged problem keeps the dense couple stress of its last secant iterate
    owners = [final[k] for k in c]
    groups = {id(r): r for r, _ in owners}

    def m_of(xi: FloatArray, j: FloatArray) -> FloatArray:
        m = np.empty_like(xi)
        for res in groups.values():
            sel = np.array([owners[jj][0] is res for jj in j])
            if sel.any():
                m[sel] = res.evaluate(xi[sel], np.array([owners[jj][1] for jj in j[sel]]))
        return m

    r2, P1, t_far = _spin_pass(
        lambda j: form_of(c[j], mu[c[j]]),
        m_of,
        np.zeros(c.size),
        np.ones(c.size),
        eps[c],
        rtol,
        h_min=1.0 / (Ri[c] + 1.0),
    )
    u_s, w_s = wall_constants_from_conditions(
        h_slip=1.0 / Ri[c],
        kappa_slip=1.0 / Ri[c],
        P_fixed=P1,
        h_fixed=1.0 / (Ri[c] + 1.0),
        u_fixed=0.0,
        u_wall_slip=-1.0,
        slip_sign=-1.0,
        eps_K=eps[c] * K[c],
    )
    j_all = np.arange(c.size)

    def g_d(d: FloatArray) -> FloatArray:
        P = r2.evaluate(np.minimum(d, t_far), j_all)[:, 1]
        u = (Ri[c] + d) * (u_s / Ri[c] - w_s * P)
        return u / u_s - f  # 1 - f at the inner wall, -f at the outer

    d = _bisect_distance(g_d, np.ones(c.size))
    for j, k in enumerate(c):
        if r2.status[j] in (FINISHED, STOPPED) and math.isfinite(d[j]):
            out[k] = WallResult(
                "ok",
                float(d[j] / eps[k]),
                float(abs(u_s[j] + 1.0)),
                float(w_s[j] - u_s[j] / Ri[k]),
                float(-tan_d[k]),
            )
    return out


__all__ = ["WallResult", "wall_quantities"]
