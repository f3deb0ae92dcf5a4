"""The numbers quoted in the closing notes, recomputed: ``python examples/verification.py``.

1. max |numerical - closed form| for m, u, omega (no gravity; identical and rougher-lower walls;
   delta = 10, 20, 25.5 deg; eps = 0.04 and 1e-3; rtol = 1e-8 and 1e-10);
2. Delta for delta = 20 deg at eps = 1e-2 ... 1e-6 in every plane-shear case and in Couette flow;
3. every profile at eps = 1e-6 finite, with its largest boundary-condition error;
4. Couette: fully rough Delta numerical / asymptotic; x_hat for f = 0.05; the torque of a cell.
"""

from __future__ import annotations

import numpy as np

from cosserat import (
    Cosserat,
    Couette,
    Material,
    Plane,
    Problem,
    Wall,
    shear_layer_thickness,
    solve,
)
from cosserat.analysis import asymptotic_thickness
from cosserat.analysis.cell import CouetteCell
from cosserat.routes.airy import xi_hat_at_fraction

MAT = Material(28.5)


def plane(eps, upper, lower=None, B=0.0):  # type: ignore[no-untyped-def]
    """The Cosserat model in plane shear with this material."""
    return Problem(Plane(eps=eps, B=B), Cosserat(material=MAT, wall=upper, lower=lower))


def closed_form_agreement() -> None:
    print("1. max |numerical - closed form| (relative to max |field|)")
    for rtol in (1e-8, 1e-10):
        for eps in (0.04, 1e-3):
            for delta in (10.0, 20.0, 25.5):
                for lower in (None, Wall.fully_rough()):
                    p = Problem(
                        Plane(eps=eps), Cosserat(material=MAT, wall=Wall(delta), lower=lower)
                    )
                    num = solve(p, rtol=rtol, check=False)
                    cf = solve(p, method="closed-form", xi=num.xi, check=False)
                    err = {
                        k: np.max(np.abs(getattr(num, k) - getattr(cf, k)))
                        / max(np.max(np.abs(getattr(cf, k))), 1e-300)
                        for k in ("m", "u", "omega")
                    }
                    walls = "identical" if lower is None else "rougher lower"
                    print(
                        f"   rtol {rtol:g} eps {eps:g} delta {delta:4.1f} {walls:13s} "
                        + " ".join(f"{k} {v:.1e}" for k, v in err.items())
                    )


CASES = {
    "no gravity, identical walls": {"upper": Wall(20.0)},
    "no gravity, rougher lower wall": {"upper": Wall(20.0), "lower": Wall(25.0)},
    "gravity B = 1, layer at the upper wall": {"upper": Wall(20.0), "B": 1.0},
    "gravity B = 0.2, layer at the lower wall (delta_L = 20, delta = 25)": {
        "upper": Wall(25.0),
        "lower": Wall(20.0),
        "B": 0.2,
    },
}


def thickness_table() -> None:
    print("2. Delta for delta = 20 deg (limit -ln f / k = 17.6688)")
    for name, kw in CASES.items():
        ds = [
            shear_layer_thickness(solve(plane(e, **kw), check=False))
            for e in (1e-2, 1e-3, 1e-4, 1e-5, 1e-6)
        ]
        print(f"   {name:62s} " + " ".join(f"{d:.4f}" for d in ds))
    ds = [
        shear_layer_thickness(
            solve(
                Problem(Couette(eps=e, Ri=1.0), Cosserat(material=MAT, wall=Wall(20.0))),
                check=False,
            )
        )
        for e in (1e-2, 1e-3, 1e-4, 1e-5, 1e-6)
    ]
    print(f"   {'Couette, Ri = 1':62s} " + " ".join(f"{d:.4f}" for d in ds))


def small_eps() -> None:
    print("3. eps = 1e-6: finite? largest boundary-condition error, residuals")
    problems = [plane(1e-6, **kw) for kw in CASES.values()]
    problems += [
        Problem(Plane(eps=1e-6, B=1.0), Cosserat(material=MAT, wall=Wall.fully_rough())),
        Problem(Plane(eps=1e-6), Cosserat(material=MAT, wall=Wall.fully_rough())),
        Problem(Couette(eps=1e-6, Ri=1.0), Cosserat(material=MAT, wall=Wall(20.0))),
        Problem(Couette(eps=1e-6, Ri=1.0), Cosserat(material=MAT, wall=Wall.fully_rough())),
    ]
    for p in problems:
        prof = solve(p)
        finite = all(np.all(np.isfinite(v)) for v in prof.columns().values())
        bc = max(abs(v) for v in prof.diagnostics.bc_errors.values())
        res = max(prof.diagnostics.residuals.values())
        print(f"   {p.describe()[:70]:70s} finite={finite} max|bc|={bc:.1e} max residual={res:.1e}")


def couette_and_cell() -> None:
    print("4. fully rough: Delta numerical / eqn-delta_soln_fr")
    for eps in (1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6):
        row = []
        for p in (
            Problem(Plane(eps=eps, B=1.0), Cosserat(material=MAT, wall=Wall.fully_rough())),
            Problem(Couette(eps=eps, Ri=1.0), Cosserat(material=MAT, wall=Wall.fully_rough())),
        ):
            try:
                row.append(shear_layer_thickness(solve(p, check=False)) / asymptotic_thickness(p))
            except Exception as exc:
                row.append(float("nan"))
                print("     ", exc)
        print(f"   eps {eps:g}: plane B = 1 {row[0]:.4f}, Couette Ri = 1 {row[1]:.4f}")
    print(f"   x_hat(f = 0.05) = {xi_hat_at_fraction(0.05):.6f}")
    cell = CouetteCell(
        density=2500.0,
        grain_diameter=1e-3,
        gap=0.02,
        inner_radius=0.02,
        fill_depth=0.1,
        rotation_rate=0.5,
        solids_fraction=0.6,
    )
    prof = solve(cell.problem(MAT, Wall(20.0, 0.5)))
    T = cell.torque_density(prof, depth=0.1)
    print(
        "   cell (rho_p 2500 kg/m3, d_p 1 mm, gap 20 mm, R_i 20 mm, fill 0.1 m, 0.5 rad/s, "
        "nu 0.6, phi 28.5, delta 20, K 0.5):"
    )
    print(
        f"     torque {cell.torque(prof):.6g} N m; per unit height at the bottom "
        f"{T[0]:.6g} N m/m, spread over r {np.ptp(T) / abs(T[0]):.1e} (relative)"
    )
    print(
        f"     wall shear stress at the bottom {cell.wall_shear_stress(prof, 0.1):.6g} Pa, "
        f"slip {cell.slip_velocity(prof) * 1e3:.4g} mm/s, wall speed "
        f"{cell.wall_speed * 1e3:.4g} mm/s, spin at the wall {cell.spin(prof)[0]:.5g} rad/s"
    )


if __name__ == "__main__":
    closed_form_agreement()
    thickness_table()
    small_eps()
    couette_and_cell()
