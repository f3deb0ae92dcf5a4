"""eqn-bc3 against what the data measure (:mod:`cosserat.studies.validate.wall_k`).

K is measured on constructed profiles whose slip and spin at the wall are known in closed
form (linear u and omega: every extrapolation is exact at its target); the held-K refit at the
free fit's K reaches the free fit's chi^2; on data the Cosserat model made, the like-for-like
test does not fire; a misfit whose stress ratio fits is read as inadequacy in the verdict.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from cosserat.analysis.corpus import read_run, write_run
from cosserat.errors import InputError, ParameterError
from cosserat.studies.validate import spin_scan as ss
from cosserat.studies.validate import wall_k as wk
from cosserat.studies.validate.synthetic import synthetic_run

GAP = 10.0
SE = 0.01
# near the upper (moving) wall, s = GAP - y from its surface: u = U0 + A s, omega = W0 + B s
U0, A, W0, B = 0.6, -0.05, -0.2, 0.01


def _profile_run(folder, name, *, lower=False, omega=None):
    """A plane run with linear u and omega; ``lower``: the same flow seen with the lower wall
    moving (y -> GAP - y, and the spin's sense turns with the reflection)."""
    y = np.arange(10) + 0.5
    s = GAP - y
    u = U0 + A * s
    w = W0 + B * s if omega is None else np.full_like(s, omega)
    half = np.full_like(s, 0.5 * A)  # -(1/2) du/dy with du/dy = -A
    if lower:
        y, w, half = GAP - y, -w, -half
    cols = {
        "y": y, "u": u, "u_se": np.full_like(s, SE), "omega": w, "omega_se": np.full_like(s, SE),
        "half_vorticity": half, "half_vorticity_se": np.full_like(s, SE),
    }  # fmt: skip
    meta = {"cell": "plane", "gap_d": GAP, "moving_wall": "lower" if lower else "upper"}
    return read_run(write_run(folder, name, meta, cols))


def _k(s0: float) -> float:
    """K at a distance s0 from the upper wall's surface: (u - 1) / omega (sigma = +1)."""
    return (U0 + A * s0 - 1.0) / (W0 + B * s0)


def test_the_measured_K_is_the_closed_form_under_every_extrapolation(tmp_path):
    run = _profile_run(tmp_path, "up")
    m = wk.measured_k(run)
    expected = {
        "first-bin": _k(0.5), "linear": _k(0.0), "second-order": _k(0.0),
        "linear-0.5": _k(-0.5), "linear+0.5": _k(0.5),
    }  # fmt: skip
    assert set(m.by) == set(wk.EXTRAPOLATIONS)
    for name, k in expected.items():
        assert m.by[name].K == pytest.approx(k, rel=1e-12), name
    assert _k(0.0) == pytest.approx(2.0)
    q = m.quoted
    assert q.slip == pytest.approx(U0 + 0.5 * A - 1.0, rel=1e-12)
    assert q.omega == pytest.approx(W0 + 0.5 * B, rel=1e-12)
    # first order in independent errors of u and omega: se_K = hypot(se, K se) / |omega|
    assert m.K_se == pytest.approx(math.hypot(SE, m.K * SE) / abs(q.omega), rel=1e-12)
    assert m.by["linear"].rolling == pytest.approx(1.0 / (2.0 * _k(0.0)), rel=1e-12)
    assert m.systematic == pytest.approx(0.5 * (max(expected.values()) - min(expected.values())))
    # the same flow with the lower wall moving: the same K (sigma = -1 there)
    low = wk.measured_k(_profile_run(tmp_path, "low", lower=True))
    for name in expected:
        assert low.by[name].K == pytest.approx(m.by[name].K, rel=1e-12), name
    # the fixed lower wall of the first run: u(0) = U0 + A GAP, omega(0) = W0 + B GAP, u_w = 0
    fixed = wk.measured_k(run, "fixed").by["linear"]
    assert fixed.K == pytest.approx((U0 + A * GAP) / -(W0 + B * GAP), rel=1e-12)
    assert "measured K = 2.18 +- " in m.text()


def test_the_weights_carry_a_quadratic_to_the_wall(tmp_path):
    s = np.array([0.4, 1.4, 2.4])
    f = 0.3 - 0.7 * s + 0.2 * s**2
    assert wk.extrapolation_weights(s, "second-order") @ f == pytest.approx(0.3, rel=1e-12)
    assert wk.extrapolation_weights(s, "linear-0.5") @ (2.0 + s) == pytest.approx(1.5)
    with pytest.raises(ParameterError, match="extrapolation must be one of first-bin, linear"):
        wk.extrapolation_weights(s, "cubic")
    with pytest.raises(ParameterError, match="three bins at increasing distances"):
        wk.extrapolation_weights(s[::-1], "linear")


def test_a_spin_within_its_errors_leaves_K_undetermined(tmp_path):
    run = _profile_run(tmp_path, "still", omega=0.5 * SE)
    m = wk.measured_k(run)
    assert not m.determined and math.isnan(m.K)
    assert m.text().startswith("K at still's moving wall is not determined: its first bin's spin")
    with pytest.raises(ParameterError, match="wall must be 'moving' or 'fixed'; got 'top'"):
        wk.measured_k(run, "top")


def test_a_couette_run_has_no_measured_K(tmp_path):
    run = _profile_run(tmp_path, "up")
    ring = dataclasses.replace(run, meta={**run.meta, "cell": "couette", "Ri_d": 20.0})
    with pytest.raises(InputError, match="run up: K is measured in plane shear only"):
        wk.measured_k(ring)


@pytest.fixture(scope="module")
def made(tmp_path_factory):
    """A run the Cosserat model made (K = 1/2) and its scan."""
    phi = 20.0
    rough = math.degrees(math.atan(math.sin(math.radians(phi))))
    path = synthetic_run(
        tmp_path_factory.mktemp("made"), "rough", "cosserat", "plane", 10.0,
        parameters={"phi": phi, "L": 3.0, "K": 0.5, "delta": rough}, wall="rough", B=1.0,
        noise=0.005, stress_noise=0.005, seed=0,
    )  # fmt: skip
    run = read_run(path)
    return run, ss.scan_run(run, [run], points=3)


def test_the_K_held_at_the_free_fit_reaches_its_chi2(made):
    run, sc = made
    free = sc.fit.value("K")
    held = wk.held_k_fit(run, sc, free, "free")
    assert held.chi2 == pytest.approx(sc.chi2_min, rel=1e-6, abs=1e-6)
    assert held.dof == sc.fit.calibration.dof + 1  # one parameter fewer
    assert held.L == pytest.approx(sc.fit.value("L"), rel=1e-3)
    assert held.omega_1 == pytest.approx(sc.omega_model, rel=1e-6)
    # any other K: no better than the free fit
    assert wk.held_k_fit(run, sc, 5.0).delta_chi2 >= -1e-6
    with pytest.raises(ParameterError, match="the held K must be a finite number >= 0; got -1"):
        wk.held_k_fit(run, sc, -1.0)


def test_a_held_k_refit_is_the_same_fit_whatever_its_name(made):
    """check_scan takes its K profile's point at K = 0.5 from the rolling refit rather than
    fitting it again: the refit is a pure function of (run, scan, K), the same floats at a
    second call, its name aside."""
    run, sc = made
    rolling = wk.held_k_fit(run, sc, wk.ROLLING_K, "rolling")
    again = wk.held_k_fit(run, sc, wk.ROLLING_K)
    assert again.name == "profile" and wk.ROLLING_K in wk.PROFILE_K
    assert repr(dataclasses.replace(rolling, name="profile")) == repr(again)


def test_on_data_the_model_made_the_fit_does_not_contradict_the_measured_K(made):
    run, sc = made
    c = wk.check_scan(sc, run)
    assert c.measured.determined and not c.contradicts and c.warning() == ""
    assert all(abs(z) < wk.CONTRADICTS_SIGMAS for z in c.like_for_like_z().values())
    assert [h.name for h in c.held] == ["rolling", "proxy", "sliding"]
    # the proxy refit holds the fit's own first-bin slip/spin at the data's (referee 9,
    # point 4), not its input K; on data the model made that costs next to nothing
    proxy = c.held[1]
    assert abs(proxy.proxy - c.measured.K) <= wk.PROXY_TOL * abs(c.measured.K)
    assert 0.0 <= proxy.delta_chi2 < 4.0
    assert f"K = {proxy.K:.3g}, where the fit's own first-bin slip/spin is" in c.text()
    rolling = c.held[0]
    assert rolling.K == 0.5 and rolling.delta_chi2 >= -1e-6
    # K -> infinity: no spin at the wall, so hardly any in the first bin
    assert abs(c.held[-1].omega_1) < 0.1 * abs(c.omega_measured)
    assert c.match is not None and c.match["matched"]  # the model reaches its own first layer
    text = c.text()
    assert text.startswith("rough: measured K = ")
    assert "eqn-bc3's limits as wall conditions (L refitted" in text
    assert "the best first-layer-matching point (within 2 se" in text
    with pytest.raises(InputError, match="run other is not the scanned run rough"):
        wk.check_scan(sc, dataclasses.replace(run, name="other"))


def test_a_fit_whose_K_the_data_contradict_is_warned(made):
    run, sc = made
    c = wk.check_scan(sc, run, refits=False)
    # the data's first bin spinning three times as fast: measured like the data, the fit's K
    # is three times the data's
    spun = {k: np.asarray(v) for k, v in run.columns.items()}
    spun["omega"] = 3.0 * spun["omega"]
    far = dataclasses.replace(run, columns=spun)
    c = dataclasses.replace(c, measured=wk.measured_k(far))
    assert c.contradicts
    assert c.warning().startswith(
        "WARNING: rough's joint fit contradicts the wall condition the data measure: measured "
        "like the data the fitted profile has K = "
    )


def test_a_misfit_with_a_fitting_stress_ratio_is_read_as_inadequacy(made):
    _, sc = made
    assert ss.misfit_reading([sc]) == ("", "")
    # the premise, a stress ratio that fits (chi^2 = n): with phi fixed from the wall's ratio
    # (stresses.material_sin_phi) this seed's two band bins sit 2.1 se from it (chi^2 9.3)
    mc = sc.fit.calibration
    mc = dataclasses.replace(mc, fields=[
        dataclasses.replace(f, chi2=float(f.n)) if f.field == "stress_ratio" else f
        for f in mc.fields
    ])  # fmt: skip
    bad = dataclasses.replace(
        sc,
        fit=dataclasses.replace(sc.fit, calibration=dataclasses.replace(mc, chi2=5.0 * mc.dof)),
        chi2_min=5.0 * mc.dof,
        wall_k={"blocks": 10},
    )
    reading, why = ss.misfit_reading([bad])
    assert reading == "inadequacy"
    assert "errors from 10 blocks raise chi^2/dof by about 9/7 = 1.3 on average" in why
    v = ss.scan_verdict([bad])
    assert v.verdict == "refuted"  # the first layer alone would support it
    assert v.numbers["reading"] == "inadequacy" and v.numbers["misfit_runs"] == ["rough"]
    assert "is read as the model's inadequacy, not understated errors" in v.evidence
    assert "The held-out first layer: rough supported" in v.evidence
    assert v.would_change.startswith("at rough: a calibration that describes u and omega")
    # referee 11, point 2: the cell run at half the speed differs from it beyond 3 se where
    # the material barely moves: part of the misfit may be understated block errors
    from types import SimpleNamespace

    from cosserat.studies.validate.rate import StaticMiss

    # omega's misfit bin of this fit: its AR(1) chi^2 share is named
    om = ss.error_models(bad)["omega"]
    top = max(om["bins"], key=lambda b: b["chi2"])
    d = round(top["distance_d"], 4)
    pair = SimpleNamespace(fast="rough", slow="rough_half",
                           static=(StaticMiss("omega", d, -3.16, d + 0.5),
                                   StaticMiss("nu", 8.3377, -4.94)))  # fmt: skip
    reading, why = ss.misfit_reading([bad], [pair])
    assert reading == "inadequacy"
    assert "is read mainly as the model's inadequacy: the model" in why
    assert "not understated errors" not in why
    assert why.endswith(
        " Part of the misfit may be understated block errors, though (scatter between runs that "
        "the block errors do not carry): where one cell is run at two speeds, the two runs "
        "differ beyond 3 se where the material barely moves (I < 0.0001 in both, no rate effect "
        f"plausible there) at rough against rough_half: omega at {d:.2g} d (z = -3.2), nu at "
        f"8.3 d (z = -4.9); those omega bins carry omega's AR(1) chi^2 {top['chi2']:.3g} of "
        f"{om['ar1']:.3g} at rough; a second seed would settle the error scale."
    )
    # as the slower run of the pair, its own distance (0.5 d further here) is matched: no bin
    slow = SimpleNamespace(fast="rough_fast", slow="rough", static=pair.static)
    assert "those omega bins carry" not in ss.misfit_reading([bad], [slow])[1]
    assert ss.scan_verdict([bad], pairs=[pair]).verdict == "refuted"
    # a pair without static misses changes nothing
    quiet = SimpleNamespace(fast="rough", slow="rough_half", static=())
    assert ss.misfit_reading([bad], [quiet]) == ss.misfit_reading([bad])
    # a stress ratio that misfits too: the errors may be understated, the rules stand
    fields = [
        dataclasses.replace(f, chi2=10.0 * f.n) if f.field == "stress_ratio" else f
        for f in mc.fields
    ]
    worse = dataclasses.replace(
        bad,
        fit=dataclasses.replace(
            bad.fit, calibration=dataclasses.replace(bad.fit.calibration, fields=fields)
        ),
    )
    assert ss.misfit_reading([worse])[0] == "errors"
    reading, why = ss.misfit_reading([worse], [pair])
    assert (
        reading == "errors"
        and "sqrt(chi^2/dof) and the 95% region is scaled alike. Such "
        "errors are seen directly (scatter between runs that the block errors do not carry): "
        "where one cell is run at two speeds, the two runs differ beyond 3 se"
        in why
    )
    assert ss.scan_verdict([worse]).verdict == "supported"
