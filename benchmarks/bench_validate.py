"""``cosserat validate`` on the shipped corpus: wall time with one process and with two, side by
side in one run, and the CPU seconds of its stages (issue 18, item 8: under 60 s on two cores).

Run: ``python benchmarks/bench_validate.py [--repeat N] [--corpus DIR] [--workers 1,2]``
(``--corpus``: another corpus folder, e.g. the five quasi-static v2 runs; default the shipped
one, what ``.ci/run``'s release check validates). The kernels are compiled (or loaded from
numba's cache) by a first call that is not timed; each timed call writes its report into a
fresh temporary folder. Prints one JSON object: the wall seconds and the CPU seconds (this
process and its workers) of every call, and the machine's load before and after.

``--stages``: instead, validate in one process (``workers=1``), with the CPU seconds of each
stage (the runs' fits, the material calibrations, the spin scans and their parts, judging, the
figures, the report's text); each stage is timed where it is called, so the stages nest (the
mu(I) solves are inside the fits and the calibrations) and are listed as they nest. Each
repeat times the shipped code and then the same run with the mu(I) plane quadrature done by
SciPy's ``quad_vec`` (the code before ``numerics.mui.plane_pieces``; its integrals are the
same to the last bit, so both runs compute the same report), side by side: the ratio
old/new of each stage is printed. The CPU seconds of two workers are about the sum of the
stages' over two; the longest job bounds the wall time from below.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import tempfile
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

STAGES = [
    # (stage, module, attribute): timed where the module's code calls it
    ("runs: analyse_run (fits, measures, run figures)", "cosserat.studies.validate.study",
     "analyse_run"),
    ("runs: u-only fits (try_fit_run)", "cosserat.studies.validate.study", "try_fit_run"),
    ("material calibrations (material_job)", "cosserat.studies.validate.study", "material_job"),
    ("judge (series, scans, verdicts)", "cosserat.studies.validate.study", "judge"),
    ("scans: joint fits and grids (spin_scans)", "cosserat.studies.validate.study",
     "spin_scans"),
    ("scans: wall check, held-K refits (check_scans)", "cosserat.studies.validate.study",
     "check_scans"),
    ("scans: joint nulls (joint_null)", "cosserat.studies.validate.study", "joint_null"),
    ("report: every figure (write_figures)", "cosserat.studies.validate.report",
     "write_figures"),
    ("report: a run's figure (write_run_figure)", "cosserat.studies.validate.report",
     "write_run_figure"),
    ("report: md, html, json (write_templates)", "cosserat.studies.validate.report",
     "write_templates"),
    ("mu(I) solves (routes.mui._profile)", "cosserat.routes.mui", "_profile"),
]  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=2, help="timed calls per setting")
    parser.add_argument("--corpus", default=None, help="corpus folder (default: the shipped one)")
    parser.add_argument("--workers", default="1,2", help="worker counts to time, comma-separated")
    parser.add_argument("--stages", action="store_true", help="stage CPU times, old vs new")
    args = parser.parse_args()
    if args.stages:
        stages(args.corpus, args.repeat)
        return
    settings = [int(w) for w in args.workers.split(",") if w.strip()]

    from cosserat.studies.validate import validate

    load_before = os.getloadavg()
    with tempfile.TemporaryDirectory() as tmp:
        validate(args.corpus, Path(tmp) / "warm", workers=1)  # compile or load, not timed
        seconds: dict[str, list[float]] = {f"workers={w}": [] for w in settings}
        cpu: dict[str, list[float]] = {f"workers={w}": [] for w in settings}
        for k in range(args.repeat):
            for workers in settings:  # interleaved: every setting sees the same machine
                before = _cpu()
                start = time.perf_counter()
                validate(args.corpus, Path(tmp) / f"w{workers}_{k}", workers=workers)
                seconds[f"workers={workers}"].append(round(time.perf_counter() - start, 2))
                cpu[f"workers={workers}"].append(round(_cpu() - before, 2))
    print(
        json.dumps(
            {
                "corpus": args.corpus or "shipped",
                "seconds": seconds,
                "cpu_seconds": cpu,
                "load_average_before": load_before,
                "load_average_after": os.getloadavg(),
            },
            indent=1,
        )
    )


def _cpu() -> float:
    """CPU seconds of this process and its ended children (the pool's workers) [s]: on a
    busy machine the wall time overstates what validate costs, this does not."""
    own = resource.getrusage(resource.RUSAGE_SELF)
    kids = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + kids.ru_utime + kids.ru_stime


@contextmanager
def _timed(totals: dict[str, float]) -> Iterator[None]:
    """Wrap every attribute of :data:`STAGES` so that its calls add their CPU seconds to
    ``totals`` (a call inside a call of the same stage is not counted twice)."""
    import importlib

    saved: list[tuple[Any, str, Any]] = []
    for stage, module, name in STAGES:
        mod = importlib.import_module(module)
        fn = getattr(mod, name)
        saved.append((mod, name, fn))
        setattr(mod, name, _wrap(fn, stage, totals, [0]))
    try:
        yield
    finally:
        for mod, name, fn in saved:
            setattr(mod, name, fn)


def _wrap(fn: Callable[..., Any], stage: str, totals: dict[str, float], depth: list[int]):
    def timed(*args: Any, **kwargs: Any) -> Any:
        depth[0] += 1
        start = time.process_time()
        try:
            return fn(*args, **kwargs)
        finally:
            depth[0] -= 1
            if depth[0] == 0:
                totals[stage] = totals.get(stage, 0.0) + time.process_time() - start

    return timed


@contextmanager
def _old_quadrature() -> Iterator[None]:
    """The mu(I) plane quadrature by ``quad_vec`` (as before ``numerics.mui``): the compiled
    kernel reports "not converged", so the route integrates with ``quad_vec`` itself."""
    from cosserat.routes import mui

    kernel = mui.plane_pieces
    mui.plane_pieces = lambda *args: (None, -1)  # type: ignore[assignment]
    try:
        yield
    finally:
        mui.plane_pieces = kernel


def stages(corpus: str | None, repeat: int) -> None:
    """``--stages`` (module docstring)."""
    from contextlib import nullcontext

    from cosserat.studies.validate import validate

    load_before = os.getloadavg()
    runs: dict[str, list[dict[str, float]]] = {"new": [], "old mu(I) quadrature": []}
    with tempfile.TemporaryDirectory() as tmp:
        validate(corpus, Path(tmp) / "warm", workers=1)  # compile or load, not timed
        for k in range(repeat):
            for label, ctx in (("new", nullcontext), ("old mu(I) quadrature", _old_quadrature)):
                totals: dict[str, float] = {}
                start = time.process_time()
                with ctx(), _timed(totals):
                    validate(corpus, Path(tmp) / f"{k}_{len(runs[label])}", workers=1)
                totals["total"] = time.process_time() - start
                runs[label].append({s: round(v, 2) for s, v in totals.items()})
    names = [s for s, _, _ in STAGES] + ["total"]
    best = {label: {s: min(r.get(s, 0.0) for r in rs) for s in names} for label, rs in runs.items()}
    print(
        json.dumps(
            {
                "corpus": corpus or "shipped",
                "cpu_seconds": runs,
                "old_over_new (best of each)": {
                    s: round(best["old mu(I) quadrature"][s] / best["new"][s], 2)
                    for s in names
                    if best["new"][s] > 0.0
                },
                "load_average_before": load_before,
                "load_average_after": os.getloadavg(),
            },
            indent=1,
        )
    )


if __name__ == "__main__":
    main()
