"""What every command shares: the parser class, usage errors, the material and wall options,
output and progress helpers."""

from __future__ import annotations

import argparse
import sys
from typing import Any, NoReturn

from .. import config
from ..model import Problem, build_problem
from ..model.build import DEFAULTS, ROUGH_WORDS
from ..model.parameters import FULLY_ROUGH
from ..routes import METHODS
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


class Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:
        raise UsageError(f"{self.prog}: {message}")


def angle_or_rough(text: str) -> float | str:
    if text.strip().lower() in ROUGH_WORDS:
        return FULLY_ROUGH
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected an angle in degrees or 'fully-rough'; got {text!r}"
        ) from None


def positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number; got {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1; got {value}")
    return value


def default_text(name: str) -> str:
    """The default of parameter ``name`` as help texts show it."""
    return config.text(DEFAULTS[name])


def add_material_and_walls(p: argparse.ArgumentParser, plane: bool) -> None:
    g = p.add_argument_group("material and walls (defaults: the paper's)")
    g.add_argument(
        "--phi", type=float, help=f"angle of internal friction [deg] ({default_text('phi')})"
    )
    wall = g.add_mutually_exclusive_group()
    wall.add_argument(
        "--delta",
        type=angle_or_rough,
        help=f"angle of wall friction [deg] or 'fully-rough' ({default_text('delta')})",
    )
    wall.add_argument(
        "--fully-rough", action="store_true", help="fully rough wall(s): tan(delta) = sin(phi)"
    )
    g.add_argument("--L", type=float, help=f"yield-condition L ({default_text('L')})")
    g.add_argument("--A", type=float, help=f"yield-condition A = a2/a1 ({default_text('A')})")
    g.add_argument("--K", type=float, help=f"wall slip coefficient ({default_text('K')})")
    if not plane:
        g.add_argument("--Ri", type=float, help=f"inner radius / gap R_i/H ({default_text('Ri')})")
    if plane:
        g.add_argument(
            "--delta-lower",
            type=angle_or_rough,
            help="lower wall's delta [deg] or 'fully-rough' (default: = delta)",
        )
        g.add_argument("--K-lower", type=float, help="lower wall's K (default: = K)")
        g.add_argument(
            "--B",
            type=float,
            help=f"gravity parameter rho_p g H / N ({default_text('B')}: no gravity)",
        )
        g.add_argument("--nu", type=float, help=f"solids fraction ({default_text('nu')})")
        g.add_argument(
            "--m-wall",
            type=float,
            help="couple stress m at the non-slipping wall (instead of eqn-nd_bc4)",
        )


def add_solution(p: argparse.ArgumentParser) -> None:
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


def solver_options(args: argparse.Namespace) -> dict[str, Any]:
    opts: dict[str, Any] = {}
    if args.rtol is not None:
        if args.method != "numerical":
            raise UsageError("--rtol applies to --method numerical only")
        opts["rtol"] = args.rtol
    return opts


def emit(text: str, out: str | None) -> None:
    if out:
        files.write_text(text, out)
    else:
        sys.stdout.write(text if text.endswith("\n") else text + "\n")


def check_outputs(args: argparse.Namespace) -> None:
    """Fail on an unusable --out or --plot before any computation."""
    if getattr(args, "out", None):
        files.check_output_file(args.out)
    if getattr(args, "plot", None):
        files.check_plot_file(args.plot)


def progress_bar(label: str):  # type: ignore[no-untyped-def]
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
