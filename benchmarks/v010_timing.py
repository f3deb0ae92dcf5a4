"""Timing baseline of cosserat v0.1.0 (commit a3288e4), to run side by side with a new core.

Run against the *old* code only, from a separate checkout of v0.1.0 first on the path::

    git worktree add --detach /work/v010 a3288e4
    PYTHONPATH=/work/v010/src python benchmarks/v010_timing.py --json out.json

It imports nothing but v0.1.0's own API (``cosserat``, ``cosserat.analysis.thickness_curve``,
``cosserat.solvers.batch.wall_quantities``) and refuses to run if the imported ``cosserat`` is
not the old code: ``cosserat.__version__`` cannot tell (the rewrite also says "0.1.0" until the
version is bumped), so the test is that ``cosserat.solvers.radau_scalar`` (v0.1.0's pure-Python
Radau integrator) is importable. Machines are shared and noisy: only ratios measured in one run,
next to the new code's benchmark, mean anything.

What is timed (all on one core, numerical route, phi = 28.5 deg, L = 10, A = 1/3, K = 0.5):

1. one profile, for P1 (plane, identical walls delta = 20, B = 0), P2 (plane, upper wall
   delta = 20, lower wall fully rough, B = 0), P3 (plane under gravity, identical walls
   delta = 20, B = 1, nu = 1) and C1 (Couette, walls delta = 20, Ri = 1), at
   eps = 0.04, 1e-2, 1e-3, 1e-4, 1e-6:

   * ``cheap``: ``solve(problem, check=False, points=3, rtol=1e-8)``, timeit-style: the number
     of calls per repeat from ``timeit.Timer.autorange`` (>= 0.2 s), 5 repeats, the minimum of
     the per-call means (garbage collection off while timing, as timeit does);
   * ``full``: the default ``solve(problem)`` (rtol 1e-8, residual and boundary checks, 201
     points), one call;

2. the curve bench (as ``benchmarks/run.py`` section 3 of v0.1.0): Delta at 50 eps log-spaced
   from 1e-1 to 1e-6 for P1, P2, P3, C1, at rtol 1e-8 and 1e-6, by the scalar route
   (``thickness_curve``, what ``cosserat thickness`` on the command line runs, with continuation
   in eps for Couette) and by the batched engine (``wall_quantities`` on the 200 problems);
   the minimum over 3 repeats;

3. sweep throughput of ``wall_quantities`` (rtol 1e-8), the minimum over 2 repeats:

   * 1,000 plane cases, identical walls: delta in linspace(8, 25, 10) x K in
     (0, 0.25, 0.5, 0.75, 1) x B in (0, 1) x eps in geomspace(0.05, 1e-6, 10);
   * 200 Couette cases: delta in (10, 15, 20, 25) x Ri in (0.5, 1, 2, 5, 10) x eps in
     geomspace(0.05, 1e-6, 10).

``--serve`` instead answers timing requests, one JSON object a line on stdin, one a line on
stdout, so that ``benchmarks/run.py`` can interleave v0.1.0's timings with the new code's
(new, old, new, old, ...: a shared machine's load moves both alike). Requests::

    {"op": "profile", "case": "P1", "eps": 0.04, "kind": "cheap" | "full", "min_time": 0.2}
        -> {"seconds": per-call mean of one timeit run, "number": calls in it}
    {"op": "stats", "case": "P1", "eps": 0.04}
        -> {"stats": the diagnostics' statistics of the cheap solve}
    {"op": "curve", "route": "thickness_curve" | "wall_quantities", "rtol": 1e-8}
        -> {"seconds": one run, "solved": Delta found}
    {"op": "sweep", "plane": [[delta, eps, B], ...], "couette": [[delta, eps, Ri], ...]}
        -> {"seconds": one wall_quantities call, "status": {status: count}}
    {"op": "quit"}

The number of calls of a profile request is chosen by ``timeit.Timer.autorange`` on its first
request and kept for the later ones. Anything v0.1.0 prints goes to stderr.

Prints Markdown tables in the style of ``benchmarks/run.py``; ``--json`` writes
``{case: seconds}`` with the keys ``"P1/eps=0.04/cheap"``, ``"P1/eps=0.04/full"``, ...,
``"curve/thickness_curve/rtol=1e-08"``, ``"curve/wall_quantities/rtol=1e-08"``, ...,
``"sweep/wall_quantities/plane-1000"``, ``"sweep/wall_quantities/couette-200"`` (seconds per
call; for the sweeps, seconds for the whole batch, so cases per second = n / seconds).
"""

from __future__ import annotations

import argparse
import importlib
import itertools
import json
import os
import platform
import sys
import time
import timeit
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np

from cosserat import Cosserat, Couette, Plane, Problem

EPS = [0.04, 1e-2, 1e-3, 1e-4, 1e-6]
RTOL = 1e-8
CURVE_EPS = [float(e) for e in np.geomspace(1e-1, 1e-6, 50)]
SWEEP_EPS = [float(e) for e in np.geomspace(0.05, 1e-6, 10)]


def require_v010() -> Any:
    """Import cosserat and make sure it is v0.1.0's code (module docstring), or exit."""
    import cosserat

    where = Path(cosserat.__file__).resolve().parent
    try:
        importlib.import_module("cosserat.solvers.radau_scalar")
    except ImportError:
        sys.exit(
            f"refusing to run: the imported cosserat ({where}) has no "
            f"cosserat.solvers.radau_scalar, so it is not v0.1.0's code. Put a v0.1.0 checkout "
            f"first on the path: PYTHONPATH=/work/v010/src python {sys.argv[0]} ..."
        )
    if getattr(cosserat, "__version__", None) != "0.1.0":
        sys.exit(f"refusing to run: cosserat.__version__ = {cosserat.__version__!r}, not 0.1.0")
    return cosserat


def problems() -> dict[str, Any]:
    """P1, P2, P3, C1 at eps = 0.1 (the eps is replaced)."""
    from cosserat import Material, Wall

    mat = Material(phi=28.5)
    w20 = Wall(delta=20.0, K=0.5)
    return {
        "P1": Problem(Plane(eps=0.1), Cosserat(material=mat, wall=w20, lower=w20)),
        "P2": Problem(
            Plane(eps=0.1), Cosserat(material=mat, wall=w20, lower=Wall.fully_rough(K=0.5))
        ),
        "P3": Problem(Plane(eps=0.1, B=1.0, nu=1.0), Cosserat(material=mat, wall=w20, lower=w20)),
        "C1": Problem(Couette(eps=0.1, Ri=1.0), Cosserat(material=mat, wall=w20)),
    }


DESCRIPTION = {
    "P1": "plane, identical walls delta 20, B = 0",
    "P2": "plane, upper delta 20 / lower fully rough, B = 0",
    "P3": "plane, gravity B = 1, identical walls delta 20",
    "C1": "Couette, delta 20, Ri = 1",
}


def sweep_cases() -> tuple[list[Any], list[Any]]:
    from cosserat import Material, Wall

    mat = Material(phi=28.5)
    plane = [
        Problem(Plane(eps=e, B=b), Cosserat(material=mat, wall=Wall(delta=float(d), K=k)))
        for d, k, b, e in itertools.product(
            np.linspace(8.0, 25.0, 10), (0.0, 0.25, 0.5, 0.75, 1.0), (0.0, 1.0), SWEEP_EPS
        )
    ]
    couette = [
        Problem(Couette(eps=e, Ri=ri), Cosserat(material=mat, wall=Wall(delta=d, K=0.5)))
        for d, ri, e in itertools.product(
            (10.0, 15.0, 20.0, 25.0), (0.5, 1.0, 2.0, 5.0, 10.0), SWEEP_EPS
        )
    ]
    return plane, couette


def best_of(fn: Callable[[], object], repeat: int) -> tuple[float, object]:
    """Minimum wall time of ``repeat`` calls, and the last result."""
    best, out = float("inf"), None
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t)
    return best, out


def timeit_min(fn: Callable[[], object], repeat: int) -> tuple[float, int]:
    """timeit-style: autorange the number of calls, ``repeat`` repeats, min per-call mean."""
    timer = timeit.Timer(fn)
    number, _ = timer.autorange()
    return min(timer.repeat(repeat=repeat, number=number)) / number, number


def table(rows: list[list[str]], header: list[str]) -> str:
    widths = [max(len(str(r[i])) for r in [header, *rows]) for i in range(len(header))]
    lines = [
        "| " + " | ".join(h.ljust(w) for h, w in zip(header, widths, strict=True)) + " |",
        "|" + "|".join("-" * (w + 2) for w in widths) + "|",
    ]
    lines += [
        "| " + " | ".join(str(c).ljust(w) for c, w in zip(r, widths, strict=True)) + " |"
        for r in rows
    ]
    return "\n".join(lines)


def profiles(results: dict[str, float], repeat: int) -> None:
    from cosserat import solve

    print(
        f"\n## 1. One profile: solve(check=False, points=3, rtol={RTOL:g}) (timeit, min of "
        f"{repeat}) and the default solve(problem) (one call)\n"
    )
    rows = []
    for name, base in problems().items():
        for eps in EPS:
            p = replace(base, eps=eps)
            cheap, number = timeit_min(
                lambda p=p: solve(p, check=False, points=3, rtol=RTOL), repeat
            )
            t = time.perf_counter()
            solve(p)
            full = time.perf_counter() - t
            results[f"{name}/eps={eps:g}/cheap"] = cheap
            results[f"{name}/eps={eps:g}/full"] = full
            rows.append(
                [
                    name,
                    DESCRIPTION[name],
                    f"{eps:g}",
                    f"{cheap * 1e3:.2f}",
                    str(number),
                    f"{full * 1e3:.1f}",
                ]
            )
    print(
        table(
            rows,
            ["case", "problem", "eps", "cheap [ms]", "calls/repeat", "full solve() [ms]"],
        )
    )


def batched() -> Callable[..., list[Any]]:
    """v0.1.0's ``cosserat.solvers.batch.wall_quantities`` (imported alone: ruff sorts a
    ``cosserat.solvers`` import by the layout of the working tree, where it may be gone)."""
    from cosserat.solvers.batch import wall_quantities

    return wall_quantities


def curves(results: dict[str, float], repeat: int) -> None:
    from cosserat.analysis import thickness_curve

    wall_quantities = batched()
    print(
        f"\n## 2. Curve bench: Delta at 50 eps from 1e-1 to 1e-6, P1 P2 P3 C1 (min of {repeat})\n"
    )
    base = problems()
    everything = [replace(p, eps=e) for p in base.values() for e in CURVE_EPS]
    rows = []
    for rtol in (1e-8, 1e-6):
        t_scalar, curves_out = best_of(
            lambda r=rtol: [thickness_curve(p, CURVE_EPS, rtol=r) for p in base.values()], repeat
        )
        n_scalar = sum(d is not None for c in curves_out for d in c.Delta)  # type: ignore[attr-defined]
        t_batch, res = best_of(lambda r=rtol: wall_quantities(everything, rtol=r), repeat)
        n_batch = sum(r.status == "ok" for r in res)  # type: ignore[attr-defined]
        results[f"curve/thickness_curve/rtol={rtol:g}"] = t_scalar
        results[f"curve/wall_quantities/rtol={rtol:g}"] = t_batch
        rows.append(
            [f"{rtol:g}", f"{t_scalar:.2f}", f"{n_scalar}/200", f"{t_batch:.2f}", f"{n_batch}/200"]
        )
    print(
        table(
            rows,
            ["rtol", "thickness_curve x4 [s]", "solved", "wall_quantities (200) [s]", "solved"],
        )
    )


def sweeps(results: dict[str, float], repeat: int) -> None:
    wall_quantities = batched()
    print(f"\n## 3. Sweep throughput: wall_quantities, rtol {RTOL:g} (min of {repeat})\n")
    plane, couette = sweep_cases()
    rows = []
    for label, cases in (("plane", plane), ("couette", couette)):
        t, res = best_of(lambda c=cases: wall_quantities(c, rtol=RTOL), repeat)
        status = [r.status for r in res]  # type: ignore[attr-defined]
        counts = ", ".join(f"{status.count(s)} {s}" for s in sorted(set(status)))
        results[f"sweep/wall_quantities/{label}-{len(cases)}"] = t
        rows.append([label, str(len(cases)), f"{t:.2f}", f"{len(cases) / t:.0f}", counts])
    print(table(rows, ["geometry", "cases", "time [s]", "cases per second", "status"]))


def serve() -> None:
    """Answer timing requests on stdin/stdout (module docstring, ``--serve``)."""
    from cosserat import Material, Wall, solve
    from cosserat.analysis import thickness_curve

    wall_quantities = batched()
    out = os.fdopen(os.dup(sys.stdout.fileno()), "w", buffering=1)
    sys.stdout = sys.stderr  # keep the protocol channel clean
    base = problems()
    numbers: dict[tuple[str, float, str], int] = {}
    everything = [replace(p, eps=e) for p in base.values() for e in CURVE_EPS]
    mat = Material(phi=28.5)
    out.write(json.dumps({"ready": True, "where": str(Path(require_v010().__file__).parent)}))
    out.write("\n")
    for line in sys.stdin:
        req = json.loads(line)
        op = req.get("op")
        if op == "quit":
            break
        if op == "profile":
            p = replace(base[req["case"]], eps=float(req["eps"]))
            if req["kind"] == "cheap":
                fn = lambda p=p: solve(p, check=False, points=3, rtol=RTOL)  # noqa: E731
            else:
                fn = lambda p=p: solve(p)  # noqa: E731
            key = (req["case"], float(req["eps"]), req["kind"])
            timer = timeit.Timer(fn)
            if key not in numbers:
                fn()
                number, total = 1, 0.0
                while True:  # autorange to min_time
                    total = timer.timeit(number)
                    if total >= float(req.get("min_time", 0.2)):
                        break
                    number *= 2
                numbers[key] = number
                reply = {"seconds": total / number, "number": number}
            else:
                number = numbers[key]
                reply = {"seconds": timer.timeit(number) / number, "number": number}
        elif op == "stats":
            p = replace(base[req["case"]], eps=float(req["eps"]))
            stats = solve(p, check=False, points=3, rtol=RTOL).diagnostics.stats
            reply = {"stats": {k: v for k, v in stats.items() if isinstance(v, int | float)}}
        elif op == "curve":
            rtol = float(req["rtol"])
            t = time.perf_counter()
            if req["route"] == "thickness_curve":
                res = [thickness_curve(p, CURVE_EPS, rtol=rtol) for p in base.values()]
                solved = sum(d is not None for c in res for d in c.Delta)
            else:
                rows = wall_quantities(everything, rtol=rtol)
                solved = sum(r.status == "ok" for r in rows)
            reply = {"seconds": time.perf_counter() - t, "solved": solved}
        elif op == "sweep":
            cases = [
                Problem(Plane(eps=e, B=b), Cosserat(material=mat, wall=Wall(delta=d, K=0.5)))
                for d, e, b in req.get("plane", [])
            ] + [
                Problem(Couette(eps=e, Ri=ri), Cosserat(material=mat, wall=Wall(delta=d, K=0.5)))
                for d, e, ri in req.get("couette", [])
            ]
            t = time.perf_counter()
            rows = wall_quantities(cases, rtol=RTOL)
            seconds = time.perf_counter() - t
            status = [r.status for r in rows]
            reply = {"seconds": seconds, "status": {k: status.count(k) for k in set(status)}}
        else:
            reply = {"error": f"unknown op {op!r}"}
        out.write(json.dumps(reply) + "\n")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", metavar="PATH", help="write {case: seconds} here")
    parser.add_argument("--quick", action="store_true", help="one repeat each (smoke test)")
    parser.add_argument(
        "--serve", action="store_true", help="answer timing requests on stdin (for run.py)"
    )
    args = parser.parse_args()
    if args.serve:
        require_v010()
        serve()
        return
    cosserat = require_v010()
    import scipy

    repeat_profile, repeat_curve, repeat_sweep = (1, 1, 1) if args.quick else (5, 3, 2)
    print(
        f"# cosserat v0.1.0 timing baseline ({time.strftime('%Y-%m-%d %H:%M')}; "
        f"cosserat from {Path(cosserat.__file__).resolve().parent}; Python "
        f"{platform.python_version()}, NumPy {np.__version__}, SciPy {scipy.__version__}; "
        f"{os.cpu_count()} CPUs)"
    )
    results: dict[str, float] = {}
    t0 = time.perf_counter()
    profiles(results, repeat_profile)
    curves(results, repeat_curve)
    sweeps(results, repeat_sweep)
    print(f"\n(total {time.perf_counter() - t0:.0f} s)")
    if args.json:
        Path(args.json).write_text(json.dumps(results, indent=1) + "\n")


if __name__ == "__main__":
    main()
