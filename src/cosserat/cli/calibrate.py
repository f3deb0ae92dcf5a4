"""``cosserat calibrate``: one material from several experiments, every model, compared."""

from __future__ import annotations

import argparse
import dataclasses
import json
from typing import Any

from .common import UsageError, add_quiet, progress_messages

FIELDS = ("u", "omega", "stress_ratio", "wall_ratio")


def _pairs(items: list[str] | None, option: str) -> dict[str, str]:
    out: dict[str, str] = {}
    for item in items or []:
        key, sep, value = item.partition("=")
        if not sep or not key.strip() or not value.strip():
            raise UsageError(f"{option} takes KEY=VALUE; got {item!r}")
        out[key.strip()] = value.strip()
    return out


def _number(option: str, key: str, text: str) -> float:
    try:
        return float(text)
    except ValueError:
        raise UsageError(f"{option} {key}={text}: the value must be a number") from None


def _per_model(
    models: list[str], values: dict[str, Any], option: str, parameters: dict[str, set[str]]
) -> dict[str, dict[str, Any]]:
    """``KEY=VALUE`` for every model that has KEY (``model:KEY=VALUE`` for one model)."""
    out: dict[str, dict[str, Any]] = {m: {} for m in models}
    for key, value in values.items():
        model, sep, name = key.partition(":")
        targets = [model] if sep else models
        name = name if sep else key
        hit = [m for m in targets if m in parameters and name in parameters[m]]
        if not hit:
            known = "; ".join(f"{m}: {', '.join(sorted(parameters.get(m, ())))}" for m in targets)
            raise UsageError(f"{option} {key}: no model has a parameter {name!r} ({known})")
        for m in hit:
            out[m][name] = value
    return out


def cmd_calibrate(args: argparse.Namespace) -> None:
    from ..calibration import calibrate
    from ..calibration.data import load, with_correlations
    from ..calibration.engine import setup
    from ..calibration.models import models as make_models
    from ..calibration.report import parameter_csv, text, write_report

    names = [m.strip() for m in args.models.split(",") if m.strip()]
    fields = None
    if args.fields:
        fields = [f.strip() for f in args.fields.split(",") if f.strip()]
        bad = [f for f in fields if f not in FIELDS]
        if bad:
            raise UsageError(f"--fields: unknown field(s) {', '.join(bad)}; known: {FIELDS}")
    rho = {
        k: _number("--bin-correlation", k, v)
        for k, v in _pairs(args.bin_correlation, "--bin-correlation").items()
    }
    if args.posterior < 0:
        raise UsageError(f"--posterior must be >= 0; got {args.posterior}")
    if args.posterior and not args.out:
        raise UsageError("--posterior writes its samples and corner plots: give --out DIR")
    skipped: list[str] = []
    runs = with_correlations(load(args.data, skipped), rho)
    chosen = make_models(names, local_spin=not args.no_local_spin)
    parameters: dict[str, set[str]] = {}
    for m in chosen:
        usable = [r for r in runs if r.cell in m.cells()]
        if usable:
            try:
                parameters[m.name] = {s.name for s in setup(m, usable).slots} | {
                    s.key for s in setup(m, usable).slots
                }
            except Exception:
                parameters[m.name] = {p.key for p in m.parameters()}
        else:
            parameters[m.name] = {p.key for p in m.parameters()}
    fix = {
        m: {k: _number("--fix", k, v) for k, v in d.items()}
        for m, d in _per_model(names, _pairs(args.fix, "--fix"), "--fix", parameters).items()
    }
    free_pairs = {k: "1" for k in (args.free or [])}
    free = {m: list(d) for m, d in _per_model(names, free_pairs, "--free", parameters).items()}
    bar = progress_messages("calibrate")
    try:
        result = calibrate(
            runs,
            models=names,
            fields=fields,
            fix=fix,
            free=free,
            bin_correlation=None,
            local_spin=not args.no_local_spin,
            evidence=args.evidence,
            posterior=args.posterior,
            out=args.out,
            seed=args.seed,
            progress=bar,
            holdout=[h.strip() for h in (args.holdout or "").split(",") if h.strip()],
            leave_one_out=args.leave_one_out,
        )
    finally:
        if bar is not None:
            bar.close()  # the bar's line ends before the report is printed
    result = dataclasses.replace(result, skipped=skipped)
    if args.out:
        write_report(result, args.out)
    if args.format == "json":
        print(json.dumps(result.to_dict(), indent=1, allow_nan=False))
    elif args.format == "csv":
        print(parameter_csv(result), end="")
    else:
        print(text(result))
        if args.out:
            print(f"\nreport: {args.out}/report.md, {args.out}/calibration.json, figures")


def add_parsers(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "calibrate",
        help="calibrate the models jointly on several runs of one material, and compare them",
        description=(
            "Fit each model jointly to every run: material parameters shared by all runs of a "
            "material, wall parameters by each wall kind, what each run's metadata give (the "
            "cell, gravity, the wall's inertial number) fixed; every measured field a model "
            "predicts (velocity, spin, stress ratio) enters the likelihood, with correlated "
            "bins (docs/calibration.md)."
        ),
    )
    p.add_argument(
        "data",
        nargs="+",
        help="corpus folders, corpus runs (run.csv with run.json) or profile files",
    )
    p.add_argument(
        "--models",
        default="cosserat,mui,ngf",
        help="models to calibrate, comma-separated (default: cosserat,mui,ngf)",
    )
    p.add_argument(
        "--fields",
        default=None,
        help="measured fields to fit, comma-separated among u, omega, stress_ratio "
        "(default: every field a model predicts)",
    )
    p.add_argument(
        "--fix",
        action="append",
        metavar="[MODEL:]KEY=VALUE",
        help="hold a parameter at VALUE (for every model that has it, or MODEL's)",
    )
    p.add_argument(
        "--free",
        action="append",
        metavar="[MODEL:]KEY",
        help="fit a parameter held fixed by default (e.g. A)",
    )
    p.add_argument(
        "--bin-correlation",
        action="append",
        metavar="FIELD=RHO",
        help="lag-1 correlation of neighbouring bins' errors, instead of the "
        "metadata's or the estimate from the data",
    )
    p.add_argument(
        "--no-local-spin",
        action="store_true",
        help="do not compare mu(I) and NGF with spin data through half the vorticity",
    )
    p.add_argument(
        "--evidence",
        action="store_true",
        help="also compute each model's Bayesian evidence (nested sampling)",
    )
    p.add_argument(
        "--posterior",
        type=int,
        default=0,
        metavar="N",
        help="draw N posterior samples per model (needs --out; extra 'posterior')",
    )
    p.add_argument(
        "--holdout",
        metavar="RUN[,RUN]",
        default=None,
        help="leave these runs out of the fit and predict them with the fitted parameters",
    )
    p.add_argument(
        "--leave-one-out",
        action="store_true",
        help="refit with each run left out in turn: does every run agree on one material?",
    )
    p.add_argument("--seed", type=int, default=0, help="seed of the starts and samplers")
    g = p.add_argument_group("output")
    g.add_argument(
        "--format",
        choices=("text", "json", "csv"),
        default="text",
        help="text: a readable summary (default); json: every number "
        "(docs/calibration.md); csv: one row per model and parameter",
    )
    g.add_argument(
        "--out",
        metavar="DIR",
        default=None,
        help="write calibration.json, report.md, figures (and posterior files) here",
    )
    add_quiet(g)
    p.set_defaults(func=cmd_calibrate)
