"""Plug-in proof: a new rheology is one module, a new cell one module.

``toy_rheology.py`` (a power-law fluid, on any cell) and ``toy_cell.py`` (plane shear under a
quadratic overburden) are registered by the ``toys`` fixture only (``conftest.py``), which
restores every registry afterwards. With no edit anywhere else they reach :func:`solve`, the
command line (``main`` in this process, where they are registered), ``cosserat models``, sweeps
and fitting; local mu(I), whose route reads only a cell's statics, solves on the new cell, and is
checked there against an independent discretisation.
"""

from __future__ import annotations

import json
import pickle

import numpy as np
import pytest
from scipy.optimize import brentq

from cosserat import (
    Cosserat,
    Couette,
    MuI,
    ParameterError,
    Plane,
    Problem,
    VerticalChannel,
    shear_layer_thickness,
    solve,
)
from cosserat.analysis.measurements import MeasuredProfile
from cosserat.calibration.single import fit_model, rank_models
from cosserat.cli import main
from cosserat.config import DEFAULT_F, MUI_I0, MUI_MU_2, MUI_MU_S
from cosserat.model.cells import CELLS
from cosserat.model.rheologies import RHEOLOGIES
from cosserat.studies.sweep import parse_spec, run_sweep


def _couette_power_law(n, Ri, x):
    """u of a power-law fluid in Couette flow in closed form: with W = u/r,
    dW/dr ~ r^(-2/n - 1), W(1) = 0, u(0) = -1."""
    a = 2.0 / n
    r = Ri + np.asarray(x, dtype=float)
    W = (r**-a - (Ri + 1.0) ** -a) / (Ri**-a - (Ri + 1.0) ** -a)
    return -r * W / Ri


def test_the_toys_are_registered_only_inside_the_fixture(toys):
    assert "stratified" in CELLS and "powerlaw" in RHEOLOGIES


def test_no_toy_is_left_registered():
    assert "stratified" not in CELLS and "powerlaw" not in RHEOLOGIES


@pytest.mark.parametrize("n", [0.4, 1.0, 2.0])
def test_the_toy_rheology_solves_on_every_cell_against_its_closed_forms(toys, n):
    law = toys.toy_rheology.PowerLaw(n=n)
    x = np.linspace(0.0, 1.0, 21)
    plane = solve(Problem(Plane(eps=0.01), law), xi=x)
    np.testing.assert_allclose(plane.u, x, atol=1e-13)
    channel = solve(Problem(VerticalChannel(eps=0.01), law), xi=x)
    np.testing.assert_allclose(
        channel.u, 1.0 - np.abs(1.0 - 2.0 * x) ** (1.0 + 1.0 / n), atol=1e-12
    )
    couette = solve(Problem(Couette(eps=0.01, Ri=0.7), law), xi=x)
    np.testing.assert_allclose(couette.u, _couette_power_law(n, 0.7, x), atol=1e-12)
    stratified = solve(Problem(toys.toy_cell.StratifiedPlane(eps=0.01, c=3.0), law), xi=x)
    np.testing.assert_allclose(stratified.u, x, atol=1e-13)  # a uniform shear stress
    for profile in (plane, channel, couette):
        assert profile.omega is None and "omega" not in profile.columns()
        back = pickle.loads(pickle.dumps(profile))
        np.testing.assert_array_equal(back.evaluate([0.3]).u, profile.evaluate([0.3]).u)
    # Delta, read by the package's generic definition: the channel over its half gap
    expected = (1.0 - (DEFAULT_F) ** (n / (n + 1.0))) / 2.0 / 0.01
    assert shear_layer_thickness(channel) == pytest.approx(expected, rel=1e-9)


def test_a_rheology_without_the_cell_says_which_cells_it_has(toys):
    cell = toys.toy_cell.StratifiedPlane(eps=0.01)
    with pytest.raises(ParameterError, match="no equations on the stratified cell; it has plane"):
        Problem(cell, Cosserat())


def _trapezoid(cell, I_w, n):
    """u on a uniform grid by the trapezoidal rule, with this test's own mu(I) and its own
    root-find on the stress level: the stress ratio T/s, s = 1 + c (1 - xi)^2."""
    xi = np.linspace(0.0, 1.0, n)
    s = 1.0 + cell.c * (1.0 - xi) ** 2

    def inertial(mu):
        return np.where(mu > MUI_MU_S, MUI_I0 * (mu - MUI_MU_S) / (MUI_MU_2 - mu), 0.0)

    def velocity(T):
        f = np.sqrt(s) * inertial(T / s)
        return np.concatenate([[0.0], np.cumsum(0.5 * (f[1:] + f[:-1]) * np.diff(xi))]) / I_w

    T = brentq(lambda T: velocity(T)[-1] - 1.0, MUI_MU_S, MUI_MU_2 * (1 - 1e-12), xtol=1e-15)
    return xi, velocity(T)


NS = np.array([129, 257, 513, 1025])


def _errors(problem):
    cell = problem.cell
    out = []
    for n in NS:
        xi, u = _trapezoid(cell, cell.I_w, n)
        out.append(np.max(np.abs(u - solve(problem, xi=xi, check=False).u)))
    return np.array(out)


def test_mui_on_the_new_cell_converges_to_an_independent_discretisation(toys):
    """No plug (the stress ratio stays above mu_s across the gap): second order."""
    problem = Problem(toys.toy_cell.StratifiedPlane(eps=0.01, c=0.3, I_w=0.3), MuI())
    profile = solve(problem)
    assert profile.diagnostics.stats["plug"] is None
    assert profile.diagnostics.residuals["velocity"] < 1e-10
    assert profile.diagnostics.residuals["law"] < 1e-10
    assert max(abs(v) for v in profile.diagnostics.bc_errors.values()) < 1e-12
    errors = _errors(problem)
    order = -np.polyfit(np.log(NS - 1.0), np.log(errors), 1)[0]
    assert 1.9 < order < 2.1, (order, errors)
    # the stress ratio T/s is largest at the moving wall, where T is the level the route found
    T = profile.diagnostics.stats["stress_ratio"]
    assert -profile.evaluate([1.0]).sigma_yx[0] == pytest.approx(T, rel=1e-14)


def test_mui_on_the_new_cell_agrees_across_a_plug_edge(toys):
    """A plug below the yield depth: the rate has a kink at its edge, so the trapezoidal
    errors are bounded by an O(h^2) envelope (as for the built-in cells, ``test_mui.py``)."""
    problem = Problem(toys.toy_cell.StratifiedPlane(eps=0.01, c=3.0, I_w=0.01), MuI())
    profile = solve(problem)
    lo, hi = profile.diagnostics.stats["plug"]
    assert lo == 0.0 and 0.0 < hi < 1.0
    np.testing.assert_array_equal(profile.evaluate(np.linspace(0.0, hi, 5)).u, 0.0)
    assert profile.diagnostics.residuals["velocity"] < 1e-10
    assert profile.diagnostics.residuals["law"] < 1e-10
    scaled = _errors(problem) * (NS - 1.0) ** 2
    assert np.max(scaled) < 10.0 * scaled[0], scaled


def test_the_command_line_takes_the_toys(toys, capsys):
    code = main(["solve", "couette", "--model", "powerlaw", "--eps", "0.01", "--Ri", "0.7",
                 "--param", "n=0.4", "--format", "json", "--points", "11"])  # fmt: skip
    out = capsys.readouterr().out
    assert code == 0
    record = json.loads(out)
    assert record["parameters"]["rheology"] == "powerlaw" and record["parameters"]["n"] == 0.4
    np.testing.assert_allclose(
        record["u"], _couette_power_law(0.4, 0.7, np.array(record["r"]) - 0.7), atol=1e-12
    )
    code = main(["solve", "stratified", "--model", "mui", "--eps", "0.01", "--param", "c=2",
                 "--param", "I_w=0.05", "--format", "json", "--points", "11"])  # fmt: skip
    record = json.loads(capsys.readouterr().out)
    assert code == 0 and record["parameters"]["c"] == 2.0 and record["parameters"]["I_w"] == 0.05
    assert main(["solve", "stratified", "--eps", "0.01"]) == 2
    err = capsys.readouterr().err
    assert "model 'cosserat' has no stratified cell; it supports: plane, couette, channel" in err
    assert main(["models", "--format", "json"]) == 0
    models = {m["name"]: m for m in json.loads(capsys.readouterr().out)}
    toy = models["powerlaw"]
    assert toy["parameters"][0]["name"] == "n" and toy["parameters"][0]["fit_range"] == [0.1, 3.0]
    assert "stratified" in toy["cells"] and "stratified" in models["mui"]["cells"]
    keys = [p["name"] for p in models["mui"]["cells"]["stratified"]["parameters"]]
    assert keys == ["eps", "c", "I_w", "stress_ratio"]


def test_sweeps_run_the_toys(toys):
    spec = parse_spec(
        {
            "fixed": {"eps": 0.01},
            "cases": [
                {"model": "powerlaw", "cell": "channel", "n": 0.5},
                {"model": "powerlaw", "cell": "stratified", "n": 2.0},
                {"model": "mui", "cell": "stratified", "c": 2.0, "I_w": 0.05},
                {"model": "powerlaw", "cell": "plane", "phi": 30.0},
            ],
        }
    )
    rows = run_sweep(spec, workers=1)
    assert [r["status"] for r in rows] == ["ok", "ok", "ok", "invalid"]
    assert rows[0]["Delta"] == pytest.approx(
        (1.0 - DEFAULT_F ** (0.5 / 1.5)) / 2.0 / 0.01, rel=1e-9
    )
    assert rows[1]["Delta"] == pytest.approx((1.0 - DEFAULT_F) / 0.01, rel=1e-9)
    mui = solve(Problem(toys.toy_cell.StratifiedPlane(eps=0.01, c=2.0, I_w=0.05), MuI()))
    assert rows[2]["Delta"] == pytest.approx(shear_layer_thickness(mui), rel=1e-12)
    assert rows[2]["wall_omega"] is None
    assert "phi" in rows[3]["message"] and "powerlaw" in rows[3]["message"]


def test_fitting_recovers_the_toy_parameter(toys):
    """Data made by the toy in Couette flow (no noise): the fit finds its flow index."""
    Ri, eps, n = 0.7, 0.02, 0.45
    x = np.linspace(0.02, 0.98, 25)
    u = -_couette_power_law(n, Ri, x)  # over the inner wall's velocity, -1
    measured = MeasuredProfile(distance_d=x / eps, u_over_uw=u, u_err=np.full(x.size, 1e-3))
    start = Problem(Couette(eps=eps, Ri=Ri), toys.toy_rheology.PowerLaw(n=1.0))
    fit = fit_model(measured, start)
    assert fit.ok and fit.parameters["n"].value == pytest.approx(n, rel=1e-5)
    assert fit.parameters["n"].stderr is not None and fit.chi2 < 1e-6
    ranking = rank_models(measured, {"geometry": "couette", "eps": eps, "Ri": Ri},
                          models=["powerlaw", "mui"], grid=2)  # fmt: skip
    assert ranking.ranked[0].model == "powerlaw"
