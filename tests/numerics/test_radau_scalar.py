"""Radau IIA for one equation (:mod:`cosserat.numerics.radau_scalar`).

The scalar integrator is the general one (:func:`cosserat.numerics.radau.radau5`, tested
against SciPy and closed forms in ``test_radau.py``) written on floats: it must return the same
numbers to the last bit, on every path (steps, rejections, events, failures). Its sensitivity
(internal differentiation) is checked against closed forms and against SciPy's integration of
the variational equation at a much tighter tolerance.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numba import njit
from scipy.integrate import solve_ivp

from cosserat.numerics.radau import EVENT, NOT_FINITE, SUCCESS, dense_eval, no_event, radau5
from cosserat.numerics.radau_scalar import RADAU_A, radau5_scalar, sensitivity

K = 50.0


# ----------------------------------------------------------------------------- problems
@njit
def lin_f(t, y, args):
    """y' = -k (y - p cos t); args = (k, p, event level, t beyond which f is NaN)."""
    if t > args[3]:
        return np.nan
    return -args[0] * (y - args[1] * math.cos(t))


@njit
def lin_dfdy(t, y, args):
    return -args[0]


@njit
def lin_derivatives(t, y, args):
    """(df/dy, df/dp)."""
    return -args[0], args[0] * math.cos(t)


@njit
def lin_event(t, y, args):
    return args[2] - y


@njit
def lin_rhs(t, y, args):
    return np.array([lin_f(t, y[0], args)])


@njit
def lin_jac(t, y, args):
    return np.array([[lin_dfdy(t, y[0], args)]])


@njit
def lin_event_vec(t, y, args):
    return lin_event(t, y[0], args)


@njit
def no_event_scalar(t, y, args):
    return 1.0


@njit
def cubic_f(t, y, args):
    """y' = -k (y - p sin t) - y^3: nonlinear, stiff for large k."""
    return -args[0] * (y - args[1] * math.sin(t)) - y**3


@njit
def cubic_dfdy(t, y, args):
    return -args[0] - 3.0 * y * y


@njit
def cubic_dfdp(t, y, args):
    return args[0] * math.sin(t)


@njit
def cubic_derivatives(t, y, args):
    return cubic_dfdy(t, y, args), cubic_dfdp(t, y, args)


@njit
def cubic_rhs(t, y, args):
    return np.array([cubic_f(t, y[0], args)])


@njit
def cubic_jac(t, y, args):
    return np.array([[cubic_dfdy(t, y[0], args)]])


def args_of(k=K, p=1.0, level=np.inf, poison=np.inf):
    return np.array([k, p, level, poison])


def both(scalar_fns, vector_fns, t0, t1, y0, rtol, atol, args, max_steps=100_000, first=0.0):
    s = radau5_scalar(*scalar_fns, t0, t1, y0, rtol, atol, args, max_steps, first)
    v = radau5(*vector_fns, t0, t1, np.array([y0]), rtol, np.array([atol]), args, max_steps, first)
    return s, v


def assert_identical(s, v):
    status, ts, hs, ys, Q, Zs, t_event, nfev, nlu, nsteps = s
    v_status, v_ts, v_hs, v_ys, v_Q, v_t_event, v_nfev, _, v_nlu, v_nsteps = v
    assert (status, nfev, nlu, nsteps) == (v_status, v_nfev, v_nlu, v_nsteps)
    for a, b in ((ts, v_ts), (hs, v_hs), (ys, v_ys), (Q, v_Q)):
        assert a.shape == b.shape
        np.testing.assert_array_equal(a, b)
    assert (math.isnan(t_event) and math.isnan(v_t_event)) or t_event == v_t_event
    assert Zs.shape == (nsteps, 3)


LIN = (lin_f, lin_dfdy, no_event_scalar)
LIN_V = (lin_rhs, lin_jac, no_event)


# ----------------------------------------------------------------------------- identity
@pytest.mark.parametrize("rtol", [1e-3, 1e-6, 1e-9, 1e-12])
def test_same_steps_and_numbers_as_radau5(rtol):
    # forwards and backwards (stiff both ways: the sign of k follows the direction), through
    # more steps than the initial capacity at the tight tolerances
    assert_identical(*both(LIN, LIN_V, 0.0, 2.0, 0.3, rtol, rtol * 1e-3, args_of()))
    assert_identical(*both(LIN, LIN_V, 2.0, 0.0, 0.0, rtol, rtol * 1e-3, args_of(k=-K)))
    cubic = (cubic_f, cubic_dfdy, no_event_scalar)
    assert_identical(
        *both(cubic, (cubic_rhs, cubic_jac, no_event), 0.0, 3.0, 2.0, rtol, 1e-12, args_of(k=1e3))
    )


def test_same_event_first_step_and_failures_as_radau5():
    level = args_of(level=0.5)
    ev = (lin_f, lin_dfdy, lin_event)
    ev_v = (lin_rhs, lin_jac, lin_event_vec)
    s, v = both(ev, ev_v, 0.0, 2.0, 0.0, 1e-8, 1e-10, level)
    assert s[0] == EVENT
    assert_identical(s, v)
    assert_identical(*both(ev, ev_v, 0.0, 2.0, 0.6, 1e-6, 1e-9, level))  # triggered at t0
    assert_identical(*both(LIN, LIN_V, 0.0, 2.0, 0.0, 1e-6, 1e-9, args_of(), first=1e-5))
    assert_identical(*both(LIN, LIN_V, 0.0, 2.0, 0.0, 1e-6, 1e-9, args_of(), max_steps=5))
    s, v = both(LIN, LIN_V, 0.0, 1.0, 0.0, 1e-6, 1e-9, args_of(poison=0.3))
    assert s[0] == NOT_FINITE
    assert_identical(s, v)
    assert_identical(*both(LIN, LIN_V, 1.0, 1.0, 0.2, 1e-6, 1e-9, args_of()))


def test_stages_lie_on_the_dense_output():
    status, ts, hs, ys, Q, Zs, *_ = radau5_scalar(
        lin_f, lin_dfdy, no_event_scalar, 0.0, 2.0, 0.3, 1e-8, 1e-11, args_of(), 100_000, 0.0
    )
    assert status == SUCCESS
    c = np.array([(4.0 - 6.0**0.5) / 10.0, (4.0 + 6.0**0.5) / 10.0, 1.0])
    stage_t = (ts[:-1, None] + c[None, :] * hs[:, None]).ravel()
    on_dense = dense_eval(ts, hs, ys, Q, stage_t)[:, 0].reshape(Zs.shape)
    np.testing.assert_allclose(ys[:-1, 0, None] + Zs, on_dense, rtol=0.0, atol=1e-14)


def test_radau_matrix_is_the_eigen_decomposition_of_radau5():
    from cosserat.numerics.radau import MU_COMPLEX, MU_REAL, TI, T

    # T^-1 A^-1 T is the block form [[MU_REAL, 0, 0], [0, Re, -Im], [0, Im, Re]] of radau5
    block = TI @ np.linalg.inv(RADAU_A) @ T
    expected = np.array(
        [
            [MU_REAL, 0.0, 0.0],
            [0.0, MU_COMPLEX.real, -MU_COMPLEX.imag],
            [0.0, MU_COMPLEX.imag, MU_COMPLEX.real],
        ]
    )
    np.testing.assert_allclose(block, expected, atol=1e-12)


# ----------------------------------------------------------------------------- sensitivity
def _solve_with_sensitivity(f, dfdy, derivatives, t0, t1, y0, s0, rtol, args):
    status, ts, hs, ys, Q, Zs, *_ = radau5_scalar(
        f, dfdy, no_event_scalar, t0, t1, y0, rtol, rtol * 1e-3, args, 100_000, 0.0
    )
    assert status == SUCCESS
    ss, dQ = sensitivity(derivatives, args, ts, hs, ys, Zs, s0)
    return ts, hs, ys, Q, ss, dQ


def test_sensitivity_of_a_linear_problem_is_its_closed_form():
    # y' = -k (y - p cos t): dy/dp = s solves s' = -k (s - cos t), the same equation at p = 1
    # with s(0) = 0; and the discrete solution is linear in p, so it is exact on its steps
    k = K
    args = args_of(p=2.0)
    ts, hs, ys, Q, ss, dQ = _solve_with_sensitivity(
        lin_f, lin_dfdy, lin_derivatives, 0.0, 2.0, 0.0, 0.0, 1e-9, args
    )

    # closed form of s' = -k (s - cos t), s(0) = 0
    def s_exact(t):
        part = k * (k * np.cos(t) + np.sin(t)) / (k * k + 1.0)
        return part - (k * k / (k * k + 1.0)) * np.exp(-k * t)

    assert np.max(np.abs(ss[:, 0] - s_exact(ts))) < 1e-9  # observed 2.3e-11
    # y = p s for y(0) = 0: the sensitivity of the computed y is y/p to round-off
    np.testing.assert_allclose(ss[:, 0] * 2.0, ys[:, 0], rtol=1e-12, atol=1e-14)
    tt = np.linspace(0.0, 2.0, 777)
    np.testing.assert_allclose(
        2.0 * dense_eval(ts, hs, ss, dQ, tt)[:, 0], dense_eval(ts, hs, ys, Q, tt)[:, 0], atol=1e-13
    )


def test_sensitivity_of_a_nonlinear_stiff_problem_against_the_variational_equation():
    k, p = 1e3, 1.5
    args = args_of(k=k, p=p)

    def augmented(t, z):
        y, s = z
        return [cubic_f(t, y, args), cubic_dfdy(t, y, args) * s + cubic_dfdp(t, y, args)]

    ref = solve_ivp(augmented, (0.0, 3.0), [2.0, 0.0], method="Radau", rtol=1e-12, atol=1e-14,
                    dense_output=True)  # fmt: skip
    for rtol in (1e-6, 1e-9):
        ts, hs, ys, Q, ss, dQ = _solve_with_sensitivity(
            cubic_f, cubic_dfdy, cubic_derivatives, 0.0, 3.0, 2.0, 0.0, rtol, args
        )
        # the derivative of the computed solution is as accurate as the solution itself
        # (observed at the steps: 1.0e-6 against 1.5e-6 at rtol 1e-6, 2.8e-10 against 4.7e-10 at
        # 1e-9; on the dense output 2.9e-5 against 4.3e-5 and 7.5e-10 against 1.2e-9)
        err_y = np.max(np.abs(ys[:, 0] - ref.sol(ts)[0]))
        err_s = np.max(np.abs(ss[:, 0] - ref.sol(ts)[1]))
        assert err_s < 2.0 * err_y, (rtol, err_s, err_y)
        tt = np.linspace(0.0, 3.0, 501)
        dense_y = np.max(np.abs(dense_eval(ts, hs, ys, Q, tt)[:, 0] - ref.sol(tt)[0]))
        dense_s = np.max(np.abs(dense_eval(ts, hs, ss, dQ, tt)[:, 0] - ref.sol(tt)[1]))
        assert dense_s < 2.0 * dense_y, (rtol, dense_s, dense_y)
