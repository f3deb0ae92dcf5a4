"""Figure data (curves on panels), a generic styled drawer, and CSV export.

A paper figure is ``compute() -> FigureData`` then ``plot(data) -> Figure``: the data is a
function of the caption's parameters only, the picture a function of the data only.
"""

from __future__ import annotations

import csv
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..._atomic import atomic_open, save_figure
from ...model.constitutive import FloatArray
from ...viz.plotting import new_figure, style

if TYPE_CHECKING:
    from matplotlib.figure import Figure

# The paper's line conventions: solid for the reference case (fully rough walls), then dashed,
# dash-dot, dotted; symbols for asymptotic (or measured) points.
LINESTYLES = ["-", "--", "-.", ":", (0, (5, 1, 1, 1, 1, 1))]
MARKERS = ["o", "D", "*", "s", "^"]


@dataclass
class Curve:
    """One curve of a panel: y against x, with Matplotlib style keywords."""

    label: str
    x: FloatArray
    y: FloatArray
    style: dict[str, Any] = field(default_factory=dict)


@dataclass
class Panel:
    """One panel: axes labels, scales and curves."""

    xlabel: str
    ylabel: str
    curves: list[Curve] = field(default_factory=list)
    xscale: str = "linear"
    yscale: str = "linear"
    tag: str = ""
    title: str = ""

    def add(self, label: str, x: FloatArray, y: FloatArray, **style_kw: Any) -> None:
        self.curves.append(Curve(label, np.asarray(x, float), np.asarray(y, float), style_kw))

    def add_symbols(
        self, label: str, x: FloatArray, y: FloatArray, marker: str, **style_kw: Any
    ) -> None:
        """Open black symbols, no line: the paper's style for data and asymptotics."""
        style = {"color": "k", "linestyle": "none", "marker": marker, "markerfacecolor": "none"}
        self.add(label, x, y, **(style | style_kw))


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

    def to_csv(self, path: str | Path) -> Path:
        """Tidy table: one row per point (panel, curve, x, y)."""
        path = Path(path)
        with atomic_open(path, newline="") as fh:
            fh.write(f"# {self.key} (figure {self.number}): {self.title}\n")
            for note in self.notes:
                fh.write(f"# {note}\n")
            writer = csv.writer(fh)
            writer.writerow(["panel", "curve", "x_name", "x", "y_name", "y"])
            for i, panel in enumerate(self.panels):
                tag = panel.tag or "abcdefgh"[i]
                for c in panel.curves:
                    for x, y in zip(c.x, c.y, strict=True):
                        writer.writerow(
                            [
                                tag,
                                c.label,
                                panel.xlabel,
                                repr(float(x)),
                                panel.ylabel,
                                repr(float(y)),
                            ]
                        )
        return path


def draw(data: FigureData, ncols: int = 2, width: float = 6.6, panel_height: float = 2.9) -> Figure:
    """Draw the panels of ``data`` in the package style."""
    n = len(data.panels)
    ncols = min(ncols, n)
    nrows = (n + ncols - 1) // ncols
    fig, axes = new_figure(nrows, ncols, width=width, height=panel_height * nrows)
    with style():
        flat = axes.ravel()
        for i, (ax, panel) in enumerate(zip(flat, data.panels, strict=False)):
            for c in panel.curves:
                ax.plot(c.x, c.y, label=c.label, **c.style)
            ax.set_xlabel(panel.xlabel)
            ax.set_ylabel(panel.ylabel)
            ax.set_xscale(panel.xscale)
            ax.set_yscale(panel.yscale)
            if n > 1:
                ax.set_title(f"({panel.tag or 'abcdefgh'[i]}) {panel.title}".rstrip(), loc="left")
            elif panel.title:
                ax.set_title(panel.title, loc="left")
            if any(c.label and not c.label.startswith("_") for c in panel.curves):
                ax.legend()
        for ax in flat[n:]:
            ax.set_visible(False)
        fig.tight_layout()
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
