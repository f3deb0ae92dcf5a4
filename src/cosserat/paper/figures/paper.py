"""The paper's figures, each as ``compute_<key>() -> FigureData`` and ``plot_<key>(data)``.

Numbers follow the order of the figures in the paper's source (1 plane-shear schematic, ...,
8 Couette schematic, ..., 14 shear-layer thickness). Parameters are the captions'; where a
caption does not give a value (which delta, which B), the choice is stated in the figure's notes.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ... import config
from ...analysis import asymptotic_thickness, shear_layer_thickness, thickness_curve
from ...model import Cosserat, Couette, Plane, Problem
from ...model.constitutive import FloatArray
from ...model.parameters import FULLY_ROUGH, Material, Wall
from ...model.rheologies.cosserat import cosserat_equations
from ...results.profile import Profile
from ...routes import solve
from .base import LINESTYLES, MARKERS, FigureData, Panel, draw, spaced_along

# the paper's parameters (cosserat.config), as the captions state them
PHI, EPS, L, A, K = config.PHI, config.EPS, config.L, config.A, config.K
DELTA, RI = config.DELTA, config.RI
MATERIAL = Material(PHI, L=L, A=A)
POINTS = 401


def plane_shear(
    *,
    material: Material,
    upper: Wall,
    lower: Wall | None = None,
    eps: float,
    B: float = 0.0,
) -> Problem:
    """The Cosserat model in plane shear: ``Problem(Plane(eps, B), Cosserat(material, upper,
    lower))``."""
    return Problem(Plane(eps=eps, B=B), Cosserat(material=material, wall=upper, lower=lower))


def couette_flow(*, material: Material, wall: Wall, eps: float, Ri: float) -> Problem:
    """The Cosserat model in Couette flow: ``Problem(Couette(eps, Ri), Cosserat(material,
    wall))``."""
    return Problem(Couette(eps=eps, Ri=Ri), Cosserat(material=material, wall=wall))


SYMBOLS = 18
"""Symbols per asymptotic curve (spaced along the curve as drawn)."""
_t = config.text
PAPER = f"phi = {_t(PHI)} deg, eps = {_t(EPS)}, L = {_t(L)}, A = {_t(A)}, K = {_t(K)}"
"""The caption's statement of the paper's parameters."""
COUETTE = rf"Couette, $\bar R_i = {_t(RI)}$"
"""Legend text of the Couette cell (mathtext: figures only)."""
COUETTE_NAME = f"Couette, Ri = {_t(RI)}"
"""The same in plain text, for tables, claims and messages."""

# axis labels (mathtext, for the pictures) and the plain column names of the tables
XI = r"$\xi$"
XI_NAME = "xi"
R_GAP = r"$(r - R_i)/H$"
R_GAP_NAME = "r_minus_Ri"  # Couette: distance from the inner cylinder over the gap
U = r"$u$"
OMEGA = r"$\omega$"
M = r"$m$"
SPIN = r"$\omega + \frac{1}{2}\,\mathrm{d}u/\mathrm{d}\xi$"
SPIN_CYL = r"$\omega + \frac{1}{2}(\mathrm{d}u/\mathrm{d}\bar r + u/\bar r)$, $\bar r = r/H$"
ASYM = r"$\bar\sigma_{yx} - \bar\sigma_{xy}$"
ASYM_CYL = r"$\bar\sigma_{r\theta} - \bar\sigma_{\theta r}$"

FIELD = {
    "u": (U, "u", lambda p: p.u),
    "omega": (OMEGA, "omega", lambda p: p.omega),
    "spin": (SPIN, "spin_minus_half_vorticity", lambda p: p.spin_minus_half_vorticity),
    "spin_cyl": (SPIN_CYL, "spin_minus_half_vorticity", lambda p: p.spin_minus_half_vorticity),
    "asym": (ASYM, "sigma_yx_minus_sigma_xy", lambda p: p.asymmetry),
    "asym_cyl": (ASYM_CYL, "sigma_r_theta_minus_sigma_theta_r", lambda p: p.asymmetry),
    "m": (M, "m", lambda p: p.m),
}
"""Profile field -> (axis label, column name, value)."""


def _delta_label(wall: Wall) -> tuple[str, str]:
    """Legend text and plain name of a wall's friction."""
    if wall.is_fully_rough:
        return "fully rough", "fully rough"
    return rf"$\delta = {wall.delta:g}^\circ$", f"delta = {wall.delta:g} deg"


def profile_panels(
    curves: list[tuple[str, str, Profile]], fields: list[str], couette: bool = False
) -> list[Panel]:
    """Panels of ``fields`` against the gap coordinate (vertical, as in the paper), one curve
    per (legend label, plain name, profile): xi = y/H, or (r - R_i)/H in a Couette cell."""
    panels = []
    for field_name in fields:
        label, column, get = FIELD[field_name]
        panel = Panel(
            xlabel=label,
            ylabel=R_GAP if couette else XI,
            x_name=column,
            y_name=R_GAP_NAME if couette else XI_NAME,
        )
        for i, (curve_label, name, prof) in enumerate(curves):
            panel.add(
                curve_label,
                get(prof),
                prof.xi,
                name=name,
                color="k",
                linestyle=LINESTYLES[i % len(LINESTYLES)],
            )
        panels.append(panel)
    return panels


# --------------------------------------------------------------------------- 2: fig-zero_g
def compute_zero_g() -> FigureData:
    walls = [Wall.fully_rough(K), Wall(25.0, K), Wall(DELTA, K), Wall(10.0, K)]
    curves = [
        (*_delta_label(w), solve(plane_shear(material=MATERIAL, upper=w, eps=EPS), points=POINTS))
        for w in walls
    ]
    return FigureData(
        "fig-zero_g",
        2,
        "identical walls, no gravity",
        f"Shear between identical walls without gravity for several delta; {PAPER}.",
        profile_panels(curves, ["u", "spin", "asym", "m"]),
        notes=["delta values (not given in the caption): fully rough, 25, 20, 10 deg"],
    )


# --------------------------------------------------------------------------- 3: fig-zero_g_aw
def compute_zero_g_aw() -> FigureData:
    rough = Wall.fully_rough(K)
    walls = [Wall(25.5, K), Wall(20.0, K), Wall(10.0, K)]
    curves = [
        (
            *_delta_label(w),
            solve(plane_shear(material=MATERIAL, upper=w, lower=rough, eps=EPS), points=POINTS),
        )
        for w in walls
    ]
    return FigureData(
        "fig-zero_g_aw",
        3,
        "rougher lower wall, no gravity",
        "Velocity and spin with a rougher lower wall (delta_L > delta), no gravity; other "
        "parameters as figure 2.",
        profile_panels(curves, ["u", "omega"]),
        notes=[
            "lower wall fully rough; delta = 25.5 deg stands for the fully rough limit "
            "(the upper wall cannot be as rough as a rougher lower wall)"
        ],
    )


# --------------------------------------------------------------------------- 4: fig-asymp_g0
def compute_asymp_g0() -> FigureData:
    eps = 1e-3
    cases = {
        "identical walls": plane_shear(material=MATERIAL, upper=Wall(DELTA, K), eps=eps),
        "rougher lower wall": plane_shear(
            material=MATERIAL, upper=Wall(DELTA, K), lower=Wall.fully_rough(K), eps=eps
        ),
    }
    xi = np.linspace(0.95, 1.0, 301)
    legend = "lines: numerical; symbols: asymptotic"
    panels = [
        Panel(xlabel=U, ylabel=XI, x_name="u", y_name=XI_NAME, legend_title=legend),
        Panel(xlabel=OMEGA, ylabel=XI, x_name="omega", y_name=XI_NAME, legend_title=legend),
    ]
    for i, (name, problem) in enumerate(cases.items()):
        num = solve(problem, points=POINTS).evaluate(xi)
        asym = solve(problem, method="asymptotic", points=POINTS)
        for panel, field_name in ((panels[0], "u"), (panels[1], "omega")):
            line = getattr(num, field_name)
            panel.add(name, line, xi, name=f"numerical, {name}", color="k", linestyle=LINESTYLES[i])
            at = xi[spaced_along(line, xi, SYMBOLS)]
            panel.add_symbols(
                name,
                getattr(asym.evaluate(at), field_name),
                at,
                MARKERS[i],
                name=f"asymptotic, {name}",
            )
    return FigureData(
        "fig-asymp_g0",
        4,
        "asymptotic vs numerical, no gravity",
        "Asymptotic (symbols) and numerical (lines) u and omega, no gravity; "
        f"phi = {_t(PHI)} deg, delta = {_t(DELTA)} deg, eps = 1e-3, L = {_t(L)}, A = {_t(A)}, "
        f"K = {_t(K)}.",
        panels,
        notes=["xi restricted to the layer, 0.95 <= xi <= 1"],
    )


# --------------------------------------------------------------------------- 5: fig-bc
def compute_bc() -> FigureData:
    base = plane_shear(material=MATERIAL, upper=Wall(10.0, K), lower=Wall.fully_rough(K), eps=EPS)
    slip = cosserat_equations(base).slip_constants
    b = slip.b
    fractions = [1.0, 0.7, 0.4, 0.1]
    curves = [
        (
            rf"$m(0) = {f:g}\,b$",
            f"m(0) = {f:g} b",
            solve(base.with_values({"m_wall": f * b}), points=POINTS),
        )
        for f in fractions
    ]
    return FigureData(
        "fig-bc",
        5,
        "effect of the couple stress at the lower wall",
        "Couple stress and velocity for four m(0) in 0 < m(0) <= b (solid: m(0) = b); "
        "delta = 10 deg, delta_L > delta, other parameters as figure 2.",
        profile_panels(curves, ["m", "u"]),
        notes=[f"b = {b:.6g}; m0 = {slip.m0:.6g} (the value eqn-nd_bc4 gives)"],
        extra={"b": b, "fractions": fractions},
    )


# --------------------------------------------------------------------------- 6: fig-finite_g
def compute_finite_g() -> FigureData:
    B_values = [0.0, 0.1, 0.3, 1.0]
    curves = [
        (
            rf"$B = {B:g}$",
            f"B = {B:g}",
            solve(
                plane_shear(material=MATERIAL, upper=Wall.fully_rough(K), eps=EPS, B=B),
                points=POINTS,
            ),
        )
        for B in B_values
    ]
    return FigureData(
        "fig-finite_g",
        6,
        "fully rough walls under gravity",
        "Fully rough walls under gravity for four B = rho_p g H / N; other parameters as figure 2.",
        profile_panels(curves, ["u", "spin", "asym", "m"]),
        notes=[
            "B values (not given in the caption): 0, 0.1, 0.3, 1; B = 10 has no real "
            f"solution at eps = {_t(EPS)}"
        ],
        extra={"B": B_values, "Delta": [shear_layer_thickness(p) for *_, p in curves]},
    )


# --------------------------------------------------------------------------- 7: fig-asymp_g_c
def compute_asymp_g_c() -> FigureData:
    eps = 1e-3
    cases = {
        ("plane, B = 1", "plane, B = 1", XI_NAME): plane_shear(
            material=MATERIAL, upper=Wall.fully_rough(K), eps=eps, B=1.0
        ),
        (COUETTE, COUETTE_NAME, R_GAP_NAME): couette_flow(
            material=MATERIAL, wall=Wall.fully_rough(K), eps=eps, Ri=RI
        ),
    }
    legend = "lines: numerical; symbols: asymptotic"
    gap = r"$\xi = y/H$ or $(r - R_i)/H$"
    panels = [
        Panel(xlabel=U, ylabel=gap, x_name="u", legend_title=legend),
        Panel(xlabel=M, ylabel=gap, x_name="m", legend_title=legend),
    ]
    placed: dict[str, list[FloatArray]] = {"u": [], "m": []}
    for i, ((label, name, y_name), problem) in enumerate(cases.items()):
        num = solve(problem, points=POINTS)
        asym = solve(problem, method="asymptotic", points=POINTS)
        for panel, field_name in ((panels[0], "u"), (panels[1], "m")):
            line = getattr(num, field_name)
            panel.add(
                label,
                line,
                num.xi,
                name=f"numerical, {name}",
                y_name=y_name,
                color="k",
                linestyle=LINESTYLES[i],
            )
            # the layered grid is dense in the layer: symbols spaced along the curve instead,
            # shifted to fall between the other cell's where the two curves run together
            at = _apart(line, num.xi, SYMBOLS - 6, placed[field_name])
            sym = getattr(asym.evaluate(at), field_name)
            placed[field_name].append(np.column_stack([sym, at]))
            panel.add_symbols(label, sym, at, MARKERS[i], name=f"asymptotic, {name}", y_name=y_name)
    return FigureData(
        "fig-asymp_g_c",
        7,
        "asymptotic vs numerical, fully rough walls",
        "Asymptotic (symbols) and numerical (lines) u and m for plane shear under gravity "
        f"(B = 1) and Couette flow (Ri = {_t(RI)}), fully rough walls; eps = 1e-3, other "
        "parameters as figure 2.",
        panels,
    )


def _apart(x: FloatArray, y: FloatArray, n: int, others: list[FloatArray]) -> FloatArray:
    """y at ``n`` points spaced along the curve (x, y), shifted along it so that they stay
    farthest (in axes-scaled units) from the symbols already placed, ``others`` [(x, y) rows]."""
    if not others:
        return y[spaced_along(x, y, n)]
    taken = np.vstack(others)
    scale = np.array(
        [np.ptp(np.concatenate([x, taken[:, 0]])) or 1.0, np.ptp(np.concatenate([y, taken[:, 1]]))]
    )

    def clearance(phase: float) -> float:
        idx = spaced_along(x, y, n, phase=phase)
        pts = np.column_stack([x[idx], y[idx]]) / scale
        gaps = np.linalg.norm(pts[:, None, :] - taken[None, :, :] / scale, axis=2)
        return float(gaps.min())

    best = max(np.linspace(0.0, 0.9, 10), key=clearance)
    return y[spaced_along(x, y, n, phase=best)]


# --------------------------------------------------------------------------- 9: fig-cyl_couette
def compute_cyl_couette() -> FigureData:
    radii = [1e6, 100.0, 10.0, 1.0]
    curves = [
        (
            r"$\bar R_i = \infty$" if R > 1e5 else rf"$\bar R_i = {R:g}$",
            "Ri = inf" if R > 1e5 else f"Ri = {R:g}",
            solve(
                couette_flow(material=MATERIAL, wall=Wall.fully_rough(K), eps=EPS, Ri=R),
                points=POINTS,
            ),
        )
        for R in radii
    ]
    return FigureData(
        "fig-cyl_couette",
        9,
        "Couette flow, fully rough walls",
        f"Fully rough Couette cell for four Ri = R_i/H; {PAPER}.",
        profile_panels(curves, ["u", "spin_cyl", "asym_cyl", "m"], couette=True),
        notes=[
            "Ri values (not given in the caption): 1e6 (for infinity), 100, 10, 1. With "
            "the paper's outer-wall conditions the Ri -> infinity limit is uniform shear "
            "with no slip at the outer wall (docs/derivation_couette.md, section 6)"
        ],
    )


# --------------------------------------------------------------------------- 10, 11: experiments
def experiment_curves(preset: str, data: Any = None) -> Panel:
    """-u against xi for a preset cell: fully rough (dot-dash) and the preset's default wall,
    2 deg below atan(sin phi) (solid)."""
    from ...studies.experiments import PRESETS

    cell = PRESETS[preset]
    panel = Panel(
        xlabel=R_GAP,
        ylabel=r"$-u$",
        title=cell.description,
        x_name=R_GAP_NAME,
        y_name="u_theta_over_wall_speed",
    )
    for delta, label, name, ls in (
        (None, r"$\delta = \tan^{-1}\sin\phi - 2^\circ$", "delta = atan(sin phi) - 2 deg", "-"),
        (FULLY_ROUGH, "fully rough", "fully rough", "-."),
    ):
        prof = solve(cell.problem(delta), points=POINTS)
        panel.add(label, prof.xi, -prof.u, name=name, color="k", linestyle=ls)
    if data is not None:
        panel.add_symbols(data.label, data.xi(cell.eps), data.u_over_uw, "o")
    return panel


def _preset_text(name: str) -> str:
    """The parameters of a preset cell as the captions state them."""
    from ...studies.experiments import PRESETS

    c = PRESETS[name]
    return f"phi = {_t(c.phi)} deg, eps = {_t(c.eps)}, Ri = {_t(c.Ri)}, K = {_t(c.K)}"


def compute_mueth(data: dict[str, Any] | None = None) -> FigureData:
    data = data or {}
    panels = [
        experiment_curves("mustard", data.get("mustard")),
        experiment_curves("poppy", data.get("poppy")),
    ]
    return FigureData(
        "fig-mueth",
        10,
        "mustard and poppy seeds (Mueth et al. 2000)",
        f"Model predictions for (a) mustard seeds ({_preset_text('mustard')}) and (b) poppy "
        f"seeds ({_preset_text('poppy')}); dot-dash: fully rough walls; solid: delta 2 deg "
        "below atan(sin phi).",
        panels,
        notes=[
            "measured points are not public; pass a profile file to overlay it "
            "(cosserat figures --data mustard=FILE)"
        ],
    )


def compute_bocquet(data: dict[str, Any] | None = None) -> FigureData:
    data = data or {}
    return FigureData(
        "fig-bocquet",
        11,
        "glass beads (Bocquet et al. 2001)",
        f"Model predictions for glass beads ({_preset_text('glass')}); dot-dash: fully rough "
        "walls; solid: delta 2 deg below atan(sin phi).",
        [experiment_curves("glass", data.get("glass"))],
        notes=["measured points are not public; pass a profile file to overlay it"],
    )


# --------------------------------------------------------------------------- 12: A sensitivity
def compute_A_sensitivity() -> FigureData:
    from ...analysis.sensitivity import existence_bound_A

    bound = existence_bound_A(
        plane_shear(material=MATERIAL, upper=Wall.fully_rough(K), eps=EPS, B=1.0)
    )
    A_values = [A, 0.9, 0.0, round(bound.value + 0.02, 2)]
    curves = [
        (
            rf"$A = {a:.3g}$",
            f"A = {a:.3g}",
            solve(
                plane_shear(
                    material=Material(PHI, L=L, A=a), upper=Wall.fully_rough(K), eps=EPS, B=1.0
                ),
                points=POINTS,
            ),
        )
        for a in A_values
    ]
    return FigureData(
        "fig-A_sensitivity",
        12,
        "sensitivity to A",
        "Plane shear between fully rough walls under gravity, B = 1, for several A; no "
        "solution below the existence bound; other parameters as figure 2.",
        profile_panels(curves, ["u", "m"]),
        notes=[
            f"computed existence bound A* = {bound.value:.4f} +- {bound.tolerance:.1e} "
            f"(paper: -0.57)"
        ],
        extra={"A_bound": bound.value, "A_bound_tol": bound.tolerance, "A": A_values},
    )


# --------------------------------------------------------------------------- 13: K sensitivity
def compute_K_sensitivity() -> FigureData:
    K_values = [0.0, 0.5, 1.0, 2.0]
    curves = [
        (
            rf"$K = {k:g}$",
            f"K = {k:g}",
            solve(
                plane_shear(material=MATERIAL, upper=Wall.fully_rough(k), eps=EPS, B=1.0),
                points=POINTS,
            ),
        )
        for k in K_values
    ]
    return FigureData(
        "fig-K_sensitivity",
        13,
        "sensitivity to K",
        "Plane shear between fully rough walls under gravity, B = 1, for several K; other "
        "parameters as figure 2.",
        profile_panels(curves, ["u", "omega"]),
        notes=["K values (not given in the caption): 0, 0.5, 1, 2"],
        extra={"K": K_values},
    )


# --------------------------------------------------------------------------- 14: fig-slt
EPS_SLT = [1e-1, 5e-2, 2e-2, 1e-2, 5e-3, 2e-3, 1e-3, 1e-4, 1e-5, 1e-6]


def thickness_problems(fully_rough: bool) -> dict[str, Problem]:
    """The four problems of figure 14 (panel b: fully rough walls)."""
    wall = Wall.fully_rough(K) if fully_rough else Wall(DELTA, K)
    problems: dict[str, Problem] = {
        "plane, identical walls": plane_shear(material=MATERIAL, upper=wall, eps=EPS),
        "plane, rougher lower wall": plane_shear(
            material=MATERIAL, upper=wall, lower=Wall.fully_rough(K), eps=EPS
        ),
        "plane, gravity B = 1": plane_shear(material=MATERIAL, upper=wall, eps=EPS, B=1.0),
        COUETTE_NAME: couette_flow(material=MATERIAL, wall=wall, eps=EPS, Ri=RI),
    }
    if fully_rough:  # no wall is rougher than fully rough
        problems.pop("plane, rougher lower wall")
    return problems


SLT_MARKERS = {
    "plane, identical walls": "o",
    "plane, rougher lower wall": "x",
    "plane, gravity B = 1": "*",
    COUETTE_NAME: "D",
}
SLT_LABELS = {COUETTE_NAME: COUETTE}
"""Legend text where it differs from the plain name."""


def compute_slt() -> FigureData:
    panels = []
    table: dict[str, dict[str, list[Any]]] = {}
    for fully_rough in (False, True):
        panel = Panel(
            xlabel=r"$\varepsilon$",
            ylabel=r"$\Delta$",
            xscale="log",
            yscale="log" if fully_rough else "linear",
            x_name="eps",
            y_name="Delta",
            legend_title="symbols: numerical; lines: small-eps law",
        )
        for name, problem in thickness_problems(fully_rough).items():
            i = list(SLT_MARKERS).index(name)  # the same line style for a case in both panels
            curve = thickness_curve(problem, EPS_SLT)
            ok = [j for j, d in enumerate(curve.Delta) if d is not None]
            eps_ok = np.array([EPS_SLT[j] for j in ok])
            delta_ok = np.array([curve.Delta[j] for j in ok])
            label = SLT_LABELS.get(name, name)
            panel.add_symbols(label, eps_ok, delta_ok, SLT_MARKERS[name], markersize=6, name=name)
            fine = np.geomspace(EPS_SLT[-1], EPS_SLT[0], 60)
            asym = np.array([asymptotic_thickness(problem.with_values({"eps": e})) for e in fine])
            panel.add(
                label,  # one legend entry: the symbol over its line
                fine,
                asym,
                name=f"small-eps law, {name}",
                color="k",
                linestyle=LINESTYLES[i % len(LINESTYLES)],
                linewidth=0.8,
            )
            table[f"{'b' if fully_rough else 'a'}: {name}"] = {
                "eps": list(EPS_SLT),
                "Delta": curve.Delta,
                "Delta_asymptotic": [
                    asymptotic_thickness(problem.with_values({"eps": e})) for e in EPS_SLT
                ],
            }
        panels.append(panel)
    return FigureData(
        "fig-slt",
        14,
        "shear-layer thickness against eps",
        f"Delta against eps: (a) delta = {_t(DELTA)} deg, (b) fully rough walls (delta = "
        f"atan(sin phi) = {MATERIAL.fully_rough_delta:.1f} deg); symbols numerical, lines the "
        f"small-eps laws; phi = {_t(PHI)} deg, L = {_t(L)}, A = {_t(A)}, K = {_t(K)}, B = 1 "
        f"(gravity), Ri = {_t(RI)} (Couette).",
        panels,
        notes=["missing symbols: no real solution at that eps (e.g. gravity B = 1 at eps = 0.1)"],
        extra={"table": table},
    )


# --------------------------------------------------------------------------- registry
def plot_default(data: FigureData):
    fig = draw(data, ncols=2)
    if data.key == "fig-asymp_g0":
        for ax in fig.axes:
            ax.set_ylim(0.95, 1.0)
    return fig
