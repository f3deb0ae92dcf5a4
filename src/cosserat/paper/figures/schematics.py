"""The two schematic figures (1: plane shear, 8: Couette cell), drawn with Matplotlib patches."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ...viz.plotting import new_figure, style
from .base import FigureData

if TYPE_CHECKING:
    from matplotlib.figure import Figure


def compute_schem_plane_shear() -> FigureData:
    return FigureData(
        "fig-schem_plane_shear",
        1,
        "plane shear (schematic)",
        "Plane shear between parallel walls: the lower wall is fixed, the upper moves at V "
        "under the normal stress N; wall friction angles delta_L (lower) and delta (upper).",
        panels=[],
    )


def plot_schem_plane_shear(data: FigureData) -> Figure:
    from matplotlib.patches import FancyArrowPatch, Rectangle

    fig, axes = new_figure(1, 1, width=4.2, height=2.8)
    ax = axes[0, 0]
    with style():
        ax.add_patch(Rectangle((0.0, 0.0), 4.0, 0.15, color="0.4"))
        ax.add_patch(Rectangle((0.0, 1.15), 4.0, 0.15, color="0.4"))
        rng = np.random.default_rng(1)
        for x, y in zip(rng.uniform(0.1, 3.9, 120), rng.uniform(0.22, 1.08, 120), strict=True):
            ax.plot(x, y, "o", color="0.7", markersize=4)

        def arrow(a, b, label, pos):
            ax.add_patch(FancyArrowPatch(a, b, arrowstyle="-|>", mutation_scale=12, color="k"))
            ax.annotate(label, pos, fontsize=11)

        arrow((2.6, 1.45), (3.6, 1.45), r"$V$", (3.65, 1.4))
        arrow((1.5, 1.85), (1.5, 1.32), r"$N$", (1.57, 1.6))
        arrow((4.4, 1.0), (4.4, 0.4), r"$g$", (4.47, 0.65))
        ax.add_patch(
            FancyArrowPatch(
                (-0.3, 0.15), (-0.3, 1.15), arrowstyle="<|-|>", mutation_scale=10, color="k"
            )
        )
        ax.annotate(r"$H$", (-0.65, 0.6), fontsize=11)
        arrow((-0.9, -0.45), (-0.3, -0.45), r"$x$", (-0.25, -0.52))
        arrow((-0.9, -0.45), (-0.9, 0.05), r"$y$", (-1.05, 0.08))
        ax.annotate(r"$\delta$", (0.1, 1.36), fontsize=10)  # clear of V and its arrow
        ax.annotate(r"$\delta_L$", (3.65, -0.2), fontsize=10)
        ax.set_xlim(-1.2, 4.8)
        ax.set_ylim(-0.6, 2.0)
        ax.set_aspect("equal")
        ax.axis("off")
    return fig


def compute_schem_cyl_couette() -> FigureData:
    return FigureData(
        "fig-schem_cyl_couette",
        8,
        "cylindrical Couette cell (schematic)",
        "Cylindrical Couette flow: the outer cylinder is fixed, the inner one (radius R_i) "
        "turns; gap H; z vertical.",
        panels=[],
    )


def plot_schem_cyl_couette(data: FigureData) -> Figure:
    from matplotlib.patches import Arc, Circle, FancyArrowPatch

    fig, axes = new_figure(1, 1, width=3.4, height=3.4)
    ax = axes[0, 0]
    with style():
        ax.add_patch(Circle((0, 0), 2.0, fill=False, linewidth=3, color="0.4"))
        ax.add_patch(Circle((0, 0), 1.0, color="0.4"))
        ax.add_patch(Circle((0, 0), 1.5, fill=False, linestyle=":", color="0.6"))
        ax.add_patch(Arc((0, 0), 1.4, 1.4, theta1=20, theta2=160, color="w", linewidth=1.5))
        ax.add_patch(
            FancyArrowPatch(
                (-0.66, 0.24), (-0.69, 0.12), arrowstyle="-|>", mutation_scale=10, color="w"
            )
        )
        ax.annotate(r"$\Omega$", (-0.12, 0.15), color="w", fontsize=11)
        ax.add_patch(
            FancyArrowPatch((0, 0), (0.71, -0.71), arrowstyle="-|>", mutation_scale=10, color="k")
        )
        ax.annotate(r"$R_i$", (-0.1, -0.62), fontsize=11, color="w")  # beside the arrow
        ax.add_patch(
            FancyArrowPatch((1.0, 0), (2.0, 0), arrowstyle="<|-|>", mutation_scale=10, color="k")
        )
        ax.annotate(r"$H$", (1.4, 0.08), fontsize=11)
        ax.annotate(r"$r$", (0.0, -1.35), fontsize=11)
        ax.annotate(r"$\theta$", (1.3, 1.3), fontsize=11)
        ax.set_xlim(-2.3, 2.3)
        ax.set_ylim(-2.3, 2.3)
        ax.set_aspect("equal")
        ax.axis("off")
    return fig
