"""Synthetic corpora made by a model: known answers for validation.

:func:`synthetic_run` writes one run in the corpus format that ``cosserat validate`` reads
(``<run>.csv`` + ``<run>.json``, ``docs/dem.md``), its fields made by a model (``cosserat``,
``mui``, ``ngf``) at given parameters, with noise of the kind the DEM corpus has:

* bins one grain diameter wide across the gap (centres at 0.5, 1.5, ... d from the lower or
  inner wall's surface);
* every field's standard error grows with the local velocity, as block errors do (the corpus's
  u_se is about 1e-3 in the creep tail and 0.02-0.04 in the band): ``se_u = noise (floor +
  sqrt(u))``, the spin's ``spin_noise (floor + sqrt(u))``, half the vorticity's
  :data:`HALF_OVER_OMEGA` of the spin's; the stresses' (the bins' and the moving wall's,
  ``wall_stress``) a fraction ``stress_noise`` of their value;
* the noise of each field is Gaussian with those standard errors and AR(1)-correlated
  between neighbouring bins (lag-1 correlation ``rho``, as the corpus's ``bin_correlation``
  records, 0.3-0.5 for the velocity of the DEM runs), drawn from ``seed``.

The truth is the model's profile averaged over each bin (as the coarse-graining averages,
weighted by r in a Couette annulus, by the Gauss-Legendre rule of validation's forward model
and the calibration's bin means, ``forward.bin_average``;
half the vorticity too, the bin's exact mean rather than a difference stencil over the binned
u: the sidecar says so with ``half_vorticity_method: bin-average``, and validation's forward
model measures a model the same way, :mod:`cosserat.studies.validate.forward`), in
the corpus's units and signs: u over the moving wall's speed, omega and half the vorticity in
units of V/d (the deck's rotation sense: counter-clockwise positive), stresses over the applied
normal stress (compressive positive, sigma_yx < 0 when the upper wall drags the grains along
+x, sigma_rt > 0 when the inner cylinder drags them along +t). A rheology without a grain spin
of its own (mu(I), NGF) turns with the material: its omega is half its vorticity. The local
inertial number is the bin's mean shear rate, V |u(s + d/2) - u(s - d/2)| / d, over sqrt(p)
with p = sigma_yy (the coarse-graining averages the shear rate over the bin); the wall speed
``V`` (default :data:`WALL_SPEED`) makes every run quasi-static (I <= 1e-3 next to the moving
wall) and fixes the rate-dependent models' I_w = V d / (H sqrt(p_w / rho_s))
(``wall_inertial_number``), the value validation's fits read from the sidecar.

The sidecar has what validation and calibration read: the cell, ``gap_d``, ``Ri_d``, ``B``,
the walls, the grains and contact law (the same for every run, so that runs of one wall form
one gap series), ``wall_speed``, ``wall_stress``, ``wall_inertial_number`` and
``quasi_static``, ``steadiness`` (steady by construction), ``bin_correlation`` (the ``rho``
the noise was drawn with) and ``synthetic_model`` (the model, its parameters, the noise).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ...analysis.corpus import COORDINATE, write_run
from ...analysis.fitting import moving_wall
from ...analysis.ranking import model_solve
from ...errors import ParameterError
from ...model import make_problem
from ...model.constitutive import FloatArray
from .forward import Bins, bin_average
from .measures import correlated_normal

WALL_SPEED = 1e-3
"""Default speed of the moving wall [sqrt(N / rho_s)]: a bin's mean shear rate is at most V/d,
so the local inertial number of every bin is at most 1e-3 [-]."""
FLOOR = 0.03
"""Standard errors are ``noise (FLOOR + sqrt(u))``: this is their floor in the creep tail,
relative to the band's [-]."""
HALF_OVER_OMEGA = 0.4
"""Half the vorticity's standard error over the spin's (the corpus's ratio is 0.2-0.5) [-]."""
QUASI_STATIC_I = 1e-3
"""The slow-flow bound on the local inertial number next to the moving wall [-]."""
WALL_BINS = 3
"""Bins next to each wall whose inertial number the sidecar records."""
WALLS = {
    "rough": {"kind": "glued-grains", "glued_diameter_d": 1.0, "glued_spacing_d": 1.0},
    "smooth": {"kind": "smooth-frictional", "glued_diameter_d": 1.0, "glued_spacing_d": 0.1},
}
"""The sidecar's ``wall`` of the two wall kinds (``docs/dem.md``)."""
GRAINS = {
    "polydispersity": "diameters uniform in [0.8, 1.2] d",
    "diameter_range_d": [0.8, 1.2],
    "density": 1.0,
}
CONTACT = {"model": "synthetic", "friction": 0.5}


def _check(name: str, value: float, lo: float, hi: float, closed_hi: bool = True) -> None:
    ok = lo <= value <= hi if closed_hi else lo <= value < hi
    if not (math.isfinite(value) and ok):
        bound = f"[{lo:g}, {hi:g}]" if closed_hi else f"[{lo:g}, {hi:g})"
        raise ParameterError(f"{name} must lie in {bound}; got {value:g}")


def _fully_rough(values: dict[str, Any]) -> None:
    """A rough wall's delta: fully rough (``"fully-rough"`` where not given), as the corpus reads
    a wall of glued grains (``docs/dem.md``: phi is then measured as sin phi = the band's
    |sigma_yx|/sigma_yy at the wall). A delta the model takes as smoother would make a sidecar
    that says what the model is not (delta = 25.5 deg at phi = 28.5 deg is 0.04% smoother:
    the stresses then give phi 0.012 deg low, and noise-free data do not fit their own model).

    Raises
    ------
    ParameterError
        A numeric delta with tan(delta) below sin(phi) by more than the model's round-off
        tolerance (``config.FULLY_ROUGH_RTOL``)."""
    from ... import config

    delta = values.setdefault("delta", "fully-rough")
    if isinstance(delta, str):
        return
    phi = float(values.get("phi", config.PHI))
    ratio = math.tan(math.radians(float(delta))) / math.sin(math.radians(phi))
    if ratio < 1.0 - config.FULLY_ROUGH_RTOL:
        raise ParameterError(
            f"a rough wall (glued grains) is fully rough, tan(delta) = sin(phi) "
            f"(eqn-bc_fullyrough); got delta = {float(delta):g} deg, tan(delta)/sin(phi) = "
            f"{ratio:.6g} at phi = {phi:g} deg: give delta = 'fully-rough' or wall = 'smooth'"
        )


def synthetic_run(
    folder: str | Path,
    name: str,
    model: str,
    cell: str,
    gap_d: float,
    *,
    parameters: Mapping[str, Any] | None = None,
    wall: str = "rough",
    B: float = 1.0,
    Ri_d: float | None = None,
    wall_speed: float = WALL_SPEED,
    noise: float = 0.03,
    spin_noise: float | None = None,
    stress_noise: float = 0.02,
    rho: float = 0.4,
    seed: int = 0,
) -> Path:
    """Write a run made by ``model`` in ``cell`` with realistic noise (module docstring).

    Parameters
    ----------
    folder, name : str or Path, str
        Where the run goes: ``<folder>/<name>.csv`` and ``.json``.
    model : str
        "cosserat", "mui" or "ngf" (any registered rheology with a route on ``cell``).
    cell : str
        "plane" (the upper wall moves; gravity B) or "couette" (the inner cylinder moves).
    gap_d : float
        H/d [-], at least 4.
    parameters : mapping, optional
        The model's parameters by key (``delta``, ``K``, ``phi``, ``L``, ``A``, ``mu_s``, ...);
        the others take their declared defaults. ``I_w`` is not given: the wall speed sets it.
    wall : str
        "rough" (glued grains) or "smooth" (a smooth frictional wall): the sidecar's wall. A
        rough wall is fully rough, as the corpus reads glued grains: its ``delta`` is
        ``"fully-rough"`` unless given, and a given one must be; a smooth wall's friction is
        its ``delta``.
    B : float
        rho_s nu g H / N of plane shear (0: no gravity) [-].
    Ri_d : float, optional
        Couette: the inner radius R_i/d (default H/d: R_i/H = 1) [-].
    wall_speed : float
        V [sqrt(N / rho_s)], in (0, 1e-3] for a quasi-static run (larger is allowed; the
        sidecar then says the run is not quasi-static).
    noise, spin_noise : float
        Standard error of u and of omega [V and V/d] in a bin where u = 1 (default
        spin_noise = noise / 2); lower where u is lower (module docstring).
    stress_noise : float
        Relative standard error of the stresses [-].
    rho : float
        Lag-1 correlation of every field's noise between neighbouring bins, in [0, 1) [-].
    seed : int
        Seed of the noise.

    Returns
    -------
    Path
        The run's CSV; :func:`cosserat.analysis.corpus.read_run` reads it back.

    Raises
    ------
    ParameterError
        A bound above broken, an unknown model or cell, parameters the model rejects, or a
        rough wall whose delta is not fully rough.
    """
    if cell not in ("plane", "couette"):
        raise ParameterError(f"cell must be 'plane' or 'couette' (a moving wall); got {cell!r}")
    if wall not in WALLS:
        raise ParameterError(f"wall must be one of {', '.join(WALLS)}; got {wall!r}")
    _check("gap_d (H/d)", gap_d, 4.0, 1e4)
    _check("wall_speed", wall_speed, 1e-9, 10.0)
    _check("noise", noise, 1e-9, 1.0)
    spin_noise = 0.5 * noise if spin_noise is None else spin_noise
    _check("spin_noise", spin_noise, 1e-9, 1.0)
    _check("stress_noise", stress_noise, 1e-9, 1.0)
    _check("rho", rho, 0.0, 1.0, closed_hi=False)
    _check("B", B, 0.0, 100.0)
    eps = 1.0 / gap_d
    values: dict[str, Any] = {"eps": eps, **dict(parameters or {})}
    if "I_w" in values:
        raise ParameterError("I_w is set by wall_speed (I_w = V d / (H sqrt(p_w / rho_s)))")
    if cell == "plane":
        values["B"] = B
    else:
        Ri_d = gap_d if Ri_d is None else Ri_d
        _check("Ri_d (R_i/d)", Ri_d, 1e-3, 1e5)
        values["Ri"] = Ri_d / gap_d
    from ...routes import RHEOLOGIES

    if model not in RHEOLOGIES:
        raise ParameterError(f"unknown model {model!r}: registered are {', '.join(RHEOLOGIES)}")
    probe = make_problem(model, cell, {"eps": eps, **({"B": B} if cell == "plane" else {})})
    I_w = wall_speed / gap_d  # the moving wall's normal stress is the applied N = 1
    if "I_w" in probe.declared():
        values["I_w"] = I_w
    if wall == "rough" and "delta" in probe.declared():
        _fully_rough(values)
    problem = make_problem(model, cell, values)
    profile = model_solve(problem, points=401)
    xw, uw = moving_wall(problem)

    n = round(gap_d)
    s = (np.arange(n) + 0.5) * gap_d / n  # bin centres from the lower/inner wall [d]
    edges = np.linspace(0.0, gap_d, n + 1)
    xi = s / gap_d
    # a bin holds the mean over its width, as the coarse-graining does (weighted by r in an
    # annulus): the rule validation's forward model and the calibration's bin means use
    lower = (Ri_d or 0.0) if cell == "couette" else 0.0
    bins = Bins(lower + s, lower + edges[:-1], lower + edges[1:], np.arange(n),
                (lower, lower + gap_d), cell == "couette")  # fmt: skip

    def at(x: FloatArray) -> Any:
        return profile.evaluate(np.clip((np.asarray(x) - lower) / gap_d, 0.0, 1.0))

    def model_half(x: FloatArray) -> FloatArray:
        g = at(x)
        return np.asarray(-0.5 * (g.du_dxi + g.kappa * g.u), dtype=float)

    def model_omega(x: FloatArray) -> FloatArray:
        g = at(x)
        return model_half(x) if g.omega is None else np.asarray(g.omega, dtype=float)

    u = bin_average(bins, lambda x: np.asarray(at(x).u, dtype=float) / uw)
    u_edges = profile.evaluate(edges / gap_d).u / uw
    # in units of V/d, in the deck's rotation sense (see the module docstring)
    half = eps * bin_average(bins, model_half) / abs(uw)
    omega = eps * bin_average(bins, model_omega) / abs(uw)
    fc = profile.evaluate(xi)
    normal = np.asarray(fc.sigma_yy, dtype=float)
    shear = np.asarray(fc.sigma_yx, dtype=float) * math.copysign(1.0, uw)
    rate = np.abs(np.diff(u_edges)) * n / gap_d  # the bin's mean |du/ds| [V/d]
    if cell == "couette":
        r_edges = (Ri_d or 0.0) + edges  # the Couette shear rate r d(u/r)/dr
        rate = np.abs(np.diff(u_edges / r_edges)) * ((Ri_d or 0.0) + s) * n / gap_d
    inertial = wall_speed * rate / np.sqrt(normal)

    rng = np.random.default_rng(seed)
    grow = FLOOR + np.sqrt(np.clip(np.abs(u), 0.0, 1.0))
    u_se = noise * grow
    omega_se = spin_noise * grow
    half_se = HALF_OVER_OMEGA * omega_se
    normal_se = stress_noise * np.abs(normal)
    shear_se = stress_noise * np.abs(shear)
    i_se = np.maximum(0.1 * inertial, 1e-9)
    coord = s + (Ri_d or 0.0) if cell == "couette" else s
    polar = cell == "couette"
    shear_name, normal_name = ("sigma_rt", "sigma_rr") if polar else ("sigma_yx", "sigma_yy")
    columns: dict[str, FloatArray] = {
        COORDINATE[cell]: coord,
        "u": u + correlated_normal(u_se, rho, rng),
        "u_se": u_se,
        "omega": omega + correlated_normal(omega_se, rho, rng),
        "omega_se": omega_se,
        "half_vorticity": half + correlated_normal(half_se, rho, rng),
        "half_vorticity_se": half_se,
        normal_name: normal + correlated_normal(normal_se, rho, rng),
        f"{normal_name}_se": normal_se,
        shear_name: shear + correlated_normal(shear_se, rho, rng),
        f"{shear_name}_se": shear_se,
        "inertial_number": inertial,
        "inertial_number_se": i_se,
    }
    moving = "upper" if cell == "plane" else "inner"
    fixed = "lower" if cell == "plane" else "outer"
    near_moving = np.argsort(np.abs(xi - xw))[:WALL_BINS]
    near_fixed = np.argsort(np.abs(xi - (1.0 - xw)))[:WALL_BINS]

    def wall_record(idx: np.ndarray, x_wall: float) -> dict[str, Any]:
        return {
            "per_bin": [float(inertial[i]) for i in idx],
            "se": [float(i_se[i]) for i in idx],
            "distance_d": [float(abs(xi[i] - x_wall) * gap_d) for i in idx],
        }

    # the stresses on the moving wall itself, as its contacts measure them (not the first bin's:
    # under gravity sigma_yy there is 1 + B nu eps / 2 times the wall's)
    fw = profile.evaluate(np.array([float(xw)]))
    wall_normal = float(np.asarray(fw.sigma_yy, dtype=float)[0])
    wall_shear = float(np.asarray(fw.sigma_yx, dtype=float)[0]) * math.copysign(1.0, uw)
    # measured with the errors the sidecar states, as every column is (drawn after the
    # columns: a seed's columns do not depend on it). Exact values with a 2% error bar made a
    # smooth wall's delta exact while the scan propagated its stated error.
    wall_noise = rng.normal(0.0, 1.0, 2) * stress_noise
    wall_normal_se, wall_shear_se = stress_noise * abs(wall_normal), stress_noise * abs(wall_shear)
    wall_normal += wall_noise[0] * abs(wall_normal)
    wall_shear += wall_noise[1] * abs(wall_shear)
    true_params = {k: v for k, v in problem.values().items() if isinstance(v, int | float | str)}
    meta: dict[str, Any] = {
        "cell": cell,
        "gap_d": float(gap_d),
        "Ri_d": None if cell == "plane" else float(Ri_d or 0.0),
        "B": float(B) if cell == "plane" else 0.0,
        "wall": dict(WALLS[wall]),
        "grains": dict(GRAINS),
        "contact": dict(CONTACT),
        "seed": seed,
        "wall_speed": wall_speed,
        "moving_wall_speed": wall_speed,
        "velocity_scale": "V, the moving wall's speed",
        "stress_scale": "N, the normal stress on the moving wall",
        "inertial_number": float(np.mean(inertial)),
        "wall_stress": {
            "normal": wall_normal,
            "shear": wall_shear,
            "normal_se": wall_normal_se,
            "shear_se": wall_shear_se,
            "note": "the model's stresses at the moving wall with the stated errors' noise "
            "(synthetic)",
        },
        "wall_inertial_number": {
            "moving": moving,
            "bins": WALL_BINS,
            "limit": QUASI_STATIC_I,
            moving: wall_record(near_moving, xw),
            fixed: wall_record(near_fixed, 1.0 - xw),
        },
        "quasi_static": bool(np.all(inertial[near_moving] <= QUASI_STATIC_I)),
        "steadiness": {"steady": True, "note": "synthetic: steady by construction"},
        "steady_drift": 0.0,
        "bin_correlation": {k: rho for k in ("u", "omega", "nu", "stress_ratio")}
        | {normal_name: rho, shear_name: rho},
        "bin_correlation_note": "the lag-1 correlation the synthetic noise was drawn with",
        "half_vorticity_method": "bin-average",
        "source": "synthetic",
        "synthetic_model": {
            "model": model,
            "parameters": true_params,
            "I_w": I_w if "I_w" in probe.declared() else None,
            "noise": noise,
            "spin_noise": spin_noise,
            "stress_noise": stress_noise,
            "rho": rho,
        },
        "columns": {k: _MEANINGS.get(k, k) for k in columns},
    }
    return write_run(folder, name, meta, columns)


_MEANINGS = {
    "y": "distance from the lower wall's surface [d]",
    "r": "distance from the axis [d]",
    "u": "velocity along the flow / V [-]",
    "omega": "grain spin x d / V, counter-clockwise positive [-]",
    "half_vorticity": "half the vorticity of u x d / V [-]",
    "inertial_number": "local I = bin-mean shear rate d / sqrt(p / rho_s) [-]",
}


def synthetic_corpus(
    folder: str | Path,
    model: str,
    *,
    plane: Mapping[str, Sequence[float]] | None = None,
    couette: Sequence[float] = (),
    parameters: Mapping[str, Mapping[str, Any]] | None = None,
    seed: int = 0,
    **options: Any,
) -> list[Path]:
    """A corpus made by ``model``: plane gap series under gravity per wall kind, and a Couette
    series at fixed R_i/H = 1 (:func:`synthetic_run` for each run).

    Parameters
    ----------
    folder : str or Path
    model : str
    plane : mapping of wall kind to gaps, optional
        ``{"rough": (20, 40, 80), "smooth": (20, 40, 80)}`` (the default) [d].
    couette : sequence of float
        Gaps of the Couette series (rough walls, R_i = H) [d].
    parameters : mapping of wall kind to parameters, optional
        The model's parameters for runs with that wall ("rough", "smooth"); for the Cosserat
        model the wall friction ``delta`` is what makes a wall rough or smooth.
    seed : int
        The first run's seed; each further run takes the next.
    **options
        Passed to :func:`synthetic_run` (noise, spin_noise, rho, wall_speed, B, ...).
    """
    plane = {"rough": (20.0, 40.0, 80.0), "smooth": (20.0, 40.0, 80.0)} if plane is None else plane
    parameters = parameters or {}
    paths = []
    k = seed
    runs = [("plane", wall, g) for wall, gaps in plane.items() for g in gaps]
    runs += [("couette", "rough", g) for g in couette]
    for cell, wall, g in runs:
        opts = {key: v for key, v in options.items() if cell == "plane" or key != "B"}
        paths.append(
            synthetic_run(
                folder,
                f"{model}_{cell}_{wall}_H{g:g}",
                model,
                cell,
                g,
                parameters=parameters.get(wall),
                wall=wall,
                seed=k,
                **opts,
            )
        )
        k += 1
    return paths


__all__ = ["WALL_SPEED", "synthetic_corpus", "synthetic_run"]
