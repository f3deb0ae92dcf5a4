"""Baseline solvers for the frictional Cosserat model of slow granular shear flow.

Independent implementations (right-hand sides written here from the paper's equations as
corrected in /work/main/docs) used to benchmark ``cosserat.solve``. The package's problem objects
are used only for parameters and for initial guesses (never its Formulation / engine).

Every function returns a dict

    {"xi", "u", "omega", "m": arrays, "success": bool, "message": str, "nodes_or_steps": int}

(plus a few diagnostic extras under "extra") and never raises: failures, including overflow and
non-finite values, are reported as success=False with a message.

Functions
---------
bvp_plane_gravity(problem, tol, *, xi=None, naive=False)   solve_bvp, plane shear (layer at
                                                  the upper wall, lower wall fixed), any B
bvp_plane_symmetric(problem, tol, *, xi=None)     solve_bvp on the upper half, both walls slip
bvp_couette(problem, tol, *, xi=None, naive=False)  solve_bvp with unknown parameter m(0), Couette
                                                  (naive: True or "outer-m")
lsoda_shooting_plane_gravity(problem, rtol, *, xi=None)   one LSODA pass + linear rescaling
lsoda_shooting_couette(problem, rtol, *, xi=None)         LSODA from the outer wall + secant on m(0)

``naive=True`` (and ``bvp_plane_symmetric`` always) is the plain use of ``solve_bvp`` the way a
user would write it: a uniform mesh of 101 points across the gap and a crude start (uniform shear:
u linear between the wall velocities, omega = -1/2, m constant at its one known boundary value, or
0), nothing from the asymptotics. Without it, the start is the package's leading-order asymptotic
solution on a mesh graded into the layer, which is what makes solve_bvp converge at small eps.

``x0`` (optional, solve_bvp only): initial mesh instead of the default graded one (uniform
bulk points plus points at spacing eps/(2k) across 40 eps/k at the slipping wall).
``xi`` (optional): points at which to return the profile (solve_bvp: its C1 cubic interpolant;
LSODA: its dense output). Default: the solver's own mesh (solve_bvp) or the integrator's steps
together with a fine grid that resolves the shear layer (LSODA).
"""

from __future__ import annotations

import math
import traceback

import numpy as np
from scipy.integrate import solve_bvp, solve_ivp

# Floor on sqrt(S) (denominator of the flow-rule ratios); S = 0 only on the yield bound.
_ROOT_FLOOR = 1e-12
# |omega| beyond this in a shooting pass is reported as (imminent) overflow (max double 1.8e308).
_OMEGA_OVERFLOW = 1e300
# Relative round-off allowance on the radicand before a solution is declared complex.
_RADICAND_TOL = 1e-10


# --------------------------------------------------------------------------- constitutive law
def _radicand(syx, sc, m, A, sphi):
    """S of eqn-nd_sigxy: (A^2-1) syx^2 + 2(A+1) sc^2 sin^2 phi - 4(A+1)^2 m^2."""
    return (
        (A * A - 1.0) * syx * syx
        + 2.0 * (A + 1.0) * (sc * sphi) ** 2
        - 4.0 * (A + 1.0) ** 2 * m * m
    )


def _closure(syx, sc, m, A, sphi):
    """(torque, F1, F2, S) on the paper's root sxy = -A syx - sqrt(S), S clipped at 0.

    torque = (syx - sxy)/(2(A+1)); F1 = (A+1)(sxy+syx)/(sxy+A syx); F2 = 2(A+1)m/(sxy+A syx).
    """
    S = _radicand(syx, sc, m, A, sphi)
    root = np.sqrt(np.maximum(S, 0.0))
    sxy = -A * syx - root
    torque = (syx - sxy) / (2.0 * (A + 1.0))
    denom = -np.maximum(root, _ROOT_FLOOR)  # = sxy + A syx
    F1 = (A + 1.0) * (sxy + syx) / denom
    F2 = 2.0 * (A + 1.0) * m / denom
    return torque, F1, F2, S


def _symmetric_m(syx, sc, A, sphi):
    """|m| at which sxy = syx: syx^2 + 2(A+1) m^2 = (sc sin phi)^2."""
    return np.sqrt(np.maximum(((sc * sphi) ** 2 - syx**2) / (2.0 * (A + 1.0)), 0.0))


def _wall_k(tan_delta, A, sphi, alpha):
    """a, m0, k at a slipping wall with sigma_c = 1 (eqn-a_b_def, eqn-k_def)."""
    a = 0.5 * tan_delta
    m0 = math.sqrt(max((sphi**2 - tan_delta**2) / (2.0 * (A + 1.0)), 0.0))
    return a, m0, m0 / (alpha * a)


# --------------------------------------------------------------------------- helpers
def _result(xi, u, omega, m, success, message, n, **extra):
    xi, u, omega, m = (np.asarray(v, dtype=float) for v in (xi, u, omega, m))
    if success and not all(np.all(np.isfinite(v)) for v in (xi, u, omega, m)):
        success = False
        message = "non-finite values in the solution (" + message + ")"
    return {
        "xi": xi,
        "u": u,
        "omega": omega,
        "m": m,
        "success": bool(success),
        "message": str(message),
        "nodes_or_steps": int(n),
        "extra": extra,
    }


def _failure(message, n=0, **extra):
    e = np.array([])
    return _result(e, e, e, e, False, message, n, **extra)


def _graded_mesh(eps, k, layer_at, n_bulk=41, n_layer=81, span=40.0):
    """Uniform bulk points plus points spaced eps/k*span/(n_layer-1) in the layer at
    xi = layer_at."""
    bulk = np.linspace(0.0, 1.0, n_bulk)
    d = (eps / k) * np.linspace(0.0, span, n_layer) if k > 0 else np.linspace(0, 1, n_layer)
    d = d[d < 1.0]
    layer = 1.0 - d if layer_at == 1.0 else d
    return np.unique(np.concatenate([bulk, layer, [0.0, 1.0]]))


def _plane_params(problem):
    mat = problem.equations.material
    if problem.equations.fixed_wall != 0.0:
        raise ValueError(
            "these baselines handle plane shear with the layer at the upper wall and a lower wall "
            f"that does not slip; problem.equations.fixed_wall = {problem.equations.fixed_wall}"
        )
    return dict(
        A=float(mat.A),
        alpha=float(mat.alpha),
        sphi=float(mat.sin_phi),
        eps=float(problem.eps),
        Bnu=float(problem.equations.B) * float(problem.equations.nu),
        syx=float(problem.equations.sigma_yx),
        K=float(problem.equations.upper.K),
        m_fix=float(problem.equations.m_at_fixed_wall),
    )


def _couette_params(problem):
    mat = problem.equations.material
    return dict(
        A=float(mat.A),
        alpha=float(mat.alpha),
        sphi=float(mat.sin_phi),
        eps=float(problem.eps),
        tand=float(problem.equations.tan_delta),
        Ri=float(problem.equations.Ri),
        K=float(problem.equations.wall.K),
    )


# =========================================================================== plane shear
def _plane_rhs_factory(P):
    A, alpha, sphi, eps, Bnu, syx = (P[k] for k in ("A", "alpha", "sphi", "eps", "Bnu", "syx"))
    ea = eps * alpha

    def rhs(x, y):
        m, _u, w = y[0], y[1], y[2]
        sc = 1.0 + Bnu * (1.0 - x)
        torque, F1, F2, _ = _closure(syx, sc, m, A, sphi)
        return np.array([torque / ea, -F1 * w, -F2 * w / ea])

    def radicand(x, m):
        return _radicand(syx, 1.0 + Bnu * (1.0 - x), m, A, sphi)

    return rhs, radicand


def _plane_initial(P, x):
    """Leading-order asymptotic solution (layer at xi = 1, u_0 = 0 at the fixed wall)."""
    A, alpha, sphi, eps, Bnu, syx, K = (
        P[k] for k in ("A", "alpha", "sphi", "eps", "Bnu", "syx", "K")
    )
    _a, _m0, k = _wall_k(-syx, A, sphi, alpha)
    m = _symmetric_m(syx, 1.0 + Bnu * (1.0 - x), A, sphi)
    e = np.exp(-k * (1.0 - x) / eps)
    u = (2.0 / k) / (K + 2.0 / k) * e
    w = -1.0 / (eps * (K + 2.0 / k)) * e
    return np.vstack([m, u, w]), k


def bvp_plane_gravity(problem, tol, *, xi=None, x0=None, naive=False):
    """solve_bvp on y = [m, u, omega] for plane shear under gravity (layer at the upper wall).

    BCs: m(0) = m at the fixed wall (sigma_xy = sigma_yx), u(0) = 0, u(1) = 1 + eps K omega(1).
    ``tol`` is solve_bvp's tol and bc_tol; max_nodes = 100000. ``naive``: start from uniform
    shear (m constant, u = xi, omega = -1/2) on a uniform 101-point mesh instead of the
    leading-order asymptotic solution on a graded mesh.
    """
    try:
        P = _plane_params(problem)
        rhs, radicand = _plane_rhs_factory(P)
        eps, K, m_fix = P["eps"], P["K"], P["m_fix"]
        _, _, k = _wall_k(-P["syx"], P["A"], P["sphi"], P["alpha"])
        if naive:
            x0 = np.linspace(0.0, 1.0, 101)
            y0 = np.vstack([np.full_like(x0, m_fix), x0, np.full_like(x0, -0.5)])
        else:
            x0 = _graded_mesh(eps, k, layer_at=1.0) if x0 is None else np.asarray(x0, float)
            y0, _ = _plane_initial(P, x0)

        def bc(ya, yb):
            return np.array([ya[0] - m_fix, ya[1], yb[1] - 1.0 - eps * K * yb[2]])

        with np.errstate(all="ignore"):
            sol = solve_bvp(rhs, bc, x0, y0, tol=tol, bc_tol=tol, max_nodes=100000)
            x = sol.x if xi is None else np.asarray(xi, dtype=float)
            y = sol.y if xi is None else sol.sol(x)
            S_min = float(np.min(radicand(sol.x, sol.y[0])))
            bc_res = float(np.max(np.abs(bc(sol.y[:, 0], sol.y[:, -1]))))
        success = sol.status == 0
        msg = f"solve_bvp status {sol.status}: {sol.message}"
        scale = 2.0 * (P["A"] + 1.0) * (P["sphi"] * (1.0 + P["Bnu"])) ** 2
        if success and S_min < -_RADICAND_TOL * scale:
            success = False
            msg += f"; but the radicand is negative (min S = {S_min:.3g}): not a real solution"
        return _result(
            x,
            y[1],
            y[2],
            y[0],
            success,
            msg,
            sol.x.size,
            max_rms_residual=float(np.max(sol.rms_residuals)) if sol.rms_residuals.size else np.nan,
            bc_residual=bc_res,
            S_min=S_min,
            niter=int(sol.niter),
        )
    except Exception as exc:  # never raise
        return _failure(f"exception: {exc!r}\n{traceback.format_exc(limit=3)}")


def bvp_plane_symmetric(problem, tol, *, xi=None):
    """solve_bvp for plane shear without gravity where both walls slip (the symmetric case).

    The plain formulation of the paper (eqn-nd_bc6): the upper half [1/2, 1] with m(1/2) = 0,
    u(1/2) = u_c = (1 + eps (K_u - K_l) omega(1))/2 and u(1) = 1 + eps K_u omega(1); the lower half
    by symmetry (m and u - u_c odd, omega even about 1/2). Crude start: m = 0, u = xi,
    omega = -1/2 on a uniform mesh of 51 points (101 across the gap). ``tol`` as in
    :func:`bvp_plane_gravity`.
    """
    try:
        mat = problem.equations.material
        if (
            float(problem.equations.B) != 0.0
            or getattr(problem.equations.case, "name", "") != "SYMMETRIC"
        ):
            raise ValueError("bvp_plane_symmetric needs the symmetric case (no gravity)")
        P = dict(
            A=float(mat.A),
            alpha=float(mat.alpha),
            sphi=float(mat.sin_phi),
            eps=float(problem.eps),
            Bnu=0.0,
            syx=float(problem.equations.sigma_yx),
        )
        rhs, radicand = _plane_rhs_factory(P)
        eps = P["eps"]
        Ku, Kl = float(problem.equations.upper.K), float(problem.equations.lower_wall.K)
        x0 = np.linspace(0.5, 1.0, 51)
        y0 = np.vstack([np.zeros_like(x0), x0.copy(), np.full_like(x0, -0.5)])

        def bc(ya, yb):
            u_c = 0.5 * (1.0 + eps * (Ku - Kl) * yb[2])
            return np.array([ya[0], ya[1] - u_c, yb[1] - 1.0 - eps * Ku * yb[2]])

        with np.errstate(all="ignore"):
            sol = solve_bvp(rhs, bc, x0, y0, tol=tol, bc_tol=tol, max_nodes=100000)
            if xi is None:
                x = np.concatenate([1.0 - sol.x[::-1][:-1], sol.x])
            else:
                x = np.asarray(xi, dtype=float)
            h = np.where(x >= 0.5, x, 1.0 - x)
            y = sol.sol(h)
            low = x < 0.5
            u_c = float(sol.y[1, 0])
            m = np.where(low, -y[0], y[0])
            u = np.where(low, 2.0 * u_c - y[1], y[1])
            S_min = float(np.min(radicand(sol.x, sol.y[0])))
        success = sol.status == 0
        msg = f"solve_bvp status {sol.status}: {sol.message}"
        scale = 2.0 * (P["A"] + 1.0) * P["sphi"] ** 2
        if success and S_min < -_RADICAND_TOL * scale:
            success = False
            msg += f"; but the radicand is negative (min S = {S_min:.3g}): not a real solution"
        return _result(x, u, y[2], m, success, msg, sol.x.size, S_min=S_min, niter=int(sol.niter))
    except Exception as exc:  # never raise
        return _failure(f"exception: {exc!r}\n{traceback.format_exc(limit=3)}")


def _fine_grid(eps, k, layer_at, n=2001):
    return _graded_mesh(eps, k, layer_at, n_bulk=n // 2 + 1, n_layer=n // 2, span=60.0)


def lsoda_shooting_plane_gravity(problem, rtol, *, xi=None):
    """One LSODA pass from xi = 0 (m = m_fixed, u = 0, omega = 1) to 1, then rescale (u, omega).

    The flow rule is linear homogeneous in (u, omega), so c = 1/(u(1) - eps K omega(1)) makes
    u(1) = 1 + eps K omega(1). omega grows like exp(k/eps): an event stops the pass when
    |omega| > 1e300, reported as overflow (success=False).
    """
    try:
        P = _plane_params(problem)
        rhs, radicand = _plane_rhs_factory(P)
        eps, K, m_fix = P["eps"], P["K"], P["m_fix"]
        _, _, k = _wall_k(-P["syx"], P["A"], P["sphi"], P["alpha"])

        def overflow(t, y):
            return _OMEGA_OVERFLOW - abs(y[2])

        overflow.terminal = True

        with np.errstate(all="ignore"):
            sol = solve_ivp(
                lambda t, y: rhs(t, y),
                (0.0, 1.0),
                [m_fix, 0.0, 1.0],
                method="LSODA",
                rtol=rtol,
                atol=rtol * 1e-3,
                dense_output=True,
                events=overflow,
            )
        nsteps = max(sol.t.size - 1, 0)
        if sol.status == 1 or (sol.t_events and sol.t_events[0].size):
            xo = float(sol.t_events[0][0]) if sol.t_events[0].size else float(sol.t[-1])
            return _failure(
                f"overflow: |omega| of the shooting pass exceeded {_OMEGA_OVERFLOW:g} at "
                f"xi = {xo:.4g} (omega grows like exp(k/eps), k/eps = {k / eps:.4g}); "
                "the rescaled profile cannot be formed in double precision",
                nsteps,
            )
        if sol.status != 0:
            return _failure(f"LSODA failed (status {sol.status}): {sol.message}", nsteps)
        _m1, u1, w1 = sol.y[:, -1]
        denom = u1 - eps * K * w1
        if not np.isfinite(denom) or denom == 0.0:
            return _failure(
                f"overflow/degenerate scaling: u(1) - eps K omega(1) = {denom!r}", nsteps
            )
        c = 1.0 / denom
        x = (
            np.unique(np.concatenate([sol.t, _fine_grid(eps, k, 1.0)]))
            if xi is None
            else np.asarray(xi, float)
        )
        with np.errstate(all="ignore"):
            y = sol.sol(x)
            S_min = float(np.min(radicand(sol.t, sol.y[0])))
        scale = 2.0 * (P["A"] + 1.0) * (P["sphi"] * (1.0 + P["Bnu"])) ** 2
        success, msg = True, f"LSODA: {sol.message} ({sol.nfev} rhs evaluations); scale c = {c:.6g}"
        if S_min < -_RADICAND_TOL * scale:
            success, msg = False, msg + f"; radicand negative (min S = {S_min:.3g})"
        return _result(
            x, c * y[1], c * y[2], y[0], success, msg, nsteps, nfev=int(sol.nfev), scale=c
        )
    except Exception as exc:
        return _failure(f"exception: {exc!r}\n{traceback.format_exc(limit=3)}")


# =========================================================================== Couette flow
def _couette_funcs(P):
    A, alpha, sphi, eps, tand, Ri = (P[k] for k in ("A", "alpha", "sphi", "eps", "tand", "Ri"))
    ea = eps * alpha
    g = 2.0 * (A + 1.0) * ea  # weight of the couple stress in eqn-nd_shsts_cyl

    def s_rt(x, m, mu):
        r = Ri + x
        return -tand * (Ri / r) ** 2 + g * (m / r - mu * Ri / r**2)

    def rhs(x, y, mu):
        m, u, w = y[0], y[1], y[2]
        r = Ri + x
        torque, F1, F2, _ = _closure(s_rt(x, m, mu), 1.0, m, A, sphi)
        wr = w + u / r
        return np.array([torque / ea - m / r, u / r - wr * F1, -wr * F2 / ea])

    def m_rhs(x, y, mu):
        m = y[0]
        torque, _, _, _ = _closure(s_rt(x, m, mu), 1.0, m, A, sphi)
        return np.array([torque / ea - m / (Ri + x)])

    def outer_m(mu):
        """m(1) from s_rt(1) = s_tr(1): s^2 + 2(A+1) m^2 = sin^2 phi, s = s0 + beta m;
        negative root."""
        r1 = Ri + 1.0
        beta = g / r1
        s0 = -tand * (Ri / r1) ** 2 - g * mu * Ri / r1**2
        qa = beta**2 + 2.0 * (A + 1.0)
        disc = -2.0 * (A + 1.0) * s0**2 + qa * sphi**2
        if disc < 0.0:
            raise ArithmeticError(f"no real m(1) for m(0) = {mu:.6g} (outer-wall condition)")
        return (-s0 * beta - math.sqrt(disc)) / qa

    def radicand(x, m, mu):
        return _radicand(s_rt(x, m, mu), 1.0, m, A, sphi)

    return rhs, m_rhs, outer_m, s_rt, radicand


def bvp_couette(problem, tol, *, xi=None, x0=None, naive=False):
    """solve_bvp for Couette flow: y = [m, u, omega], parameter p = [m(0)].

    BCs: m(0) = p; s_rt(1) = s_tr(1); u(1) = 0; u(0) = -1 - eps K omega(0).
    ``naive``: start from uniform shear (u = xi - 1, omega = -1/2) on a uniform 101-point mesh
    instead of the leading-order asymptotic solution on a graded mesh, with m = p = 0 (True) or
    m = the leading-order outer couple stress, p its value at xi = 0 (``"outer-m"``).
    """
    try:
        P = _couette_params(problem)
        rhs, _, _, s_rt, radicand = _couette_funcs(P)
        A, alpha, sphi, eps, tand, K = (P[k] for k in ("A", "alpha", "sphi", "eps", "tand", "K"))
        _, _, k = _wall_k(tand, A, sphi, alpha)
        if naive:
            x0 = np.linspace(0.0, 1.0, 101)
            m_init = (
                np.asarray(problem.equations.outer_couple_stress(x0), dtype=float)
                if naive == "outer-m"
                else np.zeros_like(x0)
            )
            y0 = np.vstack([m_init, x0 - 1.0, np.full_like(x0, -0.5)])
            p0 = np.array([m_init[0]])
        else:
            x0 = _graded_mesh(eps, k, layer_at=0.0) if x0 is None else np.asarray(x0, float)
            m_init = np.asarray(problem.equations.outer_couple_stress(x0), dtype=float)
            e = np.exp(-k * x0 / eps)
            y0 = np.vstack(
                [m_init, -(2.0 / k) / (K + 2.0 / k) * e, -1.0 / (eps * (K + 2.0 / k)) * e]
            )
            p0 = np.array([m_init[0]])

        def fun(x, y, p):
            return rhs(x, y, p[0])

        def bc(ya, yb, p):
            mu = p[0]
            s1 = s_rt(1.0, yb[0], mu)
            # sxy at xi = 1 on the paper's root, with S clipped at 0
            _, _, _, S1 = _closure(s1, 1.0, yb[0], A, sphi)
            s_tr1 = -A * s1 - math.sqrt(max(S1, 0.0))
            return np.array([ya[0] - mu, s1 - s_tr1, yb[1], ya[1] + 1.0 + eps * K * ya[2]])

        with np.errstate(all="ignore"):
            sol = solve_bvp(fun, bc, x0, y0, p=p0, tol=tol, bc_tol=tol, max_nodes=100000)
            x = sol.x if xi is None else np.asarray(xi, dtype=float)
            y = sol.y if xi is None else sol.sol(x)
            mu = float(sol.p[0])
            S_min = float(np.min(radicand(sol.x, sol.y[0], mu)))
            bc_res = float(np.max(np.abs(bc(sol.y[:, 0], sol.y[:, -1], sol.p))))
        success = sol.status == 0
        msg = f"solve_bvp status {sol.status}: {sol.message}; m(0) = {mu:.10g}"
        if success and S_min < -_RADICAND_TOL * 2.0 * (A + 1.0) * sphi**2:
            success = False
            msg += f"; but the radicand is negative (min S = {S_min:.3g}): not a real solution"
        return _result(
            x,
            y[1],
            y[2],
            y[0],
            success,
            msg,
            sol.x.size,
            m_inner=mu,
            max_rms_residual=float(np.max(sol.rms_residuals)) if sol.rms_residuals.size else np.nan,
            bc_residual=bc_res,
            S_min=S_min,
            niter=int(sol.niter),
        )
    except Exception as exc:
        return _failure(f"exception: {exc!r}\n{traceback.format_exc(limit=3)}")


def lsoda_shooting_couette(problem, rtol, *, xi=None, max_iter=50):
    """LSODA from the outer wall (xi = 1) inwards, secant on mu = m(0), then rescale (u, omega).

    For a trial mu: m(1) from s_rt(1) = s_tr(1); integrate the couple-stress balance alone from
    1 to 0 (its stable direction) and iterate the secant on m(0; mu) - mu = 0 (|step| <= rtol |mu|).
    Then one LSODA pass of [m, u, omega] with u(1) = 0, omega(1) = 1 and the scale
    c = -1/(u(0) + eps K omega(0)) so that u(0) = -1 - eps K omega(0).
    """
    try:
        P = _couette_params(problem)
        rhs, m_rhs, outer_m, _s_rt, radicand = _couette_funcs(P)
        A, alpha, sphi, eps, tand, K = (P[k] for k in ("A", "alpha", "sphi", "eps", "tand", "K"))
        _, _, k = _wall_k(tand, A, sphi, alpha)
        atol = rtol * 1e-3
        nsteps_total = 0

        def residual(mu):
            nonlocal nsteps_total
            with np.errstate(all="ignore"):
                s = solve_ivp(
                    m_rhs,
                    (1.0, 0.0),
                    [outer_m(mu)],
                    method="LSODA",
                    rtol=rtol,
                    atol=atol,
                    args=(mu,),
                )
            nsteps_total += max(s.t.size - 1, 0)
            if s.status != 0:
                raise ArithmeticError(
                    f"LSODA failed on the couple stress for mu = {mu:.6g}: {s.message}"
                )
            return float(s.y[0, -1]) - mu

        mu0 = float(problem.equations.outer_couple_stress(0.0))
        mu1 = mu0 * (1.0 + 1e-2)
        f0, f1 = residual(mu0), residual(mu1)
        converged = False
        for it in range(max_iter):  # noqa: B007 - the count is reported
            if f1 == f0:
                break
            mu2 = mu1 - f1 * (mu1 - mu0) / (f1 - f0)
            mu0, f0 = mu1, f1
            mu1 = mu2
            if abs(mu1 - mu0) <= rtol * max(abs(mu1), 1e-300):
                converged = True
                break
            f1 = residual(mu1)
        if not converged:
            return _failure(
                f"secant on m(0) did not converge in {max_iter} iterations", nsteps_total
            )
        mu = mu1
        n_secant = it + 1

        def overflow(t, y, mu):
            return _OMEGA_OVERFLOW - abs(y[2])

        overflow.terminal = True
        with np.errstate(all="ignore"):
            sol = solve_ivp(
                rhs,
                (1.0, 0.0),
                [outer_m(mu), 0.0, 1.0],
                method="LSODA",
                rtol=rtol,
                atol=atol,
                dense_output=True,
                events=overflow,
                args=(mu,),
            )
        nsteps = max(sol.t.size - 1, 0)
        nsteps_total += nsteps
        if sol.status == 1 or (sol.t_events and sol.t_events[0].size):
            xo = float(sol.t_events[0][0]) if sol.t_events[0].size else float(sol.t[-1])
            return _failure(
                f"overflow: |omega| of the shooting pass exceeded {_OMEGA_OVERFLOW:g} at "
                f"xi = {xo:.4g} (omega grows like exp(k/eps) inwards); secant had converged "
                f"to m(0) = {mu:.10g} in {n_secant} iterations",
                nsteps_total,
                m_inner=mu,
            )
        if sol.status != 0:
            return _failure(f"LSODA failed (status {sol.status}): {sol.message}", nsteps_total)
        _, u0, w0 = sol.y[:, -1]
        denom = u0 + eps * K * w0
        if not np.isfinite(denom) or denom == 0.0:
            return _failure(
                f"overflow/degenerate scaling: u(0) + eps K omega(0) = {denom!r}", nsteps_total
            )
        c = -1.0 / denom
        x = (
            np.unique(np.concatenate([sol.t, _fine_grid(eps, k, 0.0)]))
            if xi is None
            else np.asarray(xi, float)
        )
        with np.errstate(all="ignore"):
            y = sol.sol(x)
            S_min = float(np.min(radicand(sol.t, sol.y[0], mu)))
        success = True
        msg = (
            f"LSODA: {sol.message}; secant converged in {n_secant} iterations, "
            f"m(0) = {mu:.10g}; scale c = {c:.6g}"
        )
        if S_min < -_RADICAND_TOL * 2.0 * (A + 1.0) * sphi**2:
            success, msg = False, msg + f"; radicand negative (min S = {S_min:.3g})"
        return _result(
            x,
            c * y[1],
            c * y[2],
            y[0],
            success,
            msg,
            nsteps_total,
            m_inner=mu,
            secant_iterations=n_secant,
            scale=c,
            final_pass_steps=nsteps,
        )
    except Exception as exc:
        return _failure(f"exception: {exc!r}\n{traceback.format_exc(limit=3)}")
