"""Figures of a calibration: each run's measured fields beside every model, and the residuals.

A leaf like :mod:`cosserat.viz.plotting`: it draws plain data (the dictionaries of
:func:`cosserat.calibration.report.figure_data`) and imports nothing of the package at run
time.

One figure per run: a column per field (velocity on a log axis, so that a creep tail spanning
decades is visible; spin and stress ratio on linear axes), the data with their error bars, each
model's best fit as a line and, where a posterior was sampled, its 68% and 95% bands over the
posterior (its parameters drawn from the posterior; the noise of the data not added); below,
the residuals over the standard errors.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from matplotlib.figure import Figure

FIELD_AXES = {
    "u": (r"$u/u_w$", "log"),
    "omega": (r"$\omega\, d/V$", "linear"),
    "stress_ratio": (r"$|\sigma_{yx}|/\sigma_{yy}$", "linear"),
}
COUETTE_AXES = {"stress_ratio": r"$|\sigma_{r\theta}|/\sigma_{rr}$"}
MODEL_STYLES = {
    "cosserat": {"color": "C0", "linestyle": "-"},
    "mui": {"color": "C3", "linestyle": "--"},
    "ngf": {"color": "C2", "linestyle": "-."},
}
U_FLOOR = 1e-5
"""Lower limit of the log velocity axis [-], lowered to a decade below the smallest positive
measured u (not below :data:`U_FLOOR_MIN`); a point at or below it is shown at the axis edge."""
U_FLOOR_MIN = 1e-8
"""The lowest the log velocity axis goes [-]."""


def run_figure(entry: Mapping[str, Any]) -> Figure:
    """The figure of one run (module docstring).

    Parameters
    ----------
    entry : mapping
        ``name``, ``gap_d``, ``fields`` (field -> {"s", "data", "se"}), ``models`` (model ->
        field -> {"s", "values"}), optional ``bands`` (model -> field -> {"s", "q2.5", "q16",
        "q84", "q97.5"}) and ``residuals`` (model -> field -> {"s", "z"}).
    """
    import matplotlib.pyplot as plt
    import numpy as np

    from .plotting import style

    fields = [f for f in ("u", "omega", "stress_ratio") if f in entry["fields"]]
    wall = entry["fields"].get("wall_ratio")
    with style():
        fig, axes = plt.subplots(
            2,
            len(fields),
            figsize=(3.3 * len(fields) + 0.6, 5.6),
            squeeze=False,
            gridspec_kw={"height_ratios": [3, 1.3]},
            sharex="col",
        )
        for j, name in enumerate(fields):
            ax, rax = axes[0, j], axes[1, j]
            label, scale = FIELD_AXES[name]
            if entry.get("cell") == "couette" and name in COUETTE_AXES:
                label = COUETTE_AXES[name]
            d = entry["fields"][name]
            s, y, se = (np.asarray(d[k], dtype=float) for k in ("s", "data", "se"))
            floor = U_FLOOR
            if scale == "log":
                ax.set_yscale("log")
                positive = y[y > 0.0]
                if positive.size:  # a decade below the smallest positive measured u
                    floor = max(min(U_FLOOR, 0.1 * float(positive.min())), U_FLOOR_MIN)
                low = y <= floor  # measured at or below the floor (zero, negative): open marks
                if np.any(low):
                    ax.plot(
                        s[low],
                        np.full(np.count_nonzero(low), floor * 1.15),
                        "v",
                        mfc="none",
                        mec="0.4",
                        ms=4,
                        label="data <= 0, or off the axis",
                    )
                s, y, se = s[~low], y[~low], se[~low]
                shown = np.maximum(y, floor)
                lower = np.minimum(np.clip(y - se, floor, None), shown)
                ax.errorbar(
                    s,
                    shown,
                    yerr=[shown - lower, np.maximum(y + se, shown) - shown],
                    fmt="o",
                    ms=3,
                    color="k",
                    ecolor="0.5",
                    elinewidth=0.8,
                    capsize=1.5,
                    label="data",
                    zorder=3,
                )
                ax.set_ylim(floor, 1.5)
            else:
                ax.errorbar(
                    s,
                    y,
                    yerr=se,
                    fmt="o",
                    ms=3,
                    color="k",
                    ecolor="0.5",
                    elinewidth=0.8,
                    capsize=1.5,
                    label="data",
                    zorder=3,
                )
            for model, curves in entry.get("bands", {}).items():
                if name not in curves:
                    continue
                b = curves[name]
                st = MODEL_STYLES.get(model, {"color": "C4"})
                ax.fill_between(b["s"], b["q2.5"], b["q97.5"], color=st["color"], alpha=0.12, lw=0)
                ax.fill_between(b["s"], b["q16"], b["q84"], color=st["color"], alpha=0.25, lw=0)
            for model, curves in entry["models"].items():
                if name not in curves:
                    continue
                c = curves[name]
                st = MODEL_STYLES.get(model, {"color": "C4", "linestyle": ":"})
                v = np.asarray(c["values"], dtype=float)
                if scale == "log":
                    v = np.where(v > 0, v, np.nan)
                ax.plot(c["s"], v, label=model, **st)
                r = entry.get("residuals", {}).get(model, {}).get(name)
                if r is not None:
                    rax.plot(r["s"], r["z"], "o-", ms=2.5, lw=0.7, color=st["color"])
            if name == "stress_ratio" and wall is not None:
                ax.errorbar(
                    [0.0],
                    wall["data"],
                    yerr=wall["se"],
                    fmt="s",
                    ms=4,
                    mfc="none",
                    color="k",
                    capsize=1.5,
                    label="wall (contacts)",
                    zorder=3,
                )
            ax.set_ylabel(label)
            ax.set_xlim(-0.02 * float(entry["gap_d"]), float(entry["gap_d"]))
            rax.axhline(0.0, color="0.3", lw=0.6)
            for z in (-2.0, 2.0):
                rax.axhline(z, color="0.6", lw=0.5, ls=":")
            rax.set_ylabel("(model - data)/se\n(not whitened)", fontsize=7)
            rax.set_xlabel("distance from the moving wall $s/d$")
        handles, labels = [], []
        for ax in axes[0]:
            for h, lab in zip(*ax.get_legend_handles_labels(), strict=True):
                if lab not in labels:
                    handles.append(h)
                    labels.append(lab)
        fig.legend(
            handles,
            labels,
            loc="lower center",
            ncol=len(labels),
            fontsize=8,
            bbox_to_anchor=(0.5, -0.01),
        )
        fig.suptitle(f"run {entry['name']} (H = {float(entry['gap_d']):.4g} d)", fontsize=10)
        fig.tight_layout(rect=(0, 0.05, 1, 1))
    return fig


__all__ = ["FIELD_AXES", "MODEL_STYLES", "run_figure"]
