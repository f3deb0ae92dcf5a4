"""``cosserat models`` (every registered rheology, its parameters, defaults, units and
reference) and ``cosserat validate`` (the models against a corpus of measured profiles)."""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import re
import sys
import typing
from typing import Any

from .. import config
from . import files
from .common import UsageError, progress_bar
from .params import doc_parameters, nested_class, plain_text

_UNIT = re.compile(r"\[([^\[\],]*)\]")


def _unit(description: str) -> str:
    """The unit in brackets in a parameter's description ("-" for dimensionless)."""
    for match in _UNIT.finditer(description):
        text = match.group(1).strip()
        if text == "-" or re.search(r"[A-Za-z]", text):
            return text
    return ""


def _plain(value: Any) -> Any:
    if isinstance(value, float) and not math.isfinite(value):
        return str(value)
    if isinstance(value, str | int | float | bool) or value is None:
        return value
    return str(value)


def class_parameters(cls: type) -> list[dict[str, Any]]:
    """Every field of a parameter or problem class: name, default (None: required), unit,
    description; dataclass-valued fields (the material, the rheology's constants) listed as
    such with their own class name."""
    docs = doc_parameters(cls)
    hints = typing.get_type_hints(cls)
    rows = []
    for f in dataclasses.fields(cls):  # type: ignore[arg-type]
        kind = nested_class(hints.get(f.name))
        nested = kind is not None
        if f.default is not dataclasses.MISSING:
            default = f.default
        elif f.default_factory is not dataclasses.MISSING:
            default = f.default_factory()
        else:
            default = dataclasses.MISSING
        text = docs.get(f.name, "")
        rows.append(
            {
                "name": f.name,
                "required": default is dataclasses.MISSING and not nested,
                "default": None if default is dataclasses.MISSING or nested else _plain(default),
                "unit": _unit(text),
                "description": plain_text(text).rstrip("."),
                "class": kind.__name__ if nested else None,
            }
        )
    return rows


def describe_models() -> list[dict[str, Any]]:
    """Every registered rheology as plain data (what ``cosserat models`` prints)."""
    from ..routes import RHEOLOGIES

    out = []
    for name, rheology in RHEOLOGIES.items():
        constitutive: dict[str, list[dict[str, Any]]] = {}
        cells = {}
        for cell, cls in rheology.cells.items():
            rows = class_parameters(cls)
            hints = typing.get_type_hints(cls)
            for row in rows:
                kind = nested_class(hints[row["name"]])
                if kind is not None and kind.__name__ not in constitutive:
                    constitutive[kind.__name__] = class_parameters(kind)
            methods = [m for m, table in rheology.routes.items() if cls in table]
            cells[cell] = {
                "problem_class": cls.__name__,
                "methods": methods,
                "parameters": [r for r in rows if not r["class"]],
                "parameter_objects": {r["name"]: r["class"] for r in rows if r["class"]},
            }
        out.append(
            {
                "name": name,
                "title": rheology.title,
                "reference": rheology.reference,
                "parameters": constitutive,
                "cells": cells,
            }
        )
    return out


def _row_text(row: dict[str, Any]) -> str:
    default = "required" if row["required"] else f"default {row['default']}"
    unit = f" [{row['unit']}]" if row["unit"] else ""
    desc = f": {row['description']}" if row["description"] else ""
    return f"    {row['name']}{unit}, {default}{desc}"


def models_text(models: list[dict[str, Any]]) -> str:
    lines = []
    for m in models:
        lines += [f"{m['name']}: {m['title']}", f"  reference: {m['reference']}"]
        for cls, rows in m["parameters"].items():
            lines.append(f"  {cls}:")
            lines += [_row_text(r) for r in rows]
        for cell, c in m["cells"].items():
            lines.append(
                f"  cell {cell} ({c['problem_class']}; methods {', '.join(c['methods'])}):"
            )
            if c["parameter_objects"]:
                objects = ", ".join(f"{k} ({v})" for k, v in c["parameter_objects"].items())
                lines.append(f"    parameter objects: {objects}")
            lines += [_row_text(r) for r in c["parameters"]]
        lines.append("")
    return "\n".join(lines)


def cmd_models(args: argparse.Namespace) -> None:
    models = describe_models()
    if args.format == "json":
        sys.stdout.write(json.dumps(models, indent=1) + "\n")
    else:
        sys.stdout.write(models_text(models))


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
    report = validate(args.corpus, args.out, models, f=args.f, progress=progress, **near)
    if args.format == "json":
        sys.stdout.write(
            json.dumps({"verdicts": [v.to_dict() for v in report.verdicts], "out": args.out}) + "\n"
        )
    else:
        sys.stdout.write(report.to_text())
        sys.stdout.write(f"wrote {args.out}/index.html and {args.out}/report.md\n")


def add_parsers(sub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
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
    vp.add_argument("--format", choices=("text", "json"), default="text")
    vp.set_defaults(func=cmd_validate)
