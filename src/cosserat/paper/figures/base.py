"""Figure data (curves on panels), a generic styled drawer, and CSV export.

A paper figure is ``compute() -> FigureData`` then ``plot(data) -> Figure``: the data is a
function of the caption's parameters only, the picture a function of the data only.
"""

from __future__ import annotations

import csv
import json
import textwrap
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..._atomic import atomic_open, save_figure, write_text
from ...model.constitutive import FloatArray
from ...viz.plotting import STYLE, new_figure, style

if TYPE_CHECKING:
    from matplotlib.figure import Figure

# The paper's line conventions: solid for the reference case (fully rough walls), then dashed,
# dash-dot, dotted; symbols for asymptotic (or measured) points.
LINESTYLES = ["-", "--", "-.", ":", (0, (5, 1, 1, 1, 1, 1))]
MARKERS = ["o", "D", "*", "s", "^"]


@dataclass
class Curve:
    """One curve of a panel: y against x, with Matplotlib style keywords.

    ``label`` is the legend text (mathtext allowed; hidden when it starts with ``_``; curves
    of a panel with the same label share one legend entry). ``name`` is the curve's plain-text
    name in tables (unique in its panel, no LaTeX), and ``x_name``/``y_name`` override the
    panel's column names for this curve (a panel holding two cells).
    """

    label: str
    x: FloatArray
    y: FloatArray
    style: dict[str, Any] = field(default_factory=dict)
    name: str = ""
    x_name: str = ""
    y_name: str = ""

    @property
    def plain_name(self) -> str:
        return self.name or self.label.lstrip("_")


@dataclass
class Panel:
    """One panel: axes labels (mathtext, for the picture), plain column names (for tables),
    scales and curves."""

    xlabel: str
    ylabel: str
    curves: list[Curve] = field(default_factory=list)
    xscale: str = "linear"
    yscale: str = "linear"
    tag: str = ""
    title: str = ""
    x_name: str = ""
    y_name: str = ""
    legend_title: str = ""

    def add(
        self,
        label: str,
        x: FloatArray,
        y: FloatArray,
        *,
        name: str = "",
        x_name: str = "",
        y_name: str = "",
        **style_kw: Any,
    ) -> None:
        self.curves.append(
            Curve(
                label,
                np.asarray(x, float),
                np.asarray(y, float),
                style_kw,
                name=name,
                x_name=x_name,
                y_name=y_name,
            )
        )

    def add_symbols(
        self, label: str, x: FloatArray, y: FloatArray, marker: str, **style_kw: Any
    ) -> None:
        """Open black symbols, no line: the paper's style for data and asymptotics."""
        style = {"color": "k", "linestyle": "none", "marker": marker, "markerfacecolor": "none"}
        self.add(label, x, y, **(style | style_kw))


def spaced_along(
    x: FloatArray, y: FloatArray, n: int, log_x: bool = False, phase: float = 0.0
) -> FloatArray:
    """Indices of about ``n`` points evenly spaced along the curve (x, y) as drawn (each axis
    scaled to its range), for symbols that neither pile up where the curve is steep nor thin
    out where it is flat. ``phase`` (0 to 1) shifts them by that fraction of their spacing, to
    stagger the symbols of curves that run together."""
    x = np.log10(np.asarray(x, float)) if log_x else np.asarray(x, float)
    y = np.asarray(y, float)
    sx = np.ptp(x) or 1.0
    sy = np.ptp(y) or 1.0
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(x) / sx, np.diff(y) / sy))])
    targets = arc[-1] * (np.arange(n) + phase) / max(n - 1, 1)
    targets = targets[targets <= arc[-1]]
    return np.unique(np.searchsorted(arc, targets).clip(0, len(x) - 1))


@dataclass
class FigureData:
    """Everything a figure shows, plus what it was made from."""

    key: str
    number: int
    title: str
    caption: str
    panels: list[Panel]
    notes: list[str] = field(default_factory=list)
    extra: dict[str, Any] = field(default_factory=dict)

    def rows(self) -> Iterator[list[str]]:
        """The table rows (panel, curve, x_name, x, y_name, y), all plain text."""
        for i, panel in enumerate(self.panels):
            tag = panel.tag or "abcdefgh"[i]
            for c in panel.curves:
                x_name = c.x_name or panel.x_name or "x"
                y_name = c.y_name or panel.y_name or "y"
                for x, y in zip(c.x, c.y, strict=True):
                    yield [tag, c.plain_name, x_name, repr(float(x)), y_name, repr(float(y))]

    def metadata(self) -> dict[str, Any]:
        """What the table's sidecar JSON holds: the figure, its caption, notes and columns."""
        return {
            "key": self.key,
            "figure": self.number,
            "title": self.title,
            "caption": self.caption,
            "notes": list(self.notes),
            "columns": {
                "panel": "panel letter",
                "curve": "the curve's name",
                "x_name": "what x holds (dimensionless, the paper's scalings)",
                "x": "abscissa as drawn",
                "y_name": "what y holds (dimensionless, the paper's scalings)",
                "y": "ordinate as drawn",
            },
        }

    def to_csv(self, path: str | Path) -> Path:
        """Tidy table, one row per point (panel, curve, x_name, x, y_name, y): one header row of
        plain column names, readable by ``pandas.read_csv`` as it is; the title, caption and
        notes go to a JSON sidecar beside it (``<stem>.json``)."""
        path = Path(path)
        with atomic_open(path, newline="") as fh:
            writer = csv.writer(fh)
            writer.writerow(["panel", "curve", "x_name", "x", "y_name", "y"])
            writer.writerows(self.rows())
        write_text(path.with_suffix(".json"), json.dumps(self.metadata(), indent=1) + "\n")
        return path


SHORT_LABEL = 10
"""y labels up to this many characters of source (xi, Delta, -u) are set horizontal."""


def _handles(ax: Any, panel: Panel, into: dict[str, list[Any]]) -> None:
    """Collect one legend handle per distinct label into ``into`` (first panel showing it
    wins); curves of a panel sharing a label show together (a symbol over its line)."""
    mine: dict[str, list[Any]] = {}
    for line, c in zip(ax.get_lines(), panel.curves, strict=False):
        if not c.label.startswith("_"):
            mine.setdefault(c.label, []).append(line)
    for label, lines in mine.items():
        into.setdefault(label, lines)


def draw(data: FigureData, ncols: int = 2, width: float = 6.6, panel_height: float = 2.9) -> Figure:
    """Draw the panels of ``data`` in the package style.

    Legends never sit on the data: one legend below all panels holds every label (a label means
    the same curve style in every panel). Short y labels (xi, Delta) are upright.
    """
    n = len(data.panels)
    ncols = min(ncols, n)
    nrows = (n + ncols - 1) // ncols
    fig, axes = new_figure(nrows, ncols, width=width, height=panel_height * nrows)
    with style():
        fig.set_layout_engine("constrained")
        flat = axes.ravel()
        entries: dict[str, list[Any]] = {}
        for i, (ax, panel) in enumerate(zip(flat, data.panels, strict=False)):
            for c in panel.curves:
                ax.plot(c.x, c.y, label=c.label, **c.style)
            ax.set_xlabel(panel.xlabel)
            if len(panel.ylabel) <= SHORT_LABEL:  # a symbol: read it upright
                ax.set_ylabel(panel.ylabel, rotation=0, ha="right", va="center")
            else:
                ax.set_ylabel(panel.ylabel)
            ax.set_xscale(panel.xscale)
            ax.set_yscale(panel.yscale)
            title = f"({panel.tag or 'abcdefgh'[i]}) {panel.title}" if n > 1 else panel.title
            if title.strip():  # wrapped to the panel's width: neighbours' titles never touch
                chars = int(width / ncols * 72 / (0.5 * STYLE["axes.titlesize"])) - 6
                ax.set_title(textwrap.fill(title.rstrip(), chars), loc="left")
            _handles(ax, panel, entries)
        if entries:
            titles = list(dict.fromkeys(p.legend_title for p in data.panels if p.legend_title))
            fig.legend(
                [tuple(v) if len(v) > 1 else v[0] for v in entries.values()],
                list(entries),
                loc="outside lower center",
                ncols=min(len(entries), 2 if n == 1 else 4 if len(entries) != 5 else 3),
                title="; ".join(titles) or None,
                handlelength=3.0,
            )
        for ax in flat[n:]:
            ax.set_visible(False)
    return fig


def save(data: FigureData, fig: Figure, out: str | Path) -> list[Path]:
    """Write ``<key>.png``, ``<key>.pdf`` and ``<key>.csv`` into ``out``."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    stem = f"fig{data.number:02d}_{data.key.removeprefix('fig-')}"
    paths = []
    with style():
        for ext in ("png", "pdf"):
            path = out / f"{stem}.{ext}"
            save_figure(fig, path)
            paths.append(path)
    paths.append(data.to_csv(out / f"{stem}.csv"))
    return paths
