#!/usr/bin/env python3
"""The falloff curve of an edit, and the edit propagated with it.

CMU 16_15 (a walk): the edit of examples/edit_16_15_arm_up.json raises the left upper arm
35 degrees at frame 200. The pose-space falloffs (Green's function of the pose Laplacian,
diffusion distance, ISOMAP) weigh how much of that edit each other frame receives: 1 at
the edit, high again at the same phase of the other strides; the temporal spline is the
animator's usual baseline. The lower panel shows the propagated arm angle.

  PYTHONPATH=build/python /usr/bin/python3 examples/python/edit_falloff.py --out=out/falloff.png
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import mocapsolve  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", default=os.environ.get("MOCAPSOLVE_DATA", "../shared/data"))
    parser.add_argument("--edit", default=os.path.join(HERE, "..", "edit_16_15_arm_up.json"))
    parser.add_argument("--region", default="10:471", help="frames a:b the weights are normalized over")
    parser.add_argument("--out", default="edit_falloff.png")
    args = parser.parse_args(argv)
    skeleton, motion = mocapsolve.read_motion(os.path.join(args.data, "bvh/16_15.bvh"), skeleton_units="cm")
    edits = mocapsolve.read_edits(args.edit, skeleton, motion)
    frame = edits[0].frame
    curves = {}
    for method in ("green", "diffusion", "isomap"):
        curves[method] = mocapsolve.falloff(skeleton, motion, frame, method, region=args.region)
    begin, end = curves["green"]["region"]
    curves["spline"] = {"weight": mocapsolve.spline_falloff(motion.num_frames, frame, 30.0, begin, end)}
    edited = mocapsolve.propagate(skeleton, motion, edits, [curves["green"]["weight"]])

    joint = skeleton.find_joint("lhumerus")
    world = mocapsolve.joint_rotations_world(skeleton, motion)
    world_edited = mocapsolve.joint_rotations_world(skeleton, edited)

    def angle(a, b):  # Angle between two unit quaternion series, degrees.
        return np.degrees(2 * np.arccos(np.clip(np.abs(np.sum(a * b, axis=-1)), 0, 1)))

    fig, (ax_w, ax_a) = plt.subplots(2, 1, figsize=(10, 7), sharex=True)
    for method, curve in curves.items():
        ax_w.plot(curve["weight"], lw=1.5 if method == "green" else 1,
                  ls="--" if method == "spline" else "-", label=method)
    ax_w.axvline(frame, color="k", lw=0.8)
    ax_w.set_ylabel("falloff weight")
    ax_w.set_title("Falloff of the edit at frame %d of 16_15 (region %d:%d; green sigma %.3g, %d eigenpairs)"
                   % (frame, begin, end, curves["green"]["sigma"], curves["green"]["eigenpairs"]), fontsize=9)
    ax_w.legend(fontsize=8)
    ax_a.plot(angle(world[:, joint], world_edited[:, joint]), color="tab:blue")
    ax_a.axvline(frame, color="k", lw=0.8)
    ax_a.set_ylabel("lhumerus change (deg)")
    ax_a.set_xlabel("frame")
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    fig.savefig(args.out, dpi=110)
    print("edit at frame %d; weight at the edit %.3f; wrote %s" % (frame, curves["green"]["weight"][frame], args.out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
