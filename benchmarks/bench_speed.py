"""The speed targets of issue 17, item 5, measured side by side in one run.

    python benchmarks/bench_speed.py [--quick] [--sections 1,2,3,4] [--before SRC] [--out FILE]

Not tests: the machine is shared and its timings move by up to 2x, so what means something is a
ratio of two sides timed in turns (a, b, a, b, ...; the minimum per-call time of each side).
Each turn records wall time and the process's CPU time (``time.process_time``): on a loaded
machine the CPU time moves less, and sections 1 and 2 report the ratios of both.
Sections (the problems P1, P2, P3, C are those of ``benchmarks/run.py``):

1. Couette flow against a plain ``scipy.integrate.solve_bvp`` (crude start, tol 1e-6) at matched
   accuracy, measured as ``benchmarks/run.py`` section 3 does (its baselines and error measure):
   the baseline in turns with our runs at rtol 1e-6 ... 1e-10, the cheapest of ours at least as
   accurate compared. Target: >= 50x at eps 0.04 and 0.01 (eps 1e-3 and 1e-4 reported).
2. The default ``solve(p)`` against its compiled kernel alone (``solve_plane_case`` /
   ``solve_couette_case`` called from Python with the parameter vector), in turns; also
   ``solve(p)`` followed by reading its residuals (the check, computed when first read).
   Target: within 1.5x.
3. Predictions for a likelihood (``routes.numerical.predict_many``): time per problem, plane and
   Couette, batched and one by one, against ``solve(p, xi=x, check=False)``; the projected cost
   of a 10^4-sample posterior over three runs (two plane, one Couette: 3 x 10^4 predictions at
   30 points each); and what a prediction costs for mu(I) and NGF (their ``solve`` at 30 points).
   Target: 1e4 samples under 60 s on one core.
4. First-run compilation: processes with an empty ``NUMBA_CACHE_DIR`` (CPU and wall time):
   ``cosserat solve plane``, ``cosserat solve couette``, ``runtime.warm_up()``, and the test
   suite's first test that runs a kernel; with ``--before SRC`` the same for another source tree
   (e.g. the commit before this work), side by side.

Writes the tables to ``benchmarks/RESULTS_speed.md`` (``--out``; ``-`` for none).
"""

from __future__ import annotations

import argparse
import gc
import math
import os
import resource
import subprocess
import sys
import tempfile
import time
import timeit
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))

from run import (  # noqa: E402
    BASE,
    BASELINES,
    Report,
    git_commit,
    machine,
    ms,
    profile_error,
    table,
)

from cosserat import (  # noqa: E402
    Cosserat,
    Couette,
    Material,
    Plane,
    Problem,
    Wall,
    config,
    solve,
)
from cosserat.model.build import make_problem  # noqa: E402
from cosserat.numerics import cosserat as kernel  # noqa: E402
from cosserat.routes.numerical import (  # noqa: E402
    SCREEN_SLACK,
    parameter_vector,
    predict,
    predict_many,
)

RTOL = config.RTOL
ATOL = RTOL * config.ATOL_OVER_RTOL
OUR_RTOLS = [1e-6, 3e-7, 1e-7, 3e-8, 1e-8, 3e-9, 1e-9, 3e-10, 1e-10]


# ----------------------------------------------------------------- timing in turns
def _number(fn: Callable[[], object], min_time: float) -> int:
    fn()
    number = 1
    while timeit.Timer(fn).timeit(number) < min_time:
        number *= 2
    return number


def _timed(fn: Callable[[], object], number: int) -> tuple[float, float]:
    """(wall, CPU) seconds per call of ``number`` calls, the garbage collector off (as timeit)."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        w, c = time.perf_counter(), time.process_time()
        for _ in range(number):
            fn()
        return (time.perf_counter() - w) / number, (time.process_time() - c) / number
    finally:
        if enabled:
            gc.enable()


CPU: dict[str, float] = {}
"""The CPU time per call of the last :func:`in_turns` (its minimum over the rounds)."""


def in_turns(
    fns: dict[str, Callable[[], object]], rounds: int, min_time: float
) -> dict[str, float]:
    """Minimum per-call wall time of each function, timed in turns (a, b, c, a, b, c, ...);
    the minimum CPU time per call of each is left in :data:`CPU`."""
    numbers = {k: _number(fn, min_time) for k, fn in fns.items()}
    best = dict.fromkeys(fns, math.inf)
    CPU.clear()
    CPU.update(dict.fromkeys(fns, math.inf))
    for _ in range(rounds):
        for k, fn in fns.items():
            wall, cpu = _timed(fn, numbers[k])
            best[k] = min(best[k], wall)
            CPU[k] = min(CPU[k], cpu)
    return best


def with_eps(problem: Problem, eps: float) -> Problem:
    return problem.with_values({"eps": eps})


def kernel_call(problem: Any, rtol: float = RTOL) -> Callable[[], object]:
    """The compiled kernel alone at ``rtol``, called from Python with a prebuilt vector."""
    p = parameter_vector(problem)
    entry = kernel.solve_couette_case if problem.cell_name == "couette" else kernel.solve_plane_case
    atol = rtol * config.ATOL_OVER_RTOL
    return lambda: entry(p, rtol, atol, config.DEFAULT_F, config.MAX_STEPS)


def kernel_and_fields_call(problem: Any, rtol: float = RTOL) -> Callable[[], object]:
    """The kernel, then the fields and the profile's screen at the default output grid
    (``fields_checked``): what any solve returning a profile must compute, in two compiled
    calls from Python, with no Python in between (a second measure of section 2)."""
    p = parameter_vector(problem)
    entry = kernel.solve_couette_case if problem.cell_name == "couette" else kernel.solve_plane_case
    atol = rtol * config.ATOL_OVER_RTOL
    grid = solve(problem).xi.copy()
    slack = SCREEN_SLACK

    def call() -> object:
        _, info, cs, sp, g = entry(p, rtol, atol, config.DEFAULT_F, config.MAX_STEPS)
        return kernel.fields_checked(grid, p, info, *cs, g, *sp, slack)

    return call


# ----------------------------------------------------------------- 1. Couette vs solve_bvp
def against_solve_bvp(rep: Report, rounds: int, min_time: float, eps_list: list[float]) -> None:
    rep.out("\n## 1. Couette flow against a plain solve_bvp at matched accuracy\n")
    rep.out(
        "C = Couette, delta 20, Ri = 1. Baselines of `benchmarks/run.py` section 3 (crude "
        "start: uniform 101-point mesh, uniform shear, m = 0 or the leading-order outer m, "
        "tol = 1e-6, SciPy's default max_nodes); error: max of |du|, |d omega|/max|omega|, "
        "|dm| on 2001 points against the package at rtol 1e-12. Ours: `solve(p, rtol=r, xi=xi, "
        "check=False)` on the same 2001 points at r = 1e-6, 3e-7, 1e-7, ... 1e-10 (half "
        "decades; `run.py` has whole ones); the cheapest at least as accurate as the baseline "
        f"is compared. Baseline and ours timed in turns, {rounds} "
        "rounds, minimum per call, in wall time and in CPU time (each side's cheapest matched "
        "run by that clock); the kernel's share is the CPU time of the kernel alone at our "
        "rtol over that of our call (the rest: the 2001 output points and the Python around "
        "them).\n"
    )
    rows, target = [], {}
    for eps in eps_list:
        problem = with_eps(BASE["C"], eps)
        ref = solve(problem, rtol=1e-12, points=2001, check=False)
        xi = ref.xi
        ours = {
            r: (lambda r=r, p=problem, x=xi: solve(p, rtol=r, xi=x, check=False)) for r in OUR_RTOLS
        }
        errors = {r: profile_error(fn().evaluate(xi)._asdict(), ref) for r, fn in ours.items()}
        for label, fn_b, is_user in BASELINES["C"]:
            if not is_user:
                continue
            res = fn_b(problem, 1e-6, xi=xi)
            if not res["success"]:
                reason = res["message"].split(";")[0].replace("solve_bvp status ", "status ")
                rows.append([f"{eps:g}", label, "FAILS: " + reason[:50], *["-"] * 9])
                continue
            err_b = profile_error(res, ref)
            good = [r for r in OUR_RTOLS if errors[r] <= err_b]
            fns = {"baseline": lambda f=fn_b, p=problem, x=xi: f(p, 1e-6, xi=x)}
            fns.update({f"ours {r:g}": ours[r] for r in (good or OUR_RTOLS)})
            times = in_turns(fns, rounds, min_time)
            cpu = dict(CPU)
            pick = min(good or OUR_RTOLS, key=lambda r: times[f"ours {r:g}"])
            pick_cpu = min(good or OUR_RTOLS, key=lambda r: cpu[f"ours {r:g}"])
            t_ours, t_b = times[f"ours {pick:g}"], times["baseline"]
            c_ours, c_b = cpu[f"ours {pick_cpu:g}"], cpu["baseline"]
            ratio, ratio_cpu = t_b / t_ours, c_b / c_ours
            # where our call's time goes: the kernel alone at the same rtol, in turns with it
            in_turns(
                {"ours": ours[pick_cpu], "kernel": kernel_call(problem, pick_cpu)},
                rounds,
                min_time,
            )
            share = CPU["kernel"] / CPU["ours"]
            rows.append(
                [
                    f"{eps:g}",
                    label,
                    f"{err_b:.1e}",
                    ms(t_b),
                    ms(c_b),
                    f"{pick:g}" + ("" if good else " (not matched)"),
                    f"{errors[pick]:.1e}",
                    ms(t_ours),
                    ms(c_ours) + ("" if pick_cpu == pick else f" (rtol {pick_cpu:g})"),
                    f"{ratio:.0f}",
                    f"{ratio_cpu:.0f}",
                    f"{share:.0%}",
                ]
            )
            target.setdefault(eps, []).append((ratio, ratio_cpu) if good else (0.0, 0.0))
    rep.table(
        rows,
        ["eps", "baseline", "its error", "its wall [ms]", "its CPU [ms]", "our rtol",
         "our error", "our wall [ms]", "our CPU [ms]", "ratio (wall)", "ratio (CPU)",
         "kernel's share (CPU)"],
    )  # fmt: skip
    wall_met = all(min(r[0] for r in target.get(e, [(0.0, 0.0)])) >= 50.0 for e in (0.04, 0.01))
    cpu_met = all(min(r[1] for r in target.get(e, [(0.0, 0.0)])) >= 50.0 for e in (0.04, 0.01))
    rep.target(
        ">= 50x faster than plain solve_bvp (crude start, tol 1e-6), Couette, at matched "
        "accuracy, eps 0.04 and 0.01",
        "; ".join(
            f"eps {e:g}: {min(x[0] for x in r):.0f}x wall, {min(x[1] for x in r):.0f}x CPU"
            for e, r in target.items()
        ),
        *_verdict(wall_met, cpu_met),
    )


def _verdict(wall_met: bool, cpu_met: bool) -> tuple[bool, str]:
    """(met, note) for ``Report.target``: met only if met by both clocks; the note says which
    clock meets it when only one does."""
    if wall_met == cpu_met:
        return wall_met, ""
    return False, "(met in " + ("wall" if wall_met else "CPU") + " time only)"


# ----------------------------------------------------------------- 2. solve() vs kernel
def solve_against_kernel(rep: Report, rounds: int, min_time: float, eps_list: list[float]) -> None:
    rep.out("\n## 2. The default solve(p) against its compiled kernel\n")
    rep.out(
        "Per call, in turns: the kernel alone (`solve_plane_case` / `solve_couette_case` from "
        "Python, the parameter vector built once), the default `solve(p)` (rtol 1e-8, 201 "
        "points, its checks; boundary errors and the residual check deferred until read), "
        "`solve(p)` and reading a field (`.u`: the fields' arrays and the diagnostics are "
        "made when first read), `solve(p)` with its residuals read (the check on 801 points, "
        "6,400 quadrature nodes), "
        "and the default solve of a new problem each call (`solve(Problem(cell, rheology))` "
        "less the time to make the problem: what the per-problem parameter vector and output "
        f"grid cost when they are made). {rounds} rounds, minimum per call; ratios to the "
        "kernel in wall time and (in brackets) in CPU time. A second measure, not the "
        "target's: the kernel followed by the fields at the 201 output points "
        "(`fields_checked`, the compiled evaluation with the profile's screen), which any "
        "solve returning a profile must compute, and the ratio of `solve(p)` to it.\n"
    )
    rows, ratios, with_check, fresh, second, read = [], [], [], [], [], []
    for name, base in BASE.items():
        for eps in eps_list:
            problem = with_eps(base, eps)
            cell, law = problem.cell, problem.rheology
            times = in_turns(
                {
                    "kernel": kernel_call(problem),
                    "kernel+fields": kernel_and_fields_call(problem),
                    "solve": lambda p=problem: solve(p),
                    "read u": lambda p=problem: solve(p).u,
                    "checked": lambda p=problem: solve(p).diagnostics.residuals["spin"],
                    "new": lambda c=cell, r=law: solve(Problem(c, r)),
                    "make": lambda c=cell, r=law: Problem(c, r),
                },
                rounds,
                min_time,
            )
            cpu = dict(CPU)
            k, kc = times["kernel"], cpu["kernel"]
            r1, r1c = times["solve"] / k, cpu["solve"] / kc
            r2, r2c = times["checked"] / k, cpu["checked"] / kc
            t_new, c_new = times["new"] - times["make"], cpu["new"] - cpu["make"]
            ratios.append((r1, r1c, name, eps))
            read.append(cpu["read u"] / kc)
            with_check.append(r2)
            fresh.append(c_new / kc)
            kf, kfc = times["kernel+fields"], cpu["kernel+fields"]
            r3, r3c = times["solve"] / kf, cpu["solve"] / kfc
            second.append((r3, r3c, name))
            rows.append(
                [name, f"{eps:g}", f"{k * 1e6:.0f} ({kc * 1e6:.0f})",
                 f"{times['solve'] * 1e6:.0f} ({cpu['solve'] * 1e6:.0f})",
                 f"{r1:.2f} ({r1c:.2f})",
                 f"{times['read u'] * 1e6:.0f} ({cpu['read u'] * 1e6:.0f})",
                 f"{times['read u'] / k:.2f} ({cpu['read u'] / kc:.2f})",
                 f"{times['checked'] * 1e6:.0f}", f"{r2:.1f} ({r2c:.1f})",
                 f"{t_new * 1e6:.0f} ({c_new * 1e6:.0f})",
                 f"{t_new / k:.2f} ({c_new / kc:.2f})",
                 f"{kf * 1e6:.0f} ({kfc * 1e6:.0f})", f"{r3:.2f} ({r3c:.2f})"]
            )  # fmt: skip
    rep.table(
        rows,
        ["case", "eps", "kernel [us]", "solve(p) [us]", "ratio", "solve(p).u [us]", "ratio",
         "solve + residuals [us]",
         "ratio", "solve(new p) [us]", "ratio", "kernel + fields [us]",
         "solve(p) / (kernel + fields)"],
    )  # fmt: skip

    def span(n: str, i: int) -> str:
        values = [r[i] for r in ratios if r[2] == n]
        return f"{min(values):.1f}-{max(values):.1f}x"

    per_case = ", ".join(f"{n} {span(n, 0)}" for n in BASE)
    per_case_cpu = ", ".join(f"{n} {span(n, 1)}" for n in BASE)

    def span2(n: str) -> str:
        values = [r[1] for r in second if r[2] == n]
        return f"{min(values):.2f}-{max(values):.2f}x"

    second_cpu = ", ".join(f"{n} {span2(n)}" for n in BASE)
    rep.target(
        "the default `solve(p)` within 1.5x of its compiled kernel",
        f"wall: {per_case}; CPU: {per_case_cpu} (reading u as well, CPU: "
        f"{min(read):.2f}-{max(read):.2f}x; a new problem each call, CPU: "
        f"{min(fresh):.1f}-{max(fresh):.1f}x; with the residuals read, wall: "
        f"{min(with_check):.1f}-{max(with_check):.1f}x; second measure, not the target's: "
        f"solve(p) over the kernel and its 201-point evaluation, CPU: {second_cpu})",
        *_verdict(max(r[0] for r in ratios) <= 1.5, max(r[1] for r in ratios) <= 1.5),
    )


# ----------------------------------------------------------------- 3. predictions
def _trio(delta: float, K: float) -> list[Any]:
    """A calibration's three runs of one material: two plane-shear gaps, one Couette cell."""
    mat = Material(phi=28.5)
    wall = Wall(delta=delta, K=K)
    plane = Cosserat(material=mat, wall=wall, lower=Wall.fully_rough(K=K))
    return [
        Problem(Plane(eps=0.05), plane),
        Problem(Plane(eps=0.025), plane),
        Problem(Couette(eps=0.05, Ri=2.0), Cosserat(material=mat, wall=wall)),
    ]


def predictions(rep: Report, rounds: int, min_time: float, walkers: int) -> None:
    rep.out("\n## 3. Predictions for a likelihood\n")
    rng = np.random.default_rng(2026)
    points = [np.sort(rng.uniform(0.0, 1.0, 30)) for _ in range(3)]
    sets = [
        _trio(float(d), float(k))
        for d, k in zip(rng.uniform(15.0, 25.0, walkers), rng.uniform(0.3, 1.0, walkers),
                        strict=True)
    ]  # fmt: skip
    problems = [p for trio in sets for p in trio]
    xs = points * walkers
    rep.out(
        f"{walkers} walkers x 3 runs of one material (plane eps 0.05 and 0.025 with a fully "
        "rough lower wall, Couette eps 0.05, Ri 2; delta ~ U(15, 25), K ~ U(0.3, 1)), 30 data "
        "points per run; fields u, omega, sigma_yx, sigma_yy. `predict_many` on all "
        f"{len(problems)} problems in one call, on each cell's {walkers}, `predict` one problem "
        "at a time, and `solve(p, xi=x, check=False)` (a Profile at the same points), in turns.\n"
    )
    results = predict_many(problems, xs)
    worst = 0.0
    for p, x, r in zip(problems[:30], xs[:30], results[:30], strict=True):
        f = solve(p).evaluate(x)
        for name, v in r.values.items():
            worst = max(worst, float(np.max(np.abs(v - getattr(f, name)))))
    n_ok = sum(r.status == "ok" for r in results)
    times = in_turns(
        {
            "batched": lambda: predict_many(problems, xs),
            "plane eps 0.05": lambda: predict_many(problems[0::3], xs[0::3]),
            "plane eps 0.025": lambda: predict_many(problems[1::3], xs[1::3]),
            "couette": lambda: predict_many(problems[2::3], xs[2::3]),
            "one by one": lambda: [predict(p, x) for p, x in zip(problems, xs, strict=True)],
            "solve": lambda: [
                solve(p, xi=x, check=False) for p, x in zip(problems, xs, strict=True)
            ],
        },
        rounds,
        min_time,
    )
    cpu = dict(CPU)
    n = len(problems)

    def per(key: str, count: int) -> str:
        return f"{times[key] / count * 1e6:.0f} ({cpu[key] / count * 1e6:.0f})"

    rows = [
        ["predict_many, all runs", per("batched", n)],
        ["predict_many, plane eps 0.05", per("plane eps 0.05", walkers)],
        ["predict_many, plane eps 0.025", per("plane eps 0.025", walkers)],
        ["predict_many, Couette", per("couette", walkers)],
        ["predict, one problem per call", per("one by one", n)],
        ["solve(p, xi=x, check=False)", per("solve", n)],
    ]
    rep.table(rows, ["call", "per problem [us]: wall (CPU)"])
    per_sample, per_sample_cpu = times["batched"] / walkers, cpu["batched"] / walkers
    projected, projected_cpu = 1e4 * per_sample, 1e4 * per_sample_cpu
    rep.out(
        f"\n{n_ok} of {n} predictions ok; largest difference from `solve(p).evaluate(x)` over "
        f"the first 30: {worst:.1e}. Per sample of the three runs: {per_sample * 1e3:.2f} ms "
        f"of wall time ({per_sample_cpu * 1e3:.2f} ms of CPU), so a 10^4-sample posterior needs "
        f"{projected:.1f} s of predictions on one core ({projected_cpu:.1f} s of CPU).\n"
    )
    rep.target(
        "1e4-sample posterior of three runs (two plane, one Couette) < 60 s on one core "
        "(the predictions)",
        f"{per_sample * 1e3:.2f} ms per sample of three runs -> {projected:.1f} s wall, "
        f"{projected_cpu:.1f} s CPU (predict_many, 30 points per run)",
        *_verdict(projected < 60.0, projected_cpu < 60.0),
    )
    # the other rheologies: what a prediction costs through solve()
    rows = []
    x30 = points[0]
    for model in ("cosserat", "mui", "ngf"):
        for cell, params in (("plane", {"eps": 0.05}), ("couette", {"eps": 0.05, "Ri": 2.0})):
            problem = make_problem(model, cell, params)
            t = in_turns(
                {"solve": lambda p=problem: solve(p, xi=x30, check=False).u}, rounds, min_time
            )["solve"]
            rows.append([model, cell, f"{t * 1e6:.0f}"])
    rep.out("What one prediction costs by `solve(p, xi=x30, check=False)`, per model and cell:\n")
    rep.table(rows, ["model", "cell", "per problem [us]"])


# ----------------------------------------------------------------- 4. compilation
FIRST_KERNEL_TEST = "tests/test_asymptotic.py::test_asymptotic_error_shrinks_at_the_predicted_rate"


def _process(cmd: list[str], src: Path, cwd: Path) -> tuple[float, float]:
    """(CPU seconds, wall seconds) of a process with an empty NUMBA_CACHE_DIR."""
    with tempfile.TemporaryDirectory(prefix="numba-cache-") as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache, PYTHONPATH=str(src))
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t = time.perf_counter()
        subprocess.run(
            cmd, env=env, cwd=cwd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
        )
        wall = time.perf_counter() - t
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, wall


def compilation(rep: Report, before: Path | None) -> None:
    rep.out("\n## 4. First-run compilation (an empty numba cache)\n")
    py = sys.executable
    commands = {
        "`cosserat solve plane --eps 1e-3`": [py, "-m", "cosserat", "solve", "plane", "--eps",
                                               "1e-3"],
        "`cosserat solve couette --eps 1e-3`": [py, "-m", "cosserat", "solve", "couette",
                                                 "--eps", "1e-3"],
        "`runtime.warm_up()` (every batch entry point)": [
            py, "-c", "from cosserat.numerics.runtime import warm_up; warm_up()"
        ],
        # -n 0: one process (pyproject's addopts run -n auto: on a cold cache every
        # xdist worker compiles the same kernels)
        "the test suite's first kernel test": [py, "-m", "pytest", "-q", "-x", "-n", "0",
                                               "-p", "no:cacheprovider", FIRST_KERNEL_TEST],
    }  # fmt: skip
    trees = {"this tree": ROOT / "src"}
    if before is not None:
        trees = {"before": before, **trees}
    rep.out(
        "CPU time (user + system) and wall time of whole processes, each with a new empty "
        "`NUMBA_CACHE_DIR`, so numba compiles every kernel the command calls"
        + (f"; 'before' is `{before}`" if before is not None else "")
        + f". The test is `{FIRST_KERNEL_TEST}` (its file's tests come first in the suite "
        "and it is the first to run the numerical kernel).\n"
    )
    rows = []
    for what, cmd in commands.items():
        row = [what]
        for src in trees.values():
            cpu, wall = _process(cmd, src, ROOT)
            row += [f"{cpu:.1f}", f"{wall:.1f}"]
        rows.append(row)
    header = ["process"]
    for name in trees:
        header += [f"{name}: CPU [s]", f"{name}: wall [s]"]
    rep.table(rows, header)
    measured = "; ".join(
        f"{r[0]}: " + " -> ".join(r[i] for i in range(1, len(r), 2)) + " s CPU" for r in rows
    )
    rep.target("first-run compile time, measured and cut (report before/after)", measured, None)


# ----------------------------------------------------------------- main
def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer rounds, fewer cases")
    parser.add_argument("--no-compile", action="store_true", help="skip section 4")
    parser.add_argument("--sections", default="1,2,3,4", help="which sections, e.g. 1,3")
    parser.add_argument("--before", default=None, help="another src folder for section 4")
    parser.add_argument("--out", default=str(HERE / "RESULTS_speed.md"), help="'-': none")
    args = parser.parse_args()
    rounds = 3 if args.quick else 5
    min_time = 0.05 if args.quick else 0.1
    rep = Report()
    import numba
    import scipy

    load0 = os.getloadavg()[0]
    t0 = time.perf_counter()
    command = "python benchmarks/bench_speed.py" + "".join(f" {a}" for a in sys.argv[1:])
    rep.out(
        f"# cosserat speed benchmarks (issue 17, item 5)\n\n`{command}`, "
        f"{time.strftime('%Y-%m-%d %H:%M %Z')}, commit {git_commit()}; {machine()}; NumPy "
        f"{np.__version__}, SciPy {scipy.__version__}, numba {numba.__version__}; load average "
        f"at the start {load0:.1f}."
    )
    sections = {s.strip() for s in args.sections.split(",")}
    if args.no_compile:
        sections.discard("4")
    rep.out(f"Sections run: {', '.join(sorted(sections))}.")
    eps_bvp = [0.04, 0.01] if args.quick else [0.04, 0.01, 1e-3, 1e-4]
    if "1" in sections:
        against_solve_bvp(rep, rounds, min_time, eps_bvp)
    if "2" in sections:
        solve_against_kernel(
            rep, rounds, min_time, [0.04, 1e-3] if args.quick else [0.04, 1e-2, 1e-3, 1e-4]
        )
    if "3" in sections:
        predictions(rep, rounds, min_time, 30 if args.quick else 100)
    if "4" in sections:
        compilation(rep, Path(args.before) if args.before else None)
    rep.out(
        f"\n(total {time.perf_counter() - t0:.0f} s; load average at the end "
        f"{os.getloadavg()[0]:.1f})"
    )
    summary = table(rep.targets, ["target (issue 17, item 5)", "measured in this run", "status"])
    print("\n## Targets\n\n" + summary)
    if args.out != "-":
        head, rest = rep.lines[0], rep.lines[1:]
        Path(args.out).write_text("\n".join([head, "\n## Targets\n", summary, *rest]) + "\n")
        print(f"\nwrote {args.out}")


if __name__ == "__main__":
    main()
