"""The compiled Radau IIA integrator (:mod:`cosserat.numerics.radau`).

References are independent: SciPy's ``solve_ivp(method="Radau")`` at a much tighter tolerance,
or closed forms. Errors are measured in units of the local tolerance, ``|y - y_ref| / (atol +
rtol |y_ref|)``, so the bounds read as "within k tolerances"; the observed values are quoted
next to each bound.

Every distinct (fun, jac, event) triple costs a compilation of :func:`radau5` (a few seconds),
so the tests share five: Robertson, Van der Pol, a linear scalar problem with a closed form
(with and without an event) and y' = y^2 through a compiled entry point.
"""

from __future__ import annotations

import functools
import math
from typing import NamedTuple

import numpy as np
import pytest
from numba import njit
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from cosserat.numerics.radau import (
    EVENT,
    MAX_STEPS,
    NOT_FINITE,
    STEP_TOO_SMALL,
    SUCCESS,
    dense_eval,
    dense_eval1,
    no_event,
    radau5,
)

NO_ARGS = np.zeros(0)


class Result(NamedTuple):
    status: int
    ts: np.ndarray
    hs: np.ndarray
    ys: np.ndarray
    Q: np.ndarray
    t_event: float
    nfev: int
    njev: int
    nlu: int
    nsteps: int

    def dense(self, t):
        return dense_eval(self.ts, self.hs, self.ys, self.Q, np.asarray(t, dtype=float))


# ----------------------------------------------------------------------------- problems
@njit
def rob_rhs(t, y, args):
    return np.array(
        [
            -0.04 * y[0] + 1e4 * y[1] * y[2],
            0.04 * y[0] - 1e4 * y[1] * y[2] - 3e7 * y[1] ** 2,
            3e7 * y[1] ** 2,
        ]
    )


@njit
def rob_jac(t, y, args):
    return np.array(
        [
            [-0.04, 1e4 * y[2], 1e4 * y[1]],
            [0.04, -1e4 * y[2] - 6e7 * y[1], -1e4 * y[1]],
            [0.0, 6e7 * y[1], 0.0],
        ]
    )


@njit
def vdp_rhs(t, y, args):
    mu = args[0]
    return np.array([y[1], mu * (1.0 - y[0] ** 2) * y[1] - y[0]])


@njit
def vdp_jac(t, y, args):
    mu = args[0]
    return np.array([[0.0, 1.0], [-2.0 * mu * y[0] * y[1] - 1.0, mu * (1.0 - y[0] ** 2)]])


@njit
def lin_rhs(t, y, args):
    """y' = -k (y - cos t); args = (k, event level, t beyond which fun returns NaN)."""
    if t > args[2]:
        return np.array([np.nan])
    return np.array([-args[0] * (y[0] - math.cos(t))])


@njit
def lin_jac(t, y, args):
    return np.array([[-args[0]]])


@njit
def level_event(t, y, args):
    """Triggers when y reaches args[1] from below."""
    return args[1] - y[0]


def lin_args(k, level=np.inf, poison=np.inf):
    return np.array([k, level, poison])


def lin_exact(t, k, t0, y0):
    """Closed form of lin_rhs: the particular solution plus the decaying (or growing) mode."""

    def particular(s):
        return k * (k * np.cos(s) + np.sin(s)) / (k * k + 1.0)

    return particular(t) + (y0 - particular(t0)) * np.exp(-k * (np.asarray(t) - t0))


@njit
def square_rhs(t, y, args):
    return np.array([y[0] * y[0]])


@njit
def square_jac(t, y, args):
    return np.array([[2.0 * y[0]]])


@njit
def blow_up(t_end):
    """y' = y^2, y(0) = 1, so y = 1/(1 - t): called the production way, from a compiled entry
    point that passes module-level jitted functions."""
    y0, atol = np.ones(1), np.array([1e-9])
    return radau5(
        square_rhs, square_jac, no_event, 0.0, t_end, y0, 1e-6, atol, NO_ARGS, 100_000, 0.0
    )


def run(fun, jac, t0, t1, y0, rtol, atol, args=NO_ARGS, **options) -> Result:
    event = options.get("event", no_event)
    max_steps = options.get("max_steps", 100_000)
    first_step = options.get("first_step", 0.0)
    y0 = np.asarray(y0, dtype=float)
    atol = np.array(np.broadcast_to(np.asarray(atol, dtype=float), y0.shape))
    out = radau5(fun, jac, event, t0, t1, y0, rtol, atol, args, max_steps, first_step)
    return Result(*out)


def scipy_run(fun, jac, t0, t1, y0, rtol, atol, args=NO_ARGS, **kwargs):
    def f(t, y):
        return fun(t, y, args)

    def j(t, y):
        return jac(t, y, args)

    y0 = np.asarray(y0, dtype=float)
    return solve_ivp(f, (t0, t1), y0, method="Radau", rtol=rtol, atol=atol, jac=j, **kwargs)


def scaled_error(y, ref, rtol, atol):
    return float(np.max(np.abs(y - ref) / (atol + rtol * np.abs(ref))))


def assert_similar_steps(ours, scipy_steps):
    assert abs(ours - scipy_steps) <= 0.25 * scipy_steps, (ours, scipy_steps)


def test_tables_are_scipys():
    from scipy.integrate._ivp import radau as scipy_radau

    from cosserat.numerics import radau

    for name in ("C", "E", "T", "TI", "TI_COMPLEX", "P", "MU_REAL", "MU_COMPLEX"):
        np.testing.assert_array_equal(getattr(radau, name), getattr(scipy_radau, name))


# ----------------------------------------------------------------------------- Robertson
ROB_T, ROB_RTOL, ROB_ATOL = 1e5, 1e-6, np.array([1e-8, 1e-12, 1e-8])


@functools.cache
def robertson_reference():
    y0, atol = [1.0, 0.0, 0.0], ROB_ATOL * 1e-6
    return scipy_run(rob_rhs, rob_jac, 0.0, ROB_T, y0, 1e-12, atol, dense_output=True)


@pytest.mark.slow
def test_robertson_against_scipy():
    r = run(rob_rhs, rob_jac, 0.0, ROB_T, [1.0, 0.0, 0.0], ROB_RTOL, ROB_ATOL)
    assert r.status == SUCCESS and r.ts[-1] == ROB_T and math.isnan(r.t_event)
    assert r.nsteps == len(r.hs) == len(r.ts) - 1 == len(r.Q)
    assert r.ys.shape == (r.nsteps + 1, 3) and r.Q.shape == (r.nsteps, 3, 3)
    ref = robertson_reference()
    assert ref.success
    # observed: 0.020 tolerances at the steps (SciPy: 0.020), 0.18 on the dense output
    assert scaled_error(r.ys, ref.sol(r.ts).T, ROB_RTOL, ROB_ATOL) < 1.0
    tt = np.geomspace(1e-6, ROB_T, 400)
    assert scaled_error(r.dense(tt), ref.sol(tt).T, ROB_RTOL, ROB_ATOL) < 2.0
    # y1 + y2 + y3 is a linear invariant, which Runge-Kutta methods conserve (observed 1e-15)
    assert np.max(np.abs(r.ys.sum(axis=1) - 1.0)) < 1e-12
    # observed: 201 steps, nfev 1718, njev 99, nlu 274 -- SciPy's counts exactly
    sp = scipy_run(rob_rhs, rob_jac, 0.0, ROB_T, [1.0, 0.0, 0.0], ROB_RTOL, ROB_ATOL)
    assert_similar_steps(r.nsteps, len(sp.t) - 1)
    assert_similar_steps(r.nfev, sp.nfev)
    assert 0 < r.njev <= r.nfev and r.nlu >= 2


# ----------------------------------------------------------------------------- Van der Pol
VDP_MU, VDP_T, VDP_RTOL, VDP_ATOL = 1e3, 3000.0, 1e-6, np.array([1e-6, 1e-6])
VDP_ARGS = np.array([VDP_MU])


@functools.cache
def vdp_reference():
    atol = VDP_ATOL * 1e-5
    return scipy_run(
        vdp_rhs, vdp_jac, 0.0, VDP_T, [2.0, 0.0], 1e-10, atol, VDP_ARGS, dense_output=True
    )


@pytest.mark.slow
def test_van_der_pol_against_scipy():
    r = run(vdp_rhs, vdp_jac, 0.0, VDP_T, [2.0, 0.0], VDP_RTOL, VDP_ATOL, VDP_ARGS)
    assert r.status == SUCCESS and r.ts[-1] == VDP_T
    ref = vdp_reference()
    sp = scipy_run(vdp_rhs, vdp_jac, 0.0, VDP_T, [2.0, 0.0], VDP_RTOL, VDP_ATOL, VDP_ARGS)
    # observed: 919 steps, SciPy 919
    assert_similar_steps(r.nsteps, len(sp.t) - 1)
    # The steps cluster in the relaxation jumps, where y2 ~ mu and a phase error of
    # ~rtol t shows as a pointwise error of ~1e6 tolerances, for SciPy as for radau5: compare
    # that error with SciPy's at the same tolerance (observed: equal to 6 digits).
    ours = scaled_error(r.ys, ref.sol(r.ts).T, VDP_RTOL, VDP_ATOL)
    theirs = scaled_error(sp.y.T, ref.sol(sp.t).T, VDP_RTOL, VDP_ATOL)
    assert 0.5 < ours / theirs < 2.0, (ours, theirs)
    # 200 uniform interior points fall mostly on the slow manifold (observed 2.2 tolerances)
    tt = np.linspace(0.0, VDP_T, 202)[1:-1]
    assert scaled_error(r.dense(tt), ref.sol(tt).T, VDP_RTOL, VDP_ATOL) < 10.0


# ----------------------------------------------------------------------------- dense output
K = 50.0


@pytest.mark.slow
def test_dense_output_against_closed_form():
    rtol, atol = 1e-6, 1e-9
    r = run(lin_rhs, lin_jac, 0.0, 2.0, [0.0], rtol, atol, lin_args(K))
    assert r.status == SUCCESS
    # between the steps: all midpoints, and a uniform grid
    tt = np.concatenate([0.5 * (r.ts[1:] + r.ts[:-1]), np.linspace(0.0, 2.0, 1001)])
    exact = lin_exact(tt, K, 0.0, 0.0)
    dense = r.dense(tt)[:, 0]
    err = scaled_error(dense, exact, rtol, atol)
    assert err < 10.0  # observed 3.5 tolerances: the cubic interpolant is one order lower
    sp = scipy_run(lin_rhs, lin_jac, 0.0, 2.0, [0.0], rtol, atol, lin_args(K), dense_output=True)
    assert 0.5 < err / scaled_error(sp.sol(tt), exact, rtol, atol) < 2.0
    # observed: 61 steps, SciPy 61
    assert_similar_steps(r.nsteps, len(sp.t) - 1)
    # the scalar path, unsorted points, the step points, clipping just outside [t0, t_end]
    one = np.array([dense_eval1(r.ts, r.hs, r.ys, r.Q, s, 0) for s in tt])
    np.testing.assert_array_equal(one, dense)
    order = np.random.default_rng(1).permutation(len(tt))
    np.testing.assert_array_equal(r.dense(tt[order])[:, 0], dense[order])
    np.testing.assert_array_equal(r.dense(r.ts), r.ys)
    np.testing.assert_array_equal(r.dense([-1e-9, 2.0 + 1e-9]), r.ys[[0, -1]])


def test_backward_integration():
    # y' = 50 (y - cos t) is stiff and stable towards decreasing t
    rtol, atol = 1e-6, 1e-9
    r = run(lin_rhs, lin_jac, 2.0, 0.0, [0.0], rtol, atol, lin_args(-K))
    assert r.status == SUCCESS and r.ts[0] == 2.0 and r.ts[-1] == 0.0
    assert np.all(np.diff(r.ts) < 0.0) and np.all(r.hs < 0.0)
    tt = np.linspace(2.0, 0.0, 501)
    exact = lin_exact(tt, -K, 2.0, 0.0)
    assert scaled_error(r.dense(tt)[:, 0], exact, rtol, atol) < 10.0


def test_error_decreases_with_rtol():
    """Radau IIA is of order 5 but its step control uses an order-3 error estimate, so
    h ~ tol^(1/4) and the error at the steps goes as tol^(5/4); the cubic dense output is
    one order lower, ~tol. Observed slopes: 1.21 (steps) and 1.10 (dense output)."""
    rtols = 10.0 ** -np.arange(4.0, 11.0)
    tt = np.linspace(0.0, 2.0, 1001)
    exact = lin_exact(tt, K, 0.0, 0.0)
    at_steps, dense = [], []
    for rtol in rtols:
        r = run(lin_rhs, lin_jac, 0.0, 2.0, [0.0], rtol, rtol * 1e-3, lin_args(K))
        assert r.status == SUCCESS
        at_steps.append(np.max(np.abs(r.ys[:, 0] - lin_exact(r.ts, K, 0.0, 0.0))))
        dense.append(np.max(np.abs(r.dense(tt)[:, 0] - exact)))
    # the tightest run took more steps (629) than the output arrays' initial capacity (64)
    assert r.nsteps > 64 and np.all(np.isfinite(r.Q))
    np.testing.assert_allclose(r.ts[1:] - r.ts[:-1], r.hs, rtol=1e-12)
    slope_steps = np.polyfit(np.log(rtols), np.log(at_steps), 1)[0]
    slope_dense = np.polyfit(np.log(rtols), np.log(dense), 1)[0]
    assert 1.0 < slope_steps < 1.5, f"slope {slope_steps:.2f}, errors {at_steps}"
    assert 0.8 < slope_dense < 1.3, f"slope {slope_dense:.2f}, errors {dense}"


# ----------------------------------------------------------------------------- events
def _scipy_event(args):
    def g(t, y):
        return level_event(t, y, args)

    g.terminal, g.direction = True, -1
    return g


@pytest.mark.slow
def test_terminal_event_matches_solve_ivp_and_closed_form():
    rtol, atol, level = 1e-8, 1e-10, 0.5
    args = lin_args(K, level)
    r = run(lin_rhs, lin_jac, 0.0, 2.0, [0.0], rtol, atol, args, event=level_event)
    assert r.status == EVENT and r.ts[-1] == r.t_event
    # the truncated state is on the triggered side, within round-off of the level
    assert 0.0 <= r.ys[-1, 0] - level < 1e-12
    np.testing.assert_array_equal(r.dense(r.ts[-1:]), r.ys[-1:])
    # hs[-1] is the full step: t_event lies inside it
    assert 0.0 < (r.t_event - r.ts[-2]) / r.hs[-1] <= 1.0
    sp = scipy_run(lin_rhs, lin_jac, 0.0, 2.0, [0.0], rtol, atol, args, events=_scipy_event(args))
    assert sp.status == 1
    assert abs(r.t_event - sp.t_events[0][0]) < rtol * r.t_event
    exact = brentq(lambda t: lin_exact(t, K, 0.0, 0.0) - level, 0.0, 0.1, xtol=1e-15)
    slope = K * (math.cos(exact) - level)
    assert abs(r.t_event - exact) < 10.0 * (atol + rtol * level) / slope


def test_event_already_triggered_at_t0():
    r = run(lin_rhs, lin_jac, 0.0, 2.0, [0.6], 1e-6, 1e-9, lin_args(K, 0.5), event=level_event)
    assert r.status == EVENT and r.t_event == 0.0 and r.nsteps == 0
    assert r.ts.tolist() == [0.0] and r.ys.tolist() == [[0.6]]
    assert r.hs.shape == (0,) and r.Q.shape == (0, 1, 3)
    assert r.dense([0.0, 1.0]).tolist() == [[0.6], [0.6]]
    assert dense_eval1(r.ts, r.hs, r.ys, r.Q, 0.3, 0) == 0.6


def test_event_in_backward_integration():
    rtol, atol, level = 1e-8, 1e-10, 0.5
    args = lin_args(-K, level)
    r = run(lin_rhs, lin_jac, 2.0, 0.0, [0.0], rtol, atol, args, event=level_event)
    assert r.status == EVENT and r.ts[-1] == r.t_event and 0.0 < r.t_event < 2.0
    sp = scipy_run(lin_rhs, lin_jac, 2.0, 0.0, [0.0], rtol, atol, args, events=_scipy_event(args))
    assert abs(r.t_event - sp.t_events[0][0]) < rtol * r.t_event
    exact = brentq(lambda t: lin_exact(t, -K, 2.0, 0.0) - level, 0.5, 1.5, xtol=1e-15)
    assert abs(r.t_event - exact) < 1e-6


# ----------------------------------------------------------------------------- failure paths
@pytest.mark.slow
def test_blow_up_is_not_success():
    r = Result(*blow_up(2.0))
    assert r.status in (STEP_TOO_SMALL, NOT_FINITE), r.status
    assert 0.99 < r.ts[-1] < 1.01 and np.all(np.isfinite(r.ys))


def test_entry_point_is_cacheable():
    """An entry point that passes global jitted functions must leave no Python object
    address ("dynamic global") in its machine code: numba refuses to cache such code."""
    blow_up(0.5)
    (library,) = [c.library for c in blow_up.overloads.values()]
    assert not library.has_dynamic_globals


def test_non_finite_rhs_stops_with_not_finite():
    # fun is NaN beyond t = 0.3 whatever the step: step halving cannot cure it
    r = run(lin_rhs, lin_jac, 0.0, 1.0, [0.0], 1e-6, 1e-9, lin_args(K, poison=0.3))
    assert r.status == NOT_FINITE
    assert r.ts[-1] <= 0.3 and np.all(np.isfinite(r.ys)) and np.all(np.isfinite(r.Q))
    r = run(lin_rhs, lin_jac, 0.0, 1.0, [np.nan], 1e-6, 1e-9, lin_args(K))
    assert r.status == NOT_FINITE and r.nsteps == 0


def test_max_steps_first_step_and_empty_interval():
    r = run(lin_rhs, lin_jac, 0.0, 2.0, [0.0], 1e-6, 1e-9, lin_args(K), max_steps=5)
    assert r.status == MAX_STEPS and r.nsteps == 5 and len(r.ts) == 6 and r.ts[-1] < 2.0
    r = run(lin_rhs, lin_jac, 0.0, 2.0, [0.0], 1e-6, 1e-9, lin_args(K), first_step=1e-5)
    assert r.status == SUCCESS and r.hs[0] == 1e-5
    r = run(lin_rhs, lin_jac, 1.0, 1.0, [0.2], 1e-6, 1e-9, lin_args(K))
    assert r.status == SUCCESS and r.nsteps == 0 and r.ts.tolist() == [1.0]
    assert r.ys.tolist() == [[0.2]]
