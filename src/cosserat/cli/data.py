"""``cosserat compare`` and ``cosserat fit``: the model beside a measured profile."""

from __future__ import annotations

import argparse
import json
import math
import sys
from typing import Any

from ..routes import RHEOLOGIES
from . import files, params
from .common import (
    GEOMETRIES,
    PRESETS,
    UsageError,
    add_model,
    add_output,
    add_solution,
    angle_or_rough,
    check_outputs,
    default_text,
    deliver,
    model_problem,
    option_values,
    progress_messages,
    table,
)


def _add_data_model(p: argparse.ArgumentParser) -> None:
    """Options of compare/fit: the data file and the cell (None = take from file/preset)."""
    p.add_argument(
        "data",
        help="measured profile: CSV of distance_d (from the moving wall [d_p]), u_over_uw "
        "[-], optional u_err [-], header lines such as '# eps: 0.05' (docs/measurements.md)",
    )
    g = p.add_argument_group(
        "the cell (command line > --preset > the file's header > defaults, with a warning "
        "where the command line disagrees with the header; fit: what the header states wins)"
    )
    g.add_argument(
        "--preset",
        choices=PRESETS,
        default=None,
        help=(
            "the paper's experiments (Couette): phi, eps, Ri, K "
            f"(L = {default_text('L')}, A = {default_text('A')})"
        ),
    )
    g.add_argument(
        "--geometry", choices=tuple(GEOMETRIES), default=None, help="the cell (default: header)"
    )
    g.add_argument(
        "--eps",
        type=float,
        default=None,
        help="grain diameter over gap d_p/H [-] (default: header)",
    )
    g.add_argument(
        "--Ri", type=float, default=None, help="inner radius over gap R_i/H [-] (Couette)"
    )
    g.add_argument(
        "--B", type=float, default=None, help="gravity parameter rho_p g H / N [-] (plane)"
    )
    g.add_argument("--nu", type=float, default=None, help="solids fraction [-] (plane)")
    m = p.add_argument_group("the Cosserat model's material and walls (defaults: the paper's)")
    m.add_argument("--phi", type=float, default=None, help="angle of internal friction [deg]")
    wall = m.add_mutually_exclusive_group()
    wall.add_argument(
        "--delta", type=angle_or_rough, default=None, help="angle of wall friction [deg]"
    )
    wall.add_argument("--fully-rough", action="store_true", help="fully rough walls")
    m.add_argument(
        "--delta-lower", type=angle_or_rough, default=None, help="lower wall's delta [deg] (plane)"
    )
    m.add_argument("--K-lower", type=float, default=None, help="lower wall's K [-] (plane)")
    m.add_argument("--L", type=float, default=None, help="yield-condition constant L [-]")
    m.add_argument("--A", type=float, default=None, help="yield-condition ratio A = a2/a1 [-]")
    m.add_argument("--K", type=float, default=None, help="wall slip coefficient [-]")
    m.add_argument(
        "--m-wall", type=float, default=None, help="couple stress at the non-slipping wall [-]"
    )
    add_model(p)
    add_solution(p)
    add_output(p, plot="the data beside the model (linear and log axes, residuals)")


# header keys (lower case) of a measured-profile file that describe the cell, by parameter
_HEADER_KEYS = {"geometry": "geometry", "eps": "eps", "Ri": "ri", "B": "b", "nu": "nu"}
_CELL_NAMES = ("eps", "Ri", "B", "nu")


def data_problem(args: argparse.Namespace):
    """The measured profile and the model problem: command line > preset > file header >
    the declared defaults (those of :func:`cosserat.model.make_problem`). The header's Ri is
    used for Couette flow only, its B and nu for plane shear only (as the declarations say).
    For a model other than the Cosserat one, only the cell (eps, Ri, B, nu) comes from the
    preset and the header."""
    from ..model import problem_parameters
    from ..studies.experiments import PRESETS as PRESET_CELLS

    check_outputs(args)
    measured = files.read_measured(args.data)
    header = measured.meta
    preset = PRESET_CELLS[args.preset] if args.preset else None
    given = option_values(args, args.eps)
    cosserat = args.model == params.DEFAULT_MODEL

    def from_file(name: str) -> Any:
        if not cosserat and name not in _CELL_NAMES:
            return None
        if preset is not None and name in ("phi", "L", "A", "K", "eps", "Ri"):
            return getattr(preset, name)
        return header.get(_HEADER_KEYS.get(name, ""))

    geometry = given["geometry"] or from_file("geometry") or header.get("geometry")
    if geometry is None and preset is not None:
        geometry = "couette"
    if geometry is None:
        raise UsageError(
            "give --geometry plane|couette (or a 'geometry:' header line, or --preset)"
        )
    params.check_model(args.model, geometry)
    applies = problem_parameters(args.model, geometry)
    values: dict[str, Any] = {}
    for name, value in given.items():
        if name == "geometry":
            continue
        if value is None and name in applies:
            value = from_file(name)
        values[name] = value
    if values["eps"] is None:
        raise UsageError("give --eps (or an 'eps:' header line, or --preset)")
    if cosserat and values["delta"] is None and preset is not None:
        values["delta"] = preset.default_delta
    extra = params.parse_params(args.param)
    return measured, model_problem(args.model, geometry, values, extra)


def _figure(comparison: Any, title: str, path: str) -> None:
    from ..viz.plotting import comparison_plot

    files.save_figure(comparison_plot(comparison, title, residual_panel=True), path)


def _compare_csv(measured: Any, model: Any, residuals: Any) -> str:
    head = ["distance_d", "u_over_uw"] + (["u_err"] if measured.u_err is not None else [])
    lines = [",".join([*head, "model", "residual"])]
    for i in range(measured.n):
        row = [measured.distance_d[i], measured.u_over_uw[i]]
        if measured.u_err is not None:
            row.append(measured.u_err[i])
        row += [model[i], residuals[i]]
        lines.append(",".join(repr(float(v)) for v in row))
    return "\n".join(lines)


_COMPARE_COLUMNS = {
    "distance_d": {"meaning": "distance from the moving wall", "unit": "d_p"},
    "u_over_uw": {"meaning": "measured velocity over the moving wall's", "unit": "1"},
    "u_err": {"meaning": "its uncertainty (one standard deviation)", "unit": "1"},
    "model": {"meaning": "the model's velocity over the moving wall's there", "unit": "1"},
    "residual": {"meaning": "data minus model", "unit": "1"},
}


def header_disagreements(args: argparse.Namespace, header: dict[str, Any]) -> list[str]:
    """Each cell value the command line gives that the file's header states otherwise, as a
    sentence: ``compare`` uses the command line's (a what-if comparison), and says so."""
    given = option_values(args, args.eps)
    out = []
    for name, key in _HEADER_KEYS.items():
        mine, theirs = given.get(name), header.get(key)
        if mine is None or theirs is None:
            continue
        try:
            same = math.isclose(float(mine), float(theirs), rel_tol=1e-9, abs_tol=0.0)
        except (TypeError, ValueError):
            same = str(mine).strip().lower() == str(theirs).strip().lower()
        if not same:
            out.append(
                f"--{name} {mine} differs from the file's header ({key}: {theirs}); "
                f"the model is solved with the command line's {name} = {mine}"
            )
    return out


def cmd_compare(args: argparse.Namespace) -> None:
    from ..analysis.fitting import compare

    measured, problem = data_problem(args)
    for text in header_disagreements(args, measured.meta):
        print(f"cosserat: warning: {text}", file=sys.stderr)
    opts = {} if args.rtol is None else {"rtol": args.rtol}
    if args.model == params.DEFAULT_MODEL:
        comparison = compare(problem, measured, method=args.method, **opts)
    else:
        comparison = _local_comparison(measured, problem, args, opts)
    if args.plot:
        _figure(comparison, problem.describe(), args.plot)
    record = comparison.to_dict()
    record["model_name"] = args.model
    record["description"] = problem.describe()

    def render(fmt: str) -> str:
        if fmt == "json":
            return json.dumps(record, allow_nan=False)
        if fmt == "csv":
            return _compare_csv(measured, comparison.model, comparison.residuals)
        lines = [
            problem.describe(),
            f"model {args.model}, method {args.method}; {measured.n} points",
            f"rms(data - model) = {comparison.rms:.4g} (of the wall speed)",
        ]
        if comparison.chi2 is not None:
            lines.append(f"chi-square = {comparison.chi2:.4g} for {measured.n} points")
        # the CSV's columns, by the CSV's names (units in the header, meanings in the sidecar)
        cols = [measured.distance_d, measured.u_over_uw]
        head = ["distance_d [d_p]", "u_over_uw"]
        if measured.u_err is not None:
            cols.append(measured.u_err)
            head.append("u_err")
        cols += [comparison.model, comparison.residuals]
        head += ["model", "residual"]
        rows = [[float(v) for v in row] for row in zip(*cols, strict=True)]
        lines += ["", *table(head, rows, 4)]
        return "\n".join(lines)

    meta = {k: v for k, v in record.items() if k not in ("distance_d", "u_over_uw", "model")}
    meta.pop("residuals", None)
    meta["columns"] = {
        k: v for k, v in _COMPARE_COLUMNS.items() if k != "u_err" or measured.u_err is not None
    }
    line = f"{args.model} beside {measured.n} points: rms(data - model) = {comparison.rms:.4g}"
    deliver(args, render, meta, line)


def _local_comparison(measured: Any, problem: Any, args: argparse.Namespace, opts: dict) -> Any:
    """compare() for any registered rheology: the model as it is (no free parameter)."""
    from ..analysis.fitting import compare

    if args.method != "numerical":
        raise UsageError(f"--model {args.model}: compare uses --method numerical")
    return compare(problem, measured, method="numerical", **opts)


def _error_text(stderr: Any, reason: str | None = None) -> str:
    if stderr is None or not math.isfinite(stderr):
        return f"(no uncertainty{': ' + reason if reason else ''})"
    return f"+- {stderr:.2g}"


def cmd_fit_models(args: argparse.Namespace) -> None:
    """``fit --models a,b,...``: fit each model and rank them (chi^2, AIC, BIC)."""
    from ..calibration.single import rank_models

    names = [m.strip() for m in args.models.split(",") if m.strip()]
    if not names:
        raise UsageError("--models: give model names separated by commas, e.g. cosserat,mui,ngf")
    repeated = sorted({m for m in names if names.count(m) > 1})
    if repeated:
        raise UsageError(f"--models names {', '.join(repeated)} more than once")
    unknown = [m for m in names if m not in RHEOLOGIES]
    if unknown:
        raise UsageError(
            f"--models: unknown model(s) {', '.join(unknown)}; registered: {', '.join(RHEOLOGIES)}"
        )
    if args.free:
        raise UsageError("--free applies to one model; with --models each fits its default set")
    measured, problem = data_problem(args)
    cell = problem.parameters()["geometry"]
    cell_keys = ("eps", "Ri") if cell == "couette" else ("eps", "B", "nu")
    given = problem.parameters()
    cell_parameters = {k: given[k] for k in cell_keys if given.get(k) is not None}
    ranking = rank_models(measured, cell_parameters, names, cell=cell)
    if args.plot:
        files.save_figure(ranking.plot(title=f"{measured.n} points, {cell} cell"), args.plot)
    record = ranking.to_dict()

    def render(fmt: str) -> str:
        if fmt == "json":
            return json.dumps(record, allow_nan=False)
        if fmt == "csv":
            out = ["rank,model,k,chi2,reduced_chi2,AIC,BIC,akaike_weight,status"]
            weights = ranking.weights()
            for i, f in enumerate(ranking.ranked, start=1):
                cells = [str(i) if f.ok else "", f.model]
                for v in (f.k, f.chi2, f.reduced_chi2, f.aic, f.bic, weights.get(f.model)):
                    cells.append("" if v is None or not f.ok else repr(v))
                cells.append("ok" if f.ok else "not fitted")
                out.append(",".join(cells))
            return "\n".join(out)
        return ranking.to_text()

    best = ranking.best
    line = (
        f"fit of {len(names)} models: best {best.model} by AIC"
        if best is not None
        else f"fit of {len(names)} models: none could be fitted"
    )
    meta = {
        "cell": cell,
        "cell_parameters": cell_parameters,
        "columns": {
            "rank": {"meaning": "rank by AIC (empty: not fitted)", "unit": ""},
            "model": {"meaning": "rheology", "unit": ""},
            "k": {"meaning": "number of fitted parameters", "unit": ""},
            "chi2": {"meaning": "chi-square (RSS without uncertainties)", "unit": "1"},
            "reduced_chi2": {"meaning": "chi2 / (n - k)", "unit": "1"},
            "AIC": {"meaning": "Akaike information criterion", "unit": "1"},
            "BIC": {"meaning": "Bayesian information criterion", "unit": "1"},
            "akaike_weight": {"meaning": "exp(-dAIC/2), normalised", "unit": "1"},
            "status": {"meaning": "ok or not fitted (reason in the JSON)", "unit": ""},
        },
    }
    deliver(args, render, meta, line)


def cmd_fit(args: argparse.Namespace) -> None:
    """``fit``: a calibration of one run (``cosserat.calibration.single.fit``)."""
    import warnings

    from ..calibration.single import CellMismatchWarning, fit

    if args.models:
        cmd_fit_models(args)
        return
    measured, problem = data_problem(args)
    free = [f.strip() for f in args.free.split(",") if f.strip()] if args.free else None
    opts = {} if args.rtol is None else {"rtol": args.rtol}
    cosserat = args.model == params.DEFAULT_MODEL
    if not cosserat and args.method != "numerical":
        raise UsageError(f"--model {args.model}: fit uses --method numerical")
    bar = progress_messages("fit")
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", CellMismatchWarning)  # among the result's warnings
            result = fit(
                measured,
                problem,
                free=free,
                method=args.method,
                interval_for=("delta",) if cosserat else (),
                progress=bar,
                **opts,
            )
    finally:
        if bar is not None:
            bar.close()
    record = result.to_dict()
    record["model_name"] = args.model
    best = result.problem
    rows = [(n, e.value, e.stderr, e.reason, e.interval, e.unit) for n, e in result.shown().items()]
    if args.plot:
        _figure(result.comparison, "fit: " + best.describe(), args.plot)
    names = ", ".join(r[0] for r in rows)
    rms, rchi2 = result.rms or 0.0, result.reduced_chi2

    def render(fmt: str) -> str:
        if fmt == "json":
            return json.dumps(record, allow_nan=False)
        if fmt == "csv":
            out = ["parameter,unit,value,stderr,interval_low,interval_high"]
            for name, value, err, _, interval, unit in rows:
                cells = [name, unit, repr(float(value))]
                cells.append("" if err is None or not math.isfinite(err) else repr(float(err)))
                cells += ["", ""] if interval is None else [repr(float(v)) for v in interval]
                out.append(",".join(cells))
            return "\n".join(out)
        lines = [
            f"fit of {names} (model {args.model}) to {measured.n} points ({result.n_solves} "
            "solves; a calibration of one run)",
            f"best fit: {best.describe()}",
        ]
        for name, value, err, reason, interval, unit in rows:
            unit = f" [{unit}]" if unit and unit not in ("-", "1") else ""
            extra = "" if interval is None else f", interval [{interval[0]:.4g}, {interval[1]:.4g}]"
            lines.append(f"  {name} = {value:.5g} {_error_text(err, reason)}{unit}{extra}")
        tail = "" if rchi2 is None else f", reduced chi-square = {rchi2:.3g}"
        lines.append(f"rms(data - model) = {rms:.4g}{tail}")
        lines += [f"warning: {w}" for w in result.warnings]
        return "\n".join(lines)

    meta = {k: v for k, v in record.items() if k not in ("parameters", "per_run")}
    meta["columns"] = {
        "parameter": {"meaning": "fitted parameter", "unit": ""},
        "unit": {"meaning": "its unit ('-': dimensionless)", "unit": ""},
        "value": {"meaning": "best-fit value", "unit": "the row's unit"},
        "stderr": {"meaning": "standard error (empty: not identifiable)", "unit": "the row's unit"},
        "interval_low": {
            "meaning": "profile-likelihood interval, lower end",
            "unit": "the row's unit",
        },
        "interval_high": {
            "meaning": "profile-likelihood interval, upper end",
            "unit": "the row's unit",
        },
    }
    summary = ", ".join(f"{name} = {value:.4g}" for name, value, *_ in rows)
    deliver(args, render, meta, f"fit ({args.model}): {summary}; rms {rms:.4g}")


def add_parsers(sub: argparse._SubParsersAction) -> None:
    """Add this module's commands to the ``cosserat`` parser."""
    cp = sub.add_parser("compare", help="the model beside a measured velocity profile")
    _add_data_model(cp)
    cp.set_defaults(func=cmd_compare)

    fitp = sub.add_parser("fit", help="fit model parameters to a measured velocity profile")
    _add_data_model(fitp)
    fitp.add_argument(
        "--free",
        default=None,
        help=(
            "comma-separated parameters to fit (default: delta,K for the Cosserat model, "
            "among delta [deg], K, L, phi [deg], A; another model's defaults otherwise)"
        ),
    )
    fitp.add_argument(
        "--models",
        default=None,
        help=(
            "comma-separated models to fit side by side and rank by AIC and BIC "
            "(e.g. cosserat,mui,ngf); each fits its default free parameters"
        ),
    )
    fitp.set_defaults(func=cmd_fit)
