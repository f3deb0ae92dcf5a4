"""``cosserat cell``: a real Couette cell in SI units (:class:`cosserat.analysis.cell.CouetteCell`).

Grain size, radii, gap, fill depth and rotation in; torque, wall shear stress, slip velocity and
the velocity profile in SI units out. The physics (the torque of a Cosserat medium, the depth
dependence of the stresses) is in :mod:`cosserat.analysis.cell`.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import sys
import warnings
from typing import Any

from .. import config
from ..analysis.cell import CouetteCell
from ..errors import ParameterError
from ..results.wall import shear_layer_thickness
from ..routes import solve
from . import files
from .common import (
    MAX_POINTS,
    UsageError,
    add_material_and_walls,
    add_output,
    add_solution,
    check_outputs,
    deliver,
    model_problem,
    option_values,
    solver_options,
    table,
)

_DEFAULTS = {f.name: f.default for f in dataclasses.fields(CouetteCell)}

UNITS = {
    "torque": "N m",
    "torque_per_height": "N m/m",
    "torque_per_height_shear": "N m/m",
    "wall_shear_stress": "Pa",
    "mean_stress": "Pa",
    "slip_velocity": "m/s",
    "wall_speed": "m/s",
    "Delta": "grain diameters",
    "Delta_m": "m",
    "depth": "m",
    "r": "m",
    "v_theta": "m/s",
    "omega": "rad/s",
}
"""Units of the results, as the JSON output and the CSV sidecar state them."""

TABLE_ROWS = 11


def _cell(args: argparse.Namespace) -> CouetteCell:
    rate = args.rotation_rate
    if args.wall_speed is not None:
        if args.wall_speed <= 0.0 or not math.isfinite(args.wall_speed):
            raise ParameterError(f"--wall-speed must be > 0 m/s; got {args.wall_speed:g}")
        rate = args.wall_speed / args.inner_radius if args.inner_radius > 0 else args.wall_speed
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        cell = CouetteCell(
            rho_p=args.density,
            d_p=args.grain_diameter,
            gap=args.gap,
            R_i=args.inner_radius,
            fill_depth=args.fill_depth,
            rotation_rate=rate,
            nu=args.solids_fraction,
            g=args.gravity,
        )
    for w in caught:
        print(f"cosserat: warning: {' '.join(str(w.message).split())}", file=sys.stderr)
    return cell


def compute(args: argparse.Namespace) -> tuple[dict[str, Any], Any, CouetteCell]:
    """The record of results, the dimensionless profile and the cell."""
    cell = _cell(args)
    depth = cell.fill_depth if args.depth is None else args.depth
    if not 0.0 < depth <= cell.fill_depth:
        raise ParameterError(
            f"--depth must satisfy 0 < depth <= fill depth = {cell.fill_depth:g} m; got {depth:g}"
        )
    given = option_values(args, cell.eps)
    given["Ri"] = cell.Ri
    problem = model_problem("cosserat", "couette", given, {})
    profile = solve(problem, method=args.method, points=args.points, **solver_options(args))
    delta = shear_layer_thickness(profile)
    record: dict[str, Any] = {
        "inputs": {
            "grain_diameter": cell.d_p,
            "density": cell.rho_p,
            "inner_radius": cell.R_i,
            "gap": cell.gap,
            "fill_depth": cell.fill_depth,
            "rotation_rate": cell.rotation_rate,
            "solids_fraction": cell.nu,
            "gravity": cell.g,
        },
        "input_units": {
            "grain_diameter": "m",
            "density": "kg/m^3",
            "inner_radius": "m",
            "gap": "m",
            "fill_depth": "m",
            "rotation_rate": "rad/s",
            "solids_fraction": "1",
            "gravity": "m/s^2",
        },
        "description": problem.describe(),
        "parameters": problem.parameters(),
        "eps": cell.eps,
        "Ri": cell.Ri,
        "froude": cell.froude,
        "method": profile.method,
        "wall_speed": cell.wall_speed,
        "depth": depth,
        "torque": cell.torque(profile),
        "torque_per_height": float(cell.torque_density(profile, depth)[0]),
        "wall_shear_stress": cell.wall_shear_stress(profile, depth),
        "torque_per_height_shear": cell.shear_torque_density(profile, depth),
        "mean_stress": float(cell.mean_stress(depth)),
        "slip_velocity": cell.slip_velocity(profile),
        "Delta": delta,
        "Delta_m": delta * cell.d_p,
        "units": UNITS,
        "r": cell.radius(profile).tolist(),
        "v_theta": (cell.velocity(profile) + 0.0).tolist(),  # no -0.0
        "omega": cell.spin(profile).tolist(),
    }
    return record, profile, cell


def cell_text(record: dict[str, Any]) -> str:
    i = record["inputs"]
    lines = [
        f"Couette cell: grains {i['grain_diameter']:g} m ({i['density']:g} kg/m^3, solids "
        f"fraction {i['solids_fraction']:g}), inner radius {i['inner_radius']:g} m, gap "
        f"{i['gap']:g} m, fill depth {i['fill_depth']:g} m",
        f"inner cylinder: {i['rotation_rate']:.6g} rad/s, surface speed "
        f"{record['wall_speed']:.6g} m/s; Froude number {record['froude']:.3g}",
        f"model: {record['description']}",
        "",
    ]
    z = record["depth"]
    rows = [
        ("torque on the inner cylinder over the fill depth", record["torque"], "N m"),
        (f"torque per unit height at depth {z:g} m", record["torque_per_height"], "N m/m"),
        (f"wall shear stress at depth {z:g} m", record["wall_shear_stress"], "Pa"),
        (f"mean stress at depth {z:g} m", record["mean_stress"], "Pa"),
        ("slip velocity at the inner cylinder", record["slip_velocity"], "m/s"),
        ("shear-layer thickness Delta", record["Delta_m"], "m"),
    ]
    width = max(len(r[0]) for r in rows)
    lines += [f"{name.ljust(width)}  {value:.6g} {unit}" for name, value, unit in rows]
    shear = record["torque_per_height_shear"]
    lines.insert(
        -4,
        f"{'':{width}}  (the wall shear stress gives 2 pi R_i^2 tau_w = {shear:.6g} N m/m, the "
        f"couple stress {record['torque_per_height'] - shear:.6g} N m/m)",
    )
    lines[-1] += f" ({record['Delta']:.4g} grain diameters)"
    n = len(record["r"])
    picks = sorted({round(k * (n - 1) / (TABLE_ROWS - 1)) for k in range(TABLE_ROWS)})
    lines += [
        "",
        *table(
            ["r [m]", "v_theta [m/s]", "spin [rad/s]"],
            [[record["r"][k], record["v_theta"][k], record["omega"][k]] for k in picks],
        ),
    ]
    lines.append(f"({len(picks)} of {n} points; all with --format csv or json)")
    return "\n".join(lines)


def cell_csv(record: dict[str, Any]) -> str:
    lines = ["r,v_theta,omega"]
    lines += [
        f"{r!r},{v!r},{w!r}"
        for r, v, w in zip(record["r"], record["v_theta"], record["omega"], strict=True)
    ]
    return "\n".join(lines)


def cell_figure(record: dict[str, Any]) -> Any:
    from ..viz.plotting import new_figure, style

    fig, axes = new_figure(1, 2, width=7.0, height=3.0)
    with style():
        ax_v, ax_w = axes[0]
        ax_v.plot(record["r"], record["v_theta"], "k-")
        ax_v.set_xlabel("r (m)")
        ax_v.set_ylabel("azimuthal velocity (m/s)")
        ax_w.plot(record["r"], record["omega"], "k-")
        ax_w.set_xlabel("r (m)")
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

    meta = {k: v for k, v in record.items() if k not in ("r", "v_theta", "omega")}
    meta["columns"] = {
        "r": {"meaning": "radius", "unit": "m"},
        "v_theta": {"meaning": "azimuthal velocity (the inner cylinder's sense)", "unit": "m/s"},
        "omega": {"meaning": "grain spin about the vertical axis", "unit": "rad/s"},
    }
    line = (
        f"Couette cell: torque {record['torque']:.4g} N m, wall shear stress "
        f"{record['wall_shear_stress']:.4g} Pa at {record['depth']:g} m, slip "
        f"{record['slip_velocity']:.4g} m/s"
    )
    deliver(args, render, meta, line)


def add_parsers(sub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    """Add this module's command to the ``cosserat`` parser."""
    p = sub.add_parser(
        "cell",
        help="a real Couette cell in SI units: torque, wall stress, slip, velocity in m/s",
        description=(
            "The Cosserat model in a Couette cell given in SI units (inner cylinder turning, "
            "outer fixed, stresses growing with depth below the free surface): torque, wall "
            "shear stress, slip velocity and the velocity profile."
        ),
    )
    g = p.add_argument_group("the cell (SI units)")
    g.add_argument(
        "--grain-diameter", type=float, required=True, metavar="M", help="grain diameter d_p [m]"
    )
    g.add_argument(
        "--density",
        type=float,
        required=True,
        metavar="KG_M3",
        help="intrinsic density of the grains rho_p [kg/m^3] (glass: about 2500)",
    )
    g.add_argument(
        "--inner-radius", type=float, required=True, metavar="M", help="inner radius R_i [m]"
    )
    g.add_argument(
        "--gap",
        type=float,
        required=True,
        metavar="M",
        help="radial gap H between the cylinders [m]",
    )
    g.add_argument(
        "--fill-depth",
        type=float,
        required=True,
        metavar="M",
        help="depth of the granular material [m] (the total torque acts over it)",
    )
    drive = g.add_mutually_exclusive_group(required=True)
    drive.add_argument(
        "--rotation-rate",
        type=float,
        metavar="RAD_S",
        help="angular velocity of the inner cylinder Omega [rad/s]",
    )
    drive.add_argument(
        "--wall-speed",
        type=float,
        metavar="M_S",
        help="surface speed of the inner cylinder Omega R_i [m/s] (instead of --rotation-rate)",
    )
    g.add_argument(
        "--solids-fraction",
        type=float,
        default=_DEFAULTS["nu"],
        metavar="NU",
        help=f"solids fraction nu [-] (default: {_DEFAULTS['nu']:g})",
    )
    g.add_argument(
        "--gravity",
        type=float,
        default=_DEFAULTS["g"],
        metavar="G",
        help=f"gravitational acceleration [m/s^2] (default: {_DEFAULTS['g']:g})",
    )
    g.add_argument(
        "--depth",
        type=float,
        default=None,
        metavar="M",
        help=(
            "depth below the free surface at which the wall shear stress and the torque per "
            "unit height are given [m] (default: the fill depth, the bottom)"
        ),
    )
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
