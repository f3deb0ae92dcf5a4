"""The ``cosserat`` command line: a thin layer over the API (no physics here).

Bad input (a :class:`~cosserat.errors.CosseratError`, or a usage error) exits with status 2 and
one line on stderr saying what is wrong; anything else is a bug and shows as one (a traceback,
exit status 1). Defaults are the paper's, from :mod:`cosserat.config`, filled in by
:func:`cosserat.model.build_problem` (the same as for sweeps).
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path
from typing import Any, NoReturn

from .. import config
from .._version import __version__
from ..analysis import thickness_curve, thickness_limit
from ..analysis.laws import thickness_curve_asymptote
from ..errors import CosseratError
from ..model import Problem, build_problem
from ..model.build import DEFAULTS, ROUGH_WORDS
from ..model.parameters import FULLY_ROUGH
from ..routes import METHODS, solve
from . import files

GEOMETRIES = {
    "plane": "plane shear between parallel walls",
    "couette": "cylindrical Couette flow, inner cylinder turning",
}
PRESETS = ("mustard", "poppy", "glass")
MAX_POINTS = 1_000_000
"""Most output points ``solve --points`` accepts (more would only exhaust memory)."""


class UsageError(Exception):
    """Bad command-line usage (reported in one line, exit status 2)."""


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:
        raise UsageError(f"{self.prog}: {message}")


def _angle_or_rough(text: str) -> float | str:
    if text.strip().lower() in ROUGH_WORDS:
        return FULLY_ROUGH
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected an angle in degrees or 'fully-rough'; got {text!r}"
        ) from None


def _positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number; got {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1; got {value}")
    return value


def _default(name: str) -> str:
    """The default of parameter ``name`` as help texts show it."""
    return config.text(DEFAULTS[name])


def _add_material_and_walls(p: argparse.ArgumentParser, plane: bool) -> None:
    g = p.add_argument_group("material and walls (defaults: the paper's)")
    g.add_argument(
        "--phi", type=float, help=f"angle of internal friction [deg] ({_default('phi')})"
    )
    wall = g.add_mutually_exclusive_group()
    wall.add_argument(
        "--delta",
        type=_angle_or_rough,
        help=f"angle of wall friction [deg] or 'fully-rough' ({_default('delta')})",
    )
    wall.add_argument(
        "--fully-rough", action="store_true", help="fully rough wall(s): tan(delta) = sin(phi)"
    )
    g.add_argument("--L", type=float, help=f"yield-condition L ({_default('L')})")
    g.add_argument("--A", type=float, help=f"yield-condition A = a2/a1 ({_default('A')})")
    g.add_argument("--K", type=float, help=f"wall slip coefficient ({_default('K')})")
    if not plane:
        g.add_argument("--Ri", type=float, help=f"inner radius / gap R_i/H ({_default('Ri')})")
    if plane:
        g.add_argument(
            "--delta-lower",
            type=_angle_or_rough,
            help="lower wall's delta [deg] or 'fully-rough' (default: = delta)",
        )
        g.add_argument("--K-lower", type=float, help="lower wall's K (default: = K)")
        g.add_argument(
            "--B",
            type=float,
            help=f"gravity parameter rho_p g H / N ({_default('B')}: no gravity)",
        )
        g.add_argument("--nu", type=float, help=f"solids fraction ({_default('nu')})")
        g.add_argument(
            "--m-wall",
            type=float,
            help="couple stress m at the non-slipping wall (instead of eqn-nd_bc4)",
        )


def _add_solution(p: argparse.ArgumentParser) -> None:
    p.add_argument("--method", choices=METHODS, default="numerical")
    p.add_argument(
        "--rtol", type=float, default=None, help=f"numerical tolerance ({config.text(config.RTOL)})"
    )


def problem_parameters(args: argparse.Namespace, eps: Any) -> dict[str, Any]:
    """The named parameters the options give (None: not given, the default applies)."""
    params: dict[str, Any] = {
        "geometry": args.geometry,
        "delta": FULLY_ROUGH if args.fully_rough else args.delta,
        "eps": eps,
    }
    for name in ("phi", "L", "A", "K", "delta_lower", "K_lower", "B", "nu", "m_wall", "Ri"):
        params[name] = getattr(args, name, None)
    return params


def problem_from_args(args: argparse.Namespace, eps: Any) -> Problem:
    """The problem the options describe (geometry from the sub-command)."""
    return build_problem(problem_parameters(args, eps))


def _solver_options(args: argparse.Namespace) -> dict[str, Any]:
    opts: dict[str, Any] = {}
    if args.rtol is not None:
        if args.method != "numerical":
            raise UsageError("--rtol applies to --method numerical only")
        opts["rtol"] = args.rtol
    return opts


def _emit(text: str, out: str | None) -> None:
    if out:
        files.write_text(text, out)
    else:
        sys.stdout.write(text if text.endswith("\n") else text + "\n")


def _check_outputs(args: argparse.Namespace) -> None:
    """Fail on an unusable --out or --plot before any computation."""
    if getattr(args, "out", None):
        files.check_output_file(args.out)
    if getattr(args, "plot", None):
        files.check_plot_file(args.plot)


def _progress_bar(label: str):  # type: ignore[no-untyped-def]
    """A text progress bar on stderr (only when stderr is a terminal)."""
    if not sys.stderr.isatty():
        return None

    def update(i: int, n: int) -> None:
        width = 30
        done = int(width * i / n)
        sys.stderr.write(f"\r{label} [{'#' * done}{'.' * (width - done)}] {i}/{n}")
        if i == n:
            sys.stderr.write("\n")
        sys.stderr.flush()

    return update


def cmd_solve(args: argparse.Namespace) -> None:
    problem = problem_from_args(args, args.eps)
    if not 3 <= args.points <= MAX_POINTS:
        raise UsageError(f"--points must satisfy 3 <= points <= {MAX_POINTS}; got {args.points}")
    _check_outputs(args)
    profile = solve(problem, method=args.method, points=args.points, **_solver_options(args))
    if args.plot:
        files.save_figure(profile.plot(), args.plot)
    if args.format == "csv":
        _emit(profile.to_csv(), args.out)
    else:
        _emit(profile.to_json(indent=None), args.out)


def cmd_thickness(args: argparse.Namespace) -> None:
    eps_values = list(args.eps)
    problem = problem_from_args(args, eps_values[0])
    for e in eps_values[1:]:
        replace(problem, eps=e)  # validate every eps before any solve
    _check_outputs(args)
    curve = thickness_curve(
        problem,
        eps_values,
        f=args.f,
        method=args.method,
        progress=_progress_bar("thickness"),
        **_solver_options(args),
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
        _emit("\n".join(lines), args.out)
    else:
        _emit(json.dumps(record, allow_nan=False), args.out)


def _stage_bar():  # type: ignore[no-untyped-def]
    bar = _progress_bar("reproduce")

    def progress(stage: str, i: int, n: int) -> None:
        if bar is not None:
            bar(i, n)

    return progress


def cmd_reproduce(args: argparse.Namespace) -> None:
    from ..paper.reproduce import reproduce

    files.output_folder(args.out)
    out = reproduce(args.out, figures=args.only, workers=args.workers, progress=_stage_bar())
    print(f"wrote {out}/index.html and {out}/report.md")


def cmd_figures(args: argparse.Namespace) -> None:
    from ..paper.figures import FIGURES, make_figure

    data = {}
    for item in args.data or []:
        key, sep, path = item.partition("=")
        if not sep or key not in PRESETS:
            raise UsageError(f"--data takes mustard=FILE, poppy=FILE or glass=FILE; got {item!r}")
        data[key] = files.read_measured(path)
    files.output_folder(args.out)
    numbers = args.only or list(FIGURES)
    bar = _progress_bar("figures")
    for i, n in enumerate(numbers):
        make_figure(n, out=args.out, data=data)
        if bar is not None:
            bar(i + 1, len(numbers))
    print(f"wrote {len(numbers)} figures to {args.out}")


def _add_data_model(p: argparse.ArgumentParser) -> None:
    """Options of compare/fit: the data file and the cell (None = take from file/preset)."""
    p.add_argument("data", help="measured profile CSV (see docs/measurements.md)")
    p.add_argument(
        "--preset",
        choices=PRESETS,
        default=None,
        help=(
            f"the paper's experiments: phi, eps, Ri, K (L = {_default('L')}, A = {_default('A')})"
        ),
    )
    p.add_argument("--geometry", choices=tuple(GEOMETRIES), default=None)
    p.add_argument("--eps", type=float, default=None, help="d_p/H (default: file header)")
    p.add_argument("--Ri", type=float, default=None, help="R_i/H (Couette)")
    p.add_argument("--B", type=float, default=None, help="gravity parameter (plane)")
    p.add_argument("--nu", type=float, default=None)
    p.add_argument("--phi", type=float, default=None)
    wall = p.add_mutually_exclusive_group()
    wall.add_argument("--delta", type=_angle_or_rough, default=None)
    wall.add_argument("--fully-rough", action="store_true")
    p.add_argument("--delta-lower", type=_angle_or_rough, default=None)
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


def _data_problem(args: argparse.Namespace):  # type: ignore[no-untyped-def]
    """The measured profile and the model problem: command line > preset > file header >
    the paper's defaults (those of :func:`cosserat.model.build_problem`). The header's Ri is
    used for Couette flow only, its B and nu for plane shear only."""
    from ..model.build import APPLIES_TO
    from ..studies.experiments import PRESETS as PRESET_CELLS

    _check_outputs(args)
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

    measured, problem = _data_problem(args)
    comparison = compare(problem, measured, method=args.method)
    if args.plot:
        from ..viz.plotting import comparison_plot

        fig = comparison_plot(comparison, problem.describe(), residual_panel=True)
        files.save_figure(fig, args.plot)
    if args.format == "json":
        _emit(json.dumps(comparison.to_dict(), allow_nan=False), args.out)
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
        _emit("\n".join(lines), args.out)


def cmd_fit(args: argparse.Namespace) -> None:
    from ..analysis.fitting import fit

    measured, problem = _data_problem(args)
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
        _emit(json.dumps(result.to_dict(), allow_nan=False), args.out)
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
        _emit("\n".join(lines), args.out)


def cmd_sweep(args: argparse.Namespace) -> None:
    import time

    from ..studies.sweep import check_table_format, load_spec, run_sweep, write_table

    spec = load_spec(args.spec)
    out = args.out or spec.output or str(Path(args.spec).with_suffix(".csv"))
    check_table_format(out)
    files.check_output_file(out, "--out" if args.out else "the sweep table")
    start = time.perf_counter()
    rows = run_sweep(
        spec, workers=args.workers, scheduler=args.scheduler, progress=_progress_bar("sweep")
    )
    write_table(rows, out, spec.columns)
    states = ("ok", "no-solution", "error", "invalid")
    counts = {s: sum(r.get("status") == s for r in rows) for s in states}
    print(
        f"{len(rows)} cases in {time.perf_counter() - start:.1f} s -> {out} "
        f"({', '.join(f'{k}: {v}' for k, v in counts.items())})"
    )


def make_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="cosserat", description=__doc__.splitlines()[0])
    parser.add_argument("--version", action="version", version=f"cosserat {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)

    solve_p = sub.add_parser("solve", help="one profile across the gap")
    solve_geo = solve_p.add_subparsers(dest="geometry", required=True, parser_class=_Parser)
    for geometry, helptext in GEOMETRIES.items():
        sp = solve_geo.add_parser(geometry, help=helptext)
        _add_material_and_walls(sp, plane=geometry == "plane")
        sp.add_argument("--eps", type=float, required=True, help="grain diameter / gap d_p/H")
        _add_solution(sp)
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
    th_geo = th.add_subparsers(dest="geometry", required=True, parser_class=_Parser)
    for geometry, helptext in GEOMETRIES.items():
        tp = th_geo.add_parser(geometry, help=helptext)
        _add_material_and_walls(tp, plane=geometry == "plane")
        tp.add_argument("--eps", type=float, nargs="+", required=True)
        tp.add_argument(
            "--f",
            type=float,
            default=config.DEFAULT_F,
            help=f"fraction defining Delta ({config.text(config.DEFAULT_F)})",
        )
        _add_solution(tp)
        tp.add_argument("--format", choices=("json", "csv"), default="json")
        tp.add_argument("--out", default=None)
        tp.set_defaults(func=cmd_thickness)

    rp = sub.add_parser("reproduce", help="reproduce the paper's results into a folder")
    rp.add_argument("--out", required=True, help="output folder")
    rp.add_argument(
        "--only",
        type=int,
        nargs="+",
        choices=range(1, 15),
        metavar="N",
        help="only these figures (1-14)",
    )
    rp.add_argument(
        "--workers", type=_positive_int, default=None, help="worker processes (default: cores)"
    )
    rp.set_defaults(func=cmd_reproduce)

    cp = sub.add_parser("compare", help="the model beside a measured velocity profile")
    _add_data_model(cp)
    cp.set_defaults(func=cmd_compare)

    fitp = sub.add_parser("fit", help="fit delta, K (and L, phi, A) to a measured profile")
    _add_data_model(fitp)
    fitp.add_argument(
        "--free", default="delta,K", help="comma-separated free parameters among delta,K,L,phi,A"
    )
    fitp.set_defaults(func=cmd_fit)

    sw = sub.add_parser("sweep", help="run a parameter sweep from a TOML spec")
    sw.add_argument("spec", help="TOML file (see cosserat.sweep)")
    sw.add_argument("--out", default=None, help="table to write (.csv or .parquet)")
    sw.add_argument(
        "--workers", type=_positive_int, default=None, help="local processes (default: cores)"
    )
    sw.add_argument(
        "--scheduler",
        default=None,
        help="Dask scheduler address (tcp://host:port) instead of local processes",
    )
    sw.set_defaults(func=cmd_sweep)

    fp = sub.add_parser("figures", help="write every paper figure (PNG, PDF, CSV)")
    fp.add_argument("--out", required=True, help="output folder")
    fp.add_argument("--only", type=int, nargs="+", choices=range(1, 15), metavar="N")
    fp.add_argument(
        "--data",
        nargs="+",
        metavar="KEY=FILE",
        help="overlay measured profiles on figures 10-11 (mustard, poppy, glass)",
    )
    fp.set_defaults(func=cmd_figures)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = make_parser()
    try:
        args = parser.parse_args(argv)
        if getattr(args, "f", None) is not None and not 0.0 < args.f < 1.0:
            raise UsageError(f"--f must satisfy 0 < f < 1; got {args.f:g}")
        args.func(args)
    except UsageError as exc:
        print(" ".join(str(exc).split()), file=sys.stderr)
        return 2
    except CosseratError as exc:  # a model or input problem; anything else is a bug
        message = " ".join(str(exc).split()) or type(exc).__name__
        print(f"cosserat: error: {message}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
