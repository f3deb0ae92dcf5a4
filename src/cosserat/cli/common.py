"""What every command shares: the parser class, usage errors, the model, material and wall
options, the output options (``--format``, ``--out``, ``--plot``, ``--quiet``) and progress
bars."""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any, NoReturn

from .. import config
from ..errors import InputError
from ..model import Problem
from ..model import problem_parameters as declared_parameters
from ..model.cells import CELLS
from ..model.declare import Param
from ..model.parameters import FULLY_ROUGH, ROUGH_WORDS
from ..routes import METHODS
from . import files, params
from .params import UsageError

GEOMETRIES = {
    "plane": "plane shear between parallel walls",
    "couette": "cylindrical Couette flow, inner cylinder turning",
}
PRESETS = ("mustard", "poppy", "glass")
MAX_POINTS = 1_000_000
"""Most output points ``solve --points`` accepts (more would only exhaust memory)."""
FORMATS = ("text", "json", "csv")

_STATE: dict[str, Any] = {"quiet": False, "interrupt_hint": None}


class Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:
        """One line, printed by :func:`cosserat.cli.main` as every error is
        (``cosserat: error: ...``), naming the command whose options are wrong."""
        command = self.prog.removeprefix("cosserat").strip()
        where = f" (`{self.prog} --help` lists {'its' if command else 'the'} options)"
        raise UsageError(f"{message}{where}")


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


def _declared(name: str, cell: str) -> Param:
    """The declaration of the Cosserat model's (or the cell's) parameter ``name``."""
    return declared_parameters(params.DEFAULT_MODEL, cell)[name]


def default_text(name: str, cell: str = "plane") -> str:
    """The declared default of parameter ``name`` as help texts show it."""
    return _declared(name, cell).default_text()


def _help(name: str, cell: str, default: str | None = None) -> str:
    p = _declared(name, cell)
    return f"{p.meaning} [{p.unit}] (default: {default or p.default_text()})"


def cell_help(cell: str) -> str:
    """One line on a cell for ``--help`` (the first line of a new cell's docstring)."""
    if cell in GEOMETRIES:
        return GEOMETRIES[cell]
    cls = CELLS.get(cell)
    if cls is not None and cls.__doc__:
        return cls.__doc__.strip().splitlines()[0].rstrip(".")
    return cell


# --------------------------------------------------------------------------- the model
def add_model(p: argparse.ArgumentParser, cell: str | None = None) -> None:
    """``--model`` and ``--param`` (``cell``: the sub-command's cell, for the help text)."""
    g = p.add_argument_group("model")
    models = list(params.RHEOLOGIES) if cell is None else params.cells().get(cell, [])
    g.add_argument(
        "--model",
        default=params.DEFAULT_MODEL,
        metavar="NAME",
        help=(
            f"rheology: {', '.join(models)} (default: {params.DEFAULT_MODEL}; "
            "`cosserat models` describes them)"
        ),
    )
    g.add_argument(
        "--param",
        action="append",
        default=None,
        metavar="KEY=VALUE",
        help=(
            "set a parameter of the model by name (repeatable), e.g. --param mu_s=0.4 with "
            "--model mui; an unknown KEY lists the valid ones with their units"
        ),
    )


def applies(name: str, cell: str) -> bool:
    """True if the Cosserat model's (or the cell's) parameter ``name`` applies to ``cell``
    (its declaration, :func:`cosserat.model.problem_parameters`)."""
    return name in declared_parameters(params.DEFAULT_MODEL, cell)


def add_material_and_walls(p: argparse.ArgumentParser, cell: str, ri: bool = True) -> None:
    """The Cosserat model's options (``--model cosserat``) and the cell's that apply to
    ``cell``, with their declared defaults (``ri=False``: no ``--Ri``, for a cell given in SI
    units). Help texts are the declarations' meaning, unit and default."""
    g = p.add_argument_group("material and walls of the Cosserat model (defaults: the paper's)")
    g.add_argument("--phi", type=float, help=_help("phi", cell))
    wall = g.add_mutually_exclusive_group()
    wall.add_argument("--delta", type=angle_or_rough, help=_help("delta", cell))
    wall.add_argument(
        "--fully-rough", action="store_true", help="fully rough wall(s): tan(delta) = sin(phi)"
    )
    g.add_argument("--L", type=float, help=_help("L", cell))
    g.add_argument("--A", type=float, help=_help("A", cell))
    g.add_argument("--K", type=float, help=_help("K", cell))
    if applies("Ri", cell) and ri:
        g.add_argument("--Ri", type=float, help=_help("Ri", cell))
    if applies("delta_lower", cell):
        g.add_argument(
            "--delta-lower", type=angle_or_rough, help=_help("delta_lower", cell, "as --delta")
        )
    if applies("K_lower", cell):
        g.add_argument("--K-lower", type=float, help=_help("K_lower", cell, "as --K"))
    if applies("B", cell):
        g.add_argument("--B", type=float, help=_help("B", cell))
    if applies("nu", cell):
        g.add_argument("--nu", type=float, help=_help("nu", cell))
    if applies("m_wall", cell):
        g.add_argument(
            "--m-wall",
            type=float,
            help=_help("m_wall", cell, "the paper's condition sigma_xy = sigma_yx there"),
        )


def add_solution(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group("solution")
    g.add_argument(
        "--method",
        choices=METHODS,
        default="numerical",
        help="solution route (default: numerical; closed-form and asymptotic where they exist)",
    )
    g.add_argument(
        "--rtol",
        type=float,
        default=None,
        help=f"relative tolerance of --method numerical [-] (default: {config.text(config.RTOL)})",
    )


def add_output(
    p: argparse.ArgumentParser, formats: tuple[str, ...] = FORMATS, plot: str | None = None
) -> None:
    """``--format``, ``--out``, ``--plot`` (if ``plot`` describes the figure) and ``--quiet``."""
    g = p.add_argument_group("output")
    g.add_argument(
        "--format",
        choices=formats,
        default="text",
        help=(
            "text: a readable summary (default); json: every number, for programs"
            + ("; csv: a plain table with one header row" if "csv" in formats else "")
        ),
    )
    g.add_argument(
        "--out",
        metavar="FILE",
        default=None,
        help=(
            "write the results to FILE instead of stdout (csv: the metadata also, in a JSON "
            "sidecar: profile.csv -> profile.json)"
        ),
    )
    if plot:
        g.add_argument(
            "--plot",
            metavar="FILE",
            default=None,
            help=(
                f"save {plot} to FILE (png, pdf, svg: from the suffix) and print a one-line "
                "summary instead of the results (give --out to keep them too)"
            ),
        )
    add_quiet(g)


def add_quiet(g: Any) -> None:
    """``--quiet`` on a sub-command (it may also come before the command)."""
    g.add_argument(
        "-q",
        "--quiet",
        action="store_true",
        default=argparse.SUPPRESS,
        help="no progress bars (they show only when stderr is a terminal)",
    )


def set_quiet(quiet: bool) -> None:
    """Silence (or allow) the progress bars of this process."""
    _STATE["quiet"] = bool(quiet)


# --------------------------------------------------------------------------- interruptions
class Terminated(KeyboardInterrupt):
    """SIGTERM, raised as Ctrl-C is so that the same cleanup runs (``cosserat.cli.main``)."""


def set_interrupt_hint(hint: str | None) -> None:
    """What the one line after an interruption adds (where the finished work is, how to go
    on); None: nothing."""
    _STATE["interrupt_hint"] = hint


def interrupt_hint() -> str | None:
    """The hint :func:`set_interrupt_hint` left, once (then cleared)."""
    hint: str | None = _STATE["interrupt_hint"]
    _STATE["interrupt_hint"] = None
    return hint


def interrupted(exc: BaseException | None, kind: type[BaseException] = KeyboardInterrupt) -> bool:
    """True if ``exc`` is an interruption of type ``kind`` (Ctrl-C, or SIGTERM as
    :class:`Terminated`), also when it arrived inside a compiled kernel, which reports it as
    a SystemError caused by the KeyboardInterrupt."""
    seen = 0
    while exc is not None and seen < 20:
        if isinstance(exc, kind):
            return True
        exc, seen = exc.__cause__ or exc.__context__, seen + 1
    return False


# --------------------------------------------------------------------------- problems
def option_values(args: argparse.Namespace, eps: Any) -> dict[str, Any]:
    """The named parameters the options give (None: not given, the default applies)."""
    out: dict[str, Any] = {
        "geometry": args.geometry,
        "delta": FULLY_ROUGH
        if getattr(args, "fully_rough", False)
        else getattr(args, "delta", None),
        "eps": eps,
    }
    for name in ("phi", "L", "A", "K", "delta_lower", "K_lower", "B", "nu", "m_wall", "Ri"):
        out[name] = getattr(args, name, None)
    return out


def model_problem(model: str, cell: str, given: dict[str, Any], extra: dict[str, str]) -> Problem:
    """The problem of ``model`` on ``cell`` from the options ``given`` (None: not given) and
    the ``--param`` values ``extra``, built by :func:`cosserat.model.make_problem` (absent
    keys take their declared defaults, the same as in the Python API and sweeps)."""
    params.check_model(model, cell)
    params.check_keys(model, cell, extra)
    values = {k: v for k, v in given.items() if v is not None and k != "geometry"}
    twice = sorted(set(values) & set(extra))
    if twice:
        raise UsageError(f"{', '.join(twice)} given both as an option and as --param")
    valid = params.parameters(model, cell)
    stray = sorted(k for k in values if k not in valid)
    if stray:
        flags = ", ".join("--" + k.replace("_", "-") for k in stray)
        raise UsageError(
            f"{flags} do(es) not apply to --model {model} on the {cell} cell; its parameters "
            f"(--param KEY=VALUE): {', '.join(params.valid_keys(model, cell))}"
        )
    return params.build(model, cell, {**values, **extra})


def problem_from_args(args: argparse.Namespace, eps: Any) -> Problem:
    """The problem the options describe (cell from the sub-command, model from --model)."""
    return model_problem(
        getattr(args, "model", params.DEFAULT_MODEL),
        args.geometry,
        option_values(args, eps),
        params.parse_params(getattr(args, "param", None)),
    )


def solver_options(args: argparse.Namespace) -> dict[str, Any]:
    opts: dict[str, Any] = {}
    if args.rtol is not None:
        if args.method != "numerical":
            raise UsageError("--rtol applies to --method numerical only")
        opts["rtol"] = args.rtol
    return opts


# --------------------------------------------------------------------------- output
def emit(text: str, out: str | None) -> None:
    if out:
        files.write_text(text, out)
    else:
        sys.stdout.write(text if text.endswith("\n") else text + "\n")


def emit_csv(text: str, meta: dict[str, Any], out: str | None) -> None:
    """A plain CSV to ``out`` with ``meta`` in its JSON sidecar, or the CSV alone to stdout."""
    emit(text, out)
    if out:
        from ..results.profile import sidecar_path

        sidecar = str(sidecar_path(out))
        record = {"file": Path(out).name, **meta}
        files.write_text(json.dumps(record, indent=1, allow_nan=False), sidecar, "--out's sidecar")


def deliver(args: argparse.Namespace, render: Callable[[str], str], meta: Any, line: str) -> None:
    """Write the results as ``--format`` asks (``render(format)``), to ``--out`` or stdout.

    With ``--plot`` (the figure already saved) stdout gets the one-line summary ``line``
    instead of the results, which go to ``--out`` if given. ``meta`` (a callable or a dict)
    is the JSON sidecar of a CSV written to ``--out``.
    """
    plot = getattr(args, "plot", None)
    if plot and not args.out:
        print(f"{line}; figure: {plot}")
        return
    text = render(args.format)
    if args.format == "csv":
        emit_csv(text, meta() if callable(meta) else meta, args.out)
    else:
        emit(text, args.out)
    if plot:
        print(f"{line}; figure: {plot}; results: {args.out}")


def check_outputs(args: argparse.Namespace) -> None:
    """Fail on an unusable --out or --plot before any computation: a folder that does not
    exist, a directory, a FIFO or device, no permission, a figure without a known image
    suffix, or --plot naming the same file as --out."""
    out = getattr(args, "out", None)
    if out:
        files.check_output_file(out)
        if getattr(args, "format", None) == "csv":
            from ..results.profile import sidecar_path

            files.check_output_file(str(sidecar_path(out)), "--out's sidecar")
    plot = getattr(args, "plot", None)
    if plot:
        files.check_plot_file(plot)
        if out and files.same_file_key(plot) == files.same_file_key(out):
            raise InputError(
                f"cannot write --plot {plot}: it is the same file as --out; give the figure "
                "another name"
            )


def table(header: list[str], rows: list[list[Any]], digits: int = 6) -> list[str]:
    """Aligned text table: numbers with ``digits`` significant digits, None as '-'."""

    def cell(v: Any) -> str:
        if v is None:
            return "-"
        if isinstance(v, float):
            return f"{v + 0.0:.{digits}g}"  # + 0.0: no "-0"
        return str(v)

    cells = [header] + [[cell(v) for v in row] for row in rows]
    widths = [max(len(r[i]) for r in cells) for i in range(len(header))]
    return ["  ".join(c.rjust(w) for c, w in zip(r, widths, strict=True)) for r in cells]


# --------------------------------------------------------------------------- progress
def _terminal() -> bool:
    """True when progress may be drawn: stderr is a terminal and --quiet was not given."""
    return not _STATE["quiet"] and sys.stderr.isatty()


def _tqdm(**options: Any) -> Any:
    """A tqdm bar on stderr that follows the terminal's width (80 columns where the terminal
    reports none, as a pseudo-terminal without a size does)."""
    import os

    from tqdm import tqdm

    try:
        width = os.get_terminal_size(sys.stderr.fileno()).columns
    except (OSError, ValueError, AttributeError):
        width = 0
    sizing = {"dynamic_ncols": True} if width > 0 else {"ncols": 80}
    return tqdm(file=sys.stderr, **sizing, **options)


def progress_bar(label: str) -> Callable[[int, int], None] | None:
    """A tqdm progress bar on stderr as a callable ``update(i, n)`` (i of n done), or None
    when stderr is not a terminal or ``--quiet`` was given."""
    if not _terminal():
        return None
    state: dict[str, Any] = {}

    def update(i: int, n: int) -> None:
        bar = state.get("bar")
        if bar is None or bar.total != n:
            if bar is not None:
                bar.close()
            bar = state["bar"] = _tqdm(total=n, desc=label)
        bar.update(max(0, i - bar.n))
        if i >= n:
            bar.close()
            state.pop("bar", None)

    return update


class MessageBar:
    """A tqdm bar of unknown length as a callable ``step(message)`` (one tick per stage, the
    message beside it), with :meth:`close`."""

    def __init__(self, bar: Any) -> None:
        self._bar = bar

    def __call__(self, message: str) -> None:
        self._bar.set_postfix_str(message, refresh=False)
        self._bar.update(1)

    def close(self) -> None:
        self._bar.close()


def progress_messages(label: str) -> MessageBar | None:
    """A :class:`MessageBar` on stderr, or None when silent (as :func:`progress_bar`)."""
    if not _terminal():
        return None
    return MessageBar(_tqdm(total=None, desc=label, unit="step"))
