"""Figures of ``cosserat validate``: one per run, one per claim.

A leaf like :mod:`cosserat.viz.plotting`: every function draws plain data (the dictionaries
that :mod:`cosserat.studies.validate.report` builds) and imports nothing of the package above
this layer. Error bars are drawn on every measured point, velocities also on a log axis (a
creep tail spanning decades is visible there), legends sit outside the axes, tick labels are
plain numbers.
"""

from __future__ import annotations

import textwrap
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

from .calibration import MODEL_STYLES

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

U_FLOOR = 1e-4
"""Lowest velocity on the log axis when the data do not go lower [-]."""


def model_style(model: str, order: Sequence[str] = ()) -> dict[str, Any]:
    """One colour and line style per model, the same in every figure."""
    if model in MODEL_STYLES:
        return dict(MODEL_STYLES[model])
    i = list(order).index(model) if model in order else len(order)
    return {"color": f"C{(i + 4) % 10}", "linestyle": ["-", "--", "-.", ":"][i % 4]}


def _plain(ax: Axes, axis: str = "both") -> None:
    """Plain tick labels (20, 40, 80 rather than powers of ten) on log axes."""
    from matplotlib.ticker import FuncFormatter, NullFormatter

    fmt = FuncFormatter(lambda v, _: f"{v:g}")
    for name in ("x", "y") if axis == "both" else (axis,):
        a = ax.xaxis if name == "x" else ax.yaxis
        if (ax.get_xscale() if name == "x" else ax.get_yscale()) == "log":
            a.set_major_formatter(fmt)
            a.set_minor_formatter(NullFormatter())


def _legend_below(fig: Figure, axes: Sequence[Axes], ncol: int = 4) -> None:
    """One legend for the figure, below the panels (off the data)."""
    handles, labels, seen = [], [], set()
    for ax in axes:
        for h, lab in zip(*ax.get_legend_handles_labels(), strict=True):
            if lab not in seen:
                seen.add(lab)
                handles.append(h)
                labels.append(lab)
    if handles:
        fig.legend(
            handles,
            labels,
            loc="lower center",
            ncol=min(ncol, len(labels)),
            frameon=False,
            fontsize=7,
            bbox_to_anchor=(0.5, 0.0),
        )


DATA_STYLE: dict[str, Any] = {
    "fmt": "o",
    "color": "k",
    "markerfacecolor": "none",
    "capsize": 1.5,
    "elinewidth": 0.6,
    "markersize": 3,
    "label": "DEM data (+- 1 se)",
}
"""How a run figure draws measured points: open circles with 1-se bars."""


def run_figure(entry: Mapping[str, Any]) -> Figure:
    """One run: u/V with error bars (linear, and log for the creep tail) beside each fitted
    model; the spin's departure from half the vorticity with its error bars and each model's.

    Parameters
    ----------
    entry : mapping
        ``name``, ``title``, ``distance_d``, ``u``, ``u_se`` (arrays), ``models`` (model ->
        {"d", "u"}), ``order`` (model names, best first), optional ``spin`` ({"distance_d",
        "departure", "stderr", "predicted": model -> array, "near_wall_d", "gap_d"}), optional
        ``cell`` (``"channel"``: no wall moves, the distance is from the wall at y = 0 and V is
        the run's velocity scale sqrt(g d); no creep tail is named).
    """
    import numpy as np

    from .plotting import new_figure, style

    spin = entry.get("spin")
    layer = entry.get("layer")
    ncols = 3 if spin else 2
    fig, axes = new_figure(1, ncols, width=3.1 * ncols, height=4.4 if layer else 3.1)
    order = list(entry.get("order", ()))
    channel = entry.get("cell") == "channel"
    x_label = (
        r"distance from the wall at $y = 0$ [$d$]"
        if channel
        else r"distance from the moving wall [$d$]"
    )
    u_label = r"$u/V$, $V = \sqrt{g d}$ [-]" if channel else r"$u/V$ [-]"
    with style():
        d = np.asarray(entry["distance_d"], dtype=float)
        u = np.asarray(entry["u"], dtype=float)
        se = np.asarray(entry["u_se"], dtype=float)
        for j, ax in enumerate(axes[0, :2]):
            log = j == 1
            if layer:
                _layer_panel(ax, layer, d, u, se, entry["models"], order, rate=log)
                continue
            show = u > 0 if log else np.ones(u.size, bool)
            lower = np.minimum(se, u * (1 - 1e-9)) if log else se  # bars stay on a log axis
            ax.errorbar(
                d[show],
                u[show],
                yerr=[lower[show], se[show]],
                **DATA_STYLE,
            )
            for name, curve in entry["models"].items():
                cu = np.asarray(curve["u"], dtype=float)
                cd = np.asarray(curve["d"], dtype=float)
                keep = cu > 0 if log else np.ones(cu.size, bool)
                ax.plot(cd[keep], cu[keep], label=name, **model_style(name, order))
            ax.set_xlabel(x_label)
            ax.set_ylabel(u_label)
            if log:
                ax.set_yscale("log")
                pos = u[u > 0]
                lo = max(min(float(pos.min()) / 3, U_FLOOR) if pos.size else U_FLOOR, 1e-8)
                # above every point and its bar (a channel's u/V exceeds 1)
                hi = max(2.0, 1.5 * float(np.max((u + se)[u > 0]))) if pos.size else 2.0
                ax.set_ylim(lo, hi)
                n_hidden = int(np.sum(u <= 0))
                hidden = f", {n_hidden} bins with u <= 0 not shown" if n_hidden else ""
                what = "log axis" if channel else "log axis: the creep tail"
                ax.set_title(what + hidden, fontsize=8)
                _plain(ax, "x")
            else:
                ax.set_title("linear axis" if channel else "linear axis: the band", fontsize=8)
        if spin:
            ax = axes[0, 2]
            x = np.asarray(spin["distance_d"], dtype=float)
            if layer:  # the layer's panels run from the smoother wall
                x = _from_smoother(layer, x)
            o = np.argsort(x)
            y = np.asarray(spin["departure"], dtype=float)[o]
            e = np.asarray(spin["stderr"], dtype=float)[o]
            x = x[o]
            ax.errorbar(
                x,
                y,
                yerr=e,
                **DATA_STYLE,
            )
            like = layer.get("spin_like", {}) if layer else {}
            for name, pred in spin.get("predicted", {}).items():
                # a layer's Cosserat spin in the colour of its velocity curve
                look = model_style(like.get(name, name), order)
                ax.plot(x, np.asarray(pred, dtype=float)[o], label=name, **look)
            ax.axhline(0.0, color="0.5", linewidth=0.6)
            near, gap = float(spin["near_wall_d"]), float(spin["gap_d"])
            ax.axvspan(0.0, near, color="0.92", zorder=0)
            ax.axvspan(gap - near, gap, color="0.92", zorder=0)
            ax.set_xlabel(_layer_x_label(layer) if layer else x_label)
            ax.set_ylabel(r"$(\omega - \frac{1}{2}\,\mathrm{vorticity})\,d/V$ [-]")
            ax.set_title(
                "spin departure (shaded: near the walls)"
                + ("\nlines: Cosserat layer profile; NGF has no spin" if layer else ""),
                fontsize=8,
            )
        note = "\n" + textwrap.fill(layer["note"], 150) if layer else ""
        fig.suptitle(entry["title"] + note, fontsize=8)
        _legend_below(fig, list(axes[0]), ncol=3 if layer else 4)
        # fixed margins: tight_layout costs more than the drawing (saved with a tight box)
        if layer:  # a longer legend (every alternative and the spin curves) and caption
            fig.subplots_adjust(left=0.08, right=0.98, bottom=0.34, top=0.8, wspace=0.45)
        else:
            fig.subplots_adjust(left=0.08, right=0.98, bottom=0.28, top=0.8, wspace=0.45)
    return fig


def _layer_panel(
    ax: Axes, layer: Mapping[str, Any], d: Any, u: Any, se: Any,
    models: Mapping[str, Any], order: Sequence[str], rate: bool,
) -> None:  # fmt: skip
    """A layer run's panel: u/V (``rate`` False) or the shear rate between bins on a log axis
    (True), each with the alternatives' lines, the walls named and the 3 d windows of ``a``
    shaded."""
    import numpy as np

    gap, w = float(layer["gap_d"]), float(layer["within_d"])
    d = _from_smoother(layer, np.asarray(d, dtype=float))
    ax.axvspan(0.0, w, color="0.92", zorder=0, label=f"{w:g} d windows of a")
    ax.axvspan(gap - w, gap, color="0.92", zorder=0)
    if rate:
        g = layer["rate"]
        x, y, e = (np.asarray(g[k], dtype=float) for k in ("d", "rate", "se"))
        x = _from_smoother(layer, x)
        ok = y > 0
        lower = np.minimum(e, y * (1 - 1e-9))
        ax.errorbar(x[ok], y[ok], yerr=[lower[ok], e[ok]], **{**DATA_STYLE, "label": None})
        for name, c in layer["model_rates"].items():
            cx, cy = np.asarray(c["d"], dtype=float), np.asarray(c["rate"], dtype=float)
            cx = _from_smoother(layer, cx)
            keep = cy > 1e-6
            if np.any(keep):
                ax.plot(cx[keep], cy[keep], label=name, **model_style(name, order))
        ax.set_yscale("log")
        ax.set_ylabel(r"shear rate $|\mathrm{d}u/\mathrm{d}y|\,d/V$ [-]")
        ax.set_title("shear rate (log axis): uniform stress", fontsize=8)
        pos = y[ok]
        if pos.size:
            ax.set_ylim(max(float(pos.min()) / 5, 1e-4), 3 * float(pos.max()))
    else:
        ax.errorbar(d, u, yerr=se, **DATA_STYLE)
        for name, c in models.items():
            cx = _from_smoother(layer, np.asarray(c["d"], dtype=float))
            ax.plot(cx, c["u"], label=name, **model_style(name, order))
        ax.set_ylabel(r"$u/V$ [-]")
        ax.set_title("linear axis: the band", fontsize=8)
    ax.set_xlabel(_layer_x_label(layer))
    ax.set_xlim(-0.3, gap + 0.3)
    walls = layer["walls"]
    at_zero = layer.get("smoother", "moving")  # the wall at x = 0
    other = "moving" if at_zero == "fixed" else "fixed"
    for x_wall, text, ha in ((0.0, walls[at_zero], "left"), (gap, walls[other], "right")):
        ax.annotate(
            text, (x_wall, 0.0), xycoords=("data", "axes fraction"),
            xytext=(2 if ha == "left" else -2, 3),
            textcoords="offset points", ha=ha, va="bottom", fontsize=6.5, color="0.25",
        )  # fmt: skip


def _from_smoother(layer: Mapping[str, Any], x: Any) -> Any:
    """Distances from the moving wall as distances from the layer run's smoother wall [d]
    (unchanged when the moving wall is the smoother or the entry does not say)."""
    return float(layer["gap_d"]) - x if layer.get("smoother") == "fixed" else x


def _layer_x_label(layer: Mapping[str, Any]) -> str:
    """The layer panels' x label: from the smoother wall, naming which wall it is."""
    which = layer.get("smoother")
    return (
        rf"from the smoother ({which}) wall [$d$]"
        if which in ("fixed", "moving")
        else r"distance from the moving wall [$d$]"
    )


def spin_claim_figure(
    rows: Sequence[Mapping[str, Any]], models: Sequence[str] = (), title: str = ""
) -> Figure:
    """The measured departure of the spin in the first layer at each wall of each run, with
    its error bar (2 se), beside each model's prediction there (one row per run and wall).

    Parameters
    ----------
    rows : sequence of mapping
        ``label``, ``first``, ``se``, ``sheared`` (bool), ``predicted`` (model -> value),
        optional ``stencil_range`` ((low, high): the measured first-layer departure's range
        over the difference stencils, drawn as a grey bar) and ``null`` (what the measurement
        reports for grains turning with the material, drawn as a grey cross).
    models : sequence of str
        The models to draw, in order.
    title : str
        Above the axes.
    """
    import numpy as np

    from .plotting import new_figure, style

    n = max(len(rows), 1)
    fig, axes = new_figure(1, 1, width=7.5, height=1.3 + 0.26 * n)
    ax = axes[0, 0]
    with style():
        y = np.arange(len(rows))[::-1]
        for yi, r in zip(y, rows, strict=True):
            span = r.get("stencil_range")
            if span is not None:
                ax.plot(list(span), [yi, yi], color="0.75", linewidth=5, solid_capstyle="butt",
                        zorder=0, label="measured, range over the stencils")  # fmt: skip
            if r.get("null") is not None:
                ax.plot([r["null"]], [yi], marker="x", color="0.35", linestyle="none",
                        label="grains turning with the material, measured so")  # fmt: skip
            label = "measured (+- 2 se)" if r["sheared"] else "measured, wall not sheared"
            ax.errorbar([r["first"]], [yi], xerr=[2 * r["se"]], fmt="o", color="k", capsize=2,
                        markerfacecolor="k" if r["sheared"] else "none", elinewidth=0.8,
                        label=label)  # fmt: skip
            for j, m in enumerate(models):
                p = r["predicted"].get(m)
                if p is not None:
                    ax.plot([p], [yi - 0.18 * (j + 1) + 0.02], marker="dsv^"[j % 4],
                            linestyle="none", color=model_style(m, models)["color"],
                            label=f"{m} (fitted to u, measured as the data)")  # fmt: skip
        ax.axvline(0.0, color="0.5", linewidth=0.6)
        ax.set_yticks(y, [r["label"] for r in rows], fontsize=7)
        ax.set_ylim(-0.8, len(rows) - 0.2)
        ax.set_xlabel(r"$(\omega - \frac{1}{2}\,\mathrm{vorticity})\,d/V$ in the first layer [-]")
        if title:
            ax.set_title(title, fontsize=8)
        if not rows:
            ax.text(0.5, 0.5, "no spin measured", ha="center", transform=ax.transAxes)
        handles, labels = ax.get_legend_handles_labels()
        uniq = dict(zip(labels, handles, strict=True))
        if uniq:
            ax.legend(uniq.values(), uniq.keys(), loc="upper left", bbox_to_anchor=(1.02, 1.0),
                      fontsize=7, frameon=False)  # fmt: skip
        fig.subplots_adjust(left=0.32, right=0.72, bottom=0.6 / fig.get_figheight() + 0.02,
                            top=1.0 - 0.35 / fig.get_figheight())  # fmt: skip
    return fig


def _nice_ticks(lo: float, hi: float, wanted: Sequence[float]) -> list[float]:
    return [t for t in wanted if lo <= t <= hi]


def delta_claim_figure(
    series: Sequence[Mapping[str, Any]], exponents: Mapping[str, float], title: str
) -> Figure:
    """Measured Delta against H/d on log axes with error bars, one panel per gap series, each
    model's Delta curve from one joint calibration of the series (its value at each run with
    the calibration's error), and the claimed exponents through the data.

    Parameters
    ----------
    series : sequence of mapping
        ``label``, ``gaps``, ``Delta``, ``stderr``, ``usable`` (per point), ``curves``
        (model -> ``gaps``, ``Delta`` of the curve and ``points``: (H/d, Delta, se) at the
        runs).
    exponents : mapping
        Label -> exponent of the reference lines (drawn through the geometric mean of the
        usable points; not drawn, and the panel says so, when every band fills its gap or
        the usable points are at one gap).
    """

    import numpy as np

    from .plotting import new_figure, style

    n = max(1, len(series))
    fig, axes = new_figure(1, n, width=min(3.2 * n + 0.6, 11.0), height=3.6)
    axs = [axes[0, k] for k in range(n)]
    order = sorted({m for s in series for m in s.get("curves", {})})
    with style():
        if not series:
            axs[0].text(0.5, 0.5, "no series for this claim", ha="center",
                        transform=axs[0].transAxes)  # fmt: skip
        for ax, s in zip(axs, series, strict=False):
            pts = [
                (g, d, e, u)
                for g, d, e, u in zip(s["gaps"], s["Delta"], s["stderr"], s["usable"], strict=True)
                if d is not None and d > 0
            ]
            for use in (True, False):
                sel = [p for p in pts if p[3] == use]
                if sel:
                    ax.errorbar(
                        [p[0] for p in sel], [p[1] for p in sel],
                        yerr=[p[2] or 0.0 for p in sel], fmt="o", color="k",
                        markerfacecolor="k" if use else "none", capsize=2, markersize=4,
                        label="DEM data (+- 1 se)" if use else "band fills its gap: left out",
                        zorder=3,
                    )  # fmt: skip
            all_g = [p[0] for p in pts]
            all_d = [p[1] for p in pts]
            for model, c in s.get("curves", {}).items():
                st = model_style(model, order)
                cg = [(g, d) for g, d in zip(c["gaps"], c["Delta"], strict=True) if d]
                if cg:
                    ax.plot([g for g, _ in cg], [d for _, d in cg], color=st["color"],
                            linestyle=st.get("linestyle", "-"), linewidth=1.2,
                            label=f"{model}, one joint calibration")  # fmt: skip
                    all_g += [g for g, _ in cg]
                    all_d += [d for _, d in cg]
                cp = [p for p in c.get("points", []) if p[1]]
                all_d += [p[1] for p in cp]
                if cp:
                    ax.errorbar([p[0] for p in cp], [p[1] for p in cp],
                                yerr=[p[2] or 0.0 for p in cp], fmt="x", color=st["color"],
                                capsize=2, markersize=5)  # fmt: skip
            if not all_g:
                ax.text(0.5, 0.5, "no usable Delta", ha="center", transform=ax.transAxes)
                ax.set_title(s["label"], fontsize=7)
                continue
            g0, g1 = min(all_g) / 1.15, max(all_g) * 1.15
            data = [p for p in pts if p[3]]  # never the claimed laws through a left-out point
            if not data:  # the words above the left-out points
                ax.text(0.5, 0.94, "no run with a band thinner than its gap" if pts
                        else "no usable Delta", ha="center", va="top", fontsize=7,
                        transform=ax.transAxes)  # fmt: skip
            elif len({p[0] for p in data}) < 2:  # two lines through one point show nothing
                ax.text(0.5, 0.94, "one gap: no dependence on H/d to show", ha="center",
                        va="top", fontsize=7, transform=ax.transAxes)  # fmt: skip
            else:
                gg = np.geomspace(g0, g1, 20)
                d0 = float(np.exp(np.mean(np.log([p[1] for p in data]))))
                gm = float(np.exp(np.mean(np.log([p[0] for p in data]))))
                for k, (label, ex) in enumerate(exponents.items()):
                    ax.plot(gg, d0 * (gg / gm) ** ex, color="0.55",
                            linestyle=["--", "-."][k % 2], linewidth=0.8,
                            label=label)  # fmt: skip
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlim(g0, g1)
            _plain(ax)
            ax.set_xticks(_nice_ticks(g0, g1, (5, 10, 20, 40, 80, 160, 320, 640, 1280)))
            lo, hi = min(all_d) / 1.3, max(all_d) * 1.3
            ax.set_ylim(lo, hi)
            ticks = (0.5, 1, 1.5, 2, 3, 5, 7, 10, 15, 20, 30, 50, 70, 100)
            ax.set_yticks(_nice_ticks(lo, hi, ticks))
            ax.set_title(s["label"], fontsize=7)
            ax.set_xlabel(r"$H/d$ [-]")
        axs[0].set_ylabel(r"$\Delta$ [$d$]")
        markers = any(p[1] for s in series for c in s.get("curves", {}).values()
                      for p in c.get("points", []))  # fmt: skip
        fig.suptitle(title + ("  (x: each model at the runs, +- its calibration's error)"
                              if markers else ""), fontsize=8)  # fmt: skip
        _legend_below(fig, axs, ncol=3)
        fig.subplots_adjust(left=0.09, right=0.98, bottom=0.33, top=0.84, wspace=0.3)
    return fig


__all__ = ["delta_claim_figure", "model_style", "run_figure", "spin_claim_figure"]
