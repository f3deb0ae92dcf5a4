"""Reproduce every result of the paper into a folder (the README's main job).

Writes each figure as PNG, PDF and CSV, a table of the numbers the paper states beside the
ones computed here (``claims.csv``), and ``index.html`` / ``report.md`` showing them all with
captions. Figures are computed in parallel worker processes.
"""

from __future__ import annotations

import csv
import html
import json
import logging
import os
import time
from collections.abc import Callable, Sequence
from concurrent.futures import as_completed
from dataclasses import asdict, dataclass
from pathlib import Path

from .. import config
from .._atomic import atomic_open, write_text
from ..analysis.sensitivity import existence_bound_A
from ..model import PlaneShear
from ..model.parameters import Wall
from ..numerics.runtime import process_pool
from ..routes.airy import xi_hat_at_fraction
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


def _claims(figures: dict[int, FigureData]) -> list[Claim]:
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
            PlaneShear(material=MATERIAL, upper=Wall.fully_rough(), eps=0.02, B=1.0)
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
    """Compute and write every figure and the report into ``out``; returns ``out``."""
    start = time.perf_counter()
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    numbers = list(FIGURES) if figures is None else list(figures)
    workers = workers or min(len(numbers), os.cpu_count() or 1, 4)
    results: dict[int, FigureData] = {}
    # longest first, so the parallel run ends together
    order = sorted(numbers, key=lambda n: (n != 14, n != 9, n))
    if workers <= 1:
        for i, n in enumerate(order):
            results[n] = _figure_job(n, str(out))
            if progress:
                progress("figures", i + 1, len(order))
    else:
        with process_pool(workers) as pool:
            futures = {pool.submit(_figure_job, n, str(out)): n for n in order}
            for i, fut in enumerate(as_completed(futures)):
                results[futures[fut]] = fut.result()
                if progress:
                    progress("figures", i + 1, len(order))
    claims = _claims(results)
    with atomic_open(out / "claims.csv", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=list(asdict(claims[0])))
        writer.writeheader()
        writer.writerows(asdict(c) for c in claims)
    elapsed = time.perf_counter() - start
    _write_report(out, results, claims, elapsed)
    log.info("reproduced %d figures into %s in %.1f s", len(results), out, elapsed)
    return out


def _stem(data: FigureData) -> str:
    return f"fig{data.number:02d}_{data.key.removeprefix('fig-')}"


def _write_report(
    out: Path, figures: dict[int, FigureData], claims: list[Claim], elapsed: float
) -> None:
    md = [
        "# Mohan, Kesava Rao & Nott: the paper's results, reproduced",
        "",
        f"Computed by `cosserat reproduce` in {elapsed:.0f} s.",
        "",
        "## Stated versus computed",
        "",
        "| quantity | paper | computed | where | how |",
        "|---|---|---|---|---|",
    ]
    md += [f"| {c.quantity} | {c.stated} | {c.computed} | {c.where} | {c.how} |" for c in claims]
    md += ["", "## Figures", ""]
    rows = "".join(
        f"<tr><td>{html.escape(c.quantity)}</td><td>{html.escape(c.stated)}</td>"
        f"<td>{html.escape(c.computed)}</td><td>{html.escape(c.where)}</td>"
        f"<td>{html.escape(c.how)}</td></tr>"
        for c in claims
    )
    blocks = []
    for n in sorted(figures):
        d = figures[n]
        stem = _stem(d)
        notes = " ".join(d.notes)
        md += [
            f"### Figure {n} ({d.key}): {d.title}",
            "",
            f"![{d.key}]({stem}.png)",
            "",
            d.caption + (f" *Notes: {notes}*" if notes else ""),
            "",
            f"Data: [`{stem}.csv`]({stem}.csv), vector: [`{stem}.pdf`]({stem}.pdf)",
            "",
        ]
        blocks.append(
            f"<figure><img src='{stem}.png' alt='{d.key}'><figcaption><b>Figure {n}</b> "
            f"({html.escape(d.key)}). {html.escape(d.caption)}"
            + (f" <i>{html.escape(notes)}</i>" if notes else "")
            + f" [<a href='{stem}.csv'>csv</a>, <a href='{stem}.pdf'>pdf</a>]</figcaption>"
            "</figure>"
        )
    write_text(out / "report.md", "\n".join(md) + "\n")
    write_text(
        out / "index.html",
        "<!doctype html><html><head><meta charset='utf-8'><title>cosserat: reproduction"
        "</title><style>body{font-family:serif;max-width:60em;margin:auto}"
        "img{max-width:100%}td,th{border:1px solid #ccc;padding:3px}"
        "table{border-collapse:collapse}figure{margin:2em 0}</style></head><body>"
        "<h1>A frictional Cosserat model for the slow shearing of granular materials: "
        "results reproduced</h1>"
        f"<p>Computed by <code>cosserat reproduce</code> in {elapsed:.0f} s.</p>"
        "<h2>Stated versus computed</h2><table><tr><th>quantity</th><th>paper</th>"
        f"<th>computed</th><th>where</th><th>how</th></tr>{rows}</table>"
        f"<h2>Figures</h2>{''.join(blocks)}</body></html>\n",
    )
    write_text(
        out / "figures.json",
        json.dumps(
            {n: {"key": d.key, "title": d.title, "notes": d.notes} for n, d in figures.items()},
            indent=1,
        ),
    )
