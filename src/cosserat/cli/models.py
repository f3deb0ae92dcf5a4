"""``cosserat models`` (every registered rheology, its parameters as declared: meaning, unit,
default, bounds, fit range, role, source; its cells and methods; its reference) and ``cosserat
validate`` (the models against a corpus of measured profiles)."""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
from typing import Any

from .. import config
from . import files
from .common import UsageError, positive_int, progress_bar


def _plain(value: Any) -> Any:
    if isinstance(value, float) and not math.isfinite(value):
        return str(value)
    if isinstance(value, str | int | float | bool) or value is None:
        return value
    return str(value)


def _row(p: Any) -> dict[str, Any]:
    """One parameter as ``cosserat models`` lists it (its declaration as plain data)."""
    row = p.to_dict()
    row["default"] = _plain(row["default"])
    row["default_text"] = p.default_text()
    row["required"] = not p.has_default
    return row


def describe_models() -> list[dict[str, Any]]:
    """Every registered rheology as plain data (what ``cosserat models`` prints): its own
    parameters, and for each cell it is solvable on, the methods and the cell's parameters it
    reads, all from the declarations (:func:`cosserat.model.problem_parameters`)."""
    from ..model import problem_parameters
    from ..routes import RHEOLOGIES, cells_for, methods_for

    out = []
    for name, law in RHEOLOGIES.items():
        own = law.declared()
        cells = {}
        for cell in cells_for(name):
            declared = problem_parameters(name, cell)
            cells[cell] = {
                "methods": methods_for(name, cell),
                "parameters": [_row(p) for k, p in declared.items() if k not in own],
                "model_parameters": [k for k in declared if k in own],
            }
        out.append(
            {
                "name": name,
                "title": law.title,
                "reference": law.reference,
                "default_free": list(law.default_free),
                "parameters": [_row(p) for p in own.values()],
                "cells": cells,
            }
        )
    return out


def _row_text(row: dict[str, Any]) -> str:
    default = "required" if row["required"] else f"default {row['default_text']}"
    parts = [default]
    if row["bounds"]:
        parts.append(row["bounds"])
    if row["fit_range"]:
        lo, hi = row["fit_range"]
        parts.append(f"fit {lo:g} to {hi:g}" + (" (log)" if row["scale"] == "log" else ""))
    parts.append(row["role"])
    if row["cells"]:
        parts.append(f"{'/'.join(row['cells'])} only")
    unit = f" [{row['unit']}]" if row["unit"] else ""
    source = f" ({row['source']})" if row["source"] else ""
    return f"    {row['name']}{unit}, {'; '.join(parts)}: {row['meaning']}{source}"


def models_text(models: list[dict[str, Any]]) -> str:
    lines = []
    for m in models:
        lines += [f"{m['name']}: {m['title']}", f"  reference: {m['reference']}"]
        if m["default_free"]:
            lines.append(f"  fitted by default: {', '.join(m['default_free'])}")
        lines.append("  parameters:")
        lines += [_row_text(r) for r in m["parameters"]]
        for cell, c in m["cells"].items():
            lines.append(f"  cell {cell} (methods {', '.join(c['methods'])}):")
            lines += [_row_text(r) for r in c["parameters"]]
        lines.append("")
    return "\n".join(lines)


def cmd_models(args: argparse.Namespace) -> None:
    models = describe_models()
    if args.format == "json":
        sys.stdout.write(json.dumps(models, indent=1) + "\n")
    else:
        sys.stdout.write(models_text(models))


def _scan_points(text: str) -> int:
    """--spin-scan: 0 (no scan) or at least 2 points per parameter."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number; got {text!r}") from None
    if value < 0 or value == 1:
        raise argparse.ArgumentTypeError(
            f"must be 0 (no scan) or at least 2 points per parameter; got {value}"
        )
    return value


def cmd_validate(args: argparse.Namespace) -> None:
    from ..studies.validate import validate

    models = None
    if args.models:
        models = [m.strip() for m in args.models.split(",") if m.strip()]
        if not models:
            raise UsageError("--models: give model names separated by commas")
    if not 0.0 < args.f < 1.0:
        raise UsageError(f"--f must satisfy 0 < f < 1; got {args.f:g}")
    if args.near_wall is not None and args.near_wall <= 0.0:
        raise UsageError(f"--near-wall must be > 0 grain diameters; got {args.near_wall:g}")
    files.output_folder(args.out)
    bar = progress_bar("validate")

    def progress(stage: str, i: int, n: int) -> None:
        if bar is not None:
            bar(i, n)

    near = {} if args.near_wall is None else {"near_wall_d": args.near_wall}
    if args.spin_scan is not None:
        near["spin_scan"] = args.spin_scan
    if args.independent_bins:
        near["independent_bins"] = True
    if args.fit_angles:
        near["fit_angles"] = True
    workers = args.workers if args.workers is not None else min(2, os.cpu_count() or 1)
    report = validate(
        args.corpus, args.out, models, f=args.f, progress=progress, workers=workers, **near
    )
    if args.format == "json":
        sys.stdout.write(
            json.dumps({"verdicts": [v.to_dict() for v in report.verdicts], "out": args.out}) + "\n"
        )
    else:
        sys.stdout.write(report.to_text())
        sys.stdout.write(f"wrote {args.out}/index.html and {args.out}/report.md\n")


def add_parsers(sub: argparse._SubParsersAction) -> None:
    """Add ``models`` and ``validate`` to the ``cosserat`` parser."""
    mp = sub.add_parser(
        "models", help="list every rheology: parameters, defaults, units, reference"
    )
    mp.add_argument("--format", choices=("text", "json"), default="text")
    mp.set_defaults(func=cmd_models)

    vp = sub.add_parser(
        "validate",
        help="fit every model to a corpus of measured profiles and judge the paper's claims",
    )
    vp.add_argument(
        "corpus",
        nargs="?",
        default=None,
        help="folder of runs (<run>.csv + <run>.json, format cosserat-corpus/1); "
        "default: the corpus shipped with the package",
    )
    vp.add_argument("--out", required=True, help="folder for the report (created if needed)")
    vp.add_argument("--models", help="comma-separated models (default: every registered one)")
    vp.add_argument(
        "--f",
        type=float,
        default=config.DEFAULT_F,
        help=f"fraction of the wall velocity defining Delta ({config.text(config.DEFAULT_F)})",
    )
    vp.add_argument(
        "--near-wall",
        type=float,
        default=None,
        help="bins within this many grain diameters of a wall count as near it (3)",
    )
    vp.add_argument(
        "--workers",
        type=positive_int,
        default=None,
        help="processes that fit the runs and calibrate the gap series (default: 2, or 1 on "
        "one core)",
    )
    vp.add_argument(
        "--spin-scan",
        type=_scan_points,
        default=None,
        metavar="N",
        help="points per parameter (K, L) of the joint-calibration scan behind the spin_model "
        "verdict (default 11; 0: the u-only fits alone; docs/validation.md)",
    )
    vp.add_argument(
        "--independent-bins",
        action="store_true",
        help="also fit every run with its bins taken as independent and give both sets of "
        "Akaike weights in its notes (doubles to triples the fits' time)",
    )
    vp.add_argument(
        "--fit-angles",
        action="store_true",
        help="fit each run's Cosserat model to its velocity alone (phi at its default, the "
        "moving wall's delta fitted) instead of fixing phi and delta from the run's stresses",
    )
    vp.add_argument("--format", choices=("text", "json"), default="text")
    vp.set_defaults(func=cmd_validate)
