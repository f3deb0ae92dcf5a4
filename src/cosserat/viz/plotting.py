"""Plotting primitives: one Matplotlib style for the package, a quick profile plot, the
data-beside-model plot.

A leaf of the package: it imports nothing from ``cosserat`` at run time and works on any object
with the attributes it reads, so every layer may draw with it (``docs/architecture.md``).
"""

from __future__ import annotations

import logging
from collections.abc import Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from matplotlib.typing import RcKeyType
    from numpy.typing import ArrayLike

    from ..results.profile import Profile

STYLE: dict[RcKeyType, Any] = {
    "figure.figsize": (6.4, 4.8),
    "figure.dpi": 100,
    "savefig.dpi": 200,
    "savefig.bbox": "tight",
    "font.size": 10,
    "axes.labelsize": 11,
    "axes.titlesize": 10,
    "legend.fontsize": 8,
    "legend.frameon": False,
    "lines.linewidth": 1.4,
    "lines.markersize": 4,
    "axes.spines.top": True,
    "axes.spines.right": True,
    "xtick.direction": "in",
    "ytick.direction": "in",
    "xtick.top": True,
    "ytick.right": True,
    "mathtext.fontset": "cm",
    "font.family": "serif",
    "pdf.fonttype": 42,
}
"""The package's Matplotlib style (used by every figure)."""

FIELD_LABELS = {
    "xi": r"$\xi$",
    "u": r"$u$",
    "omega": r"$\omega$",
    "m": r"$m$",
    "sigma_xy": r"$\bar\sigma_{xy}$",
    "sigma_yx": r"$\bar\sigma_{yx}$",
    "sigma_yy": r"$\bar\sigma_{yy}$",
    "asymmetry": r"$\bar\sigma_{yx}-\bar\sigma_{xy}$",
    "spin_minus_half_vorticity": r"$\omega + \frac{1}{2}\,\mathrm{d}u/\mathrm{d}\xi$",
}
"""Axis labels of the profile fields (mathtext: for figures only)."""

COUETTE_LABELS = {
    "xi": r"$(r - R_i)/H$",
    "sigma_xy": r"$\bar\sigma_{\theta r}$",
    "sigma_yx": r"$\bar\sigma_{r\theta}$",
    "sigma_yy": r"$\bar\sigma_{rr}$",
    "asymmetry": r"$\bar\sigma_{r\theta}-\bar\sigma_{\theta r}$",
    "spin_minus_half_vorticity": r"$\omega + \frac{1}{2}(\mathrm{d}u/\mathrm{d}\bar r + u/\bar r)$",
}
"""The labels a Couette cell names in its own coordinates (r, theta; r-bar = r/H)."""


def field_label(problem: object, name: str) -> str:
    """Axis label of field ``name`` in the cell's own coordinates."""
    params = getattr(problem, "parameters", None)
    geometry = params().get("geometry") if callable(params) else None
    if geometry == "couette" and name in COUETTE_LABELS:
        return COUETTE_LABELS[name]
    return FIELD_LABELS[name]


def suptitle(fig: Figure, text: str, fontsize: float = 7) -> None:
    """A figure title wrapped to the figure's width (long problem descriptions are not cut)."""
    import textwrap

    chars = int(fig.get_figwidth() * 72 / (0.56 * fontsize))  # ~ half an em per character
    fig.suptitle(textwrap.fill(text, width=max(chars, 20)), fontsize=fontsize)


def upright_ylabel(ax: Axes, label: str) -> None:
    """A y label read upright when it is a short symbol (xi), along the axis otherwise."""
    if len(label) <= 10:
        ax.set_ylabel(label, rotation=0, ha="right", va="center")
    else:
        ax.set_ylabel(label)


@contextmanager
def style() -> Iterator[None]:
    """Context manager applying :data:`STYLE`."""
    import matplotlib as mpl

    # fontTools (font subsetting for the PDF) logs harmless warnings about font timestamps
    logging.getLogger("fontTools").setLevel(logging.ERROR)

    with mpl.rc_context(STYLE):
        yield


def new_figure(nrows: int = 1, ncols: int = 1, width: float = 6.4, height: float | None = None):
    """A styled figure and its axes (headless: no pyplot state)."""
    from matplotlib.figure import Figure

    height = height if height is not None else 2.9 * nrows
    with style():
        fig = Figure(figsize=(width, height))
        axes = fig.subplots(nrows, ncols, squeeze=False)
    return fig, axes


ROUND_OFF = 1e-10
"""A field whose largest magnitude is at most this fraction of its scale (:func:`field_scales`)
is zero to round-off: the quick plot draws it as zero and says so [-]. The solvers' tolerances
are 1e-8 and above, so nothing a solver resolves is this small."""


def field_scales(profile: Profile) -> dict[str, float]:
    """The scale each plotted field is measured against: the wall speed (1) for u, the larger
    of |omega| and |du/dxi|/2 for the spin minus half the vorticity (a difference of the two),
    the largest stress for the asymmetry sigma_yx - sigma_xy and the couple stress."""
    import numpy as np

    def biggest(*arrays: ArrayLike | None) -> float:
        values = [float(np.max(np.abs(a))) for a in arrays if a is not None and np.size(a)]
        return max([*values, 0.0])

    stress = biggest(profile.sigma_yx, profile.sigma_xy, profile.sigma_yy)
    du = None if profile.du_dxi is None else 0.5 * np.asarray(profile.du_dxi)
    return {
        "u": 1.0,
        "spin_minus_half_vorticity": biggest(profile.omega, du),
        "asymmetry": stress,
        "m": stress,
        "sigma_yx": stress,
    }


def zero_to_round_off(values: object, scale: float) -> bool:
    """True if every entry of ``values`` is at most :data:`ROUND_OFF` times ``scale`` in
    magnitude (a field identically zero included)."""
    import numpy as np

    v = np.asarray(values, dtype=float)
    return bool(v.size) and float(np.max(np.abs(v))) <= ROUND_OFF * scale


def quick_profile_plot(profile: Profile, fig: Figure | None = None) -> Figure:
    """u, omega + du/dxi/2, sigma_yx - sigma_xy and m against xi (as the paper's figure 2).

    A rheology without grain spin and couple stress (its omega and m are None) has only the
    velocity and the shear stress to show: those two panels, and a note in the others that
    the fields are absent. A field zero to round-off (:func:`zero_to_round_off`) is drawn as
    zero, and the panel says so."""
    import numpy as np

    with style():
        if fig is None:
            fig, axes = new_figure(2, 2, height=5.6)
        else:
            axes = fig.subplots(2, 2, squeeze=False)
        fig.set_layout_engine("constrained")
        panels = [
            ("u", profile.u),
            ("spin_minus_half_vorticity", profile.spin_minus_half_vorticity),
            ("asymmetry", profile.asymmetry),
            ("m", profile.m),
        ]
        if profile.m is None:
            panels[1:] = [("sigma_yx", profile.sigma_yx), ("absent", None), ("absent", None)]
        scales = field_scales(profile)
        for ax, (name, values) in zip(axes.ravel(), panels, strict=True):
            if values is None:
                ax.axis("off")
                ax.text(
                    0.5, 0.5, "no grain spin or couple stress\nin this rheology",
                    ha="center", va="center", transform=ax.transAxes,
                )  # fmt: skip
                continue
            if zero_to_round_off(values, scales.get(name, 1.0)):
                size = float(np.max(np.abs(values))) if len(values) else 0.0
                values = np.zeros_like(values)
                ax.text(
                    0.5, 0.92, f"zero to round-off (|max| = {size:.1e})",
                    ha="center", va="top", transform=ax.transAxes, fontsize=8,
                )  # fmt: skip
            ax.plot(values, profile.xi, color="k")
            ax.set_xlabel(field_label(profile.problem, name))
            upright_ylabel(ax, field_label(profile.problem, "xi"))
        suptitle(fig, profile.problem.describe())
    return fig


def comparison_plot(comparison, title: str = "", residual_panel: bool = False):
    """Data beside the model: linear and log velocity axes (the log axis shows the
    exponential tail), and optionally the residuals."""
    import numpy as np

    meas = comparison.measured
    d_max = float(meas.distance_d.max()) * 1.05 + 1e-9
    eps = comparison.profile.problem.eps
    d_fine = np.linspace(0.0, min(d_max, 1.0 / eps), 400)
    model = comparison.model_curve(d_fine)
    ncols = 3 if residual_panel else 2
    fig, axes = new_figure(1, ncols, width=3.3 * ncols, height=3.0)
    with style():
        fig.set_layout_engine("constrained")
        for k, ax in enumerate(axes[0, :2]):
            ax.plot(d_fine, model, "k-", label="model")
            if meas.u_err is not None:
                ax.errorbar(
                    meas.distance_d,
                    meas.u_over_uw,
                    yerr=meas.u_err,
                    fmt="o",
                    color="k",
                    markerfacecolor="none",
                    label=meas.label,
                    capsize=2,
                )
            else:
                ax.plot(
                    meas.distance_d,
                    meas.u_over_uw,
                    "o",
                    color="k",
                    markerfacecolor="none",
                    label=meas.label,
                )
            ax.set_xlabel(r"distance from the moving wall [$d_p$]")
            ax.set_ylabel(r"$u/u_w$")
            if k == 1:
                positive = meas.u_over_uw[meas.u_over_uw > 0]
                floor = max(float(positive.min()) / 3 if positive.size else 1e-4, 1e-8)
                ax.set_yscale("log")
                ax.set_ylim(floor, 1.5)
        # one legend below the panels, never on the data
        fig.legend(*axes[0, 0].get_legend_handles_labels(), loc="outside lower center", ncols=2)
        if residual_panel:
            ax = axes[0, 2]
            ax.axhline(0.0, color="0.6", linewidth=0.8)
            ax.plot(meas.distance_d, comparison.residuals, "o", color="k", markerfacecolor="none")
            ax.set_xlabel(r"distance from the moving wall [$d_p$]")
            ax.set_ylabel("data - model")
        if title:
            suptitle(fig, title, fontsize=8)
    return fig
