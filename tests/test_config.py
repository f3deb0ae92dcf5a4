"""One configuration: the paper's defaults and the tolerances live in ``cosserat.config`` only.

Every front end reads them from there (parameter classes, build_problem, command line, sweeps,
figures), and the paper's phi is not written out anywhere else in the package's code.
"""

from __future__ import annotations

import ast
import itertools
import re
from pathlib import Path

import pytest

from cosserat import config
from cosserat.cli import make_parser
from cosserat.model import make_problem, problem_parameters
from cosserat.model.parameters import Material, Wall
from cosserat.studies.experiments import PRESETS
from cosserat.studies.sweep import SweepSpec, parse_spec

PACKAGE = Path(__file__).resolve().parents[1] / "src" / "cosserat"


def test_declared_defaults_are_configs():
    declared = {**problem_parameters("cosserat", "plane"), **problem_parameters("mui", "couette")}
    assert {k: declared[k].default for k in ("phi", "L", "A", "delta", "K", "B", "nu", "Ri")} == {
        "phi": config.PHI,
        "L": config.L,
        "A": config.A,
        "delta": config.DELTA,
        "K": config.K,
        "B": config.B,
        "nu": config.NU,
        "Ri": config.RI,
    }
    assert declared["I_w"].default == config.MUI_I_W  # one default for every rheology
    assert problem_parameters("ngf", "plane")["I_w"].default == config.MUI_I_W
    plane = make_problem("cosserat", "plane", {"eps": 0.1})
    assert plane.rheology.material == Material(config.PHI, config.L, config.A)
    assert plane.rheology.wall == plane.rheology.lower_wall == Wall(config.DELTA, config.K)
    assert (plane.cell.B, plane.cell.nu) == (config.B, config.NU)
    assert make_problem("cosserat", "couette", {"eps": 0.1}).cell.Ri == config.RI


def test_sweep_and_fit_tolerances_are_configs():
    spec = parse_spec({"fixed": {"eps": 0.1}})
    assert (spec.rtol, spec.f) == (config.RTOL, config.DEFAULT_F)
    assert (SweepSpec([]).rtol, SweepSpec([]).f) == (config.RTOL, config.DEFAULT_F)
    assert PRESETS["glass"].phi == config.PHI
    assert all((p.L, p.A) == (config.L, config.A) for p in PRESETS.values())


def _help(*path: str) -> str:
    parser = make_parser()
    for name in path:
        sub = next(a for a in parser._actions if a.__class__.__name__ == "_SubParsersAction")
        parser = sub.choices[name]  # type: ignore[attr-defined]
    return " ".join(parser.format_help().split())


def test_help_texts_show_the_config_values():
    text = _help("solve", "plane")
    for option, value in [
        ("--phi PHI angle of internal friction [deg]", config.PHI),
        (
            "slip coefficient of eqn-bc3; 0: no slip, 1/2: a grain rolling without sliding [-]",
            config.K,
        ),
        ("relative tolerance of --method numerical [-]", config.RTOL),
        ("layers resolved", config.OUTPUT_POINTS),
    ]:
        assert f"{option} (default: {config.text(value)}" in text
    assert f"yield-condition constants, eqn-yc2 [-] (default: {config.text(config.A)})" in text
    assert config.text(config.A) == "1/3"
    assert f"of its wall value [-] (default: {config.text(config.DEFAULT_F)})" in _help(
        "thickness", "couette"
    )
    assert f"R_i/H [-] (default: {config.text(config.RI)})" in _help("solve", "couette")


@pytest.mark.parametrize(
    ("value", "shown"), [(28.5, "28.5"), (1.0 / 3.0, "1/3"), (10.0, "10"), (0.5, "0.5")]
)
def test_text(value, shown):
    assert config.text(value) == shown


# --------------------------------------------------------------------------- no second copy
PAPER_PHI = config.PHI
NUMBER_IN_TEXT = re.compile(r"(?<![\d.])28\.50*(?![\d.]*\d)")
# Files this change may not edit: each still writes the paper's phi out. The test fails when one
# of them no longer does, so that the entry is removed and the file stays clean (a ratchet).
KNOWN_COPIES: set[str] = set()


def _docstring_ids(tree: ast.AST) -> set[int]:
    ids = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Module | ast.ClassDef | ast.FunctionDef | ast.AsyncFunctionDef):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
                ids.add(id(body[0].value))
        # attribute docstrings: a string statement right after an assignment
        for field in ("body", "orelse", "finalbody"):
            stmts = getattr(node, field, None)
            if not isinstance(stmts, list):
                continue
            for prev, stmt in itertools.pairwise(stmts):
                if (
                    isinstance(prev, ast.Assign | ast.AnnAssign)
                    and isinstance(stmt, ast.Expr)
                    and isinstance(stmt.value, ast.Constant)
                    and isinstance(stmt.value.value, str)
                ):
                    ids.add(id(stmt.value))
    return ids


def _constant_number(node: ast.AST) -> float | None:
    """The value of a number written with constants and arithmetic only (57 / 2), else None."""
    for sub in ast.walk(node):
        if not isinstance(sub, ast.BinOp | ast.UnaryOp | ast.Constant | ast.operator | ast.unaryop):
            return None
        if isinstance(sub, ast.Constant) and (
            isinstance(sub.value, bool) or not isinstance(sub.value, int | float)
        ):
            return None
    try:
        value = eval(compile(ast.Expression(node), "<constant>", "eval"), {"__builtins__": {}})
    except (ArithmeticError, ValueError, TypeError):
        return None
    return float(value)


def paper_phi_copies(source: str) -> list[int]:
    """Lines of ``source`` that write the paper's phi in code or in a (non-doc) string."""
    tree = ast.parse(source)
    docs = _docstring_ids(tree)
    lines = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Constant) and isinstance(node.value, str):
            if id(node) not in docs and NUMBER_IN_TEXT.search(node.value):
                lines.add(node.lineno)
        elif (
            isinstance(node, ast.BinOp | ast.UnaryOp | ast.Constant)
            and _constant_number(node) == PAPER_PHI
        ):
            lines.add(node.lineno)
    return sorted(lines)


@pytest.mark.parametrize(
    "snippet",
    [
        "PHI = 28.5",
        "m = Material(phi=28.50)",
        "x = 2.85e1",
        "x = 57 / 2",
        "x = -(-28.5)",
        "DEFAULTS = {'phi': 28.5}",
        "help_text = 'angle of internal friction [deg] (28.5)'",
        "def f():\n    '''Doc.'''\n    return f'phi = 28.5 deg, {x}'",
        "class C:\n    phi: float = 28.5",
    ],
)
def test_the_scan_finds_a_reintroduced_copy(snippet):
    assert paper_phi_copies(snippet) != []


@pytest.mark.parametrize(
    "snippet",
    [
        '"""Module doc: phi = 28.5 deg."""',
        "def f():\n    '''phi = 28.5 deg'''\n    return PHI",
        "X = 1.0\n'''Attribute doc: 28.5.'''",
        "x = 1  # the paper's 28.5",
        "x = 128.5\ny = 28.55\nz = '28.51 or 128.5'",
        "x = 28",
    ],
)
def test_the_scan_leaves_docstrings_comments_and_other_numbers(snippet):
    assert paper_phi_copies(snippet) == []


def test_the_paper_phi_is_written_only_in_config():
    found = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        rel = path.relative_to(PACKAGE).as_posix()
        if rel == "config.py":
            continue
        lines = paper_phi_copies(path.read_text())
        if lines:
            found[rel] = lines
    assert "PHI: Final = 28.5" in (PACKAGE / "config.py").read_text()
    unexpected = {k: v for k, v in found.items() if k not in KNOWN_COPIES}
    assert unexpected == {}, f"the paper's phi written outside config.py: {unexpected}"
    cleaned = KNOWN_COPIES - set(found)
    assert cleaned == set(), f"no copy left in {cleaned}: remove it from KNOWN_COPIES"
