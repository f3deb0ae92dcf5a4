"""The ``cosserat-parameters`` directive: parameter tables generated from the declarations.

Every table of the docs is read at build time from the parameters' declarations
(:mod:`cosserat.model.declare`, through :func:`cosserat.model.problem_parameters` and the
registries), so that the docs cannot disagree with the code::

    .. cosserat-parameters:: rheology cosserat     (the law's own parameters)
    .. cosserat-parameters:: cell plane            (the cell's parameters)
    .. cosserat-parameters:: all                   (every rheology, then every cell)

Columns: key, meaning, unit, default, bounds (and why), fit range (and scale), role, source;
below a table, the constraints that tie its parameters together
(:class:`cosserat.model.declare.Constraint`), each with why.
"""

from __future__ import annotations

from typing import Any

from docutils import nodes
from docutils.parsers.rst import Directive
from docutils.statemachine import StringList


def _cell_text(value: Any) -> str:
    text = str(value).replace("|", "\\|")
    return text if text else " "


def _rows(params: dict[str, Any]) -> list[list[str]]:
    rows = []
    for key, p in params.items():
        fit = "-"
        if p.fit_range is not None:
            fit = f"{p.fit_range[0]:g} to {p.fit_range[1]:g}" + (
                " (log)" if p.scale == "log" else ""
            )
        cells = f" ({'/'.join(p.cells)} only)" if p.cells else ""
        choices = f"; or {', '.join(p.choices)}" if p.choices and p.numeric else ""
        rows.append(
            [
                f"``{key}``",
                p.meaning + choices + cells,
                p.unit or " ",
                p.default_text() if p.has_default else "required",
                (p.interval() + (f" ({p.reason})" if p.reason and p.interval() else ""))
                or (", ".join(p.choices) if p.choices else "-"),
                fit,
                p.role,
                p.source or "-",
            ]
        )
    return rows


def table_lines(title: str, params: dict[str, Any], owner: Any = None) -> list[str]:
    """An rST list-table of ``params`` (key -> declaration), then the constraints the class
    ``owner`` declares."""
    head = ["key", "meaning", "unit", "default", "bounds", "fit range", "role", "source"]
    lines = [
        f".. list-table:: {title}",
        "   :header-rows: 1",
        "   :widths: 8 34 6 8 14 10 7 13",
        "",
    ]
    for row in [head, *_rows(params)]:
        lines.append(f"   * - {_cell_text(row[0])}")
        lines += [f"     - {_cell_text(c)}" for c in row[1:]]
    lines.append("")
    from cosserat.model.declare import constraints

    for c in constraints(owner) if owner is not None else ():
        lines += [f"Constraint: ``{c.text}`` ({c.reason}).", ""]
    return lines


def tables(what: str, name: str | None) -> list[str]:
    from cosserat.model.cells import CELLS
    from cosserat.model.rheologies import RHEOLOGIES

    if what == "rheology":
        law = RHEOLOGIES[name]
        return table_lines(f"Parameters of the {law.title} (``{name}``)", law.declared(), law)
    if what == "cell":
        cell = CELLS[name]
        return table_lines(
            f"Parameters of the {cell.title} cell (``{name}``)", cell.declared(), cell
        )
    lines: list[str] = []
    for key in RHEOLOGIES:
        lines += tables("rheology", key)
    for key in CELLS:
        lines += tables("cell", key)
    return lines


class ParameterTables(Directive):
    """``.. cosserat-parameters:: rheology NAME | cell NAME | all`` (module docstring)."""

    required_arguments = 1
    optional_arguments = 1

    def run(self) -> list[nodes.Node]:
        what = self.arguments[0]
        name = self.arguments[1] if len(self.arguments) > 1 else None
        if what not in ("rheology", "cell", "all") or (what != "all" and name is None):
            raise self.error("cosserat-parameters takes 'rheology NAME', 'cell NAME' or 'all'")
        try:
            lines = tables(what, name)
        except KeyError:
            raise self.error(f"cosserat-parameters: no {what} named {name!r}") from None
        container = nodes.section()
        container.document = self.state.document
        self.state.nested_parse(StringList(lines, source="cosserat-parameters"), 0, container)
        return container.children


def setup(app: Any) -> dict[str, Any]:
    app.add_directive("cosserat-parameters", ParameterTables)
    return {"parallel_read_safe": True}
