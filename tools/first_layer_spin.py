"""The first layer's spin at finer resolution (issue 18; referee 5, request 1c; docs/dem.md,
"The first layer's spin at finer resolution").

    PYTHONPATH=src python tools/first_layer_spin.py RUN_FOLDER... --cache DIR [--out DIR]

Each RUN_FOLDER is a finished 2-D plane run of corpus v2 with its dumps (read only; the
folder's name is the cell's name in :func:`cosserat.dem.corpus.corpus_v2_cells`). Its dumps are
read once into ``DIR/<name>.npz`` (the fine-bin sums of
:func:`cosserat.dem.analyse.read_samples` and the layer sums of
:func:`cosserat.dem.first_layer.read_layers`; later calls read the cache). Over the steady
window the run's own ``profile.json`` kept, printed per sheared wall (the moving wall; the
layer run's smooth fixed wall too) and written to ``--out`` as ``first_layer_spin.json``:

* the first bin's omega - half vorticity under 0.25, 0.5 and 1 d bins
  (``steady_profile(..., bin_width=w)``) and the stencils ``analysis``, ``wall`` and
  ``wall-first`` (:func:`cosserat.studies.validate.forward.measured_first_layer`), with the
  Cosserat model's and the null's values measured the same way
  (:func:`~cosserat.studies.validate.forward.forward_departure`, ``null_departure``);
* the particle-level measures (:func:`cosserat.dem.first_layer.first_layer`) with the model's
  and the null's, the model's layers being the uniform averages over [0, 1) and [1, 2) d;
* the figure ``first_layer_spin.png`` (the rough run: omega and half the vorticity against
  the distance from the moving wall at 0.25 d bins, first 3 d; ``docs/first_layer_spin.png``
  is a copy).

The Cosserat model is not fitted: phi = 19 deg, L = 5 d, A = 1/3, K = 1/2, the glued-grain
walls fully rough, the smooth walls at their measured delta (:data:`DELTA`), the run's B and
gap (docs/dem.md's design values).
"""

from __future__ import annotations

import argparse
import json
import math
import tempfile
from pathlib import Path
from typing import Any

import numpy as np

from cosserat.dem.analyse import (
    RunSamples,
    merge_bins,
    merge_empty_bins,
    read_samples,
    steady_profile,
)
from cosserat.dem.coarse import Samples, block_fields
from cosserat.dem.corpus import corpus_v2_cells
from cosserat.dem.decks import build_deck
from cosserat.dem.first_layer import (
    HALF_VORTICITIES,
    LAYER_SUMS,
    LayerSamples,
    first_layer,
    layer_measures,
    read_layers,
)

WIDTHS = (0.25, 0.5, 1.0)
"""Bin widths [d]."""


def load(folder: Path, cache: Path) -> tuple[RunSamples, LayerSamples]:
    """The run's fine-bin and layer samples, from the cache or (once) from the dumps."""
    name = folder.name
    path = cache / f"{name}.npz"
    if not path.is_file():
        deck = build_deck(corpus_v2_cells()[name])
        run = read_samples(folder, deck)
        layers = read_layers(folder, deck)
        cache.mkdir(parents=True, exist_ok=True)
        s = run.samples
        np.savez_compressed(
            path,
            steps=s.steps,
            sums=s.sums,
            edges=s.edges,
            bin_area=s.bin_area,
            flow=run.flow,
            gap=run.gap,
            wall_normal=run.wall_normal,
            wall_shear=run.wall_shear,
            wall_speed_measured=run.wall_speed_measured,
            n_free=run.n_free,
            layer_steps=layers.steps,
            layer_sums=layers.sums,
            layer_u_wall=layers.u_wall,
        )
    z = np.load(path)
    run = RunSamples(
        Samples(z["steps"], z["sums"], z["edges"], z["bin_area"]),
        z["flow"],
        z["gap"],
        z["wall_normal"],
        z["wall_shear"],
        z["wall_speed_measured"],
        int(z["n_free"]),
    )
    return run, LayerSamples(z["layer_steps"], z["layer_sums"], z["layer_u_wall"])


PHI_DEG, L_D = 19.0, 5.0
"""The Cosserat model's friction angle [deg] and material length [d] (docs/dem.md's design)."""
DELTA = {"glued-grains": "fully-rough", "smooth-frictional": None}
"""A wall's friction angle in the model by its kind; a smooth wall's from :data:`SMOOTH_DELTA`."""
SMOOTH_DELTA = {"plane_smooth_H10_qs": 13.9, "plane_layer_H10_qs": 12.0}
"""The smooth walls' measured friction angle [deg] (wall stress ratio 0.248 and 0.212,
docs/dem.md)."""
STENCILS = ("analysis", "wall", "wall-first")
"""The first bin's stencils (:data:`cosserat.studies.validate.forward.STENCILS`)."""
WALL_NAMES = ("lower", "upper")
SIGNIFICANT = 3.0
"""A sign is determined where |departure| >= this many standard errors."""


def sheared_walls(name: str) -> list[tuple[int, str]]:
    """(index, label) of the walls analysed: the moving (upper) wall, and the layer run's
    smooth fixed lower wall (where its band is)."""
    out = [(1, "moving (upper)")]
    if "layer" in name:
        out.append((0, "fixed smooth (lower)"))
    return out


def model_profile(name: str, meta: dict[str, Any]) -> Any:
    """The Cosserat profile at phi = 19 deg, L = 5 d on the run's cell (not fitted)."""
    from cosserat import solve
    from cosserat.model.build import make_problem

    walls = meta.get("walls") or {"lower": meta["wall"], "upper": meta["wall"]}
    delta = {k: DELTA[w["kind"]] or SMOOTH_DELTA[name] for k, w in walls.items()}
    values = {
        "eps": 1.0 / meta["gap_d"],
        "B": meta["B"],
        "nu": 1.0,
        "phi": PHI_DEG,
        "L": L_D,
        "delta": delta["upper"],
        "delta_lower": delta["lower"],
    }
    return solve(make_problem("cosserat", "plane", values)), values


def _layer_average(f: Any, x_of: Any, k: int) -> float:
    """Uniform average of ``f`` over the distances [k, k + 1) d from a wall."""
    t, w = np.polynomial.legendre.leggauss(24)
    d = k + 0.5 * (t + 1.0)
    return float(np.sum(w * np.asarray(f(x_of(d)), dtype=float)) / np.sum(w))


def model_layers(fields: Any, run: Any, wall: int, r_1: float) -> dict[str, float]:
    """:func:`layer_measures` of a model's fields: layers the uniform averages over [0, 1) and
    [1, 2) d from the wall, at their mid-distances 0.5 and 1.5 d."""
    from cosserat.studies.validate.forward import wall_velocities

    lower, upper = 0.0, run.gap_d
    x_of = (lambda d: lower + d) if wall == 0 else (lambda d: upper - d)
    u1, u2 = (_layer_average(fields.u, x_of, k) for k in (0, 1))
    om1 = _layer_average(fields.omega, x_of, 0)
    return layer_measures(WALL_NAMES[wall], wall_velocities(run)[wall], u1, u2, 0.5, 1.5, om1, r_1)


def bins_block_departure(
    run_samples: RunSamples,
    first: int,
    blocks: int,
    gap: float,
    width: float,
    anchor: str,
    run: Any,
    wall: int,
    stencil: str,
    V: float,
) -> tuple[float, float]:
    """The first bin's omega - half vorticity under ``stencil``, per block (so omega's and
    u's correlation is in the error): (mean, se) [V/d]."""
    from cosserat.studies.validate.forward import bin_edges, stencil_half, wall_velocities

    merged = merge_empty_bins(
        merge_bins(run_samples.samples, 0.0, gap, width, anchor), first, blocks
    )
    bins = bin_edges(run)
    k = 0 if wall == 0 else bins.centre.size - 1
    vals = []
    for f in block_fields(merged, first, blocks):
        u, om = f["u"] / V, f["omega"] / V
        half = stencil_half(bins, u, wall_velocities(run), stencil)
        vals.append(om[k] - half[k])
    v = np.array(vals)
    return float(v.mean()), float(v.std(ddof=1) / math.sqrt(v.size))


def analyse(folder: Path, cache: Path, out: Path) -> dict[str, Any]:
    """Everything of the module docstring for one run."""
    from cosserat.analysis.corpus import read_run
    from cosserat.studies.validate.forward import (
        bin_edges,
        forward_departure,
        measured_first_layer,
        model_fields,
        null_departure,
        turning_with_the_material,
    )

    name = folder.name
    meta = json.loads((folder / "profile.json").read_text())
    cell = corpus_v2_cells()[name]
    deck = build_deck(cell)
    run_samples, layers = load(folder, cache)
    first = int(np.flatnonzero(run_samples.samples.steps == meta["steady_window"][0])[0])
    blocks = int(meta["blocks"])
    V = cell.wall_speed
    gap = float(run_samples.gap[first:].mean())
    model, values = model_profile(name, meta)
    rec: dict[str, Any] = {
        "gap_d": gap,
        "steady_window": meta["steady_window"],
        "blocks": blocks,
        "model": values,
        "walls": {},
    }
    runs = {}
    keys = {(1.0, "lower")} | {(w, WALL_NAMES[k]) for k, _ in sheared_walls(name) for w in WIDTHS}
    with tempfile.TemporaryDirectory() as tmp:
        for w, anchor in sorted(keys):
            prof = steady_profile(
                run_samples,
                deck,
                lammps_version=meta["lammps_version"],
                first=first,
                blocks=blocks,
                bin_width=w,
                anchor=anchor,
            )
            csv, _ = prof.write(tmp, f"{name}_w{w:g}_{anchor}")
            runs[w, anchor] = read_run(csv)
            if (w, anchor) == (WIDTHS[0], "upper"):
                rec["profile_fine"] = {
                    k: [float(x) for x in prof.columns[k]]
                    for k in (
                        "y",
                        "u",
                        "u_se",
                        "omega",
                        "omega_se",
                        "half_vorticity",
                        "half_vorticity_se",
                    )
                }
    reference = runs[1.0, "lower"]  # the run's own profile's bins
    fields = model_fields(model, reference)
    null_fields = turning_with_the_material(fields)
    dist = np.linspace(0.0, 3.0, 121)
    y = reference.gap_d - dist
    omega_m = np.asarray(fields.omega(y), dtype=float)
    rec["model_curve"] = {
        "distance_d": dist.tolist(),
        "omega": omega_m.tolist(),
        "half_vorticity": (omega_m - np.asarray(fields.point_departure(y), dtype=float)).tolist(),
    }
    for wall, label in sheared_walls(name):
        rows = []
        mine = [(w, WALL_NAMES[wall]) for w in WIDTHS]
        for w, anchor in mine + ([(1.0, "lower")] if wall == 1 else []):
            run = runs[w, anchor]
            bins = bin_edges(run)
            row_k = int(bins.order[0] if wall == 0 else bins.order[-1])
            rho = float((run.meta.get("bin_correlation") or {}).get("u") or 0.0)
            for st in STENCILS:
                dep, se_half, se_om = measured_first_layer(run, wall, st, rho)
                bdep, bse = bins_block_departure(
                    run_samples, first, blocks, gap, w, anchor, run, wall, st, V
                )
                rows.append(
                    {
                        "measure": f"{w:g} d bins from the {anchor} wall, {st}",
                        "distance_d": float(abs(bins.walls[wall] - bins.centre[-wall])),
                        "departure": dep,
                        "se_quadrature": math.hypot(se_half, se_om),
                        "departure_blocks": bdep,
                        "se": bse,
                        "cosserat": float(forward_departure(model, run, st)[row_k]),
                        "null": float(null_departure(model, run, st)[row_k]),
                    }
                )
        data = first_layer(layers, first, blocks, WALL_NAMES[wall], V)
        kept = layers.sums[first:, wall, 0]
        r_1 = float(
            kept[:, LAYER_SUMS.index("radius")].sum() / kept[:, LAYER_SUMS.index("count")].sum()
        )
        mod = model_layers(fields, reference, wall, r_1)
        nul = model_layers(null_fields, reference, wall, r_1)
        for wname in HALF_VORTICITIES:
            m, se = data[f"departure_{wname}"]
            rows.append(
                {
                    "measure": f"grains, {wname}",
                    "distance_d": data["d_1"][0],
                    "departure": m,
                    "se": se,
                    "departure_blocks": m,
                    "se_quadrature": None,
                    "cosserat": mod[f"departure_{wname}"],
                    "null": nul[f"departure_{wname}"],
                }
            )
        for r in rows:
            z = r["departure_blocks"] / r["se"] if r["se"] > 0 else math.inf
            r["z"] = z
            r["sign"] = ("+" if z > 0 else "-") if abs(z) >= SIGNIFICANT else "undetermined"
        rec["walls"][label] = {
            "rows": rows,
            "grains": data,
            "cosserat_grains": mod,
            "null_grains": nul,
        }
    return rec


def print_table(name: str, rec: dict[str, Any]) -> None:
    print(
        f"\n## {name} (gap {rec['gap_d']:.3f} d, steady {rec['steady_window']}, "
        f"{rec['blocks']} blocks)"
    )
    for label, wall in rec["walls"].items():
        g = wall["grains"]
        print(
            f"\n{label}: layer 1 at {g['d_1'][0]:.3f} d, layer 2 at {g['d_2'][0]:.3f} d; "
            f"u_wall {g['u_wall'][0]:.4f}, u_1 {g['u_1'][0]:.4f} +- {g['u_1'][1]:.4f}, "
            f"u_2 {g['u_2'][0]:.4f} +- {g['u_2'][1]:.4f}, omega_1 {g['omega_1'][0]:+.4f} "
            f"+- {g['omega_1'][1]:.4f} V/d, rolling {g['rolling'][0]:.3f} +- "
            f"{g['rolling'][1]:.3f}"
        )
        print(
            "| measure | first bin / layer at [d] | departure [V/d] | se (blocks) | "
            "se (quadrature) | sign | Cosserat | null |"
        )
        print("|---|---|---|---|---|---|---|---|")
        for r in wall["rows"]:
            q = "" if r["se_quadrature"] is None else f"{r['se_quadrature']:.3f}"
            print(
                f"| {r['measure']} | {r['distance_d']:.3f} | {r['departure_blocks']:+.3f} | "
                f"{r['se']:.3f} | {q} | {r['sign']} | {r['cosserat']:+.3f} | "
                f"{r['null']:+.3f} |"
            )


def figure(rec: dict[str, Any], path: Path) -> None:
    """omega and half the vorticity against the distance from the moving wall at 0.25 d bins
    (the rough run), first 3 d, with the grain-level layer values and the 1 d bins."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    p = {k: np.asarray(v) for k, v in rec["profile_fine"].items()}
    dist = rec["gap_d"] - p["y"]
    keep = dist <= 3.0
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    ax.errorbar(
        dist[keep],
        p["omega"][keep],
        2 * p["omega_se"][keep],
        fmt="o-",
        ms=4,
        color="C0",
        label="spin omega, 0.25 d bins",
    )
    ax.errorbar(
        dist[keep],
        p["half_vorticity"][keep],
        2 * p["half_vorticity_se"][keep],
        fmt="s--",
        ms=4,
        color="C1",
        label="half vorticity (np.gradient), 0.25 d bins",
    )
    g = rec["walls"]["moving (upper)"]["grains"]
    d1, d2 = g["d_1"][0], g["d_2"][0]
    ax.errorbar(
        [d1],
        [g["omega_1"][0]],
        [2 * g["omega_1"][1]],
        fmt="*",
        ms=12,
        color="C0",
        mec="k",
        label="layer 1's mean spin (grains)",
    )
    for key, x, mk, text in (
        ("W_layers", 0.5 * (d1 + d2), "D", "layer 1 to 2"),
        ("W_wall_second", 0.5 * d2, "v", "wall to layer 2"),
        ("W_wall_first", 0.5 * d1, "^", "wall to layer 1"),
    ):
        ax.errorbar(
            [x],
            [g[key][0]],
            [2 * g[key][1]],
            fmt=mk,
            ms=8,
            color="C1",
            mec="k",
            label=f"half vorticity, {text} (grains)",
        )
    m = {k: np.asarray(v) for k, v in rec["model_curve"].items()}
    ax.plot(
        m["distance_d"],
        m["omega"],
        "-",
        color="C0",
        lw=0.8,
        alpha=0.6,
        label="Cosserat (phi 19 deg, L 5 d), point omega",
    )
    ax.plot(
        m["distance_d"],
        m["half_vorticity"],
        "--",
        color="C1",
        lw=0.8,
        alpha=0.6,
        label="Cosserat, point half vorticity",
    )
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_xlim(0.0, 3.0)
    ax.set_xlabel("distance of the grain centres / bin centre from the moving wall [d]")
    ax.set_ylabel("[V/d]")
    ax.set_title(
        "plane_rough_H10_qs, moving wall: spin and half vorticity (error bars 2 se)", fontsize=9
    )
    ax.legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folders", nargs="+", type=Path)
    ap.add_argument("--cache", type=Path, required=True)
    ap.add_argument("--out", type=Path)
    ap.add_argument("--read-only", action="store_true", help="fill the cache and stop")
    args = ap.parse_args(argv)
    for folder in args.folders:
        load(folder, args.cache)
        print(f"{folder.name}: cached", flush=True)
    if args.read_only:
        return 0
    out = args.out or Path(".")
    out.mkdir(parents=True, exist_ok=True)
    result = {}
    for folder in args.folders:
        rec = analyse(folder, args.cache, out)
        print_table(folder.name, rec)
        result[folder.name] = rec
        if folder.name == "plane_rough_H10_qs":
            figure(rec, out / "first_layer_spin.png")
    (out / "first_layer_spin.json").write_text(json.dumps(result, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
