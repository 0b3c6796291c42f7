#!/usr/bin/env bash
# Interoperability check: a BVH written by `mocapsolve convert` must import into Blender
# (bpy.ops.import_anim.bvh) as an armature with one bone per ROOT/JOINT and an action
# spanning every frame. Not part of the test suite (it needs Blender); prints PASS or
# FAIL and exits 0 or 1.
#
# Usage: scripts/check_blender.sh [IN.bvh]
#   IN.bvh  input to convert; default: a small handmade BVH (mixed rotation orders,
#           a translated non-root joint, end sites, CRLF lines) written to a temp dir.
# Environment: MOCAPSOLVE_CLI (default build/bin/mocapsolve), BLENDER (default blender).
# Installs Debian's blender with apt-get when it is missing (needs root).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cli="${MOCAPSOLVE_CLI:-$root/build/bin/mocapsolve}"
blender="${BLENDER:-blender}"

fail() {
  echo "FAIL: $*"
  exit 1
}

[[ -x "$cli" ]] || fail "$cli not found (build it: cmake --build build --target mocapsolve_cli)"

if ! command -v "$blender" > /dev/null 2>&1; then
  [[ "$(id -u)" -eq 0 ]] || fail "blender is not installed and installing it needs root"
  echo "installing blender (apt-get) ..."
  DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends blender > /dev/null \
    || fail "apt-get install blender failed"
fi

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

input="${1:-}"
if [[ -z "$input" ]]; then
  input="$work/small.bvh"
  # 6 joints, 3 end sites, 4 frames; ZXY root, ZYX and XYZ children, a translated joint.
  printf '%s\r\n' \
    'HIERARCHY' \
    'ROOT Hips' \
    '{' \
    '	OFFSET 0 90 0' \
    '	CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation' \
    '	JOINT Spine' \
    '	{' \
    '		OFFSET 0 10 0' \
    '		CHANNELS 3 Zrotation Yrotation Xrotation' \
    '		JOINT Head' \
    '		{' \
    '			OFFSET 0 30 2' \
    '			CHANNELS 6 Xposition Yposition Zposition Xrotation Yrotation Zrotation' \
    '			End Site' \
    '			{' \
    '				OFFSET 0 12 0' \
    '			}' \
    '		}' \
    '	}' \
    '	JOINT LeftLeg' \
    '	{' \
    '		OFFSET 9 -5 0' \
    '		CHANNELS 3 Zrotation Xrotation Yrotation' \
    '		JOINT LeftFoot' \
    '		{' \
    '			OFFSET 0 -40 0' \
    '			CHANNELS 3 Zrotation Xrotation Yrotation' \
    '			End Site' \
    '			{' \
    '				OFFSET 0 -8 10' \
    '			}' \
    '		}' \
    '	}' \
    '	JOINT RightLeg' \
    '	{' \
    '		OFFSET -9 -5 0' \
    '		CHANNELS 3 Zrotation Xrotation Yrotation' \
    '		End Site' \
    '		{' \
    '			OFFSET 0 -48 0' \
    '		}' \
    '	}' \
    '}' \
    'MOTION' \
    'Frames: 4' \
    'Frame Time: 0.0333333' \
    '0 90 0 0 0 0 0 0 5 0 30 2 0 0 0 10 0 0 0 0 0 0 0 0' \
    '1 90.5 0 5 0 90 0 0 10 0 31 2 10 0 0 20 0 0 -10 0 0 -20 0 0' \
    '2 91 1 10 0 180 0 0 15 0 32 2 20 0 0 30 0 0 -20 0 0 -30 0 0' \
    '3 90.5 2 15 0 -170 0 0 20 0 31 2 30 0 0 40 0 0 -30 0 0 -40 0 0' \
    > "$input"
fi
[[ -f "$input" ]] || fail "$input not found"

output="$work/converted.bvh"
"$cli" convert "$input" "$output" > "$work/convert.log" 2>&1 \
  || fail "mocapsolve convert failed: $(tail -n 1 "$work/convert.log")"

expected_bones="$(grep -cE '^[[:space:]]*(ROOT|JOINT)[[:space:]]' "$output")"
expected_frames="$(sed -n 's/^Frames:[[:space:]]*\([0-9]*\).*/\1/p' "$output" | head -n 1)"

# Blender imports End Sites as bone tails, not bones: one bone per ROOT/JOINT. The input
# is imported too, and every bone's head is compared between the two armatures at ten
# frames: Blender's own reading of both files must agree (positions replace offsets,
# rotation orders, joint order).
read -r -d '' check_py << 'EOF' || true
import builtins
import sys
import bpy
original_path, converted_path = sys.argv[sys.argv.index("--") + 1:][:2]
# Debian's Blender 3.4 BVH add-on opens the file with mode 'rU', which Python 3.11
# removed ("ValueError: invalid mode: 'rU'"); drop the 'U' so that the add-on runs.
_open = builtins.open
def _open_without_u(file, mode="r", *args, **kwargs):
    if isinstance(mode, str):
        mode = mode.replace("U", "")
    return _open(file, mode, *args, **kwargs)
builtins.open = _open_without_u

bpy.ops.wm.read_factory_settings(use_empty=True)
def import_armature(path):
    before = set(bpy.context.scene.objects)
    bpy.ops.import_anim.bvh(filepath=path)
    new = [o for o in bpy.context.scene.objects if o not in before and o.type == "ARMATURE"]
    if len(new) != 1:
        raise SystemExit("%s: expected one armature, got %d" % (path, len(new)))
    return new[0]
original = import_armature(original_path)
converted = import_armature(converted_path)
if sorted(b.name for b in original.data.bones) != sorted(b.name for b in converted.data.bones):
    raise SystemExit("bone names differ between the input and the converted file")
action = converted.animation_data.action if converted.animation_data else None
first, last = (1, 1) if action is None else (int(action.frame_range[0]), int(action.frame_range[1]))
frames = 0 if action is None else last - first + 1
worst = 0.0
scene = bpy.context.scene
for f in sorted(set(first + (last - first) * k // 9 for k in range(10))):
    scene.frame_set(f)
    for bone in original.pose.bones:
        a = original.matrix_world @ bone.head
        b = converted.matrix_world @ converted.pose.bones[bone.name].head
        # File units, less 1e-6 relative (Blender works in float32).
        worst = max(worst, (a - b).length / (1.0 + 1e-3 * a.length))
print("MOCAPSOLVE_BLENDER bones=%d frames=%d worst=%.6g" % (len(converted.data.bones), frames, worst))
EOF

"$blender" -b --factory-startup --python-exit-code 1 --python-expr "$check_py" -- \
  "$input" "$output" > "$work/blender.log" 2>&1 \
  || fail "blender import failed: $(grep -E 'Error|error' "$work/blender.log" | tail -n 3)"
result="$(grep -o 'MOCAPSOLVE_BLENDER.*' "$work/blender.log" || true)"
[[ -n "$result" ]] || fail "blender printed no result; log: $(tail -n 5 "$work/blender.log")"

bones="$(sed -n 's/.*bones=\([0-9]*\).*/\1/p' <<< "$result")"
frames="$(sed -n 's/.*frames=\([0-9]*\).*/\1/p' <<< "$result")"
worst="$(sed -n 's/.*worst=\([^ ]*\).*/\1/p' <<< "$result")"
if [[ "$bones" != "$expected_bones" ]]; then
  fail "blender imported $bones bones, expected $expected_bones ($input)"
fi
if [[ "$frames" != "$expected_frames" ]]; then
  fail "blender imported $frames frames, expected $expected_frames ($input)"
fi
# The writer's 6 significant digits keep joint positions within 1e-3 file units.
if ! awk -v w="$worst" 'BEGIN { exit !(w < 1e-3) }'; then
  fail "bone positions differ by up to $worst file units between input and converted file"
fi
echo "PASS: blender imported $bones bones and $frames frames from mocapsolve convert output" \
  "of $input; bone heads match the input's within $worst file units"
