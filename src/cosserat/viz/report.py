"""One report writer for every report of the package (``validate``, ``reproduce``).

A report is a Markdown file and an HTML page made from Jinja2 templates
(``cosserat/viz/templates/<name>.md.j2`` and ``<name>.html.j2``) and one context of plain data:
no Markdown or HTML is assembled by string concatenation anywhere else. HTML templates escape
every value (autoescape); Markdown templates have the filter ``cell`` for a table cell (a ``|``
escaped, line breaks joined). Each file is written atomically.

A leaf like :mod:`cosserat.viz.plotting`: it imports only :mod:`cosserat._atomic`, and Jinja2
when a report is rendered.
"""

from __future__ import annotations

import functools
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from .._atomic import write_text


def md_cell(value: Any) -> str:
    """A value as one Markdown table cell: ``|`` escaped, line breaks made spaces."""
    return " ".join(str(value).split()).replace("|", "\\|")


def number(value: Any, spec: str = ".4g") -> str:
    """A number formatted with ``spec``; "-" for None."""
    return "-" if value is None else format(value, spec)


@functools.cache
def environment() -> Any:
    """The Jinja2 environment of the package's templates (cached)."""
    import jinja2

    env = jinja2.Environment(
        loader=jinja2.PackageLoader("cosserat.viz", "templates"),
        autoescape=jinja2.select_autoescape(
            enabled_extensions=("html.j2",), default_for_string=False
        ),
        undefined=jinja2.StrictUndefined,
        keep_trailing_newline=True,
        trim_blocks=True,
        lstrip_blocks=True,
    )
    env.filters["cell"] = md_cell
    env.filters["num"] = number
    return env


def render(template: str, context: Mapping[str, Any]) -> str:
    """Render the template ``template`` (a file name under ``templates/``) with ``context``."""
    return str(environment().get_template(template).render(**context))


def write_report(out: str | Path, name: str, context: Mapping[str, Any]) -> dict[str, Path]:
    """Write ``report.md`` and ``index.html`` into ``out`` from the templates ``name.md.j2``
    and ``name.html.j2``; returns the paths written."""
    out = Path(out)
    paths = {"report.md": out / "report.md", "index.html": out / "index.html"}
    md = render(f"{name}.md.j2", context)
    page = render(f"{name}.html.j2", context)
    write_text(paths["report.md"], md)
    write_text(paths["index.html"], page)
    return paths


__all__ = ["environment", "md_cell", "number", "render", "write_report"]
