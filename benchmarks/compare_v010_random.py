"""Status and Delta of 400 random problems, new core against v0.1.0 (an independent check).

Run it twice, once per version, then compare::

    PYTHONPATH=/work/v010/src python benchmarks/compare_v010_random.py old.json
    python benchmarks/compare_v010_random.py new.json
    python benchmarks/compare_v010_random.py --compare old.json new.json

Problems: 35 % Couette (Ri log-uniform in [1e-2, 1e3]), the rest plane shear (half with gravity,
B log-uniform in [1e-2, 1e2]; half with a different lower wall), eps log-uniform in
[1e-6, 0.3], delta in [3, 25.5] deg, K in [0, 1.5]; phi = 28.5 deg; seed 7; rtol 1e-8.
Measured 2026-11-23: the same status for all 400 (371 solved, 29 without a real solution);
Delta differs by at most 1.5e-6 relative (median 3e-13).
"""

from __future__ import annotations

import collections
import json
import sys

import numpy as np

from cosserat import Cosserat, Couette, Plane, Problem


def run(path: str) -> None:
    from cosserat import (
        CosseratError,
        Material,
        Wall,
        shear_layer_thickness,
        solve,
        wall_slip,
    )

    rng = np.random.default_rng(7)
    out = []
    for _ in range(400):
        eps = float(10 ** rng.uniform(-6, -0.5))
        d = float(rng.uniform(3, 25.5))
        K = float(rng.uniform(0, 1.5))
        if rng.random() < 0.35:
            Ri = float(10 ** rng.uniform(-2, 3))
            p = Problem(Couette(eps=eps, Ri=Ri), Cosserat(material=Material(28.5), wall=Wall(d, K)))
        else:
            B = float(10 ** rng.uniform(-2, 2)) if rng.random() < 0.5 else 0.0
            dl = float(rng.uniform(3, 25.5)) if rng.random() < 0.5 else None
            lower = None if dl is None else Wall(dl, K)
            p = Problem(
                Plane(eps=eps, B=B), Cosserat(material=Material(28.5), wall=Wall(d, K), lower=lower)
            )
        try:
            pr = solve(p, check=False, points=3)
            out.append(["ok", shear_layer_thickness(pr), wall_slip(pr)])
        except CosseratError as e:
            out.append([type(e).__name__, None, None])
    with open(path, "w") as fh:
        json.dump(out, fh)


def compare(old_path: str, new_path: str) -> None:
    with open(old_path) as fh:
        old = json.load(fh)
    with open(new_path) as fh:
        new = json.load(fh)
    print(collections.Counter((a[0], b[0]) for a, b in zip(old, new, strict=True)))
    errs = [
        abs(a[1] - b[1]) / abs(a[1]) for a, b in zip(old, new, strict=True) if a[0] == b[0] == "ok"
    ]
    print(f"Delta: max relative difference {max(errs):.2e}, median {np.median(errs):.2e}")


if __name__ == "__main__":
    if sys.argv[1] == "--compare":
        compare(sys.argv[2], sys.argv[3])
    else:
        run(sys.argv[1])
