"""The verdicts' short summaries (studies/validate/summaries.py) and their place in the report:
each summary function on the numbers of ``cosserat validate`` on the eight v2 runs (the keys it
reads, copied from that results.json into tests/data/verdict_numbers_v18.json), a shorter
summary for missing keys, and the report's layout (summary first, the full evidence in an
appendix whose anchors resolve)."""

from __future__ import annotations

import copy
import json
import re
from html.parser import HTMLParser
from pathlib import Path

import pytest
from scipy.stats import chi2

from cosserat.studies.validate.summaries import (
    SUMMARIES,
    SUMMARY_CHARS,
    delta_summary,
    layer_summary,
    spin_model_summary,
    spin_summary,
    summary,
)
from cosserat.studies.validate.verdicts import Verdict, free_lead
from cosserat.viz.report import render

DATA = json.loads((Path(__file__).parent / "data" / "verdict_numbers_v18.json").read_text())
# what delta_law_verdict records beside the series since the summaries (claimed exponent
# 0 for smoother walls, 1/3 for fully rough ones; the largest costed gap, 160 d)
DELTA_EXTRA = {"curve_model": "cosserat", "costed_gap_d": 160.0}
WORDS = {"spin": "supported", "smoother": "undecided", "rough": "undecided",
         "spin_model": "refuted", "layer": "supported"}  # fmt: skip


def numbers(key: str) -> dict:
    n = copy.deepcopy(DATA[key])
    if key in ("smoother", "rough"):
        n.update(DELTA_EXTRA, claimed_exponent=0.0 if key == "smoother" else 1 / 3)
    return n


def test_spin_summary_leads_with_the_model_free_ratio_and_the_verdicts_p():
    n = numbers("spin")
    text = spin_summary("supported", "beyond the null of the joint Cosserat fit's velocity", n)
    # the model-free lead as the evidence states it (verdicts.free_lead on the same walls)
    assert "layer 1 turns 2.17-2.95 times the half vorticity" in free_lead(
        n["grain_scale_model_free"]["walls"]
    )
    assert "layer 1 turns 2.17-2.95 times the half vorticity between layers 1 and 2 at 6 of 8 " in (
        text
    )
    assert "(R = 1.18-1.6) by 2.8-5.3 se (5 by >= 3 se) under independent errors." in text
    assert "pooled chi^2 = 116/18 (the weakest stencil, wall-first)" in text
    assert "the verdict's p = 7.5e-05 under t(9)" in text
    assert "without the first layers 62.3/12, p = 0.00099." in text
    assert (
        "It rests on 3 bins beyond 3 se (plane_smooth_H10_qs at 0.51 and 1.5 d, "
        "plane_smooth_H20_qs at 0.33 d); all inside their own null envelope" in text
    )
    assert len(text) <= SUMMARY_CHARS


# the joint fits' chi^2 of results.json scans[] (validate on the nine v2 runs): plane_smooth_H10_qs
# misfits overall with no field alone below p = 0.001; plane_smooth_H20_qs_s2 misfits omega
FIT_CHI2 = {
    "plane_smooth_H10_qs": {"chi2": 44.15774836682987, "dof": 19, "fields": {
        "u": {"chi2": 16.046641665808917, "n": 10}, "omega": {"chi2": 27.290524936009625, "n": 9},
        "stress_ratio": {"chi2": 0.8205817650113236, "n": 2}}},
    "plane_smooth_H20_qs_s2": {"chi2": 80.81679061158351, "dof": 39, "fields": {
        "u": {"chi2": 22.21446682145575, "n": 20}, "omega": {"chi2": 54.028143365093676, "n": 19},
        "stress_ratio": {"chi2": 4.574180425034102, "n": 2}}},
}  # fmt: skip


def _with_fit_chi2(n: dict) -> dict:
    for s in n["scans"]:
        s.update(FIT_CHI2.get(s["run"], {}))
    return n


def test_spin_model_summary_says_where_refuted_and_by_which_rule():
    text = spin_model_summary("refuted", "", _with_fit_chi2(numbers("spin_model")))
    assert text.startswith(
        "Refuted at plane_smooth_H10_qs, plane_smooth_H20_qs (size rule: best fit - data beyond "
        "3 se, one sign, under every stencil and every error model of u"
    )
    assert "; undecided at 4 (plane_rough_H10_qs, plane_rough_H10_qs_half, " in text
    assert "plane_smooth_H10_qs -0.107 against -0.281 +- 0.017" in text
    assert "plane_smooth_H20_qs -0.073 against -0.445 +- 0.042." in text
    # of the two refuted runs only plane_smooth_H10_qs is among the misfit runs: no field
    # alone misfits there, so the overall p is the misfit (referee 17, point 3(b))
    assert text.endswith(
        "At plane_smooth_H10_qs the joint fit against which it is refuted misfits its fields "
        "together (overall p = 0.0009)."
    )
    assert len(text) <= SUMMARY_CHARS


def test_spin_model_summary_names_the_field_that_misfits_beside_the_overall_p():
    # referee 17, point 3(b): plane_smooth_H20_qs_s2 misfits omega (54/19, p = 3.3e-5; u p =
    # 0.33), not its fields together; the overall p is 9.5e-5
    n = numbers("spin_model")
    n["calls"] = {**n["calls"], "plane_smooth_H20_qs_s2": "refuted"}
    n["misfit_runs"] = [*n["misfit_runs"], "plane_smooth_H20_qs_s2"]
    n["scans"] = [*n["scans"], {"run": "plane_smooth_H20_qs_s2"}]
    text = spin_model_summary("refuted", "", _with_fit_chi2(n))
    assert text.endswith(
        "At plane_smooth_H10_qs the joint fit against which it is refuted misfits its fields "
        "together (overall p = 0.0009); at plane_smooth_H20_qs_s2 it misfits (overall p = "
        "9.5e-05; omega 54/19, p = 3.3e-05)."
    )
    # referee 18, point 2: a refuted run whose joint fit fits is named with its p
    n["scans"] = [
        dict(s, chi2=39.55, dof=40) if s["run"] == "plane_smooth_H20_qs" else s for s in n["scans"]
    ]
    p = chi2.sf(39.55, 40)
    assert f"{p:.2g}" == "0.49"
    assert spin_model_summary("refuted", "", _with_fit_chi2(n)).endswith(
        "omega 54/19, p = 3.3e-05); only plane_smooth_H20_qs (p = 0.49) has a calibration that "
        "fits."
    )
    # without the fits' chi^2 the sentence is left out, not guessed
    assert "misfits" not in spin_model_summary("refuted", "", numbers("spin_model"))


@pytest.mark.parametrize(
    ("key", "expected"),
    [
        (
            "smoother",
            [
                "plane, smooth-frictional: Delta usable at 1 gap(s): no power law (1 of 2 runs' "
                "bands fill their gap)",
                "within 0.05 of the claimed 0 only over H/d = 272.9-1092, beyond the largest "
                "costed gap, 160 d",
                "needs 10 seeds per gap at 272.9/545.9/1092 d (30 runs; at the block error, 25% "
                "per run)",
            ],
        ),
        (
            "rough",
            [
                "plane, glued-grains: Delta usable at 1 gap(s): no power law (3 of 4 runs' bands "
                "fill their gap)",
                "within 0.05 of the claimed 0.333 only over H/d = 55.77-223.1, which ends beyond "
                "the largest costed gap, 160 d",
                "needs 5 seeds per gap at 55.77/111.5/223.1 d (15 runs; at the replicates' seed "
                "scatter, 18% per run)",
            ],
        ),
    ],
)
def test_delta_summaries_say_why_undecided(key, expected):
    text = delta_summary("undecided", "", numbers(key))
    for part in expected:
        assert part in text
    assert (
        "the ratio Delta_rough / Delta_smoother (1.45-1.99 over H/d = 20-160), needs 27 seeds "
        "per gap per wall kind at 20/40/80 d; 12 seeds per gap per wall kind at 40/80/160 d."
    ) in text
    assert len(text) <= SUMMARY_CHARS


def test_layer_summary_gives_a_its_z_and_the_first_warning():
    text = layer_summary("supported", "on the band's side", numbers("layer"))
    assert text.startswith(
        "a = f_smoother - f_rougher = +0.748 +- 0.043 (+17.4 se) over 2 run(s): the band at "
        "the smoother wall."
    )
    assert "7 warning(s) in full below, the first: the layers flow at a band stress ratio " in text
    assert "(0.213 +- 0.0039, 0.194 +- 0.0062) below the material's sin phi = 0.311." in text
    assert "L = 5.28 +- 0.63 d gives p = 1.3e-21, 6.3e-07 under AR(1); the runs' own L = 2.1, " in (
        text
    )
    assert len(text) <= SUMMARY_CHARS


@pytest.mark.parametrize(
    ("key", "drop"),
    [
        ("spin", "grain_scale_model_free"),
        ("spin", "carrying_bins"),
        ("spin_model", "scans"),
        ("smoother", "ratio_test"),
        ("rough", "claimed_exponent"),
        ("layer", "material_length"),
    ],
)
def test_a_missing_key_gives_a_shorter_summary_not_an_error(key, drop):
    full = summary(key, WORDS[key], "", numbers(key))
    n = numbers(key)
    del n[drop]
    short = summary(key, WORDS[key], "", n)
    assert short and len(short) < len(full)


def test_no_numbers_or_an_unknown_claim_give_no_summary():
    for key in SUMMARIES:
        assert summary(key, "undecided", "", {}) == ""
    assert summary("no such claim", "supported", "", numbers("spin")) == ""
    # a malformed number drops its sentence, not the summary
    n = numbers("layer")
    n["asymmetry"] = None
    assert summary("layer", "supported", "", n).startswith("7 warning(s)")


def test_the_summary_is_in_results_json_shape():
    v = Verdict("spin", "supported", "e", summary="s")
    assert v.to_dict()["summary"] == "s"
    assert Verdict("spin", "supported", "e").to_dict()["summary"] == ""


class _Anchors(HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.ids: set[str] = set()
        self.hrefs: list[str] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        a = dict(attrs)
        if a.get("id"):
            self.ids.add(str(a["id"]))
        if tag == "a" and (a.get("href") or "").startswith("#"):
            self.hrefs.append(str(a["href"])[1:])


def _context() -> dict:
    verdicts = []
    for key, word in (("spin", "supported"), ("smoother", "undecided"), ("layer", "supported")):
        s = summary(key, word, "", numbers(key)) if key != "layer" else ""
        verdicts.append(
            {
                "key": key,
                "claim": f"claim {key}",
                "verdict": word,
                "qualifier": "",
                "summary": s,
                "evidence": f"EVIDENCE-{key}",
                "would_change": f"CHANGE-{key}",
                "figure": f"claim_{key}.png",
                "extra_figures": [],
            }
        )
    return {
        "title": "t", "corpus": "c", "n_runs": 8, "models": "cosserat", "f": "0.1",
        "near_wall_d": "3", "rules": "RULES", "runs": [], "series": [], "notes": [],
        "verdicts": verdicts,
    }  # fmt: skip


def test_the_report_shows_the_summary_first_and_the_evidence_in_an_appendix():
    md = render("validate.md.j2", _context())
    head, appendix = md.split("\n## Evidence in full\n")
    assert "\n## Runs\n" in appendix  # the appendix closes the verdicts part
    for key in ("spin", "smoother"):
        assert f"Evidence in full: [below](#evidence-{key})" in head
        assert f"EVIDENCE-{key}" not in head and f"CHANGE-{key}" not in head
        assert f"Evidence: EVIDENCE-{key}" in appendix
        assert f"What would change it: CHANGE-{key}" in appendix
        assert head.index("In short: Model-free") < head.index("Evidence in full: [below]")
    # a verdict without a summary keeps its evidence in place, before the rules
    assert head.index("Evidence: EVIDENCE-layer") < head.index("What would change it: CHANGE-layer")
    assert head.index("What would change it: CHANGE-layer") < head.index("Rules: RULES")
    assert "evidence-layer" not in md
    # every link to an anchor resolves to an anchor of the page
    links = re.findall(r"\]\(#([^)]+)\)", md)
    assert sorted(links) == ["evidence-smoother", "evidence-spin"]
    for link in links:
        assert f'<a id="{link}"></a>' in appendix
    page = render("validate.html.j2", _context())
    anchors = _Anchors()
    anchors.feed(page)
    assert sorted(anchors.hrefs) == ["evidence-smoother", "evidence-spin"]
    assert set(anchors.hrefs) <= anchors.ids
    top, bottom = page.split("<h2>Evidence in full</h2>")
    assert "EVIDENCE-spin" in bottom and "EVIDENCE-spin" not in top
    assert "EVIDENCE-layer" in top and "EVIDENCE-layer" not in bottom


def test_without_summaries_the_report_has_no_appendix():
    ctx = _context()
    for v in ctx["verdicts"]:
        v["summary"] = ""
    md = render("validate.md.j2", ctx)
    assert "Evidence in full" not in md and md.count("Evidence: EVIDENCE-") == 3
    assert "Evidence in full" not in render("validate.html.j2", ctx)


def test_a_smoother_summary_names_the_level_its_seed_count_uses():
    """Referee 17, point 3(a): with the smooth pair's 13% scatter below the 25% block error, the
    seed count rests on the block error, and the summary says so (v19's numbers)."""
    n = numbers("smoother")
    (series,) = [v for v in n.values() if isinstance(v, dict) and "precision_needed" in v]
    need = series["precision_needed"]
    need["seeds_for_margin"].update(level=0.2512, replicated=True)
    need["seeds"] = {"relative": 0.1307, "dof": 1}
    text = delta_summary("undecided", "", n)
    assert "(30 runs; at the block error, 25% per run (the replicates' 13% is below it))" in text
    need["seeds"] = {"relative": 0.2512, "dof": 1}  # the scatter is the level: it is named
    assert "(30 runs; at the replicates' seed scatter, 25% per run)" in delta_summary(
        "undecided", "", n
    )


def test_the_layer_summary_names_a_side_only_beyond_three_se_and_no_nan_length():
    """Review of stop 29: a = +0.1 +- 0.1 (1 se) places no band; a run without an own L
    (L_fit NaN, not fitted) is left out of "the runs' own L", never printed as nan."""
    n = {"asymmetry": 0.1, "asymmetry_se": 0.1, "z": 1.0, "runs": [{}], "warnings": [],
         "material_length": [
             {"L": 4.5, "L_se": 0.5, "p": {"ar1": 1e-5}, "L_fit": float("nan")},
             {"L": 4.5, "L_se": 0.5, "p": {"ar1": 1e-4}, "L_fit": 2.7},
         ]}  # fmt: skip
    text = layer_summary("undecided", "", n)
    assert text.startswith("a = f_smoother - f_rougher = +0.1 +- 0.1 (+1 se) over 1 run(s): no ")
    assert "no side within 3 se." in text and "band at the" not in text
    assert "nan" not in text and "the runs' own L = 2.7 d." in text
    n.update(asymmetry=0.5, z=5.0)
    assert ": the band at the smoother wall." in layer_summary("supported", "", n)
