#!/usr/bin/env bash
# Interoperability check of `retarget --animation_only`: a CMU walk is retargeted onto Xbot
# twice, as the full character file and as an animation-only glTF; Blender imports Xbot.glb,
# puts the animation-only file's action on its armature (scripts/apply_animation_gltf.py)
# and compares every bone's head and tail with the full file's at 10 frames. Prints the two
# sizes, the Khronos validator's verdict on the animation-only file, and PASS (bones within
# 1e-4 m) or FAIL; exits 0 or 1. Not part of the test suite (it needs Blender).
#
# Usage: scripts/check_animation_gltf.sh [SOURCE.bvh [CHARACTER.glb]] [--render=OUT.png]
#   defaults: $MOCAPSOLVE_DATA/bvh/16_15.bvh onto $MOCAPSOLVE_DATA/gltf/Xbot.glb (data:
#   ../shared/data), MAX_FRAMES=0 (all frames).
# Environment: MOCAPSOLVE_CLI (default build/bin/mocapsolve), BLENDER (default blender).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cli="${MOCAPSOLVE_CLI:-$root/build/bin/mocapsolve}"
blender="${BLENDER:-blender}"
data="${MOCAPSOLVE_DATA:-$root/../shared/data}"
render=()
positional=()
for a in "$@"; do
  case "$a" in
    --render=*) render=("--render=$(realpath -m "${a#--render=}")" "--render_frame=${RENDER_FRAME:-60}") ;;
    *) positional+=("$a") ;;
  esac
done
source_file="${positional[0]:-$data/bvh/16_15.bvh}"
character="${positional[1]:-$data/gltf/Xbot.glb}"

fail() {
  echo "FAIL: $*"
  exit 1
}
[[ -x "$cli" ]] || fail "$cli not found (build it: cmake --build build --target mocapsolve_cli)"
command -v "$blender" > /dev/null 2>&1 || fail "blender not found (apt-get install blender)"
[[ -f "$source_file" && -f "$character" ]] || fail "$source_file or $character not found"

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
name="$(basename "${character%.*}")"
args=(retarget --quiet --source="$source_file" --target="$character" --animation_name=take
      --max_frames="${MAX_FRAMES:-0}")
"$cli" "${args[@]}" --out="$work/$name.glb" > "$work/full.log" 2>&1 \
  || fail "retarget failed: $(tail -n 1 "$work/full.log")"
"$cli" "${args[@]}" --animation_only --out="$work/${name}_animation.glb" > "$work/slim.log" 2>&1 \
  || fail "retarget --animation_only failed: $(tail -n 1 "$work/slim.log")"
full_bytes="$(stat -c %s "$work/$name.glb")"
slim_bytes="$(stat -c %s "$work/${name}_animation.glb")"
echo "sizes: full $name.glb $full_bytes bytes, animation only $slim_bytes bytes" \
  "($(awk -v a="$slim_bytes" -v b="$full_bytes" 'BEGIN { printf "%.1f", 100 * a / b }') %)"
if "$root/scripts/validate_gltf.sh" "$work/${name}_animation.glb" > "$work/validator.log" 2>&1; then
  echo "validator: $(head -n 1 "$work/validator.log")"
else
  code=$?
  [[ $code -eq 77 ]] && echo "validator unavailable: $(tail -n 1 "$work/validator.log")" \
    || fail "validator: $(cat "$work/validator.log")"
fi

"$blender" -b --factory-startup --python-exit-code 1 --python "$root/scripts/apply_animation_gltf.py" -- \
  "$character" "$work/${name}_animation.glb" --compare="$work/$name.glb" --frames=10 "${render[@]}" \
  > "$work/blender.log" 2>&1 || fail "blender: $(grep -E 'MOCAPSOLVE_APPLY|Error' "$work/blender.log" | tail -n 3)"
result="$(grep -o 'MOCAPSOLVE_APPLY.*' "$work/blender.log" | tail -n 1 || true)"
[[ -n "$result" ]] || fail "blender printed no result; log: $(tail -n 5 "$work/blender.log")"
echo "blender: ${result#MOCAPSOLVE_APPLY }"
worst="$(sed -n 's/.*worst_m=\([^ ]*\).*/\1/p' <<< "$result")"
awk -v w="$worst" 'BEGIN { exit !(w < 1e-4) }' \
  || fail "bones of the character with the applied animation differ from the full file's by $worst m"
echo "PASS: the animation-only glTF plays on $character as the full file does (bones within $worst m)"
