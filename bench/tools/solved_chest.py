#!/usr/bin/env python3
"""The solved chest of a take against another solve of it, frame by frame (issue 32).

  solved_chest.py A.bvh [B.bvh]

A and B solve the same take on skeletons of one template (the same joint names, as
`pipeline` writes solved.bvh: a sparse protocol's cut against the full-body take), world y
up. Per file, means over the frames: the spine's lean (root -> lowerneck against up), and
the shoulder line's roll (lhumerus -> rhumerus origins: its elevation, signed, and its
absolute value); what a viewer sees of the chest, and where held arms hang from. With B:
per frame, the angle between A's and B's spine directions and between their shoulder
lines (the files share the take's world frame), mean / median / max. Joint angles are not
compared: a spine chain's split between lowerback, upperback and thorax is a gauge the
markers do not fix (full-body fits differ from the template's mean pose by 20-100 degrees
per joint).
"""
import sys

import numpy as np


def axis_matrix(axis, degrees):
    c, s = np.cos(np.radians(degrees)), np.sin(np.radians(degrees))
    if axis == "X":
        return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])
    if axis == "Y":
        return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def read_bvh(path):
    """(names, parents, offsets, channels per joint, frames as an array)."""
    names, parents, offsets, channels, stack, pending = [], [], [], [], [], None
    lines = iter(open(path).read().splitlines())
    for line in lines:
        words = line.split()
        if not words:
            continue
        if words[0] in ("ROOT", "JOINT"):
            names.append(words[1])
            parents.append(stack[-1] if stack else -1)
            offsets.append(np.zeros(3))
            channels.append([])
            pending = len(names) - 1
        elif words[0] == "End":
            pending = None
        elif words[0] == "{":
            stack.append(pending)
        elif words[0] == "}":
            stack.pop()
        elif words[0] == "OFFSET" and stack[-1] is not None and stack[-1] == len(names) - 1 and pending is not None:
            offsets[-1] = np.array([float(v) for v in words[1:4]])
        elif words[0] == "CHANNELS":
            channels[-1] = words[2:]
        elif words[0] == "MOTION":
            break
    next(lines)  # Frames:
    next(lines)  # Frame Time:
    frames = np.array([[float(v) for v in l.split()] for l in lines if l.strip()])
    return names, parents, offsets, channels, frames


def positions(bvh):
    """World positions per frame: {joint name: array (frames, 3)}."""
    names, parents, offsets, channels, frames = bvh
    out = {n: np.zeros((len(frames), 3)) for n in names}
    for f, row in enumerate(frames):
        rotation, position, k = {}, {}, 0
        for j in range(len(names)):
            r, t = np.eye(3), offsets[j].copy()
            for channel in channels[j]:
                if channel.endswith("rotation"):
                    r = r @ axis_matrix(channel[0], row[k])
                elif channels[j] and parents[j] < 0:
                    t["XYZ".index(channel[0])] += row[k]
                k += 1
            p = parents[j]
            position[j] = t if p < 0 else position[p] + rotation[p] @ t
            rotation[j] = r if p < 0 else rotation[p] @ r
            out[names[j]][f] = position[j]
    return out


def unit(v):
    return v / np.linalg.norm(v, axis=1, keepdims=True)


def chest(path):
    p = positions(read_bvh(path))
    spine = unit(p["lowerneck"] - p["root"])
    shoulders = unit(p["rhumerus"] - p["lhumerus"])
    return spine, shoulders


def degrees(cosine):
    return np.degrees(np.arccos(np.clip(cosine, -1.0, 1.0)))


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    solved = [chest(path) for path in sys.argv[1:]]
    for path, (spine, shoulders) in zip(sys.argv[1:], solved):
        roll = 90.0 - degrees(shoulders[:, 1])
        print("%s: spine lean %.1f deg, shoulder line roll %.1f deg (abs %.1f), %d frames" %
              (path, degrees(spine[:, 1]).mean(), roll.mean(), np.abs(roll).mean(), len(spine)))
    if len(solved) == 2:
        n = min(len(solved[0][0]), len(solved[1][0]))
        for name, index in (("spine", 0), ("shoulder line", 1)):
            d = degrees(np.sum(solved[0][index][:n] * solved[1][index][:n], axis=1))
            print("A against B, %s: mean %.1f median %.1f max %.1f deg" % (name, d.mean(), np.median(d), d.max()))


if __name__ == "__main__":
    main()
