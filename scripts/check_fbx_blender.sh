#!/usr/bin/env bash
# Interoperability check: an FBX written by `mocapsolve convert IN OUT.fbx` must import
# into Blender (bpy.ops.import_scene.fbx, headless) with no error or warning, as one
# armature whose bone heads at 10 sampled frames match our forward kinematics of IN
# (`mocapsolve fk`) within 0.1 mm, whose action spans the clip's frames, at the clip's
# rate, with the file's axes (Y up) and unit. For a glTF character IN (written with its
# skinned mesh) the mesh's vertex and vertex-group counts are printed.
# For any one input by hand; the test suite runs the same import on the files the pipeline
# writes (tests/python/test_fbx_blender.py). Prints PASS or FAIL and exits 0 or 1.
#
# Usage: scripts/check_fbx_blender.sh [IN [ANIMATION]]
#   IN         .bvh, .amc (no: needs --skeleton), or a glTF character (.glb/.gltf); default
#              $MOCAPSOLVE_DATA/bvh/01_01.bvh (MOCAPSOLVE_DATA default ../shared/data).
#   ANIMATION  the clip of a glTF IN (name or index).
# Environment: MOCAPSOLVE_CLI (default build/bin/mocapsolve), BLENDER (default blender),
# PYTHON (default /usr/bin/python3).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cli="${MOCAPSOLVE_CLI:-$root/build/bin/mocapsolve}"
blender="${BLENDER:-blender}"
python="${PYTHON:-/usr/bin/python3}"
data="${MOCAPSOLVE_DATA:-$root/../shared/data}"

fail() {
  echo "FAIL: $*"
  exit 1
}

[[ -x "$cli" ]] || fail "$cli not found (build it: cmake --build build --target mocapsolve_cli)"
command -v "$blender" > /dev/null 2>&1 || fail "blender is not installed (apt-get install blender)"

input="${1:-$data/bvh/01_01.bvh}"
animation="${2:-}"
[[ -f "$input" ]] || fail "$input not found"

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
output="$work/out.fbx"
convert_args=(convert "$input" "$output" --clip_name=take)
fk_args=(fk "--motion=$input" "--out=$work/expected.csv" --quiet)
if [[ -n "$animation" ]]; then
  convert_args+=("--animation=$animation")
  fk_args+=("--animation=$animation")
fi
"$cli" "${convert_args[@]}" > "$work/convert.log" 2>&1 \
  || fail "mocapsolve convert failed: $(tail -n 1 "$work/convert.log")"
"$cli" "${fk_args[@]}" > "$work/fk.log" 2>&1 || fail "mocapsolve fk failed: $(tail -n 1 "$work/fk.log")"
fps="$(sed -n 's/.* at \([0-9.e+-]*\) fps.*/\1/p' "$work/convert.log" | head -n 1)"

# Blender's armature object carries the file's axes and unit (FBX Y up turned Z up, scaled
# by UnitScaleFactor / 100 to metres); bone heads in armature space are in file units, so
# they compare with our FK as they are, and the difference in metres is that times the
# object's scale.
read -r -d '' blender_py << 'PYEOF' || true
import csv, json, sys
import bpy
from mathutils import Matrix
fbx_path, expected_path, out_path = sys.argv[sys.argv.index("--") + 1:][:3]
expected = {}
for row in csv.DictReader(open(expected_path)):
    expected.setdefault(int(row["frame"]), {})[row["joint"]] = (float(row["x"]), float(row["y"]), float(row["z"]))
nf = len(expected)
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.fbx(filepath=fbx_path)
armatures = [o for o in bpy.context.scene.objects if o.type == "ARMATURE"]
if len(armatures) != 1:
    raise SystemExit("expected one armature, got %d" % len(armatures))
arm = armatures[0]
scene = bpy.context.scene
action = arm.animation_data.action if arm.animation_data else None
if action is None:
    raise SystemExit("the armature has no action")
first, last = int(round(action.frame_range[0])), int(round(action.frame_range[1]))
scale = arm.matrix_world.to_scale()[0]
axes = arm.matrix_world.to_3x3() * (1.0 / scale)
y_up_to_z_up = Matrix(((1, 0, 0), (0, 0, -1), (0, 1, 0)))
axes_error = max(abs(axes[i][k] - y_up_to_z_up[i][k]) for i in range(3) for k in range(3))
worst, worst_at, compared, missing = 0.0, "", 0, 0
for f in sorted(set((nf - 1) * k // 9 for k in range(10))):
    scene.frame_set(first + f)
    for name, p in expected[f].items():
        bone = arm.pose.bones.get(name)
        if bone is None:
            missing += 1
            continue
        d = scale * sum((a - b) ** 2 for a, b in zip(bone.head, p)) ** 0.5
        compared += 1
        if d > worst:
            worst, worst_at = d, "%s at frame %d" % (name, f)
meshes = [o for o in scene.objects if o.type == "MESH"]
json.dump({"first": first, "last": last, "frames": nf, "fps": scene.render.fps / scene.render.fps_base,
           "bones": len(arm.data.bones), "worst": worst, "worst_at": worst_at, "compared": compared,
           "missing": missing, "scale": scale, "axes_error": axes_error,
           "vertices": sum(len(o.data.vertices) for o in meshes),
           "groups": sum(len(o.vertex_groups) for o in meshes)}, open(out_path, "w"))
PYEOF

"$blender" -b --factory-startup --python-exit-code 1 --python-expr "$blender_py" -- \
  "$output" "$work/expected.csv" "$work/blender.json" > "$work/blender.log" 2>&1 \
  || fail "blender import failed: $(grep -iE 'error|exception' "$work/blender.log" | tail -n 3)"
warnings="$(grep -iE 'warning|error' "$work/blender.log" || true)"

"$python" - "$work/blender.json" "$input" "$(stat -c %s "$output")" "$fps" "$warnings" << 'PYEOF'
import json, sys
got = json.load(open(sys.argv[1]))
source, size, fps, warnings = sys.argv[2], int(sys.argv[3]), float(sys.argv[4] or 0), sys.argv[5]
problems = []
if got["missing"]:
    problems.append("%d joint samples have no bone" % got["missing"])
if got["last"] - got["first"] + 1 != got["frames"]:
    problems.append("action spans frames %d..%d, the clip has %d" % (got["first"], got["last"], got["frames"]))
if fps and abs(got["fps"] - fps) > 1e-4 * fps:
    problems.append("scene rate %.6g fps, the clip's %.6g" % (got["fps"], fps))
if got["axes_error"] > 1e-6:
    problems.append("the armature's axes are not FBX Y up turned to Blender Z up")
if got["worst"] > 1e-4:
    problems.append("bone heads differ from our FK by up to %.4g mm (%s)" % (got["worst"] * 1e3, got["worst_at"]))
if warnings.strip():
    problems.append("blender printed: " + warnings.strip().splitlines()[0])
summary = ("%s: %d bones, frames %d..%d at %.6g fps, %.6g m per file unit, %d vertices in %d groups, FBX %d "
           "bytes; largest bone head difference %.4g mm over %d joint samples at 10 frames" %
           (source, got["bones"], got["first"], got["last"], got["fps"], got["scale"], got["vertices"],
            got["groups"], size, got["worst"] * 1e3, got["compared"]))
if problems:
    print("FAIL: " + summary + "; " + "; ".join(problems))
    sys.exit(1)
print("PASS: " + summary)
PYEOF
