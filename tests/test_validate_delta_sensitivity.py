"""Delta's sensitivity to f (referee 5, request 7): an exponential band is well conditioned at
every f; a creep floor makes the small f ill-conditioned, and a gap series then uses the
smallest f at which its runs are well conditioned, saying so."""

from __future__ import annotations

import math
import re
from dataclasses import replace

import numpy as np
import pytest

from cosserat.analysis.corpus import read_corpus, read_run, write_run
from cosserat.errors import ParameterError
from cosserat.studies.validate.measures import (
    CONDITION_SIGMAS,
    SENSITIVITY_F,
    DeltaSensitivity,
    measured_thickness,
    thickness_sensitivity,
)
from cosserat.studies.validate.study import sensitivity_fs, series_f

S = np.arange(0.5, 20.0, 1.0)  # distances from the moving wall [d]


def _write(folder, name, floor, gap=20.0, se=0.002):
    u = np.exp(-S / 2.0) + floor
    meta = {"cell": "plane", "gap_d": gap, "B": 1.0, "wall": {"kind": "glued-grains"}}
    write_run(folder, name, meta, {"y": gap - S, "u": u, "u_se": np.full(S.size, se)})
    return read_run(folder / f"{name}.csv")


def test_an_exponential_band_is_well_conditioned_at_every_f(tmp_path):
    t = thickness_sensitivity(_write(tmp_path, "exp", 0.0))
    assert t.f == SENSITIVITY_F and t.ill == ()
    # Delta - s_1 = w ln(1/f) (w = 2 d) up to the linear interpolation between bins
    for f, v, w in zip(t.f, t.value, t.decay, strict=True):
        assert v == pytest.approx(0.5 + 2.0 * math.log(1.0 / f), abs=0.06)
        assert w == pytest.approx(2.0, abs=0.04)
    assert all(abs(z) <= CONDITION_SIGMAS for z in t.shift if z is not None)
    assert t.conditioned_f(0.05) == 0.05
    assert t.text().endswith("well conditioned at every f")


def test_a_creep_floor_makes_small_f_ill_conditioned(tmp_path):
    """u = exp(-s/2) + 0.03: at f = 0.05 the target 0.05 u(0) = 0.040 sits just above the
    floor, Delta there is 9.2 d against 6.0 and 4.1 d at f = 0.1 and 0.2, and the decay length
    (Delta - s_1)/ln(1/f) moves from 2.9 to 2.4 to 2.25 d, each step beyond 2 se."""
    run = _write(tmp_path, "floor", 0.03)
    t = thickness_sensitivity(run)
    assert t.ill == (0.05, 0.1)
    assert t.value[0] == pytest.approx(measured_thickness(run, 0.05).value)
    assert t.stderr[0] == pytest.approx(measured_thickness(run, 0.05).stderr, rel=1e-12)
    assert t.decay[0] > t.decay[1] > t.decay[2]
    assert t.shift[0] > CONDITION_SIGMAS and t.shift[2] is None  # the last f has no next
    assert t.conditioned_f(0.05) == 0.2
    assert "ill-conditioned at f = 0.05, 0.1" in t.text()
    d = t.to_dict()
    assert d["ill_conditioned_f"] == [0.05, 0.1] and d["f"] == [0.05, 0.1, 0.2]


def test_a_series_uses_the_f_at_which_its_runs_are_well_conditioned(tmp_path):
    _write(tmp_path, "a", 0.03, gap=20.0)
    _write(tmp_path, "b", 0.0, gap=40.0)
    runs = read_corpus(tmp_path).runs
    ((_key, (f, note)),) = series_f(runs, 0.05).items()
    assert f == 0.2
    assert note.startswith("a is ill-conditioned at f = 0.05 (its decay length")
    assert note.endswith("well conditioned at f = 0.2): the series' Delta and its calibrations "
                         "use f = 0.2")  # fmt: skip
    # a series whose runs are well conditioned keeps validate's f, with no note
    for p in tmp_path.iterdir():
        p.unlink()
    _write(tmp_path, "c", 0.0, gap=20.0)
    ((_key, (f, note)),) = series_f(read_corpus(tmp_path).runs, 0.05).items()
    assert (f, note) == (0.05, "")
    assert sensitivity_fs(0.3) == (0.05, 0.1, 0.2, 0.3)


def test_bad_fractions(tmp_path):
    run = _write(tmp_path, "x", 0.0)
    with pytest.raises(ParameterError, match=re.escape("fs must be increasing fractions")):
        thickness_sensitivity(run, (0.1, 0.05))


def test_validate_uses_the_series_f_for_its_delta_and_says_so(tmp_path):
    """End to end: the series of a floored run and a clean one takes its Delta at f = 0.2
    (the points and the note), while each run's own Delta stays at validate's f."""
    from cosserat.studies.validate import validate

    a = _write(tmp_path, "a", 0.03, gap=20.0)
    _write(tmp_path, "b", 0.0, gap=40.0)
    report = validate(tmp_path, models=["cosserat"])
    (series,) = report.groups
    assert series.notes[0].endswith("use f = 0.2")
    point = next(p for p in series.points if p.run == "a")
    assert point.value == pytest.approx(measured_thickness(a, 0.2).value)
    result = next(r for r in report.results if r.run.name == "a")
    assert result.thickness.value == pytest.approx(measured_thickness(a, 0.05).value)
    assert result.sensitivity is not None and result.sensitivity.ill == (0.05, 0.1)
    assert "f = 0.2" in report.verdict("rough").evidence


def test_the_runs_table_tag_names_the_used_f_and_the_shift():
    """Referee 17, point 8: plane_smooth_H20_qs_s2's numbers (ill at f = 0.1 only, its decay
    length moving by -3.36 se to f = 0.2; -0.80 se from 0.05 to 0.1): the table says its Delta
    is at f = 0.05, which is not flagged."""
    t = DeltaSensitivity(
        (0.05, 0.1, 0.2),
        (4.01, 3.30, 2.69),
        (0.58, 0.36, 0.29),
        (1.20, 1.25, 1.41),
        (0.19, 0.16, 0.18),
        (-0.803, -3.364, None),
        (0.1,),
    )
    assert t.tag(0.05) == (
        "ill-conditioned at f = 0.1: its decay length shifts -3.4 se to the next f (beyond "
        "2 se); this Delta is at f = 0.05, not flagged"
    )
    assert t.tag(0.1).endswith("this Delta is at f = 0.1, one of them")
    assert replace(t, ill=()).tag(0.05) == ""
