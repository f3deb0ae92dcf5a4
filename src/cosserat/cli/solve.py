"""``cosserat solve`` and ``cosserat thickness``: one profile, and Delta against eps."""

from __future__ import annotations

import argparse
import json
from dataclasses import replace

from .. import config
from ..analysis import thickness_curve, thickness_limit
from ..analysis.laws import thickness_curve_asymptote
from ..routes import solve
from . import files
from .common import (
    GEOMETRIES,
    MAX_POINTS,
    Parser,
    UsageError,
    add_material_and_walls,
    add_solution,
    check_outputs,
    emit,
    problem_from_args,
    progress_bar,
    solver_options,
)


def cmd_solve(args: argparse.Namespace) -> None:
    problem = problem_from_args(args, args.eps)
    if not 3 <= args.points <= MAX_POINTS:
        raise UsageError(f"--points must satisfy 3 <= points <= {MAX_POINTS}; got {args.points}")
    check_outputs(args)
    profile = solve(problem, method=args.method, points=args.points, **solver_options(args))
    if args.plot:
        files.save_figure(profile.plot(), args.plot)
    if args.format == "csv":
        emit(profile.to_csv(), args.out)
    else:
        emit(profile.to_json(indent=None), args.out)


def cmd_thickness(args: argparse.Namespace) -> None:
    eps_values = list(args.eps)
    problem = problem_from_args(args, eps_values[0])
    for e in eps_values[1:]:
        replace(problem, eps=e)  # validate every eps before any solve
    check_outputs(args)
    curve = thickness_curve(
        problem,
        eps_values,
        f=args.f,
        method=args.method,
        progress=progress_bar("thickness"),
        **solver_options(args),
    )
    limit = thickness_limit(problem, args.f)
    asym = thickness_curve_asymptote(problem, eps_values, args.f)
    record = {
        "problem": problem.parameters()["geometry"],
        "parameters": {k: v for k, v in problem.parameters().items() if k != "eps"},
        "method": args.method,
        "f": args.f,
        "eps": eps_values,
        "Delta": curve.Delta,
        "Delta_asymptote": limit,
        "Delta_asymptotic": asym,
        "failures": {repr(e): why for e, why in curve.failures.items()},
    }
    if args.format == "csv":
        lines = ["eps,Delta,Delta_asymptotic"]
        lines += [
            f"{e!r},{d!r},{a!r}" for e, d, a in zip(eps_values, curve.Delta, asym, strict=True)
        ]
        emit("\n".join(lines), args.out)
    else:
        emit(json.dumps(record, allow_nan=False), args.out)


def add_parsers(sub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    """Add this module's commands to the ``cosserat`` parser."""
    solve_p = sub.add_parser("solve", help="one profile across the gap")
    solve_geo = solve_p.add_subparsers(dest="geometry", required=True, parser_class=Parser)
    for geometry, helptext in GEOMETRIES.items():
        sp = solve_geo.add_parser(geometry, help=helptext)
        add_material_and_walls(sp, plane=geometry == "plane")
        sp.add_argument("--eps", type=float, required=True, help="grain diameter / gap d_p/H")
        add_solution(sp)
        sp.add_argument(
            "--points",
            type=int,
            default=config.OUTPUT_POINTS,
            help=f"output points, layers resolved ({config.OUTPUT_POINTS})",
        )
        sp.add_argument("--format", choices=("json", "csv"), default="json")
        sp.add_argument("--out", default=None, help="write to this file instead of stdout")
        sp.add_argument("--plot", default=None, help="also save a quick plot (PNG/PDF)")
        sp.set_defaults(func=cmd_solve)

    th = sub.add_parser("thickness", help="shear-layer thickness Delta against eps")
    th_geo = th.add_subparsers(dest="geometry", required=True, parser_class=Parser)
    for geometry, helptext in GEOMETRIES.items():
        tp = th_geo.add_parser(geometry, help=helptext)
        add_material_and_walls(tp, plane=geometry == "plane")
        tp.add_argument("--eps", type=float, nargs="+", required=True)
        tp.add_argument(
            "--f",
            type=float,
            default=config.DEFAULT_F,
            help=f"fraction defining Delta ({config.text(config.DEFAULT_F)})",
        )
        add_solution(tp)
        tp.add_argument("--format", choices=("json", "csv"), default="json")
        tp.add_argument("--out", default=None)
        tp.set_defaults(func=cmd_thickness)
