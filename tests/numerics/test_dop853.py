"""The compiled DOP853 (quadrature pass) against SciPy's: same steps, dense output, events."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numba import njit
from scipy.integrate import solve_ivp

from cosserat.numerics.dop853 import dop853, dop853_eval1
from cosserat.numerics.radau import EVENT, MAX_STEPS, SUCCESS


@njit
def _rhs(t, y, args):
    """A pair like the spin pass: l' = rate(t), P' = exp(l) g(t)."""
    out = np.empty(2)
    out[0] = -args[0] * (1.0 + 0.5 * math.sin(3.0 * t))
    out[1] = math.exp(y[0]) * (1.0 + t * t)
    return out


@njit
def _threshold(t, y, args):
    return y[0] + args[1]


@njit
def _never(t, y, args):
    return 1.0


@njit
def _run(rtol, args, with_event):
    if with_event:
        return dop853(
            _rhs, _threshold, 0.0, 2.0, np.zeros(2), rtol, np.full(2, rtol * 1e-2), args, 10_000
        )
    return dop853(_rhs, _never, 0.0, 2.0, np.zeros(2), rtol, np.full(2, rtol * 1e-2), args, 10_000)


def _scipy(rtol, args):
    return solve_ivp(
        lambda t, y: _rhs(t, y, args), (0.0, 2.0), [0.0, 0.0], method="DOP853",
        rtol=rtol, atol=rtol * 1e-2, dense_output=True,
    )  # fmt: skip


@pytest.mark.slow
@pytest.mark.parametrize("rtol", [1e-4, 1e-8, 1e-11])
def test_same_steps_as_scipy(rtol):
    args = np.array([5.0, 3.0])
    status, ts, ys, _, nfev, nsteps = _run(rtol, args, False)
    ref = _scipy(rtol, args)
    assert status == SUCCESS
    assert nsteps == ref.t.size - 1
    # the error estimate cancels stage terms much larger than itself, so its round-off
    # (relative 1e-16 |K| / err, up to 1e-5 at rtol = 1e-11) moves the step sizes slightly
    np.testing.assert_allclose(ts, ref.t, rtol=1e-4)
    np.testing.assert_allclose(ys[-1], ref.y[:, -1], rtol=10 * rtol)
    assert nfev == ref.nfev  # the dense-output stages included, as SciPy counts them


def test_dense_output_matches_scipy_between_steps():
    args = np.array([5.0, 3.0])
    _, ts, ys, F, _, _ = _run(1e-8, args, False)
    ref = _scipy(1e-8, args)
    for t in np.linspace(0.0, 2.0, 97):
        for c in (0, 1):
            assert dop853_eval1(ts, ys, F, t, c) == pytest.approx(
                ref.sol(t)[c], rel=1e-9, abs=1e-13
            )


def test_dense_output_is_exact_for_the_closed_form():
    """l = -5 (t - cos(3t)/6 + 1/6) in closed form: the dense output error is tolerance-sized."""
    args = np.array([5.0, 3.0])
    _, ts, ys, F, _, _ = _run(1e-10, args, False)
    t = np.linspace(0.0, 2.0, 301)
    exact = -5.0 * (t - np.cos(3.0 * t) / 6.0 + 1.0 / 6.0)
    got = np.array([dop853_eval1(ts, ys, F, s, 0) for s in t])
    assert np.max(np.abs(got - exact)) < 1e-8


def test_terminal_event_keeps_the_step_it_fired_in():
    args = np.array([5.0, 3.0])
    status, ts, ys, _, _, _ = _run(1e-8, args, True)
    assert status == EVENT
    assert ys[-1, 0] <= -3.0 < ys[-2, 0]
    assert ts[-1] < 2.0


@pytest.mark.slow
def test_step_budget():
    @njit
    def run():
        return dop853(
            _rhs, _never, 0.0, 2.0, np.zeros(2), 1e-12, np.full(2, 1e-14), np.array([5.0, 3.0]), 3
        )

    status, ts, *_ = run()
    assert status == MAX_STEPS
    assert ts.size == 4
