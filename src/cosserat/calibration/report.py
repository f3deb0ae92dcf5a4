"""A calibration as text, as a folder (JSON, Markdown report, figures), and as figure data.

The text (:func:`text`), the JSON
(:meth:`~cosserat.calibration.result.Calibration.to_dict`) and the report
(:func:`write_report`) say the same things: the comparison with its assumptions, each model's
parameters with errors and roles, chi^2 with its p-value per run and field, the runs tests, and
every warning naming its run.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from .._atomic import save_figure, write_text
from . import diagnostics as dg
from .result import Calibration

PERCENTILES = (2.5, 16.0, 50.0, 84.0, 97.5)


def _fmt(x: Any, digits: int = 4) -> str:
    if x is None:
        return "-"
    if isinstance(x, float):
        if not math.isfinite(x):
            return "-"
        return f"{x:.{digits}g}"
    return str(x)


def _value(e: Any) -> str:
    err = "" if e.stderr is None else f" +- {e.stderr:.2g}"
    if e.stderr is not None and e.scale > 1.0:
        err += f" (scaled for the misfit: +- {e.stderr_scaled:.2g})"
    unit = "" if e.unit in ("", "-") else f" {e.unit}"
    note = []
    if e.derived:
        note.append("derived")
    elif not e.free:
        note.append("fixed")
    elif e.reason:
        note.append(e.reason)
    if e.shared:
        note.append(f"shared by {len(e.runs)} runs")
    if e.jackknife is not None:
        lo, hi, se = e.jackknife
        note.append(f"one run left out: {lo:.4g}-{hi:.4g}, jackknife se {se:.2g}")
    return f"{e.value:.5g}{err}{unit}" + (f" ({'; '.join(note)})" if note else "")


def comparison_rows(cal: Calibration) -> list[list[str]]:
    ok = [m for m in cal.models if m.ok]
    aic0 = min((m.aic for m in ok if m.aic is not None), default=None)
    w_aic, w_ev = cal.weights("aic"), cal.weights("evidence")
    rows = []
    for m in cal.models:
        if not m.ok:
            rows.append([m.model, "failed", "", "", "", "", "", "", "", ""])
            continue
        rows.append(
            [
                m.model,
                str(m.k),
                str(m.n),
                _fmt(m.chi2, 5),
                str(m.dof),
                _p_cell(dg.p_text(dg.chi2_log10_p(m.chi2 or 0.0, m.dof))),
                _fmt(None if m.aic is None or aic0 is None else m.aic - aic0, 4),
                _fmt(m.bic, 6),
                "-" if m.evidence is None else f"{m.evidence[0]:.1f} +- {m.evidence[1]:.1f}",
                (_fmt(w_aic.get(m.model), 3) if cal.calibrated_weights else "n/c")
                + ("" if not w_ev else f" / {_fmt(w_ev.get(m.model), 3)}"),
            ]
        )
    return rows


def _p_cell(text: str) -> str:
    """The p column: ``0.034``, or ``z = 12.3`` below ``cosserat._text.SIGNIFICANCE_P``."""
    return text[4:] if text.startswith("p = ") else text


def _table(header: Sequence[str], rows: Sequence[Sequence[str]]) -> list[str]:
    widths = [max(len(h), *(len(r[i]) for r in rows)) for i, h in enumerate(header)]
    line = "  ".join(h.ljust(w) for h, w in zip(header, widths, strict=True))
    out = [line, "-" * len(line)]
    out += ["  ".join(c.ljust(w) for c, w in zip(r, widths, strict=True)) for r in rows]
    return out


HEADER = ["model", "k", "n", "chi2", "dof", "p", "dAIC", "BIC", "ln Z", "weight AIC/Z"]


TEXT_WARNINGS = 12
"""Warnings per model in the printed summary (the JSON and the report have them all)."""


def text(cal: Calibration, full: bool = False) -> str:
    """The readable summary printed by ``cosserat calibrate`` (``full``: every warning)."""
    runs = ", ".join(f"{r.name} ({r.cell}, H = {r.gap_d:.4g} d)" for r in cal.runs)
    lines = [f"Calibration on {len(cal.runs)} run(s): {runs}"]
    lines += [f"skipped: {note}" for note in cal.skipped] + [""]
    lines += _table(HEADER, comparison_rows(cal))
    if cal.calibrated_weights:
        lines.append(f"best by AIC: {cal.best or '-'}")
    else:
        lines.append(
            f"lowest AIC: {cal.lowest_aic or '-'}; the weights are NOT calibrated: a model misfits "
            "(p < 1e-3), and being the least bad does not make a model right"
        )
    if cal.notes:
        lines += ["", "What the runs say of themselves, whatever the model:"]
        lines += [f"  - {n}" for n in cal.notes]
    for m in cal.models:
        lines += ["", f"{m.model}: " + ("" if m.ok else f"FAILED: {m.message}")]
        if not m.ok:
            continue
        for name, e in m.parameters.items():
            lines.append(f"  {name} = {_value(e)}")
        for run, entry in m.per_run().items():
            parts = [
                f"{f}: chi2 {_fmt(d['chi2'], 4)}/{d['n']}"
                + ("" if d["runs_test_p"] is None else f" (runs p {d['runs_test_p']:.2g})")
                for f, d in entry["fields"].items()
            ]
            lines.append(f"  run {run}: " + "; ".join(parts))
        for f in m.held_out:
            lp = dg.chi2_log10_p(f.chi2, f.n)
            lines.append(
                f"  held out, predicted: run {f.run}, {f.field}: chi2 {f.chi2:.4g}/{f.n} "
                f"({dg.p_text(lp)})"
            )
        if m.posterior is not None:
            p = m.posterior
            lines.append(
                f"  posterior: {p.samples} draws (acceptance {p.acceptance:.2f}, "
                f"{p.seconds:.1f} s)" + (f", written to {p.path}" if p.path else "")
            )
            for name, q in p.parameters.items():
                lines.append(
                    f"    {name}: median {q['q50']:.5g}, 68% [{q['q16']:.5g}, {q['q84']:.5g}]"
                )
        if m.warnings:
            lines.append(f"  warnings ({len(m.warnings)}):")
            shown = m.warnings if full else m.warnings[:TEXT_WARNINGS]
            lines += [f"    - {w}" for w in shown]
            if len(shown) < len(m.warnings):
                lines.append(
                    f"    ... and {len(m.warnings) - len(shown)} more (--format json, or the "
                    "report written with --out, lists them all)"
                )
    lines += ["", "Assumptions:"]
    seen: list[str] = []
    for m in cal.models:
        for a in m.assumptions:
            if a not in seen:
                seen.append(a)
    lines += [f"  - {a}" for a in seen + list(cal.comparison)]
    return "\n".join(lines)


def figure_data(cal: Calibration, points: int = 160) -> list[dict[str, Any]]:
    """Per run: the data, each model's best-fit curves, its residuals and (where sampled) its
    bands over the posterior, as ``cosserat.viz.calibration.run_figure`` takes them."""
    entries: dict[str, dict[str, Any]] = {}
    for run in cal.runs:
        entries[run.name] = {
            "name": run.name,
            "cell": run.cell,
            "gap_d": run.gap_d,
            "fields": {n: {"s": f.s, "data": f.value, "se": f.se} for n, f in run.fields.items()},
            "models": {},
            "residuals": {},
            "bands": {},
        }
    for m in cal.models:
        if not m.ok or m.internal is None:
            continue
        s, opt = m.internal[0], m.internal[1]
        for run, curves in s.curves(opt.theta, points).items():
            entries[run]["models"][m.model] = {
                f: {"s": c[0], "values": c[1]} for f, c in curves.items()
            }
        for f in m.fields:
            entries[f.run]["residuals"].setdefault(m.model, {})[f.field] = {
                "s": f.s,
                "z": (f.model - f.data) / f.se,
            }
        if len(m.internal) > 2:
            bands = _bands(s, m.internal[2], points)
            for run_name, fields in bands.items():
                entries[run_name]["bands"][m.model] = fields
    return list(entries.values())


def _bands(s: Any, chain: Any, points: int, draws: int = 100) -> dict[str, dict[str, Any]]:
    flat = chain.reshape(-1, chain.shape[-1])
    rng = np.random.default_rng(0)
    pick = flat[rng.choice(flat.shape[0], size=min(draws, flat.shape[0]), replace=False)]
    acc: dict[str, dict[str, list[Any]]] = {}
    grids: dict[str, dict[str, Any]] = {}
    for theta in pick:
        for run, curves in s.curves(theta, points).items():
            for f, (grid, values) in curves.items():
                acc.setdefault(run, {}).setdefault(f, []).append(values)
                grids.setdefault(run, {})[f] = grid
    out: dict[str, dict[str, Any]] = {}
    for run, fields in acc.items():
        for f, rows in fields.items():
            q = np.percentile(np.array(rows), PERCENTILES, axis=0)
            out.setdefault(run, {})[f] = {
                "s": grids[run][f],
                **{f"q{p:g}": q[i] for i, p in enumerate(PERCENTILES)},
            }
    return out


def write_report(cal: Calibration, out: str | Path) -> list[Path]:
    """``calibration.json``, ``report.md`` and one figure per run (``fit_<run>.png``) in
    ``out``; returns the paths written."""
    from ..viz.calibration import run_figure

    folder = Path(out)
    folder.mkdir(parents=True, exist_ok=True)
    paths = [write_text(folder / "calibration.json", cal.to_json() + "\n")]
    figures = []
    import matplotlib.pyplot as plt

    for entry in figure_data(cal):
        fig = run_figure(entry)
        figures.append(save_figure(fig, folder / f"fit_{entry['name']}.png", dpi=130))
        plt.close(fig)
    corners = sorted(folder.glob("corner_*.png"))
    md = ["# Calibration", "", "```", text(cal, full=True), "```", ""]
    for p in figures:
        md += [f"![{p.stem}]({p.name})", ""]
    for p in corners:
        md += [f"![{p.stem}]({p.name})", ""]
    paths.append(write_text(folder / "report.md", "\n".join(md)))
    return paths + figures


def parameter_csv(cal: Calibration) -> str:
    """One row per model and parameter (``--format csv``)."""
    header = [
        "model",
        "parameter",
        "value",
        "stderr",
        "unit",
        "free",
        "shared",
        "role",
        "at_bound",
        "reason",
    ]
    rows = [",".join(header)]
    for m in cal.models:
        for name, e in m.parameters.items():
            cells = [
                m.model,
                name,
                repr(float(e.value)),
                "" if e.stderr is None else repr(float(e.stderr)),
                e.unit,
                str(e.free),
                str(e.shared),
                e.role,
                e.at_bound or "",
                e.reason,
            ]
            rows.append(",".join(f'"{c}"' if "," in c else c for c in cells))
    return "\n".join(rows) + "\n"


__all__ = ["figure_data", "parameter_csv", "text", "write_report"]
