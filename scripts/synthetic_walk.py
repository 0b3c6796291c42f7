#!/usr/bin/env python3
"""A synthetic walking body with known truth, from a numpy model of its own (not `corrupt`'s
generator nor any project skeleton): writes its marker take (.c3d or .trc, mm, Y up) and the
subject that generated it (skeleton + marker set, mocapsolve.subject JSON).

The body: pelvis (6 dofs), lower and upper trunk, neck and head (3 dofs each); per side a
hip (3), knee hinge (1), ankle (2), toes hinge (1), shoulder (3), elbow hinge (1), wrist (2).
The gait: a stride of 1.1 s whose length and cadence drift slowly (so no two strides are
alike), hip flexion, knee flexion with its swing peak, ankle roll-over and toe-off, pelvis
rotation, obliquity and bob, counter-swinging arms with elbows that flex in the swing, and a
head that looks around at its own slow pace. 41 markers with CMU's names (so
scripts/damage.py finds the feet, hands and head), each rigid on one bone.

usage: synthetic_walk.py --out=walk.trc --subject_out=walk_subject.json [--seconds=10 --rate=120]
"""
import argparse
import json
import sys

import numpy as np

# name, parent, offset (mm, parent frame), rotation axes.
JOINTS = [
    ("pelvis", None, (0, 0, 0), "zyx"),
    ("lowerback", "pelvis", (0, 110, -20), "zyx"),
    ("upperback", "lowerback", (0, 230, 0), "zyx"),
    ("neck", "upperback", (0, 220, 10), "zyx"),
    ("head", "neck", (0, 110, 20), "zyx"),
]
for side, s in (("l", 1), ("r", -1)):
    JOINTS += [
        (side + "femur", "pelvis", (s * 95, -70, 0), "zyx"),
        (side + "tibia", side + "femur", (0, -440, 0), "x"),
        (side + "foot", side + "tibia", (0, -430, 0), "zx"),
        (side + "toes", side + "foot", (0, -60, 140), "x"),
        (side + "humerus", "upperback", (s * 180, 190, -10), "zyx"),
        (side + "radius", side + "humerus", (0, -300, 0), "x"),
        (side + "hand", side + "radius", (0, -255, 0), "zx"),
    ]

MARKERS = [("LFWT", "pelvis", (120, 20, 90)), ("RFWT", "pelvis", (-120, 20, 90)),
           ("LBWT", "pelvis", (80, 40, -110)), ("RBWT", "pelvis", (-80, 40, -110)),
           ("T10", "lowerback", (0, 150, -110)), ("STRN", "upperback", (0, 40, 120)),
           ("CLAV", "upperback", (0, 180, 80)), ("C7", "upperback", (0, 230, -70)),
           ("RBAC", "upperback", (-80, 120, -120)), ("LSHO", "upperback", (170, 210, -20)),
           ("RSHO", "upperback", (-170, 210, -20)),
           ("LFHD", "head", (60, 90, 90)), ("RFHD", "head", (-60, 90, 90)),
           ("LBHD", "head", (60, 80, -90)), ("RBHD", "head", (-60, 80, -90))]
for side, s in (("L", 1), ("R", -1)):
    p = side.lower()
    MARKERS += [(side + "THI", p + "femur", (s * 70, -250, 20)), (side + "KNE", p + "tibia", (s * 55, -5, 0)),
                (side + "SHN", p + "tibia", (s * 45, -220, 40)), (side + "ANK", p + "tibia", (s * 40, -425, 0)),
                (side + "HEE", p + "foot", (0, -40, -60)), (side + "TOE", p + "foot", (0, -45, 150)),
                (side + "MT5", p + "toes", (s * 45, -25, 10)),
                (side + "UPA", p + "humerus", (s * 55, -150, -20)), (side + "ELB", p + "humerus", (s * 20, -295, -45)),
                (side + "FRM", p + "radius", (s * 40, -170, -20)), (side + "WRA", p + "hand", (s * 35, -5, 20)),
                (side + "WRB", p + "hand", (-s * 30, -5, 20)), (side + "FIN", p + "hand", (s * 10, -80, 25))]

AXIS = {"x": 0, "y": 1, "z": 2}


def rot(axis, angle):
    c, s = np.cos(angle), np.sin(angle)
    i, j = [(1, 2), (2, 0), (0, 1)][AXIS[axis]]
    r = np.tile(np.eye(3), angle.shape + (1, 1))
    r[..., i, i], r[..., i, j], r[..., j, i], r[..., j, j] = c, -s, s, c
    return r


def gait(t, rng):
    """Angles (frames,) per joint and axis, and the pelvis path (frames, 3) in mm."""
    # Cadence and stride length drift: phase is the integral of a slowly varying frequency.
    freq = (1.0 / 1.1) * (1.0 + 0.06 * np.sin(2 * np.pi * t / 7.3 + rng.uniform(0, 6)))
    dt = t[1] - t[0]
    phase = 2 * np.pi * np.cumsum(freq) * dt
    amp = 1.0 + 0.1 * np.sin(2 * np.pi * t / 5.1 + rng.uniform(0, 6))
    a = {}
    for side, shift in (("l", 0.0), ("r", np.pi)):
        ph = phase + shift
        a[side + "femur"] = {"x": amp * (-0.42 * np.sin(ph) - 0.05), "z": 0.05 * np.sin(ph), "y": 0.08 * np.cos(ph)}
        swing = np.clip(np.sin(ph + 0.9), 0, None) ** 2
        a[side + "tibia"] = {"x": 0.12 + 1.0 * amp * swing + 0.12 * np.clip(np.sin(ph - 1.6), 0, None)}
        a[side + "foot"] = {"x": 0.15 * np.sin(ph - 0.4) - 0.22 * np.clip(np.sin(ph + 0.3), 0, None) ** 3,
                            "z": 0.04 * np.sin(ph)}
        a[side + "toes"] = {"x": -0.45 * np.clip(np.sin(ph + 0.6), 0, None) ** 4}
        a[side + "humerus"] = {"x": amp * 0.32 * np.sin(ph) + 0.05, "z": (1 if side == "l" else -1) * 0.12,
                               "y": 0.05 * np.sin(ph)}
        a[side + "radius"] = {"x": -(0.35 + 0.25 * np.clip(np.sin(ph + 0.5), 0, None))}
        a[side + "hand"] = {"x": 0.1 * np.sin(ph + 1.0), "z": 0.08 * np.sin(2 * ph)}
    a["pelvis"] = {"y": 0.08 * np.sin(phase), "z": 0.05 * np.sin(phase + 0.5), "x": 0.06 + 0.02 * np.sin(2 * phase)}
    a["lowerback"] = {"y": -0.05 * np.sin(phase), "x": 0.02 * np.sin(2 * phase), "z": 0.0 * t}
    a["upperback"] = {"y": -0.06 * np.sin(phase), "x": 0.0 * t, "z": 0.02 * np.sin(phase)}
    a["neck"] = {"y": 0.25 * np.sin(2 * np.pi * t / 4.3), "x": 0.08 * np.sin(2 * np.pi * t / 2.9), "z": 0.0 * t}
    a["head"] = {"y": 0.2 * np.sin(2 * np.pi * t / 3.7 + 1.0), "x": 0.05 * np.sin(2 * phase), "z": 0.0 * t}
    speed = 1250.0 * amp / 1.0  # mm/s
    root = np.stack([25.0 * np.sin(phase), 940.0 + 18.0 * np.cos(2 * phase), np.cumsum(speed) * dt], axis=1)
    return a, root


def forward(angles, root, frames):
    """World positions of the markers (frames, markers, 3)."""
    world = {}
    for name, parent, offset, axes in JOINTS:
        r = np.tile(np.eye(3), (frames, 1, 1))
        for ax in axes:  # Product order left to right, as rotation_axes.
            angle = np.broadcast_to(np.asarray(angles.get(name, {}).get(ax, 0.0), float), (frames,))
            r = r @ rot(ax, angle)
        if parent is None:
            world[name] = (r, root.copy())
        else:
            pr, pt = world[parent]
            world[name] = (pr @ r, pt + pr @ np.array(offset, float))
    out = np.zeros((frames, len(MARKERS), 3))
    for m, (_, joint, offset) in enumerate(MARKERS):
        r, t = world[joint]
        out[:, m] = t + r @ np.array(offset, float)
    return out


def subject_json():
    channels = {"x": "Xrotation", "y": "Yrotation", "z": "Zrotation"}
    joints = []
    for name, parent, offset, axes in JOINTS:
        j = {"name": name, "parent": parent, "offset": list(map(float, offset)),
             "channels": ([] if parent else ["Xposition", "Yposition", "Zposition"]) + [channels[a] for a in axes],
             "rotation_axes": list(axes)}
        joints.append(j)
    ends = [{"name": n + "_End", "parent": n, "offset": [0.0, -80.0, 0.0]}
            for n in ("head", "ltoes", "rtoes", "lhand", "rhand")]
    markers = [{"label": l, "attachments": [{"joint": j, "weight": 1, "offset": list(map(float, o))}]}
               for l, j, o in MARKERS]
    return {"format": "mocapsolve.subject", "version": 1, "name": "synthetic_walk",
            "skeleton": {"units": "mm", "metres_per_unit": 0.001, "joints": joints, "end_sites": ends},
            "markerset": {"format": "mocapsolve.markerset", "version": 1, "units": "mm", "markers": markers},
            "marker_files": {"axes": "x,y,z", "scale": 0, "label_prefix": ""}, "amc_fps": 120}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", required=True, help=".c3d or .trc")
    parser.add_argument("--subject_out", required=True)
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--rate", type=float, default=120.0)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    frames = int(round(args.seconds * args.rate))
    t = np.arange(frames) / args.rate
    angles, root = gait(t, np.random.default_rng(args.seed))
    positions = forward(angles, root, frames)
    import mocapsolve
    mocapsolve.write_markers(args.out, mocapsolve.Markers(positions, [m[0] for m in MARKERS], args.rate, "mm"))
    with open(args.subject_out, "w") as f:
        json.dump(subject_json(), f, indent=1)
    print("wrote %s (%d frames, %d markers) and %s" % (args.out, frames, len(MARKERS), args.subject_out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
