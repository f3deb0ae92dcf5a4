"""Tests for batch_ode (run: pytest -s to see the timing report)."""

from __future__ import annotations

import numpy as np
import pytest
from numpy.typing import NDArray
from scipy.integrate import solve_ivp

from cosserat.routes.batch_ode import FAILED, FINISHED, STOPPED, dop853_batch, radau_scalar_batch

# ----------------------------------------------------------------- helpers
A_, B_, ALPHA = 0.18198511713310117, 0.2552829152620393, 8.660254037844386
EPS_LIST = np.array([0.5, 1e-1, 1e-2, 1e-3, 1e-4, 1e-6])


def scaled_err(y: NDArray, exact: NDArray, rtol: float, atol: float) -> NDArray:
    return np.abs(y - exact) / (atol + rtol * np.abs(exact))


def eps_problem(eps: NDArray):
    """Right-hand side, Jacobian and stop function of the domain problem."""

    def fun(t, y, i):
        return (-A_ + np.sqrt(B_**2 - y**2)) / (eps[i] * ALPHA)

    def jac(t, y, i):
        return -y / np.sqrt(B_**2 - y**2) / (eps[i] * ALPHA)

    def stop(t, y, i):
        return B_**2 - y**2

    return fun, jac, stop


def eps_reference(eps: float, tq: NDArray) -> NDArray:
    sol = solve_ivp(
        lambda t, y: (-A_ + np.sqrt(B_**2 - y**2)) / (eps * ALPHA),
        (0.0, 0.5),
        [0.0],
        method="Radau",
        rtol=1e-12,
        atol=1e-14,
        dense_output=True,
    )
    return sol.sol(tq)[0]


# ------------------------------------------------------- stiff scalar batch
LAM = np.logspace(0, 6, 13)


def stiff_batch():
    """Forward problems y' = -lam (y - cos t) - sin t on [0, 1] and their
    mirror images y' = +lam (y - cos t) - sin t integrated backwards from 1
    to 0, so that the stiff transient decays in the integration direction.
    (Integrating the forward equation backwards is exponentially
    ill-conditioned for moderate lam; SciPy's Radau blows up the same way.)
    Exact: y = cos t + exp(-s lam (t - t0)) with s = +1 / -1."""
    n = LAM.size
    lam = np.concatenate([LAM, LAM])
    sgn = np.r_[np.ones(n), -np.ones(n)]
    t0 = np.r_[np.zeros(n), np.ones(n)]
    t1 = 1.0 - t0

    def exact(t, i):
        return np.cos(t) + np.exp(-sgn[i] * lam[i] * (t - t0[i]))

    def fun(t, y, i):
        return -sgn[i] * lam[i] * (y - np.cos(t)) - np.sin(t)

    def jac(t, y, i):
        return -sgn[i] * lam[i] + 0 * y

    return lam, sgn, t0, t1, exact(t0, np.arange(2 * n)), exact, fun, jac


def dense_errors(res, exact, rtol, atol, lo, hi, npts=200, seed=0):
    """Max scaled error per problem at random points of [lo_i, hi_i]."""
    n = lo.size
    u = np.random.default_rng(seed).uniform(size=(n, npts))
    tq = lo[:, None] + u * (hi - lo)[:, None]
    ii = np.broadcast_to(np.arange(n)[:, None], tq.shape)
    yd = res.evaluate(tq, ii)
    assert yd.shape == tq.shape + res.y.shape[1:]
    e = scaled_err(yd, exact(tq, ii), rtol, atol)
    return e.reshape(n, -1).max(axis=1)


@pytest.mark.parametrize("use_jac", [True, False])
def test_radau_stiff_forward_backward(use_jac: bool) -> None:
    rtol, atol = 1e-6, 1e-9
    lam, _, t0, t1, y0, exact, fun, jac = stiff_batch()
    res = radau_scalar_batch(fun, jac if use_jac else None, t0, t1, y0, rtol, atol)
    n = lam.size
    assert np.all(res.status == FINISHED)
    np.testing.assert_array_equal(res.t_final, t1)
    assert scaled_err(res.y_final, exact(t1, np.arange(n)), rtol, atol).max() < 10
    # all step points
    pid = np.repeat(np.arange(n), np.diff(res.offsets))
    assert scaled_err(res.y, exact(res.t, pid), rtol, atol).max() < 10
    for i in (0, n - 1):  # step points monotone in the integration direction
        tt, _ = res.steps(i)
        assert np.all(np.diff(tt) * res.direction[i] > 0)
    # Dense output: fine where steps stay short.  For lam >= 1e3 the stiff
    # error estimator allows steps of ~0.8 on the smooth manifold and the
    # O(h^4) collocation polynomial is off by up to ~600 tol (SciPy alike,
    # see test_radau_dense_output_like_scipy); max_step cures it.
    e = dense_errors(res, exact, rtol, atol, t0, t1)
    assert e[lam <= 100].max() < 10
    res = radau_scalar_batch(fun, jac if use_jac else None, t0, t1, y0, rtol, atol, max_step=0.1)
    assert dense_errors(res, exact, rtol, atol, t0, t1).max() < 10
    assert scaled_err(res.y_final, exact(t1, np.arange(n)), rtol, atol).max() < 10


def scipy_radau(L, t0, t1, y0, rtol, atol):  # type: ignore[no-untyped-def]
    """SciPy's Radau on the same test equation y' = -L (y - cos t) - sin t, the reference."""
    return solve_ivp(
        lambda t, y: -L * (y - np.cos(t)) - np.sin(t),
        (t0, t1),
        [y0],
        method="Radau",
        rtol=rtol,
        atol=atol,
        jac=lambda t, y: [[-L]],
        dense_output=True,
    )


def test_radau_dense_output_like_scipy() -> None:
    """Where the collocation dense output is poor, SciPy's is equally poor."""
    rtol, atol = 1e-6, 1e-9
    lam, sgn, t0, t1, y0, exact, fun, jac = stiff_batch()
    res = radau_scalar_batch(fun, jac, t0, t1, y0, rtol, atol)
    ours = dense_errors(res, exact, rtol, atol, t0, t1, npts=500)
    for i in np.flatnonzero(lam >= 1e3):
        L = sgn[i] * lam[i]
        sol = scipy_radau(L, t0[i], t1[i], y0[i], rtol, atol)
        tq = np.linspace(t0[i], t1[i], 2001)
        ref = scaled_err(sol.sol(tq)[0], exact(tq, i), rtol, atol).max()
        mine = scaled_err(res.evaluate(tq, i), exact(tq, i), rtol, atol).max()
        assert mine < 2 * ref + 10, (lam[i], mine, ref)
    assert ours.max() < 2000


def test_radau_step_counts_like_scipy() -> None:
    rtol, atol = 1e-6, 1e-9
    lam, sgn, t0, t1, y0, _, fun, jac = stiff_batch()
    res = radau_scalar_batch(fun, jac, t0, t1, y0, rtol, atol)
    for i in (0, 6, 12, 13, 25):  # lam = 1, 1e3, 1e6 forward; 1, 1e6 backward
        L = sgn[i] * lam[i]
        sol = scipy_radau(L, t0[i], t1[i], y0[i], rtol, atol)
        ns = len(sol.t) - 1
        # identical controller: equal up to round-off-induced divergence
        assert abs(res.nsteps[i] - ns) <= max(2, 0.1 * ns), (i, res.nsteps[i], ns)
    assert res.nsteps[12] < 100  # lam = 1e6: stiffness costs nothing


# ---------------------------------------------------------- domain problem
@pytest.mark.parametrize("use_jac", [True, False])
def test_eps_problem_against_reference(use_jac: bool) -> None:
    rtol = 1e-8
    fun, jac, _ = eps_problem(EPS_LIST)
    n = EPS_LIST.size
    res = radau_scalar_batch(fun, jac if use_jac else None, 0.0, 0.5, np.zeros(n), rtol, 1e-12)
    assert np.all(res.status == FINISHED)
    tq = np.linspace(0, 0.5, 51)[1:]
    for i, eps in enumerate(EPS_LIST):
        ref = eps_reference(eps, tq)
        rel = np.abs(res.evaluate(tq, i) - ref) / np.abs(ref)
        assert rel.max() < 5 * rtol, (eps, rel.max())


def test_eps_problem_event_not_reached() -> None:
    fun, jac, stop = eps_problem(EPS_LIST)
    n = EPS_LIST.size
    plain = radau_scalar_batch(fun, jac, 0.0, 0.5, np.zeros(n), 1e-8, 1e-12)
    ev = radau_scalar_batch(fun, jac, 0.0, 0.5, np.zeros(n), 1e-8, 1e-12, stop=stop)
    assert np.all(ev.status == FINISHED)
    assert np.all(np.isnan(ev.t_event))
    np.testing.assert_array_equal(ev.t, plain.t)
    np.testing.assert_array_equal(ev.y, plain.y)


def test_radau_event_reached_mixed_batch() -> None:
    """Problem n (y' = 1) stops at y = 0.7 amid eps problems that do not;
    also a backward copy (y' = 1 from y(1) = 1 down to t = 0, stop at y = 0.3)."""
    fun_e, jac_e, _ = eps_problem(EPS_LIST)
    n = EPS_LIST.size

    def fun(t, y, i):
        out = np.ones_like(y)
        m = i < n
        out[m] = fun_e(t[m], y[m], i[m])
        return out

    def jac(t, y, i):
        out = np.zeros_like(y)
        m = i < n
        out[m] = jac_e(t[m], y[m], i[m])
        return out

    def stop(t, y, i):
        return np.where(i < n, B_**2 - y**2, np.where(i == n, 0.7 - y, y - 0.3))

    t0 = np.r_[np.zeros(n + 1), 1.0]
    t1 = np.r_[np.full(n, 0.5), 1.0, 0.0]
    y0 = np.r_[np.zeros(n + 1), 1.0]
    res = radau_scalar_batch(fun, jac, t0, t1, y0, 1e-8, 1e-12, stop=stop)
    assert np.all(res.status[:n] == FINISHED)
    assert res.status[n] == STOPPED and res.status[n + 1] == STOPPED
    assert abs(res.t_event[n] - 0.7) < 1e-10 and abs(res.t_final[n] - 0.7) < 1e-10
    assert abs(res.y_final[n] - 0.7) < 1e-10
    assert abs(res.t_event[n + 1] - 0.3) < 1e-10
    assert abs(res.y_final[n + 1] - 0.3) < 1e-10


def test_radau_failure_is_reported() -> None:
    """y' = y^2 (blow-up at t=1) and a problem leaving sqrt's domain fail
    with a message; the healthy problem in the batch is unaffected."""

    def fun(t, y, i):
        with np.errstate(invalid="ignore"):
            return np.where(i == 0, y**2, np.where(i == 1, -np.sqrt(y) - 1.0, -y))

    res = radau_scalar_batch(fun, None, 0.0, 2.0, np.array([1.0, 0.5, 1.0]), 1e-6, 1e-9)
    assert res.status[2] == FINISHED
    assert abs(res.y_final[2] - np.exp(-2.0)) < 1e-5
    for i in (0, 1):
        assert res.status[i] == FAILED and res.message[i]
        assert np.all(np.isfinite(res.steps(i)[1]))


def test_max_steps_and_per_problem_tolerances() -> None:
    res = radau_scalar_batch(
        lambda t, y, i: -y, None, 0.0, [1.0, 100.0], [1.0, 1.0], [1e-3, 1e-10], 1e-12, max_steps=20
    )
    assert res.status[0] == FINISHED and res.status[1] == FAILED
    assert "Maximum number of steps" in res.message[1] and res.nsteps[1] == 20
    assert abs(res.y_final[0] - np.exp(-1)) < 1e-2


def test_degenerate_inputs() -> None:
    res = radau_scalar_batch(
        lambda t, y, i: -y, None, [0.0, 1.0], [0.0, 2.0], [1.0, 1.0], 1e-6, 1e-9
    )
    assert res.status.tolist() == [FINISHED, FINISHED]
    assert res.nsteps[0] == 0
    np.testing.assert_allclose(res.evaluate([0.0, 0.0], [0, 0]), [1.0, 1.0])
    out = res.evaluate(np.array([[1.5, 2.0], [1.0, 1.25]]), np.array([[1, 1], [1, 1]]))
    assert out.shape == (2, 2)
    np.testing.assert_allclose(out, np.exp(-(np.array([[1.5, 2], [1, 1.25]]) - 1)), rtol=1e-5)


# ------------------------------------------------------------------ DOP853
def quad_batch():
    """y0' = -k, y1' = exp(y0) cos t; forward from t=0 and backward from 1."""
    kf = np.array([0.5, 3.0, 30.0, 300.0, 1000.0, 3000.0])  # last two: y0 < -745
    kb = np.array([0.5, 3.0, 30.0, 300.0])
    k = np.concatenate([kf, kb])
    t0 = np.r_[np.zeros(kf.size), np.ones(kb.size)]
    t1 = 1.0 - t0

    def exact(t, i):
        kk = k[i]
        y1 = (kk + np.exp(-kk * t) * (np.sin(t) - kk * np.cos(t))) / (kk**2 + 1)
        return np.stack([-kk * t, y1], axis=-1)

    def fun(t, y, i):
        return np.stack([-k[i] + 0 * t, np.exp(y[:, 0]) * np.cos(t)], axis=1)

    def stop(t, y, i):
        return y[:, 0] + 745.0

    return k, t0, t1, exact(t0, np.arange(k.size)), exact, fun, stop


def test_dop853_quadrature_forward_backward_event() -> None:
    rtol, atol = 1e-9, np.array([1e-12, 1e-14])
    k, t0, t1, y0, exact, fun, stop = quad_batch()
    res = dop853_batch(fun, t0, t1, y0, rtol, atol, stop=stop)
    n = k.size
    hit = np.r_[False, False, False, False, True, True, np.zeros(4, bool)]
    assert np.all(res.status[hit] == STOPPED)
    assert np.all(res.status[~hit] == FINISHED)
    np.testing.assert_allclose(res.t_event[hit], 745.0 / k[hit], rtol=1e-12)
    tend = np.where(hit, 745.0 / k, t1)
    np.testing.assert_allclose(res.t_final, tend, rtol=1e-12)
    # Global errors are relative to the size of y along the trajectory (y1
    # decays to 0 when integrating backwards), hence a per-problem scale.
    idx = np.arange(n)
    pid = np.repeat(idx, np.diff(res.offsets))
    ex = exact(res.t, pid)
    ymax = np.maximum.reduceat(np.abs(ex), res.offsets[:-1], axis=0)
    assert (np.abs(res.y - ex) / (atol + rtol * ymax[pid])).max() < 10
    assert (np.abs(res.y_final - exact(tend, idx)) / (atol + rtol * ymax)).max() < 10
    u = np.random.default_rng(1).uniform(size=(n, 300))
    tq = t0[:, None] + u * (tend - t0)[:, None]
    ii = np.broadcast_to(idx[:, None], tq.shape)
    yd = res.evaluate(tq, ii)
    assert yd.shape == (*tq.shape, 2)
    assert (np.abs(yd - exact(tq, ii)) / (atol + rtol * ymax[ii])).max() < 10


def test_dop853_matches_scipy() -> None:
    al = np.array([1.0, 1.5, 2.0, 0.5])

    def fun(t, y, i):
        return np.stack([al[i] * y[:, 0] - y[:, 0] * y[:, 1], -y[:, 1] + y[:, 0] * y[:, 1]], axis=1)

    t1 = np.array([10.0, 10.0, -10.0, 5.0])
    y0 = np.array([[1.0, 2.0], [2.0, 1.0], [1.5, 1.5], [0.5, 0.3]])
    res = dop853_batch(fun, 0.0, t1, y0, 1e-8, 1e-10)
    for i in range(4):
        sol = solve_ivp(
            lambda t, y, a=al[i]: [a * y[0] - y[0] * y[1], -y[1] + y[0] * y[1]],
            (0, t1[i]),
            y0[i],
            method="DOP853",
            rtol=1e-8,
            atol=1e-10,
            dense_output=True,
        )
        # same algorithm: same steps, same evaluations, same values
        assert res.nsteps[i] == len(sol.t) - 1 and res.nfev[i] == sol.nfev
        np.testing.assert_allclose(res.y_final[i], sol.y[:, -1], rtol=1e-12)
        tq = np.linspace(0, t1[i], 41)
        np.testing.assert_allclose(res.evaluate(tq, i), sol.sol(tq).T, rtol=1e-11, atol=1e-12)
