"""Calibration benchmarks (issue 17): interval coverage over noisy replicas, and speed.

    python benchmarks/bench_calibration.py coverage [--replicas 200] [--models cosserat,mui,ngf]
    python benchmarks/bench_calibration.py speed

``coverage``: for each model, ``replicas`` synthetic data sets of three runs (plane shear
under gravity at H = 20 and 40 d, a Couette cell at H = 20 d, R_i = 20 d; bins one grain
wide; AR(1) noise with rho = 0.5 on u and 0.2 on the spin) made by the model at known
parameters; each is calibrated jointly and the fraction of replicas whose 68% interval
(value +- stderr) covers the truth is counted per parameter. Nominal: 0.683; with 200
replicas the binomial 2-sigma band is 0.617-0.749; the 95% coverage and the mean pull
(value - truth)/stderr are given too. Results are appended, one JSON line per replica, to
``benchmarks/results/coverage_<model>.jsonl`` (a rerun continues where it stopped), and
summarised at the end as one JSON list.

``speed``: a 10^4-sample joint posterior of the Cosserat model over the same three runs on
one core, the time of one likelihood evaluation, and the evidence (nested sampling).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

import numpy as np

from cosserat.calibration.joint import calibrate_model
from cosserat.calibration.models import Model
from cosserat.calibration.synthetic import make_runs

TRUTH = {
    "cosserat": {"phi": 20.0, "L": 8.0, "roughness[rough]": 0.8, "K[rough]": 0.6},
    "mui": {"mu_s": 0.3, "I_0": 0.3},
    "ngf": {"mu_s": 0.3, "b": 1.0, "A": 0.5},
}
RHO = {"u": 0.5, "omega": 0.2}
RESULTS = Path(__file__).parent / "results"


def coverage(model: str, replicas: int) -> dict:
    RESULTS.mkdir(exist_ok=True)
    path = RESULTS / f"coverage_{model}.jsonl"
    done = [json.loads(line) for line in path.read_text().splitlines()] if path.exists() else []
    m = Model(model)
    with path.open("a") as fh:
        for seed in range(len(done), replicas):
            t0 = time.perf_counter()
            runs = make_runs(m, TRUTH[model], rho=RHO, seed=1000 + seed)
            mc = calibrate_model(m, runs, seed=seed)
            row = {"seed": 1000 + seed, "ok": mc.ok, "chi2": mc.chi2, "dof": mc.dof,
                   "seconds": time.perf_counter() - t0, "parameters": {}}  # fmt: skip
            for name, value in TRUTH[model].items():
                e = mc.parameters.get(name) if mc.ok else None
                row["parameters"][name] = None if e is None else {
                    "value": e.value, "stderr": e.stderr, "truth": value}  # fmt: skip
            fh.write(json.dumps(row) + "\n")
            fh.flush()
            done.append(row)
            print(f"{model} {seed + 1}/{replicas} {row['seconds']:.1f}s", file=sys.stderr)
    summary = {
        "model": model,
        "replicas": len(done),
        "failed": sum(not r["ok"] for r in done),
        "layout": "plane H = 20 and 40 d (B = 1), Couette H = 20 d (R_i = 20 d); one wall kind; "
        "bins 1 d; se u 0.01, omega 0.01, stress ratio 0.005",
        "noise": f"AR(1), rho {RHO} (given to the calibration, not estimated)",
    }
    for name in TRUTH[model]:
        hits, hits95, bias, n, undefined = 0, 0, [], 0, 0
        for r in done:
            p = r["parameters"].get(name)
            if p is None or p["stderr"] is None:
                undefined += 1
                continue
            n += 1
            hits += abs(p["value"] - p["truth"]) <= p["stderr"]
            hits95 += abs(p["value"] - p["truth"]) <= 1.959964 * p["stderr"]
            bias.append((p["value"] - p["truth"]) / p["stderr"])
        summary[name] = {
            "truth": TRUTH[model][name],
            "coverage_68": hits / n if n else None,
            "coverage_95": hits95 / n if n else None,
            "mean_pull": float(np.mean(bias)) if bias else None,
            "n": n,
            "no_stderr": undefined,
        }
    chi2 = [r["chi2"] / r["dof"] for r in done if r["ok"]]
    summary["reduced_chi2_mean"] = float(np.mean(chi2)) if chi2 else None
    summary["seconds_per_replica"] = float(np.mean([r["seconds"] for r in done]))
    return summary


def speed() -> dict:
    from cosserat.calibration.posterior import run_sampler

    m = Model("cosserat")
    runs = make_runs(m, TRUTH["cosserat"], rho=RHO, seed=7)
    mc = calibrate_model(m, runs)
    s, opt = mc.internal
    theta = opt.theta
    s.log_likelihood(theta)
    t0 = time.perf_counter()
    n = 200
    for _ in range(n):
        s.log_likelihood(theta)
    per_eval = (time.perf_counter() - t0) / n
    t0 = time.perf_counter()
    sampler, burn = run_sampler(s, opt, mc.covariance, 10_000, seed=0)
    seconds = time.perf_counter() - t0
    draws = sampler.get_chain(discard=burn).shape
    return {
        "likelihood_ms": per_eval * 1e3,
        "posterior_1e4_seconds": seconds,
        "posterior_draws_retained": int(draws[0] * draws[1]),
        "posterior_evaluations": int(sampler.iteration * sampler.nwalkers),
        "cpu_count_used": 1,
        "load_average": os.getloadavg()[0],
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("what", choices=("coverage", "speed"))
    ap.add_argument("--replicas", type=int, default=200)
    ap.add_argument("--models", default="cosserat,mui,ngf")
    args = ap.parse_args()
    if args.what == "speed":
        print(json.dumps(speed(), indent=1))
        return
    print(json.dumps([coverage(m, args.replicas) for m in args.models.split(",")], indent=1))


if __name__ == "__main__":
    main()
