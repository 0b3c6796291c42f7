#!/usr/bin/env python3
"""Scores a subject fitted to a sparse gait-lab take (bench/sparse_protocols.sh): per marker,
whether the joint the fit attached it to is on the segment the protocol puts it on (joint
markers such as knees and ankles: either segment), in the CMU template's joint names.

    score_sparse_protocol.py SUBJECT.json   -> prints "right/total" and the wrong ones
"""
import json
import sys

PELVIS = {"root", "lhipjoint", "rhipjoint", "lowerback"}
TRUNK = {"lowerback", "upperback", "thorax", "lowerneck"}


def expected(label):
    """The CMU joints a protocol label may ride on, or None for a label not scored."""
    low = label.lower()
    side = "l" if low.startswith("l") else "r"
    key = low[1:].strip() if low[0] in "lr" and low not in ("c7",) else low
    table = {
        "asi": PELVIS, "psi": PELVIS, "asis": PELVIS, "sacrum": PELVIS,
        "thi": {side + "femur"}, "bway": {side + "femur"},
        "kne": {side + "femur", side + "tibia"}, "knee 1": {side + "femur", side + "tibia"},
        "tib": {side + "tibia"}, "tibia wand": {side + "tibia"},
        "ank": {side + "tibia", side + "foot"}, "mall": {side + "tibia", side + "foot"},
        "hee": {side + "foot"}, "heel": {side + "foot"},
        "toe": {side + "foot", side + "toes"}, "met": {side + "foot", side + "toes"},
        "c7": TRUNK, "should": {"thorax", side + "clavicle", side + "humerus"},
    }
    return table.get(key)


def main():
    subject = json.load(open(sys.argv[1]))
    right, total, wrong = 0, 0, []
    for marker in subject["markerset"]["markers"]:
        want = expected(marker["label"])
        if want is None:
            continue
        joint = marker["attachments"][0]["joint"]
        total += 1
        if joint in want:
            right += 1
        else:
            wrong.append("%s on %s" % (marker["label"], joint))
    print("%d/%d%s" % (right, total, (" (" + ", ".join(wrong) + ")") if wrong else ""))


if __name__ == "__main__":
    main()
