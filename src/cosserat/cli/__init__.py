"""The ``cosserat`` command line: a thin layer over the API (no physics here).

Bad input exits with status 2 and one line on stderr saying what is wrong.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path
from typing import Any, NoReturn

from .._version import __version__
from ..analysis import thickness_curve, thickness_limit
from ..analysis.laws import thickness_curve_asymptote
from ..config import DEFAULT_F
from ..errors import CosseratError
from ..model import CouetteFlow, PlaneShear, Problem
from ..model.parameters import FULLY_ROUGH, Material, Wall
from ..routes import METHODS, solve

PAPER_DEFAULTS = {
    "phi": 28.5,
    "delta": 20.0,
    "L": 10.0,
    "A": 1.0 / 3.0,
    "K": 0.5,
    "B": 0.0,
    "nu": 1.0,
}


GEOMETRIES = {
    "plane": "plane shear between parallel walls",
    "couette": "cylindrical Couette flow, inner cylinder turning",
}


class UsageError(Exception):
    """Bad command-line usage (reported in one line, exit status 2)."""


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:
        raise UsageError(f"{self.prog}: {message}")


def _angle_or_rough(text: str) -> float | str:
    if text.lower() in ("rough", "fully-rough", "fully_rough"):
        return FULLY_ROUGH
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected an angle in degrees or 'fully-rough'; got {text!r}"
        ) from None


def _add_material_and_walls(p: argparse.ArgumentParser, plane: bool) -> None:
    g = p.add_argument_group("material and walls (defaults: the paper's)")
    g.add_argument(
        "--phi",
        type=float,
        default=PAPER_DEFAULTS["phi"],
        help="angle of internal friction [deg] (28.5)",
    )
    wall = g.add_mutually_exclusive_group()
    wall.add_argument(
        "--delta",
        type=_angle_or_rough,
        default=PAPER_DEFAULTS["delta"],
        help="angle of wall friction [deg] or 'fully-rough' (20)",
    )
    wall.add_argument(
        "--fully-rough", action="store_true", help="fully rough wall(s): tan(delta) = sin(phi)"
    )
    g.add_argument("--L", type=float, default=PAPER_DEFAULTS["L"], help="yield-condition L (10)")
    g.add_argument(
        "--A", type=float, default=PAPER_DEFAULTS["A"], help="yield-condition A = a2/a1 (1/3)"
    )
    g.add_argument(
        "--K", type=float, default=PAPER_DEFAULTS["K"], help="wall slip coefficient (0.5)"
    )
    if not plane:
        g.add_argument("--Ri", type=float, default=1.0, help="inner radius / gap R_i/H (1)")
    if plane:
        g.add_argument(
            "--delta-lower",
            type=_angle_or_rough,
            default=None,
            help="lower wall's delta [deg] or 'fully-rough' (default: = delta)",
        )
        g.add_argument("--K-lower", type=float, default=None, help="lower wall's K (default: = K)")
        g.add_argument(
            "--B",
            type=float,
            default=PAPER_DEFAULTS["B"],
            help="gravity parameter rho_p g H / N (0: no gravity)",
        )
        g.add_argument("--nu", type=float, default=PAPER_DEFAULTS["nu"], help="solids fraction (1)")
        g.add_argument(
            "--m-wall",
            type=float,
            default=None,
            help="couple stress m at the non-slipping wall (instead of eqn-nd_bc4)",
        )


def _add_solution(p: argparse.ArgumentParser) -> None:
    p.add_argument("--method", choices=METHODS, default="numerical")
    p.add_argument("--rtol", type=float, default=None, help="numerical tolerance (1e-8)")


def build_problem(args: argparse.Namespace, eps: float) -> Problem:
    """The problem the options describe (geometry from the sub-command)."""
    material = Material(phi=args.phi, L=args.L, A=args.A)
    delta = FULLY_ROUGH if args.fully_rough else args.delta
    upper = Wall(delta, args.K)
    if args.geometry == "couette":
        return CouetteFlow(material=material, wall=upper, eps=eps, Ri=args.Ri)
    lower_delta = delta if args.delta_lower is None else args.delta_lower
    lower_K = args.K if args.K_lower is None else args.K_lower
    return PlaneShear(
        material=material,
        upper=upper,
        lower=Wall(lower_delta, lower_K),
        eps=eps,
        B=args.B,
        nu=args.nu,
        m_fixed_wall=args.m_wall,
    )


def _solver_options(args: argparse.Namespace) -> dict[str, Any]:
    opts: dict[str, Any] = {}
    if args.rtol is not None:
        if args.method != "numerical":
            raise UsageError("--rtol applies to --method numerical only")
        opts["rtol"] = args.rtol
    return opts


def _emit(text: str, out: str | None) -> None:
    if out:
        Path(out).write_text(text if text.endswith("\n") else text + "\n")
    else:
        sys.stdout.write(text if text.endswith("\n") else text + "\n")


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
    problem = build_problem(args, args.eps)
    if args.points < 3:
        raise UsageError("--points must be at least 3")
    profile = solve(problem, method=args.method, points=args.points, **_solver_options(args))
    if args.plot:
        profile.plot().savefig(args.plot)
    if args.format == "csv":
        _emit(profile.to_csv(), args.out)
    else:
        _emit(profile.to_json(indent=None), args.out)


def cmd_thickness(args: argparse.Namespace) -> None:
    eps_values = list(args.eps)
    problem = build_problem(args, eps_values[0])
    for e in eps_values[1:]:
        replace(problem, eps=e)  # validate every eps before any solve
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

    out = reproduce(args.out, figures=args.only, workers=args.workers, progress=_stage_bar())
    print(f"wrote {out}/index.html and {out}/report.md")


def cmd_figures(args: argparse.Namespace) -> None:
    from ..analysis.measurements import read_profile
    from ..paper.figures import FIGURES, make_figure

    data = {}
    for item in args.data or []:
        key, sep, path = item.partition("=")
        if not sep or key not in ("mustard", "poppy", "glass"):
            raise UsageError(f"--data takes mustard=FILE, poppy=FILE or glass=FILE; got {item!r}")
        data[key] = read_profile(path)
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
        choices=("mustard", "poppy", "glass"),
        default=None,
        help="the paper's experiments: phi, eps, Ri, K (L = 10, A = 1/3)",
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


def _data_problem(args: argparse.Namespace):  # type: ignore[no-untyped-def]
    """The measured profile and the model problem: command line > preset > file header >
    the paper's defaults."""
    from ..analysis.measurements import read_profile
    from ..studies.experiments import PRESETS

    measured = read_profile(args.data)
    header = measured.meta
    preset = PRESETS[args.preset] if args.preset else None

    def pick(
        name: str,
        header_key: str | None = None,
        preset_attr: str | None = None,
        default: object = None,
    ) -> object:
        value = getattr(args, name)
        if value is not None:
            return value
        if preset is not None and preset_attr is not None:
            return getattr(preset, preset_attr)
        if header_key is not None and header_key in header:
            return header[header_key]
        return default

    geometry = pick("geometry", "geometry", None, None)
    if geometry is None:
        geometry = "couette" if preset is not None else None
    if geometry not in GEOMETRIES:
        raise UsageError(
            "give --geometry plane|couette (or a 'geometry:' header line, or --preset)"
        )
    eps = pick("eps", "eps", "eps")
    if eps is None:
        raise UsageError("give --eps (or an 'eps:' header line, or --preset)")
    ns = argparse.Namespace(
        geometry=geometry,
        phi=pick("phi", None, "phi", PAPER_DEFAULTS["phi"]),
        L=pick("L", None, "L", PAPER_DEFAULTS["L"]),
        A=pick("A", None, "A", PAPER_DEFAULTS["A"]),
        K=pick("K", None, "K", PAPER_DEFAULTS["K"]),
        delta=args.delta if args.delta is not None else PAPER_DEFAULTS["delta"],
        fully_rough=args.fully_rough,
        Ri=pick("Ri", "ri", "Ri", 1.0),
        B=pick("B", "b", None, 0.0),
        nu=pick("nu", "nu", None, 1.0),
        delta_lower=args.delta_lower,
        K_lower=args.K_lower,
        m_wall=args.m_wall,
    )
    if args.delta is None and not args.fully_rough and preset is not None:
        ns.delta = preset.default_delta
    return measured, build_problem(ns, float(eps))  # type: ignore[arg-type]


def cmd_compare(args: argparse.Namespace) -> None:
    from ..analysis.fitting import compare

    measured, problem = _data_problem(args)
    comparison = compare(problem, measured, method=args.method)
    if args.plot:
        from ..viz.plotting import comparison_plot

        comparison_plot(comparison, problem.describe(), residual_panel=True).savefig(args.plot)
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

        comparison_plot(
            result.comparison, "fit: " + result.problem.describe(), residual_panel=True
        ).savefig(args.plot)
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

    from ..studies.sweep import load_spec, run_sweep, write_table

    spec = load_spec(args.spec)
    out = args.out or spec.output or str(Path(args.spec).with_suffix(".csv"))
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
        sp.add_argument("--points", type=int, default=201, help="output points (layers resolved)")
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
        tp.add_argument("--f", type=float, default=DEFAULT_F, help="fraction defining Delta (0.05)")
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
    rp.add_argument("--workers", type=int, default=None, help="worker processes (default: cores)")
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
    sw.add_argument("--workers", type=int, default=None, help="local processes (default: cores)")
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
        print(str(exc), file=sys.stderr)
        return 2
    except (CosseratError, ValueError, ArithmeticError) as exc:
        message = " ".join(str(exc).split()) or type(exc).__name__
        print(f"cosserat: error: {message}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
