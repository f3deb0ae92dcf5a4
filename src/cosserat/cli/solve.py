"""``cosserat solve`` and ``cosserat thickness``: one profile, and Delta against eps."""

from __future__ import annotations

import argparse
import json
import re
from typing import Any

from .. import config
from ..analysis import thickness_curve, thickness_limit
from ..analysis.laws import thickness_curve_asymptote
from ..model.parameters import FULLY_ROUGH
from ..routes import solve
from . import files, params
from .common import (
    MAX_POINTS,
    Parser,
    UsageError,
    add_material_and_walls,
    add_model,
    add_output,
    add_solution,
    cell_help,
    check_outputs,
    deliver,
    model_problem,
    option_values,
    problem_from_args,
    progress_bar,
    solver_options,
    table,
)

TABLE_ROWS = 11
"""Rows of the profile table in ``--format text``."""


# --------------------------------------------------------------------------- solve
def profile_text(profile: Any) -> str:
    """A readable summary of a profile: the problem, Delta, slip, a short table."""
    s = profile.summary()
    d = s["diagnostics"]
    lines = [s["description"]]
    tol = "" if d["rtol"] is None else f", rtol {d['rtol']:g}"
    residual = max(d["residuals"].values(), default=None)
    check = "" if residual is None else f"; largest equation residual {residual:.2g}"
    lines.append(f"model {s['rheology']}, method {s['method']}{tol}, {s['points']} points{check}")
    if s["Delta"] is None:
        lines.append(f"Delta: not defined ({s['Delta_undefined']})")
    else:
        lines.append(
            f"Delta = {s['Delta']:.6g} grain diameters (where the velocity relative to the "
            f"far field has fallen to {config.DEFAULT_F:g} of its wall value)"
        )
    spin = (
        "no grain spin in this rheology"
        if s["wall_omega"] is None
        else f"wall spin = {s['wall_omega']:.6g}"
    )
    lines.append(f"wall slip = {s['wall_slip']:.6g}, {spin} (in the scales of u and omega)")
    cols = profile.columns()
    n = profile.xi.size
    picks = sorted({round(k * (n - 1) / (TABLE_ROWS - 1)) for k in range(TABLE_ROWS)})
    names = list(cols)[:5]
    lines += ["", *table(names, [[float(cols[c][i]) for c in names] for i in picks])]
    lines.append(
        f"({len(picks)} of {n} points; every column with --format csv or json; meanings with "
        "--format json)"
    )
    return "\n".join(lines)


def one_line(profile: Any) -> str:
    s = profile.summary()
    delta = "Delta undefined" if s["Delta"] is None else f"Delta = {s['Delta']:.6g}"
    return f"{s['cell']} ({s['rheology']}, {s['method']}): {delta}, wall slip {s['wall_slip']:.6g}"


def model_names(text: str) -> list[str]:
    """The models of ``--models a,b,...``, checked (as ``fit --models``)."""
    names = [m.strip() for m in text.split(",") if m.strip()]
    if not names:
        raise UsageError("--models: give model names separated by commas, e.g. cosserat,mui,ngf")
    repeated = sorted({m for m in names if names.count(m) > 1})
    if repeated:
        raise UsageError(f"--models names {', '.join(repeated)} more than once")
    unknown = [m for m in names if m not in params.RHEOLOGIES]
    if unknown:
        raise UsageError(
            f"--models: unknown model(s) {', '.join(unknown)}; registered: "
            f"{', '.join(params.RHEOLOGIES)}"
        )
    return names


def models_figure(profiles: dict[str, Any]) -> Any:
    """The velocity profiles of several models on one cell, overlaid."""
    from ..viz.plotting import new_figure, style

    fig, axes = new_figure(1, 1, width=5.0, height=3.6)
    ax = axes[0][0]
    with style():
        for name, profile in profiles.items():
            cols = profile.columns()
            coord = next(iter(cols))
            ax.plot(cols[coord], cols["u"], label=name)
        first = next(iter(profiles.values()))
        ax.set_xlabel(next(iter(first.column_meanings().values())).split(",")[0])
        ax.set_ylabel("u (velocity over its scale)")
        ax.set_title(first.problem.cell.title)
        ax.legend()
        fig.tight_layout()
    return fig


def cmd_solve_models(args: argparse.Namespace) -> None:
    """``solve CELL --models a,b,...``: each model on the cell, side by side (the options a
    model does not take go to the others; ``--plot`` overlays the velocity profiles)."""
    if args.model != params.DEFAULT_MODEL:
        raise UsageError("give --model or --models, not both")
    names = model_names(args.models)
    cell = args.geometry
    for name in names:
        params.check_model(name, cell)
    given = option_values(args, args.eps)
    extra = params.parse_params(args.param)
    taken: set[str] = set()
    problems = {}
    for name in names:
        valid = params.parameters(name, cell)
        own = {k: v for k, v in given.items() if k == "geometry" or k in valid}
        own_extra = {k: v for k, v in extra.items() if k in valid}
        taken |= {k for k, v in own.items() if v is not None} | set(own_extra)
        problems[name] = model_problem(name, cell, own, own_extra)
    unused = [
        "--" + k.replace("_", "-")
        for k, v in given.items()
        if v is not None and k not in taken | {"geometry"}
    ] + [f"--param {k}" for k in extra if k not in taken]
    if unused:
        raise UsageError(f"{', '.join(unused)}: none of --models {args.models} takes it")
    if not 3 <= args.points <= MAX_POINTS:
        raise UsageError(f"--points must satisfy 3 <= points <= {MAX_POINTS}; got {args.points}")
    check_outputs(args)
    profiles = {
        name: solve(p, method=args.method, points=args.points, **solver_options(args))
        for name, p in problems.items()
    }
    if args.plot:
        files.save_figure(models_figure(profiles), args.plot)

    def render(fmt: str) -> str:
        if fmt == "json":
            record = {"cell": cell, "models": {n: p.to_dict() for n, p in profiles.items()}}
            return json.dumps(record, allow_nan=False)
        if fmt == "csv":
            coord = next(iter(next(iter(profiles.values())).columns()))
            out = [f"model,{coord},u"]
            for n, p in profiles.items():
                cols = p.columns()
                out += [
                    f"{n},{float(x)!r},{float(u)!r}"
                    for x, u in zip(cols[coord], cols["u"], strict=True)
                ]
            return "\n".join(out)
        return "\n\n".join(profile_text(p) for p in profiles.values())

    def meta() -> dict[str, Any]:
        first = next(iter(profiles.values()))
        coord, meaning = next(iter(first.column_meanings().items()))
        return {
            "cell": cell,
            "models": {n: p.summary() for n, p in profiles.items()},
            "columns": {
                "model": {"meaning": "rheology", "unit": ""},
                coord: {"meaning": meaning, "unit": "1"},
                "u": {"meaning": "velocity over the cell's velocity scale", "unit": "1"},
            },
        }

    line = "; ".join(one_line(p) for p in profiles.values())
    deliver(args, render, meta, line)


def cmd_solve(args: argparse.Namespace) -> None:
    if getattr(args, "models", None):
        cmd_solve_models(args)
        return
    problem = problem_from_args(args, args.eps)
    if not 3 <= args.points <= MAX_POINTS:
        raise UsageError(f"--points must satisfy 3 <= points <= {MAX_POINTS}; got {args.points}")
    check_outputs(args)
    profile = solve(problem, method=args.method, points=args.points, **solver_options(args))
    if args.plot:
        files.save_figure(profile.plot(), args.plot)

    def render(fmt: str) -> str:
        if fmt == "csv":
            return str(profile.to_csv())
        if fmt == "json":
            return str(profile.to_json(indent=None))
        return profile_text(profile)

    deliver(args, render, profile.summary, one_line(profile))


# --------------------------------------------------------------------------- thickness
def _without_eps(text: str) -> str:
    return re.sub(r",? ?eps = [^,;]+", "", text)


def thickness_figure(record: dict[str, Any]) -> Any:
    """Delta against eps on log axes, with the small-eps asymptote where the model has one."""
    from ..viz.plotting import new_figure, style

    fig, axes = new_figure(1, 1, width=4.8, height=3.6)
    ax = axes[0, 0]
    with style():
        points = [(e, d) for e, d in zip(record["eps"], record["Delta"], strict=True) if d]
        if points:
            ax.loglog(*zip(*points, strict=True), "ko-", label="model")
        asym = [
            (e, a) for e, a in zip(record["eps"], record["Delta_asymptotic"] or [], strict=False)
        ]
        asym = [(e, a) for e, a in asym if a]
        if asym:
            ax.loglog(*zip(*asym, strict=True), "k--", label="small-eps asymptote")
        if record["Delta_asymptote"]:
            ax.axhline(record["Delta_asymptote"], color="0.5", lw=0.8, label="eps -> 0 limit")
        from matplotlib.ticker import FuncFormatter

        plain = FuncFormatter(lambda v, _: f"{v:g}")
        ax.yaxis.set_major_formatter(plain)
        ax.yaxis.set_minor_formatter(plain)
        ax.set_xlabel(r"$\varepsilon = d_p/H$")
        ax.set_ylabel(r"$\Delta$ (grain diameters)")
        ax.legend(loc="best")
        ax.set_title(_without_eps(record["description"]), fontsize=6)
        fig.tight_layout()
    return fig


def thickness_text(record: dict[str, Any]) -> str:
    lines = [
        f"Delta against eps for: {_without_eps(record['description'])}",
        f"model {record['model']}, method {record['method']}, f = {record['f']:g} "
        "(Delta in grain diameters)",
    ]
    if record["Delta_asymptote"] is not None:
        lines.append(f"eps -> 0 limit of Delta: {record['Delta_asymptote']:.6g}")
    rows = [
        [e, d, None if a is None else a]
        for e, d, a in zip(
            record["eps"],
            record["Delta"],
            record["Delta_asymptotic"] or [None] * len(record["eps"]),
            strict=True,
        )
    ]
    lines += ["", *table(["eps", "Delta", "asymptotic"], rows)]
    for e, why in record["failures"].items():
        lines.append(f"eps = {e}: {' '.join(why.split())}")
    return "\n".join(lines)


def thickness_csv(record: dict[str, Any]) -> str:
    lines = ["eps,Delta,Delta_asymptotic"]
    asym = record["Delta_asymptotic"] or [None] * len(record["eps"])
    for e, d, a in zip(record["eps"], record["Delta"], asym, strict=True):
        lines.append(",".join("" if v is None else repr(v) for v in (e, d, a)))
    return "\n".join(lines)


def cmd_thickness_vs_gap(args: argparse.Namespace) -> None:
    """``thickness CELL --vs-gap``: Delta against H/d for each model on the cell."""
    from ..analysis.gap import DEFAULT_CELL, DEFAULT_GAPS, thickness_vs_gap

    if args.eps is not None:
        raise UsageError("--vs-gap sets the gaps itself: give H/d values to --vs-gap, not --eps")
    gaps = list(args.vs_gap) or list(DEFAULT_GAPS)
    bad = [g for g in gaps if not g > 2.0]
    if bad:
        raise UsageError(f"--vs-gap: every H/d must exceed 2; got {', '.join(map(str, bad))}")
    models = None
    if args.models:
        models = [m.strip() for m in args.models.split(",") if m.strip()]
    cell_parameters = dict(DEFAULT_CELL.get(args.geometry, {}))
    for key in ("B", "nu", "Ri"):
        if getattr(args, key, None) is not None:
            cell_parameters[key] = getattr(args, key)
    # the Cosserat options are the Cosserat model's parameters; --param those of --model
    model_parameters: dict[str, dict[str, object]] = {}
    cosserat = {
        name: getattr(args, name)
        for name in ("phi", "L", "A", "K")
        if getattr(args, name, None) is not None
    }
    if getattr(args, "fully_rough", False):
        cosserat["delta"] = FULLY_ROUGH
    elif getattr(args, "delta", None) is not None:
        cosserat["delta"] = args.delta
    for name in ("delta_lower", "K_lower", "m_wall"):
        if getattr(args, name, None) is not None:
            option = "--" + name.replace("_", "-")
            raise UsageError(f"{option} does not apply to --vs-gap (one wall moves, one series)")
    if cosserat:
        model_parameters[params.DEFAULT_MODEL] = cosserat
    given = {k: params.convert(v) for k, v in params.parse_params(args.param).items()}
    if given:
        model_parameters.setdefault(args.model, {}).update(given)
    unused = [m for m in model_parameters if models is not None and m not in models]
    if unused:
        raise UsageError(f"parameters are given for {', '.join(unused)}, which --models leaves out")
    check_outputs(args)
    study = thickness_vs_gap(
        args.geometry,
        models,
        gaps,
        cell_parameters=cell_parameters,
        model_parameters=model_parameters,
        f=args.f,
    )
    if args.plot:
        files.save_figure(study.plot(), args.plot)
    record = study.to_dict()

    def render(fmt: str) -> str:
        if fmt == "json":
            return json.dumps(record, allow_nan=False)
        if fmt == "csv":
            out = ["series,model,gap_d,Delta"]
            for series in study.series:
                for g, d in zip(series.gaps, series.Delta, strict=True):
                    label = series.label.replace(",", ";")
                    out.append(f"{label},{series.model},{g!r},{'' if d is None else repr(d)}")
            return "\n".join(out)
        return study.to_text()

    slopes = [
        f"{s.label}: {s.slope_large_gap:.2f}" for s in study.series if s.slope_large_gap is not None
    ]
    line = f"{args.geometry}: slope of Delta vs H/d at the largest gaps: " + "; ".join(slopes)
    meta = {k: v for k, v in record.items() if k != "series"}
    meta["columns"] = {
        "series": {"meaning": "model and wall of the series", "unit": ""},
        "model": {"meaning": "rheology", "unit": ""},
        "gap_d": {"meaning": "gap over grain diameter H/d", "unit": "1"},
        "Delta": {"meaning": "shear-layer thickness (empty: no solution)", "unit": "d"},
    }
    deliver(args, render, meta, line)


def cmd_thickness(args: argparse.Namespace) -> None:
    if args.vs_gap is not None:
        cmd_thickness_vs_gap(args)
        return
    if args.eps is None:
        raise UsageError("give --eps (one or more d_p/H), or --vs-gap for Delta against H/d")
    eps_values = list(args.eps)
    problem = problem_from_args(args, eps_values[0])
    for e in eps_values[1:]:
        problem.with_values({"eps": e})  # validate every eps before any solve
    check_outputs(args)
    curve = thickness_curve(
        problem,
        eps_values,
        f=args.f,
        method=args.method,
        progress=progress_bar("thickness") if len(eps_values) > 1 else None,
        **solver_options(args),
    )
    cosserat = problem.model == params.DEFAULT_MODEL
    limit = thickness_limit(problem, args.f) if cosserat else None
    asym = thickness_curve_asymptote(problem, eps_values, args.f) if cosserat else None
    record = {
        "problem": problem.parameters()["geometry"],
        "model": args.model,
        "description": problem.describe(),
        "parameters": {k: v for k, v in problem.parameters().items() if k != "eps"},
        "method": args.method,
        "f": args.f,
        "eps": eps_values,
        "Delta": curve.Delta,
        "Delta_asymptote": limit,
        "Delta_asymptotic": asym,
        "failures": {repr(e): why for e, why in curve.failures.items()},
        "units": "Delta in grain diameters; eps = d_p/H",
    }
    if args.plot:
        files.save_figure(thickness_figure(record), args.plot)

    def render(fmt: str) -> str:
        if fmt == "csv":
            return thickness_csv(record)
        if fmt == "json":
            return json.dumps(record, allow_nan=False)
        return thickness_text(record)

    found = [d for d in curve.Delta if d is not None]
    line = (
        f"{record['problem']} ({args.model}): Delta from {min(found):.4g} to {max(found):.4g} "
        f"over {len(found)} of {len(eps_values)} eps"
        if found
        else f"{record['problem']} ({args.model}): no eps with a solution"
    )
    meta = {k: v for k, v in record.items() if k not in ("eps", "Delta", "Delta_asymptotic")}
    meta["columns"] = {
        "eps": {"meaning": "grain diameter over gap d_p/H", "unit": "1"},
        "Delta": {"meaning": "shear-layer thickness (empty: no solution)", "unit": "d_p"},
        "Delta_asymptotic": {"meaning": "small-eps asymptotic Delta", "unit": "d_p"},
    }
    deliver(args, render, meta, line)


# --------------------------------------------------------------------------- parsers
def _add_cell_options(p: argparse.ArgumentParser, cell: str) -> None:
    if params.DEFAULT_MODEL in params.cells().get(cell, []):
        add_material_and_walls(p, cell)
    add_model(p, cell)


def add_parsers(sub: argparse._SubParsersAction) -> None:
    """Add this module's commands to the ``cosserat`` parser."""
    cells = params.cells()
    solve_p = sub.add_parser(
        "solve",
        help="one profile across the gap",
        description="Solve one cell with one model; prints a summary, the profile as a table "
        "(--format csv) or every number (--format json).",
    )
    solve_geo = solve_p.add_subparsers(dest="geometry", required=True, parser_class=Parser)
    for cell in cells:
        sp = solve_geo.add_parser(cell, help=cell_help(cell), description=cell_help(cell))
        sp.add_argument(
            "--eps", type=float, required=True, help="grain diameter over gap d_p/H [-]"
        )
        _add_cell_options(sp, cell)
        add_solution(sp)
        sp.add_argument(
            "--points",
            type=int,
            default=config.OUTPUT_POINTS,
            help=f"output points across the gap, layers resolved (default: {config.OUTPUT_POINTS})",
        )
        sp.add_argument(
            "--models",
            default=None,
            metavar="A,B,...",
            help=(
                "comma-separated models solved side by side on this cell (as fit --models); "
                "--plot overlays their velocity profiles"
            ),
        )
        add_output(sp, plot="a quick plot of the profile (with --models: every model's)")
        sp.set_defaults(func=cmd_solve)

    th = sub.add_parser(
        "thickness",
        help="shear-layer thickness Delta against eps",
        description="Delta (in grain diameters) at each eps, with the small-eps asymptote "
        "where the model has one.",
    )
    th_geo = th.add_subparsers(dest="geometry", required=True, parser_class=Parser)
    for cell in cells:
        tp = th_geo.add_parser(cell, help=cell_help(cell), description=cell_help(cell))
        tp.add_argument(
            "--eps",
            type=float,
            nargs="+",
            default=None,
            help="one or more grain diameter over gap d_p/H [-] (or use --vs-gap)",
        )
        tp.add_argument(
            "--vs-gap",
            type=float,
            nargs="*",
            default=None,
            metavar="H/d",
            help=(
                "Delta against the gap H/d for every model on this cell (the paper's "
                "distinguishing prediction: gap-independent for walls smoother than the "
                "material, ~ (H/d)^(1/3) for fully rough ones); optional gaps [-] "
                "(default: 10 20 40 80 160 320)"
            ),
        )
        tp.add_argument(
            "--models",
            default=None,
            help="with --vs-gap: comma-separated models (default: every one on this cell)",
        )
        _add_cell_options(tp, cell)
        tp.add_argument(
            "--f",
            type=float,
            default=config.DEFAULT_F,
            help=(
                "Delta is where the velocity relative to the far field has fallen to this "
                f"fraction of its wall value [-] (default: {config.text(config.DEFAULT_F)})"
            ),
        )
        add_solution(tp)
        add_output(tp, plot="Delta against eps on log axes")
        tp.set_defaults(func=cmd_thickness)
