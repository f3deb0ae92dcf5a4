"""Reproduce every result of the paper into a folder (the README's main job).

Writes each figure as PNG, PDF and CSV, a table of the numbers the paper states beside the
ones computed here (``claims.csv``), and ``index.html`` / ``report.md`` showing them all with
captions. Figures are computed in parallel worker processes.
"""

from __future__ import annotations

import csv
import json
import logging
import os
import time
from collections.abc import Callable, Sequence
from concurrent.futures import as_completed
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from .. import config
from .._atomic import atomic_open, remove_stale_temporaries, write_text
from ..analysis.sensitivity import existence_bound_A
from ..model import Cosserat, Plane, Problem
from ..model.parameters import Wall
from ..numerics.runtime import worker_processes
from ..routes.airy import xi_hat_at_fraction
from ..viz.report import write_report
from .figures import FIGURES, FigureData, make_figure
from .figures.paper import MATERIAL

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class Claim:
    """A number the paper states beside the one the package computes."""

    quantity: str
    stated: str
    computed: str
    where: str
    how: str


def _figure_job(number: int, out: str) -> FigureData:
    import matplotlib

    matplotlib.use("Agg")
    data, _ = make_figure(number, out=out)
    import matplotlib.pyplot as plt

    plt.close("all")
    return data


def _claims(figures: dict[int, FigureData], independent: bool = True) -> list[Claim]:
    claims = []
    table = figures[14].extra["table"] if 14 in figures else {}
    for name, row in table.items():
        if not name.startswith("a:") or row["Delta"][-1] is None:
            continue
        claims.append(
            Claim(
                f"Delta as eps -> 0, {name[3:]} (delta = 20 deg)",
                "17.67",
                f"{row['Delta'][-1]:.4f}",
                "eqn-delta_soln, fig. 14a",
                f"numerical at eps = {row['eps'][-1]:g}; law -ln f / k = "
                f"{row['Delta_asymptotic'][-1]:.4f}",
            )
        )
    for name, row in table.items():
        if name.startswith("b:") and "identical" not in name and row["Delta"][-1] is not None:
            ratio = row["Delta"][-1] / row["Delta_asymptotic"][-1]
            ratio3 = row["Delta"][-4] / row["Delta_asymptotic"][-4]
            claims.append(
                Claim(
                    f"Delta numerical / eqn-delta_soln_fr, {name[3:]}, fully rough",
                    "-> 1",
                    f"{ratio3:.4f} (1e-3), {ratio:.4f} (1e-6)",
                    "eqn-delta_soln_fr, fig. 14b",
                    "numerical / Airy law",
                )
            )
    if not independent:
        return claims + _later_claims(figures)
    claims.append(
        Claim(
            "x_hat where u = 0.05 in the Airy inner layer",
            "1.275",
            f"{xi_hat_at_fraction(0.05):.4f}",
            "eqn-delta_soln_fr",
            "Brent root of (Ai'(x)^2 - x Ai(x)^2)/Ai'(0)^2 = 0.05",
        )
    )
    claims.append(
        Claim(
            "fully rough delta = atan(sin phi) [deg]",
            "25.5",
            f"{MATERIAL.fully_rough_delta:.4f}",
            "fig. 14 caption",
            f"atan(sin {config.text(config.PHI)} deg)",
        )
    )
    return claims + _later_claims(figures)


def _later_claims(figures: dict[int, FigureData]) -> list[Claim]:
    claims = []
    if 12 in figures:
        extra = figures[12].extra
        claims.append(
            Claim(
                "smallest A with a solution (plane, gravity B = 1, fully rough, eps = 0.04)",
                "-0.57",
                f"{extra['A_bound']:.4f} +- {extra['A_bound_tol']:.0e}",
                "section 'Parameter sensitivity', fig. 12",
                "bisection on where the yield radicand turns negative",
            )
        )
        alt = existence_bound_A(
            Problem(Plane(eps=0.02, B=1.0), Cosserat(material=MATERIAL, wall=Wall.fully_rough()))
        )
        claims.append(
            Claim(
                "the same bound at eps B nu = 0.02 (eps = 0.02, B = 1; or eps = 0.04, B = 0.5)",
                "-0.57",
                f"{alt.value:.4f} +- {alt.tolerance:.0e}",
                "section 'Parameter sensitivity'",
                "which parameters reproduce the paper's number: the bound depends on eps B nu",
            )
        )
    if 6 in figures:
        B, d = figures[6].extra["B"], figures[6].extra["Delta"]
        claims.append(
            Claim(
                "the layer thins as B grows (fig. 6)",
                "qualitative",
                ", ".join(f"{x:.3g}" for b, x in zip(B, d, strict=True) if b > 0),
                "fig. 6",
                "Delta for B = 0.1, 0.3, 1 (B = 0 shears uniformly; its Delta is measured "
                "from u_0 = 1/2)",
            )
        )
    return claims


def reproduce(
    out: str | Path,
    figures: Sequence[int] | None = None,
    workers: int | None = None,
    progress: Callable[[str, int, int], None] | None = None,
) -> Path:
    """Compute and write every figure and the report into ``out``; returns ``out``.

    Each file appears whole (written beside and renamed). An interrupted run (Ctrl-C,
    SIGTERM) stops its workers and removes their temporary files: ``out`` keeps the figures
    finished so far and the earlier run's report. Temporary files of a run that was killed
    (SIGKILL) are removed by the next run into ``out``.
    """
    start = time.perf_counter()
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    remove_stale_temporaries(out)  # of an earlier run that was killed while writing
    numbers = list(FIGURES) if figures is None else list(figures)
    workers = workers or min(len(numbers), os.cpu_count() or 1, 4)
    results: dict[int, FigureData] = {}
    # longest first, so the parallel run ends together
    order = sorted(numbers, key=lambda n: (n != 14, n != 15, n != 9, n))
    try:
        if workers <= 1:
            for i, n in enumerate(order):
                results[n] = _figure_job(n, str(out))
                if progress:
                    progress("figures", i + 1, len(order))
        else:
            with worker_processes(workers) as pool:  # stopped at once on an interruption
                futures = {pool.submit(_figure_job, n, str(out)): n for n in order}
                for i, fut in enumerate(as_completed(futures)):
                    results[futures[fut]] = fut.result()
                    if progress:
                        progress("figures", i + 1, len(order))
    except BaseException:
        remove_stale_temporaries(out)  # of workers killed while writing (they are stopped)
        raise
    # a partial run (--only) updates what an earlier run wrote instead of replacing it
    previous, previous_claims = _previous_state(out) if figures is not None else ({}, [])
    entries = {n: e for n, e in previous.items() if n not in results}
    entries.update({n: _entry(d) for n, d in results.items()})
    tagged = _tagged_claims(results)
    tagged += [(s, c) for s, c in previous_claims if s in entries and s not in results and s]
    tagged.sort(key=lambda sc: _SOURCE_ORDER[sc[0]])
    claims = [c for _, c in tagged]
    with atomic_open(out / "claims.csv", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=list(asdict(claims[0])))
        writer.writeheader()
        writer.writerows(asdict(c) for c in claims)
    write_text(
        out / "claims.json",
        json.dumps([{"source": s, **asdict(c)} for s, c in tagged], indent=1) + "\n",
    )
    elapsed = time.perf_counter() - start
    _write_report(out, entries, claims, elapsed)
    log.info("reproduced %d figures into %s in %.1f s", len(results), out, elapsed)
    return out


# the report lists the claims in this order of their source figure (0: none)
_SOURCE_ORDER = {14: 0, 0: 1, 12: 2, 6: 3}


def _tagged_claims(figures: dict[int, FigureData]) -> list[tuple[int, Claim]]:
    """The claims of :func:`_claims`, each with the figure it comes from (0: none)."""
    tagged: list[tuple[int, Claim]] = [
        (n, c) for n in (14, 12, 6) if n in figures for c in _claims({n: figures[n]}, False)
    ]
    tagged += [(0, c) for c in _claims({}, True)]
    return sorted(tagged, key=lambda sc: _SOURCE_ORDER[sc[0]])


def _entry(data: FigureData) -> dict[str, Any]:
    return {
        "key": data.key,
        "title": data.title,
        "caption": data.caption,
        "notes": data.notes,
        "stem": _stem(data),
    }


def _previous_state(out: Path) -> tuple[dict[int, dict[str, Any]], list[tuple[int, Claim]]]:
    """What an earlier run wrote into ``out`` (``figures.json``, ``claims.json``), if any."""
    try:
        figures = json.loads((out / "figures.json").read_text())
        claims = json.loads((out / "claims.json").read_text())
        entries = {int(n): e for n, e in figures.items() if {"stem", "caption"} <= set(e)}
        return entries, [(int(c.pop("source")), Claim(**c)) for c in claims]
    except (OSError, ValueError, TypeError, KeyError):
        return {}, []


def _stem(data: FigureData) -> str:
    return f"fig{data.number:02d}_{data.key.removeprefix('fig-')}"


def _write_report(
    out: Path, figures: dict[int, dict[str, Any]], claims: list[Claim], elapsed: float
) -> None:
    """``report.md`` and ``index.html`` from the templates ``reproduce.*.j2``
    (:func:`cosserat.viz.report.write_report`), and ``figures.json``."""
    context = {
        "title": "cosserat: reproduction",
        "elapsed": elapsed,
        "claims": [asdict(c) for c in claims],
        "figures": [
            {**figures[n], "number": n, "notes": " ".join(figures[n]["notes"])}
            for n in sorted(figures)
        ],
    }
    write_report(out, "reproduce", context)
    write_text(
        out / "figures.json",
        json.dumps(
            {n: figures[n] for n in sorted(figures)},
            indent=1,
        ),
    )
