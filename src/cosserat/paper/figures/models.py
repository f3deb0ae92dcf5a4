"""The registered rheologies side by side (a page of the reproduction report, not a figure of
the paper): the same Couette cell and the same plane shear under gravity with every model
overlaid (velocity, and the spin where the model has one of its own), and Delta against H/d,
the prediction the paper says will distinguish the models.

Generic over :data:`cosserat.routes.RHEOLOGIES`: a rheology registered later appears here
without an edit.
"""

from __future__ import annotations

import numpy as np

from ... import config
from ...analysis.gap import thickness_vs_gap
from ...analysis.ranking import model_solve
from ...errors import CosseratError
from ...model import make_problem
from ...routes import RHEOLOGIES, models_for
from .base import LINESTYLES, MARKERS, FigureData, Panel, draw

CELLS = {
    "couette": {"eps": config.EPS, "Ri": config.RI},
    "plane": {"eps": config.EPS, "B": 1.0},
}
"""The two cells: the paper's Couette cell (figure 9's eps and Ri) and plane shear under
gravity B = 1 (figure 6's largest B)."""
GAPS = (10.0, 20.0, 40.0, 80.0, 160.0, 320.0)
POINTS = 201
COLORS = ["k", "tab:blue", "tab:red", "tab:green", "tab:purple", "tab:orange"]


def _style(styles: dict[str, dict], label: str, markevery: int | None = None) -> dict:
    """One style per series label in every panel (the figure has one legend for all panels):
    colour, line style and an open marker, spaced along profiles by ``markevery``."""
    if label not in styles:
        i = len(styles)
        styles[label] = {
            "color": COLORS[i % len(COLORS)],
            "linestyle": LINESTYLES[i % 5],
            "marker": MARKERS[i % len(MARKERS)],
            "markerfacecolor": "none",
        }
    style = dict(styles[label])
    if markevery is not None:
        style["markevery"] = markevery
    return style


def _models(cell: str) -> list[str]:
    return models_for(cell)


def compute_models() -> FigureData:
    """Profiles of every model on both cells, and Delta against the gap."""
    panels: list[Panel] = []
    notes: list[str] = []
    extra: dict = {"gap_studies": {}}
    spinless: set[str] = set()
    styles: dict[str, dict] = {}  # one style per series label across the panels
    for cell, params in CELLS.items():
        u_panel = Panel(xlabel=r"$u$", ylabel=r"$\xi$", title=f"{cell}: velocity")
        s_panel = Panel(
            xlabel=r"$\omega + \frac{1}{2}(\mathrm{d}u/\mathrm{d}\xi + \kappa u)$",
            ylabel=r"$\xi$",
            title=f"{cell}: spin minus half vorticity",
        )
        for model in _models(cell):
            own = {"delta": "fully-rough"} if model == "cosserat" else {}
            try:
                prof = model_solve(make_problem(model, cell, {**params, **own}), points=POINTS)
            except CosseratError as exc:
                notes.append(f"{model} on the {cell} cell: {' '.join(str(exc).split())}")
                continue
            label = f"{model}, fully rough" if model == "cosserat" else model
            style = _style(styles, label, markevery=max(1, POINTS // 8))
            u_panel.add(label, prof.u, prof.xi, **style)
            spin = prof.spin_minus_half_vorticity
            if spin is not None and np.any(spin != 0.0):
                s_panel.add(label, spin, prof.xi, **style)
            else:
                spinless.add(model)
        panels += [u_panel, s_panel]
    for cell in CELLS:
        study = thickness_vs_gap(cell, gaps=GAPS, cell_parameters={
            k: v for k, v in CELLS[cell].items() if k != "eps"
        })  # fmt: skip
        extra["gap_studies"][cell] = study.to_dict()
        panel = Panel(
            xlabel=r"$H/d$", ylabel=r"$\Delta$ [$d$]", xscale="log", yscale="log",
            title=f"{cell}: Delta against the gap",
        )  # fmt: skip
        for s in study.series:
            ok = [(g, d) for g, d in zip(s.gaps, s.Delta, strict=True) if d is not None]
            if not ok:
                continue
            g = np.array([p[0] for p in ok])
            d = np.array([p[1] for p in ok])
            last = s.slope_large_gap
            if last is not None:
                notes.append(
                    f"{cell}, {s.label}: slope of Delta against H/d between the two largest "
                    f"gaps {last:.2f}"
                )
            panel.add(s.label, g, d, **_style(styles, s.label))
        gg = np.geomspace(GAPS[0], GAPS[-1], 20)
        panel.add("slope 1/3", gg, 3.0 * (gg / GAPS[0]) ** (1 / 3), color="0.5", linestyle=":")
        panels.append(panel)
        for s in study.series:
            if s.failures:
                notes.append(
                    f"{cell}, {s.label}: no solution at H/d = "
                    + ", ".join(f"{g:g}" for g in s.failures)
                )
    if spinless:
        notes.append(
            f"no spin of its own (omega is half the vorticity): {', '.join(sorted(spinless))}"
        )
    names = ", ".join(RHEOLOGIES)
    caption = (
        f"Every registered rheology ({names}) on the same Couette cell (eps = "
        f"{config.text(config.EPS)}, Ri = {config.text(config.RI)}) and the same plane shear "
        f"under gravity (eps = {config.text(config.EPS)}, B = 1): velocity, the spin minus "
        "half the vorticity where the model has a spin of its own, and Delta against H/d with "
        "every other dimensionless number fixed (the Cosserat model for a wall with delta = "
        f"{config.text(config.DELTA)} deg and a fully rough one; mu(I) and NGF at their "
        "defaults, no-slip walls). The paper predicts Delta independent of the gap for the "
        "smoother wall and ~ (H/d)^(1/3) for the fully rough one as H/d -> infinity."
    )
    notes.append("the Cosserat profiles are for fully rough walls, as figures 6 and 9")
    return FigureData(
        "fig-models",
        15,
        "the rheologies side by side",
        caption,
        panels,
        notes=notes,
        extra=extra,
    )


def plot_models(data: FigureData):
    from matplotlib.ticker import NullFormatter, ScalarFormatter

    fig = draw(data, ncols=2)
    for ax in fig.axes:
        if ax.get_yscale() == "log":  # 2, 5, 10, 20 rather than 2 x 10^0
            ax.yaxis.set_major_formatter(ScalarFormatter())
            ax.yaxis.set_minor_formatter(NullFormatter())
    for ax in fig.axes:
        legend = ax.get_legend()
        for text in legend.get_texts() if legend else []:
            text.set_fontsize(6)
    return fig


__all__ = ["compute_models", "plot_models"]
