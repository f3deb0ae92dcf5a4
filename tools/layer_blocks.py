"""Is the layer run's band stationary? a and the wall slip per time block (referee 5, requests
4 and 1 of V1; docs/dem.md, "The layer position").

    PYTHONPATH=src python tools/layer_blocks.py RUN_FOLDER [--json OUT]

RUN_FOLDER is a finished run of the layer cell with its dumps (``atoms.dump``,
``contacts.dump``, kept with ``--keep-dumps``; read only), e.g.
``/work/dem_runs/plane_layer_H10_qs``. The cell is corpus v2's ``plane_layer_H10_qs``
(:func:`cosserat.dem.corpus.corpus_v2_cells`). Printed, over the steady window (MSER-5, as the
run's own profile): for 2, 4 and 10 contiguous blocks, each block's u/V in the 1 d bins,
``f_fixed``, ``f_moving`` and ``a`` (:func:`cosserat.studies.validate.layer.jump_fractions`),
the first layer's speed (grain centres 0.25-0.5 d from the smooth wall, in 0.25 d bins: the
slip on that wall) and the mean bulk speed; the split-half difference of ``a`` in standard
errors from the blocks' spread within each half (10 blocks, 5 a half); a histogram of the bulk
speed over 0.5M-step windows (a stick-slip mixture would be bimodal); and the standard error
of the mean bulk speed against the block length (blocking: where it levels off, the blocks
are longer than the correlation time).
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path
from typing import Any

import numpy as np

from cosserat.dem.analyse import merge_bins, read_samples, steady_start
from cosserat.dem.coarse import block_fields
from cosserat.dem.corpus import corpus_v2_cells
from cosserat.dem.decks import build_deck
from cosserat.studies.validate.layer import jump_fractions

CELL = "plane_layer_H10_qs"
"""The layer cell of corpus v2."""


def analyse(folder: str | Path) -> dict[str, Any]:
    """The per-block numbers of the module docstring, as plain numbers."""
    cell = corpus_v2_cells()[CELL]
    run = read_samples(folder, build_deck(cell))
    first = steady_start(run)
    gap = float(run.gap[first:].mean())
    V = cell.wall_speed
    bins = merge_bins(run.samples, 0.0, gap)
    s = bins.centres.copy()
    s[0], s[-1] = 0.5 * bins.edges[1], 0.5 * (bins.edges[-2] + gap)
    fine = merge_bins(run.samples, 0.0, gap, width=0.25)
    n = run.samples.sums.shape[0] - first
    out: dict[str, Any] = {"steady_from_step": int(run.samples.steps[first]), "gap_d": gap}
    for nb in (2, 4, 10):
        bounds = first + (np.arange(nb + 1) * n) // nb
        rows = []
        for k, (f, g) in enumerate(
            zip(block_fields(bins, first, nb), block_fields(fine, first, nb), strict=True)
        ):
            u = f["u"] / V
            ff, _, fm, _ = jump_fractions(gap - s, u, np.full(u.size, 0.01), gap)
            rows.append(
                {
                    "steps": [
                        int(run.samples.steps[bounds[k]]),
                        int(run.samples.steps[bounds[k + 1] - 1]),
                    ],
                    "u": [round(float(x), 4) for x in u],
                    "f_fixed": ff,
                    "f_moving": fm,
                    "a": ff - fm,
                    "first_layer_speed": float(g["u"][1] / V),
                    "bulk_speed": float(run.flow[bounds[k] : bounds[k + 1]].mean() / V),
                }
            )
        out[f"blocks_{nb}"] = rows
    a10 = np.array([r["a"] for r in out["blocks_10"]])
    h1, h2 = a10[:5], a10[5:]
    se = math.sqrt(h1.var(ddof=1) / 5 + h2.var(ddof=1) / 5)
    out["split_half"] = {
        "a_first": h1.mean(),
        "a_second": h2.mean(),
        "z": (h2.mean() - h1.mean()) / se,
    }
    flow = run.flow[first:] / V
    w = 50  # samples of 10k steps: 0.5M steps
    means = flow[: (flow.size // w) * w].reshape(-1, w).mean(axis=1)
    counts, edges = np.histogram(means, bins=8)
    out["bulk_speed_0p5M"] = {
        "counts": counts.tolist(),
        "edges": [round(float(e), 3) for e in edges],
    }
    out["blocking"] = {
        int(b): float(
            flow[: (flow.size // b) * b].reshape(-1, b).mean(1).std(ddof=1)
            / math.sqrt(flow.size // b)
        )
        for b in (1, 10, 50, 100, 189)
    }
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder")
    parser.add_argument("--json", help="write the numbers here as JSON")
    args = parser.parse_args()
    out = analyse(args.folder)
    for nb in (2, 4, 10):
        print(f"{nb} blocks:")
        for r in out[f"blocks_{nb}"]:
            print(
                f"  steps {r['steps'][0]}-{r['steps'][1]}: a = {r['a']:+.3f} (f_fixed "
                f"{r['f_fixed']:.3f}, f_moving {r['f_moving']:.3f}), first layer "
                f"{r['first_layer_speed']:.3f} V, bulk {r['bulk_speed']:.3f} V"
            )
    h = out["split_half"]
    print(
        f"split half (10 blocks): a = {h['a_first']:.3f} then {h['a_second']:.3f}, "
        f"z = {h['z']:+.2f}"
    )
    b = out["bulk_speed_0p5M"]
    print(
        f"bulk speed over 0.5M steps: counts {b['counts']} between {b['edges'][0]} and "
        f"{b['edges'][-1]} V"
    )
    print(
        "blocking, se of the mean bulk speed [V] by block length [10k-step samples]:",
        out["blocking"],
    )
    if args.json:
        Path(args.json).write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
