"""Micro-benchmark of the compiled Radau IIA integrator: ``python benchmarks/bench_radau.py``.

One scalar stiff problem, y' = -(y - cos t) / 1e-3 on [0, 1], y(0) = 0, integrated by

* ``cosserat.numerics.radau.radau5`` called from Python through a cached ``@njit`` entry point
  (the production pattern: module-level right-hand side, Jacobian and entry point);
* the same kernel called in a compiled loop (the cost of the integration alone, without the
  Python call and the boxing of the returned arrays);
* ``scipy.integrate.solve_ivp(method="Radau")`` with the analytic Jacobian;
* v0.1.0's pure-Python ``cosserat.solvers.radau_scalar.radau_scalar`` (finite-difference
  Jacobian, as it always uses), which the compiled core replaced: loaded from a v0.1.0 checkout
  (``$COSSERAT_V010`` or /work/v010/src) under another package name, so that it sits beside the
  new ``cosserat``; its row is left out if there is no such checkout.

Prints, for a few tolerances, the accepted steps of each and the time per call and per step.
"""

from __future__ import annotations

import importlib
import math
import os
import sys
import time
import types
from collections.abc import Callable
from functools import partial

import numpy as np
from numba import njit
from scipy.integrate import solve_ivp

from cosserat.numerics.radau import no_event, radau5

EPS_STIFF = 1e-3
T_END = 1.0


@njit(cache=True)
def rhs(t: float, y: np.ndarray, args: np.ndarray) -> np.ndarray:
    return np.array([-(y[0] - math.cos(t)) / args[0]])


@njit(cache=True)
def jac(t: float, y: np.ndarray, args: np.ndarray) -> np.ndarray:
    return np.array([[-1.0 / args[0]]])


@njit(cache=True)
def solve(rtol: float, atol: float):  # type: ignore[no-untyped-def]
    """The production pattern: global jitted functions, so this entry point is cached."""
    args = np.array([EPS_STIFF])
    return radau5(
        rhs, jac, no_event, 0.0, T_END, np.zeros(1), rtol, np.array([atol]), args, 100_000, 0.0
    )


@njit(cache=True)
def solve_many(rtol: float, atol: float, repeats: int) -> float:
    s = 0.0
    for _ in range(repeats):
        s += solve(rtol, atol)[3][-1, 0]
    return s


def per_call(fn: Callable[[], object], budget: float = 0.5) -> float:
    """Best-of-5 mean time of one call [s], each batch sized to ``budget`` seconds."""
    fn()
    t = time.perf_counter()
    fn()
    once = max(time.perf_counter() - t, 1e-7)
    number = max(1, int(budget / 5 / once))
    best = math.inf
    for _ in range(5):
        t = time.perf_counter()
        for _ in range(number):
            fn()
        best = min(best, (time.perf_counter() - t) / number)
    return best


def v010_radau_scalar() -> Callable[..., object] | None:
    """v0.1.0's pure-Python radau_scalar, imported from a v0.1.0 checkout as ``cosserat_v010``.

    Only the modules it needs run (its package ``__init__`` files are replaced by empty
    modules), so nothing of the old package shadows the new one.
    """
    root = os.path.join(os.environ.get("COSSERAT_V010", "/work/v010/src"), "cosserat")
    if not os.path.isfile(os.path.join(root, "solvers", "radau_scalar.py")):
        return None
    for name, path in (("cosserat_v010", root), ("cosserat_v010.solvers", f"{root}/solvers")):
        if name not in sys.modules:
            module = types.ModuleType(name)
            module.__path__ = [path]
            sys.modules[name] = module
    try:
        return importlib.import_module("cosserat_v010.solvers.radau_scalar").radau_scalar  # type: ignore[no-any-return]
    except ImportError:
        return None


def main() -> None:
    t = time.perf_counter()
    solve(1e-6, 1e-8)
    solve_many(1e-6, 1e-8, 1)
    print(f"first calls (cache load or compilation): {time.perf_counter() - t:.2f} s")
    radau_scalar = v010_radau_scalar()
    if radau_scalar is None:
        print("no v0.1.0 checkout with radau_scalar ($COSSERAT_V010): its row is left out")

    def f_py(t: float, y: np.ndarray) -> np.ndarray:
        return -(y - math.cos(t)) / EPS_STIFF

    def j_py(t: float, y: np.ndarray) -> np.ndarray:
        return np.array([[-1.0 / EPS_STIFF]])

    def f_scalar(t: float, y: float) -> float:
        return -(y - math.cos(t)) / EPS_STIFF

    print(f"y' = -(y - cos t)/{EPS_STIFF:g} on [0, {T_END:g}], atol = rtol/100; time per call")
    header = f"{'method':34s} {'rtol':>6s} {'steps':>6s} {'us/call':>10s} {'us/step':>9s}"
    print(header)
    print("-" * len(header))
    for rtol in (1e-4, 1e-6, 1e-8):
        atol = rtol * 1e-2
        out = solve(rtol, atol)
        steps = int(out[9])
        reps = 200
        rows = [
            ("radau5, from Python (cached entry)", steps, per_call(partial(solve, rtol, atol))),
            ("radau5, compiled loop", steps, per_call(partial(solve_many, rtol, atol, reps))),
        ]
        ivp = partial(solve_ivp, f_py, (0.0, T_END), [0.0], method="Radau", rtol=rtol, atol=atol)
        sol = ivp(jac=j_py)
        rows.append(("solve_ivp(method='Radau')", len(sol.t) - 1, per_call(partial(ivp, jac=j_py))))
        if radau_scalar is not None:
            call = partial(radau_scalar, f_scalar, 0.0, T_END, 0.0, rtol, atol)
            rows.append(("radau_scalar (v0.1.0, pure Python)", call().steps, per_call(call)))
        rows[1] = (rows[1][0], steps, rows[1][2] / reps)
        for name, n_steps, sec in rows:
            us = sec * 1e6
            print(f"{name:34s} {rtol:6.0e} {n_steps:6d} {us:10.1f} {us / n_steps:9.2f}")
        assert out[1][-1] == T_END and abs(out[3][-1, 0] - sol.y[0, -1]) < 1e3 * atol
    hits, misses = dict(solve.stats.cache_hits), dict(solve.stats.cache_misses)
    print(f"solve() numba cache: hits {list(hits.values())}, misses {list(misses.values())}")


if __name__ == "__main__":
    main()
