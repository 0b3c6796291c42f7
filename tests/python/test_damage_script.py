"""scripts/damage.py, the independent damage model, on a small synthetic take: whole
segments go missing together for 30-90 frames, swaps exchange two markers of different
bones bit for bit for 20-100 frames, and the mask says which marker's sample is where."""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
import damage  # noqa: E402

LABELS = ["LFHD", "RFHD", "LBHD", "RBHD", "LHEE", "LTOE", "LMT5", "LWRA", "LWRB", "LFIN", "C7", "LSHO", "LELB"]


def synthetic_take(frames=400):
    """Markers in mm: the head and the hand markers rigid among themselves, the hand and
    the elbow swinging against the torso (so their distances vary)."""
    rng = np.random.default_rng(0)
    t = np.arange(frames) / 120.0
    base = rng.uniform(-150.0, 150.0, size=(len(LABELS), 3)) + np.array([0.0, 0.0, 1000.0])
    positions = np.repeat(base[None], frames, axis=0)
    swing = np.stack([80.0 * np.sin(2.0 * np.pi * t), 60.0 * np.cos(1.3 * np.pi * t), 0.0 * t], axis=1)
    for label in ("LWRA", "LWRB", "LFIN", "LELB"):
        positions[:, LABELS.index(label)] += swing * (0.5 if label == "LELB" else 1.0)
    return positions


def test_segments_and_pairs_are_found_from_the_labels_and_the_motion():
    groups = damage.segment_groups(["Subject:" + l for l in LABELS])
    assert groups["head"] == [0, 1, 2, 3]
    assert groups["left foot"] == [4, 5, 6]
    assert groups["left hand"] == [7, 8, 9]
    pairs = damage.cross_bone_pairs(synthetic_take(), 0.001, near_mm=400.0)
    hand, head = LABELS.index("LWRA"), LABELS.index("LFHD")
    assert any(hand in p for p in pairs)
    assert (0, 1) not in pairs and (head, LABELS.index("RBHD")) not in pairs  # Rigid: same bone.


def test_damage_hides_whole_segments_and_swaps_bit_for_bit():
    clean = synthetic_take()
    truth, damaged, mask, events = damage.damage(clean, LABELS, 0.001, 120.0, seed=3, occlusions=3, swaps=3,
                                                 wobbles=10, near_mm=400.0)
    assert np.array_equal(truth, truth.astype(np.float32).astype(np.float64))
    assert np.abs(truth - clean).max() < 7.0  # Wobble: a few mm.
    occlusions = [e for e in events if e["kind"] == "occlusion"]
    swaps = [e for e in events if e["kind"] == "swap"]
    assert occlusions and swaps
    for e in occlusions:
        idx = [LABELS.index(l) for l in e["markers"]]
        assert 30 <= e["last_frame"] - e["first_frame"] + 1 <= 90
        block = damaged[e["first_frame"]:e["last_frame"] + 1, idx]
        assert np.isnan(block).all()
        assert (mask[e["first_frame"]:e["last_frame"] + 1, idx] == damage.OCCLUDED).all()
    for e in swaps:
        a, b = (LABELS.index(l) for l in e["markers"])
        assert 20 <= e["last_frame"] - e["first_frame"] + 1 <= 100
        for f in range(e["first_frame"], e["last_frame"] + 1):
            for own, other in ((a, b), (b, a)):
                if mask[f, other] == damage.SWAPPED:  # Marker `other`'s sample is under label `own`.
                    assert np.array_equal(damaged[f, own], truth[f, other])
                elif mask[f, other] == damage.SWAP_GAP:  # ...under a label the gap hides.
                    assert np.isnan(damaged[f, own]).all()
    untouched = mask == damage.CLEAN
    assert np.array_equal(damaged[untouched], truth[untouched])
