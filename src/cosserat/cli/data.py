"""``cosserat compare`` and ``cosserat fit``: the model beside a measured profile."""

from __future__ import annotations

import argparse
import json
import sys
from typing import Any

from ..model import build_problem
from ..routes import METHODS
from . import files
from .common import (
    GEOMETRIES,
    PRESETS,
    UsageError,
    angle_or_rough,
    check_outputs,
    default_text,
    emit,
    problem_parameters,
)


def _add_data_model(p: argparse.ArgumentParser) -> None:
    """Options of compare/fit: the data file and the cell (None = take from file/preset)."""
    p.add_argument("data", help="measured profile CSV (see docs/measurements.md)")
    p.add_argument(
        "--preset",
        choices=PRESETS,
        default=None,
        help=(
            "the paper's experiments: phi, eps, Ri, K "
            f"(L = {default_text('L')}, A = {default_text('A')})"
        ),
    )
    p.add_argument("--geometry", choices=tuple(GEOMETRIES), default=None)
    p.add_argument("--eps", type=float, default=None, help="d_p/H (default: file header)")
    p.add_argument("--Ri", type=float, default=None, help="R_i/H (Couette)")
    p.add_argument("--B", type=float, default=None, help="gravity parameter (plane)")
    p.add_argument("--nu", type=float, default=None)
    p.add_argument("--phi", type=float, default=None)
    wall = p.add_mutually_exclusive_group()
    wall.add_argument("--delta", type=angle_or_rough, default=None)
    wall.add_argument("--fully-rough", action="store_true")
    p.add_argument("--delta-lower", type=angle_or_rough, default=None)
    p.add_argument("--K-lower", type=float, default=None)
    p.add_argument("--L", type=float, default=None)
    p.add_argument("--A", type=float, default=None)
    p.add_argument("--K", type=float, default=None)
    p.add_argument("--m-wall", type=float, default=None)
    p.add_argument("--method", choices=METHODS, default="numerical")
    p.add_argument("--format", choices=("json", "text"), default="text")
    p.add_argument("--plot", default=None, help="save a plot (PNG/PDF)")
    p.add_argument("--out", default=None)


# header keys (lower case) of a measured-profile file that describe the cell, by parameter
_HEADER_KEYS = {"geometry": "geometry", "eps": "eps", "Ri": "ri", "B": "b", "nu": "nu"}


def data_problem(args: argparse.Namespace):  # type: ignore[no-untyped-def]
    """The measured profile and the model problem: command line > preset > file header >
    the paper's defaults (those of :func:`cosserat.model.build_problem`). The header's Ri is
    used for Couette flow only, its B and nu for plane shear only."""
    from ..model.build import APPLIES_TO
    from ..studies.experiments import PRESETS as PRESET_CELLS

    check_outputs(args)
    measured = files.read_measured(args.data)
    header = measured.meta
    preset = PRESET_CELLS[args.preset] if args.preset else None
    given = problem_parameters(args, args.eps)

    def from_file(name: str) -> Any:
        if preset is not None and name in ("phi", "L", "A", "K", "eps", "Ri"):
            return getattr(preset, name)
        return header.get(_HEADER_KEYS.get(name, ""))

    geometry = given["geometry"] or from_file("geometry")
    if geometry is None and preset is not None:
        geometry = "couette"
    if geometry is None:
        raise UsageError(
            "give --geometry plane|couette (or a 'geometry:' header line, or --preset)"
        )
    params = {"geometry": geometry}
    for name, value in given.items():
        if name == "geometry":
            continue
        if value is None and APPLIES_TO.get(name, geometry) == geometry:
            value = from_file(name)
        params[name] = value
    if params["eps"] is None:
        raise UsageError("give --eps (or an 'eps:' header line, or --preset)")
    if params["delta"] is None and preset is not None:
        params["delta"] = preset.default_delta
    return measured, build_problem(params)


def cmd_compare(args: argparse.Namespace) -> None:
    from ..analysis.fitting import compare

    measured, problem = data_problem(args)
    comparison = compare(problem, measured, method=args.method)
    if args.plot:
        from ..viz.plotting import comparison_plot

        fig = comparison_plot(comparison, problem.describe(), residual_panel=True)
        files.save_figure(fig, args.plot)
    if args.format == "json":
        emit(json.dumps(comparison.to_dict(), allow_nan=False), args.out)
    else:
        lines = [
            problem.describe(),
            f"points: {measured.n}",
            f"rms(data - model): {comparison.rms:.4g}",
        ]
        if comparison.chi2 is not None:
            lines.append(f"chi-square: {comparison.chi2:.4g} for {measured.n} points")
        lines.append("distance_d,u_over_uw,model,residual")
        lines += [
            f"{d:g},{u:g},{m:.6g},{r:.3g}"
            for d, u, m, r in zip(
                measured.distance_d,
                measured.u_over_uw,
                comparison.model,
                comparison.residuals,
                strict=True,
            )
        ]
        emit("\n".join(lines), args.out)


def cmd_fit(args: argparse.Namespace) -> None:
    from ..analysis.fitting import fit

    measured, problem = data_problem(args)
    free = [f.strip() for f in args.free.split(",") if f.strip()]
    bar = (lambda msg: print(f"fit: {msg}", file=sys.stderr)) if sys.stderr.isatty() else None
    result = fit(measured, problem, free=free, method=args.method, progress=bar)
    if args.plot:
        from ..viz.plotting import comparison_plot

        fig = comparison_plot(
            result.comparison, "fit: " + result.problem.describe(), residual_panel=True
        )
        files.save_figure(fig, args.plot)
    if args.format == "json":
        emit(json.dumps(result.to_dict(), allow_nan=False), args.out)
    else:
        lines = [f"fit of {', '.join(free)} to {measured.n} points ({result.n_solves} solves)"]
        for name, par in result.parameters.items():
            interval = (
                ""
                if par.interval is None
                else (f"  interval [{par.interval[0]:.4g}, {par.interval[1]:.4g}]")
            )
            lines.append(f"  {name} = {par.value:.5g} +- {par.stderr:.2g}{interval}")
        lines.append(f"  rms = {result.rms:.4g}, reduced chi-square = {result.reduced_chi2:.3g}")
        lines += [f"warning: {w}" for w in result.warnings]
        emit("\n".join(lines), args.out)


def add_parsers(sub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    """Add this module's commands to the ``cosserat`` parser."""
    cp = sub.add_parser("compare", help="the model beside a measured velocity profile")
    _add_data_model(cp)
    cp.set_defaults(func=cmd_compare)

    fitp = sub.add_parser("fit", help="fit delta, K (and L, phi, A) to a measured profile")
    _add_data_model(fitp)
    fitp.add_argument(
        "--free", default="delta,K", help="comma-separated free parameters among delta,K,L,phi,A"
    )
    fitp.set_defaults(func=cmd_fit)
