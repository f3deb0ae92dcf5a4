"""Every figure of the paper (1-14) and the rheologies side by side (15):
``FIGURES[n].compute()`` then ``FIGURES[n].plot(data)``."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from . import models, paper, schematics
from .base import FigureData, save

if TYPE_CHECKING:
    from matplotlib.figure import Figure


@dataclass(frozen=True)
class PaperFigure:
    """A figure of the paper: its number, label, and the two halves of its making."""

    number: int
    key: str
    compute: Callable[..., FigureData]
    plot: Callable[[FigureData], Figure]
    takes_data: bool = False


FIGURES: dict[int, PaperFigure] = {
    f.number: f
    for f in [
        PaperFigure(
            1,
            "fig-schem_plane_shear",
            schematics.compute_schem_plane_shear,
            schematics.plot_schem_plane_shear,
        ),
        PaperFigure(2, "fig-zero_g", paper.compute_zero_g, paper.plot_default),
        PaperFigure(3, "fig-zero_g_aw", paper.compute_zero_g_aw, paper.plot_default),
        PaperFigure(4, "fig-asymp_g0", paper.compute_asymp_g0, paper.plot_default),
        PaperFigure(5, "fig-bc", paper.compute_bc, paper.plot_default),
        PaperFigure(6, "fig-finite_g", paper.compute_finite_g, paper.plot_default),
        PaperFigure(7, "fig-asymp_g_c", paper.compute_asymp_g_c, paper.plot_default),
        PaperFigure(
            8,
            "fig-schem_cyl_couette",
            schematics.compute_schem_cyl_couette,
            schematics.plot_schem_cyl_couette,
        ),
        PaperFigure(9, "fig-cyl_couette", paper.compute_cyl_couette, paper.plot_default),
        PaperFigure(10, "fig-mueth", paper.compute_mueth, paper.plot_default, takes_data=True),
        PaperFigure(11, "fig-bocquet", paper.compute_bocquet, paper.plot_default, takes_data=True),
        PaperFigure(12, "fig-A_sensitivity", paper.compute_A_sensitivity, paper.plot_default),
        PaperFigure(13, "fig-K_sensitivity", paper.compute_K_sensitivity, paper.plot_default),
        PaperFigure(14, "fig-slt", paper.compute_slt, paper.plot_default),
        PaperFigure(15, "fig-models", models.compute_models, models.plot_models),
    ]
}


def make_figure(
    number: int, out: str | None = None, data: dict[str, Any] | None = None
) -> tuple[FigureData, Any]:
    """Compute and plot figure ``number``; save PNG, PDF and CSV into ``out`` if given."""
    spec = FIGURES[number]
    fig_data = spec.compute(data) if spec.takes_data else spec.compute()
    fig = spec.plot(fig_data)
    if out is not None:
        save(fig_data, fig, out)
    return fig_data, fig


__all__ = ["FIGURES", "FigureData", "PaperFigure", "make_figure"]
