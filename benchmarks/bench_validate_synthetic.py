"""``validate`` on larger synthetic corpora with known answers: the version of
``tests/test_validate_synthetic.py`` too slow for the test suite (issue 18, "How it is shown").

For each model that makes the data (cosserat, mui, ngf): plane shear under gravity (B = 1) with
rough and smooth walls at H/d = 20, 40, 80, 160 and Couette at R_i/H = 1, H/d = 20, 40, 80,
realistic noise (u_se = 0.03 (0.03 + sqrt(u)), rho = 0.4, several seeds), every model fitted
(``--models`` to restrict). Prints one JSON object: per model and seed, each claim's verdict,
each series' slope with the Cosserat fits' own, and the seconds.

Run: ``python benchmarks/bench_validate_synthetic.py [--seeds N] [--noise X] [--models a,b]``.
"""

from __future__ import annotations

import argparse
import json
import os
import tempfile
import time
from pathlib import Path


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=2, help="corpora per model")
    parser.add_argument("--noise", type=float, default=0.03, help="u's error where u = 1")
    parser.add_argument("--models", default=None, help="models fitted (default: every one)")
    parser.add_argument("--makers", default="cosserat,mui,ngf", help="models making the data")
    args = parser.parse_args()

    from cosserat.studies.validate import validate
    from cosserat.studies.validate.synthetic import synthetic_corpus

    fitted = None if args.models is None else args.models.split(",")
    out: dict[str, list[dict[str, object]]] = {}
    with tempfile.TemporaryDirectory() as tmp:
        for maker in args.makers.split(","):
            params = (
                {"rough": {"delta": "fully-rough"}, "smooth": {"delta": 15.0}}
                if maker == "cosserat"
                else None
            )
            for seed in range(args.seeds):
                folder = Path(tmp) / f"{maker}_{seed}"
                start = time.perf_counter()
                synthetic_corpus(folder, maker,
                                 plane={"rough": (20.0, 40.0, 80.0, 160.0),
                                        "smooth": (20.0, 40.0, 80.0, 160.0)},
                                 couette=(20.0, 40.0, 80.0), parameters=params,
                                 noise=args.noise, seed=1000 * seed)  # fmt: skip
                report = validate(folder, models=fitted)
                out.setdefault(maker, []).append(
                    {
                        "seed": 1000 * seed,
                        "verdicts": {v.key: v.verdict for v in report.verdicts},
                        "series": {
                            g.key: {
                                "slope": None if g.slope is None else round(g.slope.slope, 3),
                                "stderr": None if g.slope is None else round(g.slope.stderr, 3),
                                "cosserat_fits": None
                                if g.model_slopes.get("cosserat") is None
                                else round(g.model_slopes["cosserat"].slope, 3),
                            }
                            for g in report.groups
                        },
                        "seconds": round(time.perf_counter() - start, 1),
                    }
                )
    print(json.dumps({"results": out, "load_average": os.getloadavg()}, indent=1))


if __name__ == "__main__":
    main()
