"""Stored reference values from cosserat v0.1.0 (commit a3288e4), to test a new solver core against.

What it computes
----------------
For a fixed list of plane-shear and Couette problems (``CASES`` below: the paper's material,
phi = 28.5 deg with the v0.1.0 defaults L = 10, A = 1/3; walls with K = 0.5), each solved by
v0.1.0's default numerical route at ``rtol = 1e-10`` through the public API
(``solve(problem, rtol=1e-10)``, residual and boundary checks on), it records

* ``Delta``: the shear-layer thickness, ``shear_layer_thickness(profile)`` (f = 0.05);
* ``wall_slip`` and ``wall_omega``: ``wall_slip(profile)``, ``wall_omega(profile)``;
* ``wall_stress``: sigma_yx (sigma_r_theta) at the slipping wall,
  ``profile.evaluate([profile.slip_wall]).sigma_yx[0]``;
* ``m_inner``: m(0) of the Couette shooting, ``profile.diagnostics.stats["m_inner"]``
  (null for plane shear);
* ``u``, ``omega``, ``m`` at xi = 0, 0.001, 0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 1
  (``profile.evaluate(xi)``, the dense evaluator, not the output grid);
* for information, the profile's ODE residuals and boundary-condition errors as v0.1.0
  reports them, and for plane shear which wall slips (``case``).

A case for which v0.1.0 raises ``NoSolutionError`` is kept, with ``status = "no-solution"``,
its message, and nulls for the values; any other ``CosseratError`` would be kept the same way
with ``status = "error"`` (none is expected).

JSON layout::

    {"generated_by": ..., "commit": "a3288e4", "rtol": 1e-10, "xi": [...],
     "cases": [{"name": ..., "geometry": "plane" | "couette",
                "parameters": {every constructor argument; a fully rough wall's delta is
                               the string "rough"},
                "status": "ok" | "no-solution", "message": ...,
                "Delta": ..., "wall_slip": ..., "wall_omega": ..., "wall_stress": ...,
                "m_inner": ..., "xi": [...], "u": [...], "omega": [...], "m": [...], ...}]}

``parameters`` of a plane case: ``{"material": {"phi", "L", "A"}, "upper": {"delta", "K"},
"lower": {"delta", "K"}, "eps", "B", "nu", "m_fixed_wall"}`` (the lower wall written out even
when it is the default copy of the upper one); of a Couette case: ``{"material": {...},
"wall": {"delta", "K"}, "eps", "Ri"}``. Floats are written with ``repr`` precision, so they
read back bit for bit.

How to run
----------
Against the *old* code only, from a separate checkout of v0.1.0 put first on the path::

    git worktree add --detach /work/v010 a3288e4
    PYTHONPATH=/path/to/v0.1.0/src python benchmarks/make_v010_reference.py \\
        --out tests/data/v010_reference.json

It refuses to run unless the imported ``cosserat`` is the old code. ``cosserat.__version__``
cannot tell (the rewritten package also says "0.1.0" until the version is bumped), so the test
is that ``cosserat.solvers.radau_scalar`` (v0.1.0's pure-Python scalar Radau integrator, gone in
the compiled core) is importable. When the imported source sits in a git checkout, its HEAD
must also be a3288e4. Takes a few seconds (37 cases, ~1.5 s of solving).
"""

from __future__ import annotations

import argparse
import importlib
import json
import platform
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

from cosserat import Cosserat, Couette, Plane, Problem

COMMIT = "a3288e4"
RTOL = 1e-10
XI = [0.0, 0.001, 0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 1.0]
PHI = 28.5
K = 0.5
ROUGH = "rough"  # how a fully rough wall's delta is written in the JSON

EPS_PLANE = [0.04, 1e-2, 1e-3, 1e-4, 1e-6]
EPS_ROUGH_PLANE = [0.04, 1e-2, 1e-3, 1e-4]
EPS_COUETTE = [0.04, 1e-2, 1e-3, 1e-4, 1e-6]
EPS_COUETTE_RI = [0.04, 1e-3]
EPS_COUETTE_ROUGH = [0.04, 1e-2, 1e-3]


def require_v010() -> Any:
    """Import cosserat and make sure it is v0.1.0's code (module docstring), or exit."""
    import cosserat

    where = Path(cosserat.__file__).resolve().parent
    try:
        importlib.import_module("cosserat.solvers.radau_scalar")
    except ImportError:
        sys.exit(
            f"refusing to run: the imported cosserat ({where}) has no cosserat.solvers."
            f"radau_scalar, so it is not v0.1.0's code (its __version__ = "
            f"{getattr(cosserat, '__version__', '?')!r} does not tell). Put a v0.1.0 checkout "
            f"first on the path: PYTHONPATH=/path/to/v0.1.0/src python {sys.argv[0]} ..."
        )
    if getattr(cosserat, "__version__", None) != "0.1.0":
        sys.exit(f"refusing to run: cosserat.__version__ = {cosserat.__version__!r}, not 0.1.0")
    head = source_commit(where)
    if head is not None and not head.startswith(COMMIT):
        sys.exit(
            f"refusing to run: the imported cosserat ({where}) is a git checkout at {head}, "
            f"not {COMMIT} (v0.1.0)"
        )
    return cosserat


def source_commit(where: Path) -> str | None:
    """HEAD of the git checkout holding ``where`` and whether it is clean, or None."""
    try:
        head = subprocess.run(
            ["git", "-C", str(where), "rev-parse", "HEAD"],
            capture_output=True,
            text=True,
            check=True,
        ).stdout.strip()
        dirty = subprocess.run(
            ["git", "-C", str(where), "status", "--porcelain", "--", "."],
            capture_output=True,
            text=True,
            check=True,
        ).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return None
    return head + (" (modified)" if dirty else "")


# --------------------------------------------------------------------------- the cases
def wall(delta: float | str, k: float = K) -> dict[str, Any]:
    return {"delta": delta, "K": k}


def material() -> dict[str, Any]:
    """phi = 28.5 deg with v0.1.0's defaults for L and A, written out (read from the code)."""
    from cosserat import Material

    m = Material(phi=PHI)
    return {"phi": m.phi, "L": m.L, "A": m.A}


def plane(
    name: str, eps: float, upper: dict, lower: dict, B: float = 0.0, nu: float = 1.0, **kw: Any
) -> dict[str, Any]:
    params = {"material": material(), "upper": upper, "lower": lower, "eps": eps, "B": B, "nu": nu}
    params["m_fixed_wall"] = kw.get("m_fixed_wall")
    return {"name": name, "geometry": "plane", "parameters": params}


def couette(name: str, eps: float, w: dict, Ri: float) -> dict[str, Any]:
    params = {"material": material(), "wall": w, "eps": eps, "Ri": Ri}
    return {"name": name, "geometry": "couette", "parameters": params}


def cases() -> list[dict[str, Any]]:
    out = []
    for e in EPS_PLANE:
        out.append(plane(f"plane-symmetric-delta20-eps{e:g}", e, wall(20.0), wall(20.0)))
    for e in EPS_PLANE:
        out.append(plane(f"plane-upper20-lower-rough-eps{e:g}", e, wall(20.0), wall(ROUGH)))
    for e in EPS_PLANE:
        out.append(
            plane(f"plane-gravity-B1-delta20-eps{e:g}", e, wall(20.0), wall(20.0), B=1.0, nu=1.0)
        )
    for e in EPS_PLANE:
        out.append(
            plane(
                f"plane-layer-at-lower-upper25-lower20-B0.2-eps{e:g}",
                e,
                wall(25.0),
                wall(20.0),
                B=0.2,
            )
        )
    for e in EPS_ROUGH_PLANE:
        out.append(plane(f"plane-both-rough-B1-eps{e:g}", e, wall(ROUGH), wall(ROUGH), B=1.0))
    for e in EPS_COUETTE:
        out.append(couette(f"couette-delta20-Ri1-eps{e:g}", e, wall(20.0), 1.0))
    for Ri in (0.5, 10.0):
        for e in EPS_COUETTE_RI:
            out.append(couette(f"couette-delta20-Ri{Ri:g}-eps{e:g}", e, wall(20.0), Ri))
    for e in EPS_COUETTE_ROUGH:
        out.append(couette(f"couette-rough-Ri1-eps{e:g}", e, wall(ROUGH), 1.0))
    out.append(m_fixed_wall_case())
    return out


def m_fixed_wall_case() -> dict[str, Any]:
    """Upper delta 20, lower fully rough, eps 1e-2, m at the fixed (lower) wall = bound / 2.

    v0.1.0 (``problems/plane.py``, ``PlaneShear._validate_m_fixed_wall``) admits
    ``0 <= m_fixed_wall <= b`` with the layer at the upper wall, b =
    ``problem.equations.couple_stress_bound(fixed_wall)`` (where the radicand of
    eqn-nd_sigxy vanishes).
    """
    case = plane(
        "plane-upper20-lower-rough-m-fixed-half-bound-eps0.01", 1e-2, wall(20.0), wall(ROUGH)
    )
    problem = build(case)
    assert problem.equations.fixed_wall == 0.0, problem.equations.case
    case["parameters"]["m_fixed_wall"] = 0.5 * problem.equations.couple_stress_bound(
        problem.equations.fixed_wall
    )
    return case


def build(case: dict[str, Any]) -> Any:
    """The v0.1.0 problem of a case record."""
    from cosserat import FULLY_ROUGH, Material, Wall

    p = case["parameters"]

    def make_wall(w: dict[str, Any]) -> Wall:
        return Wall(delta=FULLY_ROUGH if w["delta"] == ROUGH else w["delta"], K=w["K"])

    mat = Material(**p["material"])
    if case["geometry"] == "plane":
        return Problem(
            Plane(eps=p["eps"], B=p["B"], nu=p["nu"]),
            Cosserat(
                material=mat,
                wall=make_wall(p["upper"]),
                lower=make_wall(p["lower"]),
                m_fixed_wall=p["m_fixed_wall"],
            ),
        )
    return Problem(
        Couette(eps=p["eps"], Ri=p["Ri"]), Cosserat(material=mat, wall=make_wall(p["wall"]))
    )


# --------------------------------------------------------------------------- solving
def floats(values: Any) -> list[float]:
    return [float(v) for v in values]


def run_case(case: dict[str, Any]) -> dict[str, Any]:
    from cosserat import (
        CosseratError,
        NoSolutionError,
        shear_layer_thickness,
        solve,
        wall_omega,
        wall_slip,
    )

    problem = build(case)
    record = dict(case)
    if case["geometry"] == "plane":
        record["case"] = problem.equations.case.value
    empty = dict.fromkeys(
        ["Delta", "wall_slip", "wall_omega", "wall_stress", "m_inner", "u", "omega", "m"]
    )
    try:
        profile = solve(problem, rtol=RTOL)
    except NoSolutionError as exc:
        return record | {"status": "no-solution", "message": str(exc)} | empty | {"xi": XI}
    except CosseratError as exc:
        return (
            record
            | {"status": "error", "message": f"{type(exc).__name__}: {exc}"}
            | empty
            | {"xi": XI}
        )
    fields = profile.evaluate(XI)
    stats = profile.diagnostics.stats
    return record | {
        "status": "ok",
        "message": profile.diagnostics.message,
        "Delta": float(shear_layer_thickness(profile)),
        "wall_slip": float(wall_slip(profile)),
        "wall_omega": float(wall_omega(profile)),
        "wall_stress": float(profile.evaluate([profile.slip_wall]).sigma_yx[0]),
        "m_inner": float(stats["m_inner"]) if case["geometry"] == "couette" else None,
        "xi": XI,
        "u": floats(fields.u),
        "omega": floats(fields.omega),
        "m": floats(fields.m),
        "residuals": {k: float(v) for k, v in profile.diagnostics.residuals.items()},
        "bc_errors": {k: float(v) for k, v in profile.diagnostics.bc_errors.items()},
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", required=True, help="JSON file to write")
    args = parser.parse_args()
    cosserat = require_v010()
    import numpy
    import scipy

    where = Path(cosserat.__file__).resolve().parent
    print(f"cosserat {cosserat.__version__} from {where} (git: {source_commit(where)})")
    t_all = time.perf_counter()
    results = []
    for case in cases():
        t = time.perf_counter()
        rec = run_case(case)
        dt = time.perf_counter() - t
        results.append(rec)
        shown = f"Delta = {rec['Delta']:.10g}" if rec["status"] == "ok" else rec["message"][:70]
        print(f"  {rec['name']:55s} {rec['status']:11s} {dt:6.2f} s  {shown}")
    elapsed = time.perf_counter() - t_all
    document = {
        "generated_by": (
            f"benchmarks/make_v010_reference.py with cosserat {cosserat.__version__} "
            f"(solve(problem, rtol={RTOL:g}), default numerical route); Python "
            f"{platform.python_version()}, NumPy {numpy.__version__}, SciPy {scipy.__version__}"
        ),
        "commit": COMMIT,
        "rtol": RTOL,
        "xi": XI,
        "cases": results,
    }
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(document, indent=1, allow_nan=False) + "\n")
    status = [r["status"] for r in results]
    counts = ", ".join(f"{status.count(s)} {s}" for s in sorted(set(status)))
    print(f"{len(results)} cases ({counts}) in {elapsed:.1f} s -> {out}")


if __name__ == "__main__":
    main()
