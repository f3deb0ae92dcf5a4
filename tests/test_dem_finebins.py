"""The profile at a chosen bin width (fine bins merged, ``steady_profile(..., bin_width=)``) and
the particle-level measure of the first layer (:mod:`cosserat.dem.first_layer`), on made-up
grains whose answers are known exactly."""

from __future__ import annotations

import math

import numpy as np
import pytest

from cosserat.dem import PlaneShearDEM, RunLength, build_deck
from cosserat.dem.analyse import (
    FINE_BIN,
    RunSamples,
    check_bin_width,
    merge_bins,
    merge_empty_bins,
    steady_profile,
)
from cosserat.dem.coarse import SUMS, Grains2D, Samples, bin_sums
from cosserat.dem.first_layer import (
    LAYER_SUMS,
    RECORD_NOTE,
    SHEARED_SLIP,
    LayerSamples,
    first_layer,
    first_layer_record,
    layer_measures,
    layer_sums,
)
from cosserat.errors import InputError, ParameterError

GAP = 6.0
V = 0.0025
SLOPE = 0.13 * V  # du/dy [velocity / d]
FINE = np.arange(-1.0, GAP + 2.0 + 1e-9, FINE_BIN)


def _grains(shift: float, empty_below: float = 0.0) -> Grains2D:
    """A pair of equal grains at +-0.06 d about each fine bin's centre inside the gap, moving
    at u = SLOPE y + shift (mean of the pair: u at the centre); none below ``empty_below``."""
    centres = 0.5 * (FINE[1:] + FINE[:-1])
    centres = centres[(centres > empty_below) & (centres < GAP)]
    s = np.concatenate([centres - 0.06, centres + 0.06])
    n = s.size
    return Grains2D(s, SLOPE * s + shift, np.zeros(n), np.full(n, 0.01 * V), np.ones(n),
                    np.full(n, 0.2), np.zeros((n, 4)))  # fmt: skip


def _run(empty_below: float = 0.0, samples: int = 8) -> RunSamples:
    shifts = 0.01 * V * np.sin(np.arange(samples))
    sums = np.stack([bin_sums(_grains(c, empty_below), FINE) for c in shifts])
    area = np.diff(FINE) * 20.0
    series = np.ones(samples)
    return RunSamples(Samples(np.arange(samples) * 1000, sums, FINE, area), V * series,
                      GAP * series, series, -0.3 * series, V * series, 100)  # fmt: skip


DECK = build_deck(PlaneShearDEM(gap=GAP, wall_speed=V, run=RunLength(settle_steps=0, steps=20_000,
                                                        dump_every=1_000)))  # fmt: skip


@pytest.mark.parametrize("width", [0.25, 0.5, 1.0, 2.0])
def test_a_linear_profile_has_the_same_half_vorticity_at_every_bin_width(width):
    p = steady_profile(_run(), DECK, lammps_version="synthetic", first=0, blocks=4,
                       bin_width=width)  # fmt: skip
    c = p.columns
    assert c["y"].size == round(GAP / width)
    np.testing.assert_allclose(c["y"], np.arange(0.5 * width, GAP, width), rtol=0, atol=1e-12)
    np.testing.assert_allclose(c["u"], SLOPE * c["y"] / V + np.mean(0.01 * np.sin(range(8))),
                               rtol=0, atol=1e-12)  # fmt: skip
    np.testing.assert_allclose(c["half_vorticity"], -0.5 * SLOPE / V, rtol=1e-12)
    assert p.sidecar.get("bin_width_d") == (None if width == 1.0 else width)


@pytest.mark.parametrize("width", [0.25, 0.5, 1.0, 1.5])
def test_merged_bins_keep_the_mass_at_every_width(width):
    run = _run()
    merged = merge_bins(run.samples, 0.0, GAP, width)
    m = SUMS.index("mass")
    np.testing.assert_allclose(merged.sums[..., m].sum(axis=1), run.samples.sums[..., m].sum(1),
                               rtol=1e-13)  # fmt: skip
    np.testing.assert_allclose(np.diff(merged.edges), width, rtol=1e-12)


def test_bins_counted_from_the_upper_wall():
    run = _run()
    merged = merge_bins(run.samples, 0.0, 5.5, 1.0, anchor="upper")
    np.testing.assert_allclose(merged.edges, [0.0, 0.5, 1.5, 2.5, 3.5, 4.5, 5.5])
    np.testing.assert_allclose(merged.sums.sum(axis=1), run.samples.sums.sum(axis=1), rtol=1e-13)
    np.testing.assert_allclose(merge_bins(run.samples, 0.0, 5.25, 1.0, "upper").edges,
                               [0.0, 1.25, 2.25, 3.25, 4.25, 5.25])  # fmt: skip
    p = steady_profile(run, DECK, lammps_version="synthetic", first=0, blocks=4, bin_width=0.5,
                       anchor="upper")  # fmt: skip
    np.testing.assert_allclose(p.columns["half_vorticity"], -0.5 * SLOPE / V, rtol=1e-12)
    assert p.sidecar["bins_from"] == "upper"
    with pytest.raises(ParameterError, match=r"^anchor must be 'lower' or 'upper'; got 'top'"):
        merge_bins(run.samples, 0.0, GAP, 1.0, anchor="top")


def test_an_empty_bin_at_the_wall_joins_its_neighbour():
    run = _run(empty_below=0.25)  # no centre in [0, 0.25): as next to a real wall
    fine = merge_bins(run.samples, 0.0, GAP, 0.25)
    merged = merge_empty_bins(fine, 0, 4)
    assert merged.edges[0] == 0.0 and merged.edges[1] == 0.5
    assert merged.sums.shape[1] == fine.sums.shape[1] - 1
    np.testing.assert_allclose(merged.sums.sum(axis=1), fine.sums.sum(axis=1), rtol=1e-13)
    np.testing.assert_allclose(merged.bin_area.sum(), fine.bin_area.sum(), rtol=1e-13)
    p = steady_profile(run, DECK, lammps_version="synthetic", first=0, blocks=4, bin_width=0.25)
    assert p.columns["y"][0] == 0.25  # midway between the wall and the bin's inner edge
    assert np.all(np.isfinite(p.columns["u"])) and np.all(np.isfinite(p.columns["omega"]))


def test_an_empty_bin_inside_the_gap_joins_its_neighbour_toward_the_middle():
    run = _run()
    fine = merge_bins(run.samples, 0.0, GAP, 0.25)
    sums = fine.sums.copy()
    sums[:, 5] = 0.0  # [1.25, 1.5] d: in the lower half, so it joins [1.5, 1.75] d
    sums[2:4, 20] = 0.0  # [5, 5.25] d, empty in the second block only: joins [4.75, 5] d
    merged = merge_empty_bins(Samples(fine.steps, sums, fine.edges, fine.bin_area), 0, 4)
    np.testing.assert_allclose(merged.edges[5:7], [1.25, 1.75])
    np.testing.assert_allclose(merged.edges[18:20], [4.75, 5.25])
    assert merged.sums.shape[1] == fine.sums.shape[1] - 2
    np.testing.assert_allclose(merged.sums.sum(axis=1), sums.sum(axis=1), rtol=1e-13)
    np.testing.assert_allclose(merged.bin_area.sum(), fine.bin_area.sum(), rtol=1e-13)
    sums[:, 2:] = 0.0
    with pytest.raises(InputError, match=r"^3 bins left after merging those with no grain"):
        merge_empty_bins(Samples(fine.steps, sums, fine.edges, fine.bin_area), 0, 4)


@pytest.mark.parametrize("width", [0.3, 0.1, 0.0, -0.5, math.nan])
def test_a_bin_width_not_made_of_fine_bins_is_refused(width):
    with pytest.raises(ParameterError, match=r"^bin_width must be a whole multiple of the fine"):
        check_bin_width(width)
    with pytest.raises(ParameterError, match=r"^bin_width must be"):
        steady_profile(_run(), DECK, lammps_version="x", first=0, blocks=4, bin_width=width)


# ---------------------------------------------------------------- the first layer, grain by grain
def test_layer_sums_assign_each_grain_to_its_layer():
    d = np.array([0.4, 0.6, 0.99, 1.0, 1.7, 2.0, 3.5, -0.1])
    vt = np.arange(8.0)
    om = -np.arange(8.0)
    m = np.full(8, 2.0)
    r = np.full(8, 0.5)
    s = layer_sums(d, vt, om, m, r)
    assert s.shape == (2, len(LAYER_SUMS))
    k = LAYER_SUMS.index
    np.testing.assert_array_equal(s[:, k("count")], [3, 2])
    np.testing.assert_allclose(s[:, k("mom")], [2.0 * (0 + 1 + 2), 2.0 * (3 + 4)])
    np.testing.assert_allclose(s[:, k("m_dist")], [2.0 * 1.99, 2.0 * 2.7])


def test_layer_measures_of_a_uniform_shear_agree_and_depart_by_nothing():
    # grains turning with a linear velocity u = 1 - g d (distance d from the upper wall),
    # the wall moving with it (no slip): every half vorticity is -(1/2) du/dy = -g/2
    g = 0.1
    u = lambda d: 1.0 - g * d  # noqa: E731
    m = layer_measures("upper", u(0.0), u(0.55), u(1.5), 0.55, 1.5, -0.5 * g, 0.5)
    for w in ("W_layers", "W_wall_second", "W_wall_first"):
        assert m[w] == pytest.approx(-0.5 * g, rel=1e-12)
        assert m[f"departure_{w}"] == pytest.approx(0.0, abs=1e-15)
    # the lower wall's frame is the mirror (y = d): the vorticity changes sign
    lower = layer_measures("lower", u(0.0), u(0.55), u(1.5), 0.55, 1.5, 0.5 * g, 0.5)
    assert lower["W_layers"] == pytest.approx(0.5 * g, rel=1e-12)


def test_layer_measures_of_grains_rolling_on_a_slipping_wall():
    # the wall moves at 1, the first layer at 0.4 rolling without sliding (radius 0.5):
    # its top point moves with the wall, u - omega r = 1 -> omega = -1.2
    m = layer_measures("upper", 1.0, 0.4, 0.3, 0.5, 1.5, -1.2, 0.5)
    assert m["omega_roll"] == pytest.approx(-1.2)
    assert m["rolling"] == pytest.approx(1.0)
    assert m["W_wall_first"] == pytest.approx(-0.5 * 0.6 / 0.5)
    assert m["W_wall_second"] == pytest.approx(-0.5 * 0.7 / 1.5)
    assert m["W_layers"] == pytest.approx(-0.5 * 0.1)
    assert m["departure_W_layers"] == pytest.approx(-1.2 + 0.05)


def test_layer_measures_refuse_bad_input():
    with pytest.raises(ParameterError, match=r"^wall must be one of lower, upper; got 'top'"):
        layer_measures("top", 1.0, 0.5, 0.3, 0.5, 1.5, 0.0, 0.5)
    with pytest.raises(ParameterError, match=r"0 < d_1 < d_2; got 1.5, 0.5"):
        layer_measures("upper", 1.0, 0.5, 0.3, 1.5, 0.5, 0.0, 0.5)


def _layer_samples(samples: int = 6) -> LayerSamples:
    """Per sample, at the upper wall: layer 1 one grain at 0.5 d moving at 0.6 V + c, spin
    -0.3 V/d; layer 2 one at 1.5 d moving at 0.4 V + c; c alternating +-0.01 V."""
    sums = np.zeros((samples, 2, 2, len(LAYER_SUMS)))
    for t in range(samples):
        c = 0.01 * V * (-1) ** t
        u = np.array([0.6 * V + c, 0.4 * V + c])
        one = layer_sums(np.array([0.5, 1.5]), u, np.full(2, -0.3 * V), np.full(2, 2.0),
                         np.full(2, 0.5))  # fmt: skip
        sums[t] = one[None]
    return LayerSamples(np.arange(samples), sums, np.tile([0.0, V], (samples, 1)))


def test_first_layer_block_means_and_errors():
    out = first_layer(_layer_samples(), 0, 3, "upper", V)
    assert out["u_1"][0] == pytest.approx(0.6, rel=1e-12)
    assert out["omega_1"] == pytest.approx((-0.3, 0.0), abs=1e-12)
    # each block holds two samples, +c and -c: the block means agree, no spread
    assert out["W_layers"][0] == pytest.approx(-0.5 * 0.2, rel=1e-9)
    assert out["departure_W_layers"][0] == pytest.approx(-0.3 + 0.1, rel=1e-9)
    assert out["W_wall_second"][0] == pytest.approx(-0.5 * 0.6 / 1.5, rel=1e-9)
    assert out["u_wall"] == pytest.approx((1.0, 0.0), abs=1e-12)
    with pytest.raises(ParameterError, match=r"^scale \(the velocity scale\) must be > 0"):
        first_layer(_layer_samples(), 0, 3, "upper", 0.0)


def test_read_layers_from_a_made_up_dump(tmp_path):
    """Two wall disks each side and four grains at known distances from the walls' surfaces:
    the layers, the gap and the walls' velocities are read back exactly."""
    from cosserat.dem.decks import ATOM_COLUMNS
    from cosserat.dem.first_layer import read_layers
    from cosserat.dem.geometry import FREE, LOWER_WALL, UPPER_WALL

    info = DECK.layout.info
    off = info["surface_offset"]
    top = off + info["upper_offset"] if "upper_offset" in info else 2.0 * off
    gap = 5.7
    y_up = gap + top
    R = 0.5
    # (distance from the lower surface, vx, omega): layer 1 and 2 of the lower wall, layer 1
    # and 2 of the upper one (distances 0.4 and 1.3 from it)
    grains = [(0.6, 0.1 * V, 0.02 * V), (1.5, 0.2 * V, 0.0), (gap - 0.4, 0.7 * V, -0.3 * V),
              (gap - 1.3, 0.5 * V, -0.1 * V)]  # fmt: skip
    rows = [[k + 1, FREE, R, 1.0 + k, off + s, vx, 0.0, om] for k, (s, vx, om) in enumerate(grains)]
    rows += [[5 + k, LOWER_WALL, R, float(k), 0.0, 0.0, 0.0, 0.0] for k in range(2)]
    rows += [[7 + k, UPPER_WALL, R, float(k), y_up, V, 0.0, 0.0] for k in range(2)]
    with (tmp_path / "atoms.dump").open("w") as fh:
        for step in range(0, 21_000, 1_000):
            fh.write(f"ITEM: TIMESTEP\n{step}\nITEM: NUMBER OF ATOMS\n{len(rows)}\n")
            fh.write("ITEM: BOX BOUNDS pp fm pp\n0 30\n-1 16\n-0.5 0.5\n")
            fh.write(f"ITEM: ATOMS {' '.join(ATOM_COLUMNS)}\n")
            fh.writelines(" ".join(repr(float(v)) for v in r) + "\n" for r in rows)
    layers = read_layers(tmp_path, DECK)
    assert layers.sums.shape == (21, 2, 2, len(LAYER_SUMS))
    np.testing.assert_allclose(layers.u_wall, np.tile([0.0, V], (21, 1)), rtol=1e-12)
    k = LAYER_SUMS.index
    np.testing.assert_array_equal(layers.sums[0, :, :, k("count")], [[1, 1], [1, 1]])
    out = first_layer(layers, 0, 10, "upper", V)
    assert out["d_1"][0] == pytest.approx(0.4, abs=1e-9)
    assert out["d_2"][0] == pytest.approx(1.3, abs=1e-9)
    assert out["u_1"][0] == pytest.approx(0.7, rel=1e-9)
    assert out["omega_1"][0] == pytest.approx(-0.3, rel=1e-9)
    assert out["W_wall_first"][0] == pytest.approx(0.5 * (0.7 - 1.0) / 0.4, rel=1e-9)
    low = first_layer(layers, 0, 10, "lower", V)
    assert low["d_1"][0] == pytest.approx(0.6, abs=1e-9)
    assert low["W_layers"][0] == pytest.approx(-0.5 * 0.1 / 0.9, rel=1e-9)
    # read_samples takes the same layer sums in its pass over the dumps (with the contacts;
    # a listed neighbour that does not touch carries no force), for the sidecar's record
    from cosserat.dem.analyse import read_samples
    from cosserat.dem.decks import CONTACT_COLUMNS

    with (tmp_path / "contacts.dump").open("w") as fh:
        for step in range(0, 21_000, 1_000):
            fh.write(f"ITEM: TIMESTEP\n{step}\nITEM: NUMBER OF ENTRIES\n1\n")
            fh.write("ITEM: BOX BOUNDS pp fm pp\n0 30\n-1 16\n-0.5 0.5\n")
            fh.write(f"ITEM: ENTRIES {' '.join(CONTACT_COLUMNS)}\n1 2 0 0 0 0 0 0\n")
    run = read_samples(tmp_path, DECK)
    same = run.extra["layers"]
    np.testing.assert_array_equal(same.steps, layers.steps)
    np.testing.assert_array_equal(same.sums, layers.sums)
    np.testing.assert_array_equal(same.u_wall, layers.u_wall)


def _two_wall_layers(samples: int, lower_u1: float) -> LayerSamples:
    """:func:`_layer_samples` at the upper wall, and at the (fixed) lower wall one grain at
    0.5 d moving at ``lower_u1`` V, one at 1.5 d at 2 ``lower_u1`` V, both without spin."""
    sums = _layer_samples(samples).sums.copy()
    for t in range(samples):
        u = np.array([lower_u1 * V, 2.0 * lower_u1 * V])
        sums[t, 0] = layer_sums(np.array([0.5, 1.5]), u, np.zeros(2), np.full(2, 2.0),
                                np.full(2, 0.4))  # fmt: skip
    return LayerSamples(np.arange(samples) * 1000, sums, np.tile([0.0, V], (samples, 1)))


def test_the_sidecar_record_is_first_layer_over_the_profiles_window():
    """steady_profile adds ``first_layer``: the moving wall's measures of :func:`first_layer`
    over the same window and blocks, each with its se; a fixed wall only where layer 1 moves
    relative to it by at least SHEARED_SLIP V."""
    run = _run(samples=20)
    layers = _two_wall_layers(20, 0.01)
    run.extra["layers"] = layers
    prof = steady_profile(run, DECK, lammps_version="test", first=4, blocks=4)
    rec = prof.sidecar["first_layer"]
    assert set(rec["walls"]) == {"upper"} and rec["blocks"] == 4 and rec["note"] == RECORD_NOTE
    up = rec["walls"]["upper"]
    want = first_layer(layers, 4, 4, "upper", V)
    for name, (value, se) in want.items():
        assert up[name] == pytest.approx(value, rel=1e-12, abs=1e-15)
        assert up[f"{name}_se"] == pytest.approx(se, abs=1e-15)
    assert up["moving"] is True and up["u_1"] == pytest.approx(0.6, rel=1e-12)
    assert up["departure_W_wall_second"] == pytest.approx(-0.3 + 0.5 * 0.6 / 1.5, rel=1e-9)
    assert up["r_1"] == 0.5 and up["grains_1"] == 1.0 and up["grains_2"] == 1.0
    # the profile itself does not change with the record
    bare = steady_profile(_run(samples=20), DECK, lammps_version="test", first=4, blocks=4)
    assert "first_layer" not in bare.sidecar
    assert {k: v for k, v in prof.sidecar.items() if k != "first_layer"} == bare.sidecar
    for k, v in bare.columns.items():
        np.testing.assert_array_equal(prof.columns[k], v)


def test_a_fixed_wall_whose_first_layer_slips_is_recorded():
    slipping = first_layer_record(_two_wall_layers(6, SHEARED_SLIP + 1e-3), 0, 3, V)
    assert set(slipping["walls"]) == {"lower", "upper"}
    low = slipping["walls"]["lower"]
    assert low["moving"] is False and low["r_1"] == pytest.approx(0.4)
    # no spin, u = 0.051 at 0.5 d and 0.102 at 1.5 d above a wall at rest
    assert low["W_layers"] == pytest.approx(-0.5 * (SHEARED_SLIP + 1e-3), rel=1e-9)
    assert low["departure_W_wall_first"] == pytest.approx((SHEARED_SLIP + 1e-3), rel=1e-9)
    resting = first_layer_record(_two_wall_layers(6, SHEARED_SLIP - 1e-3), 0, 3, V)
    assert set(resting["walls"]) == {"upper"}
    with pytest.raises(ParameterError, match=r"^moving must be one of lower, upper; got 'top'"):
        first_layer_record(_two_wall_layers(6, 0.0), 0, 3, V, moving="top")
