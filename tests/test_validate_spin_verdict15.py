"""The spin verdict after referee round 15, point 3(ii): claim_spin.png's model-free panel (each
sheared wall's layer-1 omega_1/W_layers against its matched R, +- 2 se of their difference
under independent errors) and its caption. Every expected number is worked by hand."""

from __future__ import annotations

import pytest

from cosserat.studies.validate.report import spin_caption

FREE = {
    # omega_1 -0.3, ratio 3 -> W_layers -0.1; se 0.02 -> bar 2 x 0.02/0.1 = 0.4; z -6.5
    "a": {"wall": "moving", "ratio": 3.0, "omega_1": -0.3, "se_independent": 0.02,
          "z_independent": -6.5, "matched": {"ratio": 1.7}},
    # omega_1 -0.15, ratio 1.5 -> W_layers -0.1; se 0.05 -> bar 1.0; z -0.4
    "b:fixed": {"wall": "fixed", "ratio": 1.5, "omega_1": -0.15, "se_independent": 0.05,
                "z_independent": -0.4, "matched": {"ratio": 1.3}},
    # no matched R: not drawn
    "c": {"wall": "moving", "ratio": 2.0, "omega_1": -0.2, "matched": None},
}  # fmt: skip


def test_the_model_free_panel_draws_each_walls_ratio_against_its_r():
    """Three panels where the model-free rows are given (two without them); the third draws
    wall a at 3 with an x bar of 0.4 each side and b's fixed wall (square) at 1.5 with 1.0,
    the matched R at 1.7 and 1.3 (diamonds), c (no match) left out, y labels on the right."""
    import numpy as np

    from cosserat.viz.validation import spin_claim_figure

    assert len(spin_claim_figure([], [], "t").axes) == 2
    fig = spin_claim_figure([], [], "t", "analysis", FREE)
    assert len(fig.axes) == 3
    cx = fig.axes[2]
    assert [t.get_text() for t in cx.get_yticklabels()] == ["a: moving", "b: fixed"]
    bars = cx.containers
    assert len(bars) == 2
    centres = [float(b.lines[0].get_xdata()[0]) for b in bars]
    assert centres == pytest.approx([3.0, 1.5], rel=1e-12)
    assert [b.lines[0].get_marker() for b in bars] == ["o", "s"]
    spans = [np.asarray(b.lines[2][0].get_segments()[0])[:, 0] for b in bars]
    assert spans[0] == pytest.approx([2.6, 3.4], rel=1e-12)
    assert spans[1] == pytest.approx([0.5, 2.5], rel=1e-12)
    diamonds = [ln for ln in cx.get_lines() if ln.get_marker() == "D"]
    assert [float(d.get_xdata()[0]) for d in diamonds] == pytest.approx([1.7, 1.3])
    texts = [t.get_text() for t in cx.get_legend().get_texts()]
    assert "R: a velocity matched to the layer means" in texts
    assert cx.yaxis.get_ticks_position() == "right"


def test_the_caption_names_the_model_free_panel_and_counts_its_walls():
    """With the model-free rows the bins' panel is the middle one and the caption's last
    sentence reads the right panel, counting the walls beyond 2 se (1 of 2: a, not b; c has no
    match); without them the bins' panel stays "Right"."""
    text = spin_caption([], FREE)
    assert " Middle: the near-wall bins' departure beyond each wall's null" in text
    assert text.endswith("so a bar missing its diamond is a wall beyond 2 se (1 of 2).")
    assert " Right: the near-wall bins'" in spin_caption([])
    assert "model-free" not in spin_caption([])
