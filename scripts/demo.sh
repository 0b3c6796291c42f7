#!/usr/bin/env bash
# The bundled default through every capability: generate the project's own demo clip,
# inspect it, convert it, run forward kinematics, solve and repair its markers, filter,
# edit and retarget; then the main job, `mocapsolve pipeline`: one take from markers to an
# animated character (on the demo take, and on CMU 02_05 onto Xbot when ../shared/data is there).
# Outputs go to out/demo/ (override with MOCAPSOLVE_DEMO_OUT).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/setup.sh
out=${MOCAPSOLVE_DEMO_OUT:-out/demo}
mkdir -p "$out"
ms=build/bin/mocapsolve

echo; echo "== 1. generate: the bundled default clip (procedural walk, made by the project)"
$ms generate --demo_out="$out/walk.bvh" --frames=240 --fps=60

echo; echo "== 2. info"
$ms info "$out/walk.bvh" --report="$out/info.json"

echo; echo "== 3. convert: centimetres to metres, every joint to XYZ Euler order"
$ms convert "$out/walk.bvh" "$out/walk_m_xyz.bvh" --scale=0.01 --euler_order=XYZ

echo; echo "== 4. fk: global joint positions per frame"
$ms fk --motion="$out/walk.bvh" --out="$out/walk_positions.csv" --quiet
head -4 "$out/walk_positions.csv"

echo; echo "== 5. bench: forward kinematics throughput"
$ms bench --problem=fk --repeats=3 --json="$out/bench_fk.json" | grep -v '^JSON'

echo; echo "== 6. markers: synthesize a C3D from the clip (3 markers per bone, 1 mm noise)"
$ms markers --motion="$out/walk.bvh" --skeleton_units=cm --markerset=auto:3 \
  --write_markerset="$out/true_markerset.json" --noise_mm=1 --seed=7 --out="$out/walk_markers.c3d"
$ms info "$out/walk_markers.c3d"

echo; echo "== 7. calibrate: where each marker rides, from the clip and its markers"
$ms calibrate --motion="$out/walk.bvh" --skeleton_units=cm --markers="$out/walk_markers.c3d" \
  --attach=auto --out="$out/calibrated_markerset.json" | tail -1

echo; echo "== 8. solve: joint angles from the markers, Ceres and DLS on the same residuals"
for solver in ceres dls; do
  $ms solve --quiet --skeleton="$out/walk.bvh" --skeleton_units=cm --markers="$out/walk_markers.c3d" \
    --markerset="$out/calibrated_markerset.json" --solver=$solver --out="$out/solved_$solver.bvh" \
    --report="$out/solve_$solver.json" --plot="$out/solve_${solver}_residual.svg"
done

echo; echo "== 9. solve --mode=clip: all frames as one sparse problem with smoothness"
$ms solve --quiet --skeleton="$out/walk.bvh" --skeleton_units=cm --markers="$out/walk_markers.c3d" \
  --markerset="$out/calibrated_markerset.json" --solver=dls --mode=clip --out="$out/solved_clip.bvh" \
  --report="$out/solve_clip.json"

echo; echo "== 10. bench: both solvers on the same per-frame problems"
$ms bench --problem=marker_solve --repeats=3 --bench_skeleton="$out/walk.bvh" --skeleton_units=cm \
  --bench_markers="$out/walk_markers.c3d" --bench_markerset="$out/calibrated_markerset.json" \
  --json="$out/bench_marker_solve.json" | grep -v '^JSON'

echo; echo "== 11. filter and blend: multiresolution (Laplacian pyramid) filtering of the clip"
$ms filter --motion="$out/walk.bvh" --levels=2 --out="$out/walk_filtered.bvh"
$ms blend --a="$out/walk.bvh" --b="$out/walk_filtered.bvh" --transition=100:112 --b_start=0 \
  --out="$out/walk_blend.bvh"

echo; echo "== 12. repair: damage the markers, find the broken intervals against a robust reference, refill"
$ms corrupt --markers="$out/walk_markers.c3d" --out="$out/walk_markers_damaged.c3d" \
  --mask_out="$out/walk_damage.csv" --gaps=6 --swaps=1
$ms repair --quiet --skeleton="$out/walk.bvh" --skeleton_units=cm --markers="$out/walk_markers_damaged.c3d" \
  --markerset="$out/calibrated_markerset.json" --out_markers="$out/walk_markers_repaired.c3d" \
  --report="$out/repair.json" | head -1
echo "-- evaluate: repair against linear, polynomial, PCA and reference-only fills on the same damage"
$ms evaluate --quiet --skeleton="$out/walk.bvh" --skeleton_units=cm --markers="$out/walk_markers.c3d" \
  --markerset="$out/calibrated_markerset.json" --gaps=6 --swaps=1 --report="$out/evaluate.json" | head -11
echo "-- evaluate --method=leave_one_out: each marker predicted by the solve of the others (no ground truth needed)"
$ms evaluate --quiet --method=leave_one_out --skeleton="$out/walk.bvh" --skeleton_units=cm \
  --markers="$out/walk_markers.c3d" --markerset="$out/calibrated_markerset.json" \
  --report="$out/leave_one_out.json" | tail -1

echo; echo "== 13. edit propagation: the falloff of a pose edit through the walk, and the edit itself"
$ms distance --motion="$out/walk.bvh" --frame=60 --method=green,isomap --out="$out/falloff.csv" \
  --plot="$out/falloff.svg" --report="$out/falloff.json" | tail -2
cat > "$out/edit.json" <<'JSON'
{"comment": "raise the left arm 30 degrees at frame 60", "frame": 60,
 "joints": {"LeftArm": {"rotation_offset_deg": [0, 0, 30]}}}
JSON
$ms propagate --motion="$out/walk.bvh" --skeleton_units=cm --edit="$out/edit.json" --keep_contacts \
  --out="$out/walk_edited.bvh" --weights_csv="$out/edit_weights.csv" --report="$out/edit_report.json" | tail -2

echo; echo "== 14. retarget: CesiumMan's walk onto RiggedFigure (other proportions), by mesh vertices"
gltf_dir="${MOCAPSOLVE_DATA:-../shared/data}/gltf"
if [ -f "$gltf_dir/CesiumMan.glb" ] && [ -f "$gltf_dir/RiggedFigure.glb" ]; then
  $ms retarget --source="$gltf_dir/CesiumMan.glb" --target="$gltf_dir/RiggedFigure.glb" \
    --out="$out/riggedfigure_walk.glb" --out_bvh="$out/riggedfigure_walk.bvh" --report="$out/retarget.json" 2>&1 | tail -1
  echo "-- joint_map: the bundled walk's skeleton onto RiggedFigure, found by body roles (an editable --joint_map file)"
  $ms joint_map --source="$out/walk.bvh" --target="$gltf_dir/RiggedFigure.glb" --out="$out/joint_map.json" &&
    grep -m1 '"confidence"' "$out/joint_map.json"
else
  echo "(skipped: no $gltf_dir/CesiumMan.glb; set MOCAPSOLVE_DATA to the shared data folder)"
fi

echo; echo "== 15. pipeline: the main job, one take end to end (subject, repair and solve, characters)"
$ms calibrate --quiet --motion="$out/walk.bvh" --skeleton_units=cm --markers="$out/walk_markers.c3d" \
  --attach=auto --out="$out/walk_subject_markerset.json" --out_subject="$out/walk_subject.json" | tail -1
characters=()
[ -f "$gltf_dir/Xbot.glb" ] && characters=(--character="$gltf_dir/Xbot.glb")
$ms pipeline --quiet --subject="$out/walk_subject.json" --markers="$out/walk_markers_damaged.c3d" \
  "${characters[@]}" --out_dir="$out/pipeline_walk"
echo "-- label: the damaged take's points named again from the subject alone (its labels ignored: any"
echo "   order, ghosts, dropouts), as for a raw capture before labelling"
$ms label --subject="$out/walk_subject.json" --markers="$out/walk_markers_damaged.c3d" \
  --out="$out/walk_labelled.c3d" --report="$out/label.json" 2>/dev/null | head -1
echo "-- live: the take replayed as a stream (as fast as possible), each frame solved as it arrives"
$ms live --quiet --subject="$out/walk_subject.json" --input="replay:$out/walk_markers.c3d" --replay_speed=0 \
  --output=- --report="$out/live.json" > "$out/walk_live.jsonl"
/usr/bin/python3 -c "import json,sys; r=json.load(open(sys.argv[1])); print('live: %d frames in, %d out, latency median %.3f ms, p99 %.3f ms' % (r['frames_in'], r['frames_out'], r['latency_ms']['median'], r['latency_ms']['p99']))" "$out/live.json" 2>/dev/null || true
data_dir="${MOCAPSOLVE_DATA:-../shared/data}"
if [ -f "$data_dir/c3d/cmu_02_05.c3d" ] && [ -f "$data_dir/gltf/Xbot.glb" ]; then
  echo "-- CMU 02_05 onto Xbot, with the subject calibrated once on 02_01"
  $ms calibrate --quiet --motion="$data_dir/amc/02_01.amc" --skeleton="$data_dir/amc/02.asf" \
    --markers="$data_dir/c3d/02_01.c3d" --axes=y,z,x --out="$out/cmu02_markerset.json" \
    --out_subject="$out/cmu02_subject.json" | tail -1
  $ms pipeline --quiet --subject="$out/cmu02_subject.json" --markers="$data_dir/c3d/cmu_02_05.c3d" \
    --character="$data_dir/gltf/Xbot.glb" --formats=glb,fbx --out_dir="$out/pipeline_02_05"
  echo "outputs: $out/pipeline_02_05/ (repaired.c3d, solved.bvh, Xbot.glb and Xbot.fbx with the take as animation 'cmu_02_05', report.json)"
  echo "-- CMU 02_01 onto Xbot with no subject at all: fitted from the take first (--subject=auto; 10 s, 35 s on a loaded machine)"
  $ms pipeline --quiet --subject=auto --markers="$data_dir/c3d/02_01.c3d" --character="$data_dir/gltf/Xbot.glb" \
    --view=off --out_dir="$out/pipeline_02_01_auto" | sed -n 1p
fi

# Every promised output must be there: a missing one fails the demo loudly (a step that
# only warned, such as a page the viewer runtime could not write, is caught here).
promised=(walk.bvh info.json walk_m_xyz.bvh walk_positions.csv walk_markers.c3d calibrated_markerset.json
          solved_ceres.bvh solved_dls.bvh solved_clip.bvh walk_filtered.bvh walk_blend.bvh
          walk_markers_damaged.c3d walk_markers_repaired.c3d repair.json evaluate.json leave_one_out.json
          falloff.csv walk_edited.bvh walk_subject.json pipeline_walk/report.json pipeline_walk/solved.bvh
          pipeline_walk/repaired.c3d pipeline_walk/view.html walk_labelled.c3d label.json walk_live.jsonl live.json)
[ -f "$data_dir/c3d/cmu_02_05.c3d" ] && [ -f "$data_dir/gltf/Xbot.glb" ] &&
  promised+=(pipeline_02_05/report.json pipeline_02_05/Xbot.glb pipeline_02_05/Xbot.fbx pipeline_02_05/view.html
             pipeline_02_01_auto/subject.json pipeline_02_01_auto/Xbot.glb)
[ -f "$gltf_dir/CesiumMan.glb" ] && [ -f "$gltf_dir/RiggedFigure.glb" ] && promised+=(riggedfigure_walk.glb)
absent=()
for file in "${promised[@]}"; do [ -s "$out/$file" ] || absent+=("$file"); done
if [ ${#absent[@]} -gt 0 ]; then
  echo "demo: FAILED: promised outputs missing in $out/: ${absent[*]}" >&2
  exit 1
fi

echo
echo "Done. Outputs in $out/:"
ls -1 "$out" | sed 's/^/  /'
echo "Real data: see README.md (\"Running on real files\")."
