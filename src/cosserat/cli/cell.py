"""``cosserat cell [plane|couette|channel]``: a laboratory cell in SI units
(:mod:`cosserat.analysis.cell`), for every rheology (``--model cosserat|mui|ngf``).

Grain size and density, gap, the drive and the loading in; wall shear stress, slip velocity,
shear-layer thickness, the velocity and spin profiles (and for Couette flow the torque) in SI
units out. The inertial number of a rate-dependent law is computed from the cell's speed,
stress, grain size and density, never fitted. The options are the Python names
(``--grain-diameter`` is ``grain_diameter``, ...); the physics is in
:mod:`cosserat.analysis.cell`.
"""

from __future__ import annotations

import argparse
import json
import math
import re
import sys
import warnings
from typing import Any

from .. import config
from ..analysis.cell import LAB_CELLS, UNITS, CouetteCell, LabCell
from ..errors import ParameterError
from ..routes import solve
from . import files
from .common import (
    MAX_POINTS,
    UsageError,
    add_material_and_walls,
    add_model,
    add_output,
    add_solution,
    check_outputs,
    deliver,
    model_problem,
    option_values,
    solver_options,
    table,
)
from .params import RHEOLOGIES, check_model, parse_params

TABLE_ROWS = 11

_TITLES = {"plane": "Plane shear", "couette": "Couette cell", "channel": "Vertical channel"}

PROFILE_COLUMNS = {
    "plane": ("y", "v_x", "omega"),
    "couette": ("r", "v_theta", "omega"),
    "channel": ("y", "v_x", "omega"),
}
"""The CSV columns of each cell's profile (position, velocity, spin): the cell's own names, as
``solve`` exports them. The JSON record has them as ``position``, ``velocity``, ``spin`` (the
Python names of :meth:`cosserat.analysis.cell.LabCell.results`) and, for the Couette cell, also
under the names of 0.1 (``r``, ``v_theta``, ``omega``; deprecated, removed in 0.3)."""

_MEANINGS = {
    "plane": (
        "height above the fixed lower wall",
        "velocity along the walls (the upper wall's sense)",
    ),
    "couette": ("radius", "azimuthal velocity (the inner cylinder's sense)"),
    "channel": ("distance across the channel from a wall", "downward velocity"),
}

# flags by cell: which apply where (the rest are refused with a one-line error)
_CELL_FLAGS = {
    "plane": ("normal_stress", "wall_speed"),
    "couette": ("inner_radius", "fill_depth", "rotation_rate", "wall_speed", "depth"),
    "channel": ("normal_stress", "centre_speed"),
}
_ALL_FLAGS = sorted({f for flags in _CELL_FLAGS.values() for f in flags})


def _flag(name: str) -> str:
    return "--" + name.replace("_", "-")


def _positive(args: argparse.Namespace, name: str) -> float | None:
    value = getattr(args, name)
    if value is None:
        return None
    if not (math.isfinite(value) and value > 0.0):
        raise ParameterError(f"{_flag(name)} must be > 0 {UNITS[name]}; got {value:g}")
    return float(value)


def _lab_cell(args: argparse.Namespace) -> LabCell:
    kind = args.cell_kind
    stray = [f for f in _ALL_FLAGS if getattr(args, f) is not None and f not in _CELL_FLAGS[kind]]
    if stray:
        raise UsageError(
            f"{', '.join(_flag(f) for f in stray)} do(es) not apply to the {kind} cell; it "
            f"takes {', '.join(_flag(f) for f in _CELL_FLAGS[kind])}"
        )
    common: dict[str, Any] = {
        "grain_diameter": args.grain_diameter,
        "density": args.density,
        "gap": args.gap,
        "solids_fraction": args.solids_fraction,
        "gravity": args.gravity,
    }
    missing = [k for k in ("grain_diameter", "density", "gap") if common[k] is None]
    if kind == "couette":
        missing += [k for k in ("inner_radius", "fill_depth") if getattr(args, k) is None]
        speed = _positive(args, "wall_speed")
        rate = args.rotation_rate
        if speed is not None and rate is not None:
            raise UsageError("give --rotation-rate or --wall-speed, not both")
        if speed is None and rate is None:
            missing.append("rotation_rate (or --wall-speed)")
        if missing:
            raise UsageError(_missing(kind, missing))
        if speed is not None:
            radius = _positive(args, "inner_radius")
            rate = speed / radius if radius else speed
        extra = {
            "inner_radius": args.inner_radius,
            "fill_depth": args.fill_depth,
            "rotation_rate": rate,
        }
    elif kind == "plane":
        missing += [k for k in ("normal_stress", "wall_speed") if getattr(args, k) is None]
        if missing:
            raise UsageError(_missing(kind, missing))
        extra = {"normal_stress": args.normal_stress, "wall_speed": args.wall_speed}
    else:
        if missing:
            raise UsageError(_missing(kind, missing))
        extra = {"normal_stress": args.normal_stress, "centre_speed": args.centre_speed}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            lab = LAB_CELLS[kind](**common, **extra)
        except ParameterError as exc:
            raise ParameterError(_flags(str(exc))) from None
    for w in caught:
        print(f"cosserat: warning: {' '.join(str(w.message).split())}", file=sys.stderr)
    return lab


def _flags(text: str) -> str:
    """A message of :mod:`cosserat.analysis.cell` with its names as the flags."""
    for name in sorted(UNITS, key=len, reverse=True):
        if "_" in name or name in ("gap", "density", "gravity", "depth"):
            text = re.sub(rf"(?<![\w-]){name}\b", _flag(name), text)
    return text


def _missing(kind: str, names: list[str]) -> str:
    flags = ", ".join(_flag(n) for n in names)
    return f"the {kind} cell needs {flags}"


def compute(args: argparse.Namespace) -> tuple[dict[str, Any], Any, LabCell]:
    """The record of results, the dimensionless profile and the laboratory cell."""
    kind = args.cell_kind
    model = args.model
    check_model(model, kind)
    lab = _lab_cell(args)
    extra = parse_params(args.param)
    rate_dependent = model in RHEOLOGIES and RHEOLOGIES[model].rate_dependent
    depth = None
    if isinstance(lab, CouetteCell):  # kind == "couette"
        fill = lab.fill_depth
        depth = fill if args.depth is None else args.depth
        if not (math.isfinite(depth) and 0.0 < depth <= fill):
            raise ParameterError(
                f"--depth must satisfy 0 < depth <= fill depth = {fill:g} m (the stresses grow "
                f"with depth below the free surface); got {depth:g}"
            )
    given = option_values(args, lab.eps)
    try:
        given.update(lab.values(rate_dependent, depth))
    except ParameterError as exc:
        raise ParameterError(_flags(str(exc))) from None
    given["geometry"] = kind
    taken = sorted(k for k in extra if k in lab.values(rate_dependent, depth) or k == "I_w")
    if taken:
        raise UsageError(
            f"--param {', '.join(taken)}: computed from the cell in SI units here, not given"
        )
    try:
        problem = model_problem(model, kind, given, extra)
    except ParameterError as exc:
        if "I_w" in given and str(exc).startswith("I_w "):
            raise ParameterError(
                f"the cell's inertial number I_w = V d_p / (H sqrt(p / rho_p)) = "
                f"{given['I_w']:.4g} is out of the range of {model}: {exc}"
            ) from None
        raise
    profile = solve(problem, method=args.method, points=args.points, **solver_options(args))
    results = lab.results(profile, depth)
    record: dict[str, Any] = {
        "cell": kind,
        "model": problem.model,
        "inputs": {k: v for k, v in lab.inputs().items() if v is not None},
        "input_units": {k: UNITS[k] for k, v in lab.inputs().items() if v is not None},
        "description": problem.describe(),
        "parameters": problem.parameters(),
        "method": profile.method,
        **results,
        "units": {k: UNITS[k] for k in results if k in UNITS},
    }
    if isinstance(lab, CouetteCell):  # the names of 0.1, kept one release
        record["inputs"]["rotation_rate"] = lab.rotation_rate
        record["wall_speed"] = lab.wall_speed
        record["units"]["wall_speed"] = "m/s"
        record["r"], record["v_theta"], record["omega"] = (
            results["position"],
            results["velocity"],
            results["spin"],
        )
        record["units"].update({"r": "m", "v_theta": "m/s", "omega": "rad/s"})
    return record, profile, lab


def _fmt(value: Any, unit: str) -> str:
    return "-" if value is None else f"{value:.6g} {unit}".rstrip()


def _inertial_line(record: dict[str, Any]) -> str:
    I_w = record.get("I_w")
    if I_w is None:
        return ""
    line = f"inertial number of the drive I_w = {I_w:.4g}"
    if record["model"] not in RHEOLOGIES or not RHEOLOGIES[record["model"]].rate_dependent:
        line += f" (unused: the {record['model']} model is rate-independent)"
    return line


def cell_text(record: dict[str, Any]) -> str:
    kind = record["cell"]
    i = record["inputs"]
    head = (
        f"{_TITLES[kind]}: grains {i['grain_diameter']:g} m ({i['density']:g} kg/m^3, solids "
        f"fraction {i['solids_fraction']:g}), gap {i['gap']:g} m, gravity {i['gravity']:g} m/s^2"
    )
    if kind == "couette":
        drive = (
            f"inner radius {i['inner_radius']:g} m, fill depth {i['fill_depth']:g} m; inner "
            f"cylinder {i['rotation_rate']:.6g} rad/s, surface speed "
            f"{record['velocity_scale']:.6g} m/s; Froude number {record['froude']:.3g}"
        )
    elif kind == "plane":
        drive = (
            f"upper wall at {i['wall_speed']:.6g} m/s under {i['normal_stress']:.6g} Pa; "
            f"B = {record['B']:.4g}"
        )
    else:
        drive = (
            f"wall normal stress {record['normal_stress']:.6g} Pa (B = {record['B']:.4g}); "
            f"centre-line speed {record['velocity_scale']:.6g} m/s"
        )
    lines = [
        head,
        drive,
        f"model: {record['description']}",
        _inertial_line(record),
        "",
    ]
    lines = [line for line in lines[:-1] if line] + [""]
    rows: list[tuple[str, str]] = []
    if kind == "couette":
        z = record["depth"]
        rows += [
            ("torque on the inner cylinder over the fill depth", _fmt(record["torque"], "N m")),
            (
                f"torque per unit height at depth {z:g} m",
                _fmt(record["torque_per_height"], "N m/m"),
            ),
            (f"wall shear stress at depth {z:g} m", _fmt(record["wall_shear_stress"], "Pa")),
            (f"mean stress at depth {z:g} m", _fmt(record["mean_stress"], "Pa")),
            ("slip velocity at the inner cylinder", _fmt(record["slip_velocity"], "m/s")),
        ]
    else:
        where = "upper wall" if kind == "plane" else "walls"
        rows += [
            (f"wall shear stress on the {where}", _fmt(record["wall_shear_stress"], "Pa")),
            (f"slip velocity at the {where}", _fmt(record["slip_velocity"], "m/s")),
        ]
    rows.append(
        (
            "shear-layer thickness Delta",
            f"{record['Delta_m']:.6g} m ({record['Delta']:.4g} grain diameters)",
        )
    )
    width = max(len(r[0]) for r in rows)
    lines += [f"{name.ljust(width)}  {value}" for name, value in rows]
    if kind == "couette":
        shear = record["torque_per_height_shear"]
        lines.insert(
            -4,
            f"{'':{width}}  (the wall shear stress gives 2 pi R_i^2 tau_w = {shear:.6g} N m/m, "
            f"the couple stress {record['torque_per_height'] - shear:.6g} N m/m)",
        )
    x, v, _ = PROFILE_COLUMNS[kind]
    n = len(record["position"])
    picks = sorted({round(k * (n - 1) / (TABLE_ROWS - 1)) for k in range(TABLE_ROWS)})
    lines += [
        "",
        *table(
            [f"{x} [m]", f"{v} [m/s]", "spin [rad/s]"],
            [[record["position"][k], record["velocity"][k], record["spin"][k]] for k in picks],
        ),
    ]
    lines.append(f"({len(picks)} of {n} points; all with --format csv or json)")
    return "\n".join(lines)


def cell_csv(record: dict[str, Any]) -> str:
    lines = [",".join(PROFILE_COLUMNS[record["cell"]])]
    lines += [
        f"{r!r},{v!r},{w!r}"
        for r, v, w in zip(record["position"], record["velocity"], record["spin"], strict=True)
    ]
    return "\n".join(lines)


def cell_figure(record: dict[str, Any]) -> Any:
    from ..viz.plotting import new_figure, style

    x = PROFILE_COLUMNS[record["cell"]][0]
    velocity = _MEANINGS[record["cell"]][1]
    fig, axes = new_figure(1, 2, width=7.0, height=3.0)
    with style():
        ax_v, ax_w = axes[0]
        ax_v.plot(record["position"], record["velocity"], "k-")
        ax_v.set_xlabel(f"{x} (m)")
        ax_v.set_ylabel(f"{velocity.split(' (')[0]} (m/s)")
        ax_w.plot(record["position"], record["spin"], "k-")
        ax_w.set_xlabel(f"{x} (m)")
        ax_w.set_ylabel("grain spin (rad/s)")
        fig.tight_layout()
    return fig


def cmd_cell(args: argparse.Namespace) -> None:
    if not 3 <= args.points <= MAX_POINTS:
        raise UsageError(f"--points must satisfy 3 <= points <= {MAX_POINTS}; got {args.points}")
    check_outputs(args)
    record, _, _ = compute(args)
    if args.plot:
        files.save_figure(cell_figure(record), args.plot)

    def render(fmt: str) -> str:
        if fmt == "csv":
            return cell_csv(record)
        if fmt == "json":
            return json.dumps(record, allow_nan=False)
        return cell_text(record)

    kind = record["cell"]
    x, v, w = PROFILE_COLUMNS[kind]
    position, velocity = _MEANINGS[kind]
    meta = {
        k: val
        for k, val in record.items()
        if k not in ("position", "velocity", "spin", "r", "v_theta", "omega")
    }
    meta["columns"] = {
        x: {"meaning": position, "unit": "m"},
        v: {"meaning": velocity, "unit": "m/s"},
        w: {"meaning": "grain spin about the axis normal to the flow plane", "unit": "rad/s"},
    }
    parts = [f"{_TITLES[kind]}:"]
    if kind == "couette":
        parts.append(f"torque {record['torque']:.4g} N m,")
    parts.append(f"wall shear stress {record['wall_shear_stress']:.4g} Pa")
    if kind == "couette":
        parts.append(f"at {record['depth']:g} m")
    parts.append(f"slip {record['slip_velocity']:.4g} m/s, Delta {record['Delta_m']:.4g} m")
    line = " ".join(parts).replace(" Pa slip", " Pa, slip").replace(" m slip", " m, slip")
    deliver(args, render, meta, line)


def add_parsers(sub: argparse._SubParsersAction) -> None:
    """Add this module's command to the ``cosserat`` parser."""
    p = sub.add_parser(
        "cell",
        help="a laboratory cell in SI units (plane, couette, channel; any --model)",
        description=(
            "A laboratory cell given in SI units, for every rheology: plane shear (upper wall "
            "moving under a normal stress), a Couette cell (inner cylinder turning, stresses "
            "growing with depth below the free surface) or a vertical channel (gravity flow "
            "between walls at rest). Out: wall shear stress, slip velocity, shear-layer "
            "thickness, velocity and spin profiles in SI units, and for the Couette cell the "
            "torque. A rate-dependent law's inertial number is computed from the cell's "
            "speed, stress, grain size and density."
        ),
    )
    p.add_argument(
        "cell_kind",
        nargs="?",
        choices=tuple(LAB_CELLS),
        default="couette",
        metavar="CELL",
        help="plane, couette or channel (default: couette, as in 0.1)",
    )
    g = p.add_argument_group("every cell (SI units)")
    g.add_argument("--grain-diameter", type=float, metavar="M", help="grain diameter [m]")
    g.add_argument(
        "--density",
        type=float,
        metavar="KG_M3",
        help=(
            "intrinsic density of the grains, rho_p (the rho_s of mu(I) and NGF) [kg/m^3] "
            "(glass: about 2500)"
        ),
    )
    g.add_argument(
        "--gap",
        type=float,
        metavar="M",
        help="gap H between the walls (the radial gap, the channel's width) [m]",
    )
    g.add_argument(
        "--solids-fraction",
        type=float,
        default=0.6,
        metavar="NU",
        help="solids fraction [-] (default: 0.6)",
    )
    g.add_argument(
        "--gravity",
        type=float,
        default=9.81,
        metavar="G",
        help="gravitational acceleration [m/s^2] (default: 9.81; plane shear takes 0)",
    )
    pc = p.add_argument_group("plane and channel")
    pc.add_argument(
        "--normal-stress",
        type=float,
        metavar="PA",
        help=(
            "normal stress on the (upper) wall N [Pa] (plane: required; channel: required for "
            "mu(I) and NGF, it sets the flow)"
        ),
    )
    pc.add_argument(
        "--centre-speed",
        type=float,
        metavar="M_S",
        help="channel, Cosserat model: the centre-line speed [m/s] (its velocity scale)",
    )
    c = p.add_argument_group("couette")
    c.add_argument("--inner-radius", type=float, metavar="M", help="inner radius R_i [m]")
    c.add_argument(
        "--fill-depth",
        type=float,
        metavar="M",
        help="depth of the granular material [m] (the total torque acts over it)",
    )
    c.add_argument(
        "--rotation-rate",
        type=float,
        metavar="RAD_S",
        help="angular velocity of the inner cylinder Omega [rad/s]",
    )
    c.add_argument(
        "--depth",
        type=float,
        default=None,
        metavar="M",
        help=(
            "depth below the free surface at which the wall shear stress, the torque per "
            "unit height and (mu(I), NGF) the inertial number are taken [m] (default: the "
            "fill depth, the bottom)"
        ),
    )
    g.add_argument(
        "--wall-speed",
        type=float,
        metavar="M_S",
        help=(
            "plane: speed of the upper wall [m/s] (required); couette: surface speed of the "
            "inner cylinder Omega R_i [m/s] (instead of --rotation-rate)"
        ),
    )
    add_model(p)
    add_material_and_walls(p, "couette", ri=False)
    add_solution(p)
    p.add_argument(
        "--points",
        type=int,
        default=config.OUTPUT_POINTS,
        help=f"output points across the gap (default: {config.OUTPUT_POINTS})",
    )
    add_output(p, plot="the velocity and spin profiles in SI units")
    p.set_defaults(func=cmd_cell, geometry="couette")
