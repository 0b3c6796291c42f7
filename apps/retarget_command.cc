// mocapsolve retarget: a source character's glTF animation onto a target character by
// their meshes (thesis chapter 4; problems/retarget/).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/progress.h"
#include "apps/retarget_flags.h"
#include "apps/solver_flags.h"
#include "apps/view_flags.h"
#include "io/bvh_writer.h"
#include "io/gltf_reader.h"
#include "io/gltf_writer.h"
#include "io/json_reader.h"
#include "kinematics/rotation.h"
#include "io/motion_file.h"
#include "settings/retarget_settings.h"
#include "problems/retarget/retarget_character.h"

// Shared with other commands: the retarget options (apps/retarget_flags.cc, also read by
// pipeline), --solver (apps/solver_flags.cc; here dls | dls_generic | ceres, and dls when
// not given), --max_frames (apps/solve_command.cc).
DECLARE_int32(max_frames);

DEFINE_string(source, "", "Source motion: a skinned character (.glb/.gltf) or a skeleton motion (.bvh, "
              ".amc with --skeleton=X.asf, .fbx).");
DEFINE_bool(source_mesh, true, "Track a skinned glTF source's own mesh; false: treat it as a "
            "skeleton only (the target's mesh is bound to its skeleton, as for BVH/AMC/FBX).");
DEFINE_string(source_animation, "", "Animation of the source, by name or index (default: the first).");
DEFINE_string(source_skin, "", "Skin of the source file (name or index; default: skin 0).");
DEFINE_string(target_skin, "", "Skin of the target file (name or index; default: skin 0).");
DEFINE_string(out_bvh, "", "Also write the result as BVH (target skeleton, metres).");
DEFINE_string(animation_name, "", "Name of the new animation in --out (.glb/.gltf); default: "
              "'retargeted from <source animation or file>'.");
DEFINE_double(frame_rate, 0.0, "Sampling rate of the source animation; 0 = its key rate.");
DEFINE_int32(loop, 1, "Repeat the source clip N times (timing long clips).");
DEFINE_bool(stage_times, false, "Time FK, skinning, Jacobian and solve separately (dls only; "
            "the report gets each stage's share of an iteration, thesis Table 3).");

namespace mocapsolve {
namespace {

JsonObject Stages(const RetargetStageTimes& stages) {
  const double total = stages.total();
  auto share = [total](double seconds) { return total > 0 ? 100.0 * seconds / total : 0.0; };
  JsonObject out;
  out.Add("iterations", stages.iterations)
      .Add("fk_percent", share(stages.fk))
      .Add("skinning_percent", share(stages.skinning))
      .Add("jacobian_percent", share(stages.jacobian))
      .Add("solve_percent", share(stages.solve))
      .Add("update_percent", share(stages.update))
      .Add("us_per_iteration", stages.iterations > 0 ? 1e6 * total / stages.iterations : 0.0);
  return out;
}

bool HasExtension(const std::string& path, const std::string& extension) {
  return path.size() > extension.size() &&
         path.compare(path.size() - extension.size(), extension.size(), extension) == 0;
}

Status RunRetarget(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  if (FLAGS_source.empty() || FLAGS_target.empty()) return Status::Error("--source and --target are required");
  if (FLAGS_out.empty() && FLAGS_out_bvh.empty()) return Status::Error("--out or --out_bvh is required");
  for (const std::string& out : {FLAGS_out, FLAGS_out_bvh, FLAGS_report}) {
    if (out.empty()) continue;
    for (const std::string& in : {FLAGS_source, FLAGS_target, FLAGS_skeleton, RetargetSettingsFromFlags().joint_map}) {
      if (in.empty()) continue;
      Status status = CheckNotAnInput(out, in);
      if (!status.ok()) return status;
    }
  }
  const bool out_bvh = IsTextOutputPath(FLAGS_out, ".bvh");
  if (!FLAGS_out.empty() && !out_bvh && !HasExtension(FLAGS_out, ".glb") && !HasExtension(FLAGS_out, ".gltf")) {
    return Status::Error("--out: " + FLAGS_out + ": expected .glb, .gltf or .bvh");
  }
  if (FLAGS_animation_only && (FLAGS_out.empty() || out_bvh)) {
    return Status::Error("--animation_only: applies to a .glb/.gltf --out");
  }
  Status status = CheckViewFlag({FLAGS_source, FLAGS_target, FLAGS_skeleton, RetargetSettingsFromFlags().joint_map});
  if (!status.ok()) return status;
  CharacterRetargetOptions options;
  status = RetargetOptionsFromFlags(&options);
  if (!status.ok()) return status;
  if (FLAGS_loop < 1 || FLAGS_loop > 1000) return Status::Error("--loop: must be in [1, 1000]");
  if (FLAGS_max_frames < 0) return Status::Error("--max_frames: must be >= 0");
  options.clip.solve.time_stages = FLAGS_stage_times;
  const RetargetSolveOptions& solve = options.clip.solve;

  const auto start = std::chrono::steady_clock::now();
  GltfDocument target_document;
  SetStage("inputs");
  status = GltfDocument::Read(FLAGS_target, &target_document);
  if (!status.ok()) return status;
  GltfCharacter target;
  GltfReadOptions target_options;
  target_options.skin = FLAGS_target_skin;
  status = ReadGltfCharacter(target_document, target_options, &target);
  if (!status.ok()) return Status::Error("--target: " + status.message());

  // The source: a skinned glTF (its mesh is tracked unless --source_mesh=false) or any
  // motion file (the target's mesh is bound to its skeleton).
  const std::string source_extension = FileExtension(FLAGS_source);
  const bool gltf_source = source_extension == ".glb" || source_extension == ".gltf";
  const bool use_source_mesh = gltf_source && FLAGS_source_mesh;
  GltfCharacter source_character;
  Skeleton source_skeleton;
  Motion clip;
  if (use_source_mesh) {
    GltfDocument source_document;
    status = GltfDocument::Read(FLAGS_source, &source_document);
    if (!status.ok()) return status;
    GltfReadOptions source_options;
    source_options.skin = FLAGS_source_skin;
    status = ReadGltfCharacter(source_document, source_options, &source_character);
    if (!status.ok()) return status;
    GltfAnimationOptions animation_options;
    animation_options.animation = FLAGS_source_animation;
    animation_options.frame_rate = FLAGS_frame_rate;
    status = ReadGltfAnimation(source_document, source_character, animation_options, &clip);
    if (!status.ok()) return status;
  } else {
    if (!FLAGS_source_skin.empty()) return Status::Error("--source_skin: applies to a skinned glTF source only");
    MotionFileOptions motion_options;
    motion_options.skeleton_path = FLAGS_skeleton;
    motion_options.amc_frame_rate = FLAGS_amc_fps;
    motion_options.animation = FLAGS_source_animation;
    motion_options.sample_rate = FLAGS_frame_rate;
    status = ReadMotionFile(FLAGS_source, motion_options, &source_skeleton, &clip);
    if (!status.ok()) return status;
  }
  if (clip.num_frames() == 0) return Status::Error(FLAGS_source + ": the animation has no frames");
  Motion motion;
  motion.frame_rate = clip.frame_rate;
  for (int l = 0; l < FLAGS_loop; ++l) {
    for (const Pose& pose : clip.frames) motion.frames.push_back(pose);
  }
  if (FLAGS_max_frames > 0 && motion.num_frames() > FLAGS_max_frames) motion.frames.resize(FLAGS_max_frames);

  RetargetCharacter source_view;
  if (use_source_mesh) {
    source_view = {&source_character.skeleton, &source_character.mesh, source_character.bind_pose,
                   source_character.rest_pose};
  } else {
    source_view.skeleton = &source_skeleton;
  }
  const RetargetCharacter target_view = {&target.skeleton, &target.mesh, target.bind_pose, target.rest_pose};
  CharacterRetargetResult retarget;
  Progress progress("retarget", motion.num_frames(), FLAGS_quiet);
  SetStage("retarget");
  status = RetargetMotionOntoCharacter(source_view, motion, target_view, options, &retarget,
                                       [&](int done, int) { progress.Update(done); });
  if (!status.ok()) return Status::Error(FLAGS_source + " -> " + FLAGS_target + ": " + status.message());
  const double setup_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() -
      retarget.clip.solve_seconds;
  const RetargetClipResult& result = retarget.clip;
  const RetargetSetup& setup = retarget.setup;
  for (const std::string& note : retarget.notes) {
    if (!FLAGS_quiet) std::fprintf(stderr, "note: %s\n", note.c_str());
  }

  std::string name = FLAGS_animation_name;
  if (name.empty()) {
    std::string from = FLAGS_source_animation;
    if (from.empty()) {
      from = FLAGS_source.substr(FLAGS_source.find_last_of('/') + 1);
    }
    name = "retargeted from " + from;
  }
  SetStage("writing");
  if (!FLAGS_out.empty()) {
    if (out_bvh) {
      status = WriteBvh(FLAGS_out, target.skeleton, result.motion);
    } else {
      GltfWriteOptions write_options;
      write_options.animation_only = FLAGS_animation_only;
      status = WriteGltfWithAnimation(target_document, target, result.motion, name, FLAGS_out, write_options);
    }
    if (!status.ok()) return status;
  }
  // --view: the source's skeleton beside the target character playing the result.
  status = WriteViewFlag([&](ViewScene* scene) {
    const Skeleton& skeleton = use_source_mesh ? source_character.skeleton : source_skeleton;
    ViewTransform transform;
    Status made = MakeMotionViewTransform(FLAGS_source, skeleton, motion, -1, &transform);
    if (!made.ok()) return made;
    scene->title = "retarget: " + FileStem(FLAGS_source) + " -> " + FileStem(FLAGS_target);
    scene->frame_rate = motion.frame_rate > 0 ? motion.frame_rate : 30.0;
    scene->notes.push_back(transform.note);
    scene->skeletons.push_back(MakeViewSkeleton("source: " + FileStem(FLAGS_source), skeleton, motion, transform));
    ViewCharacter character;
    character.name = FileStem(FLAGS_target);
    character.animation = name;
    GltfWriteOptions page_copy;
    page_copy.compact = true;  // Int16 rotations, still joints as one key: the page only plays it.
    made = SerializeGltfWithAnimation(target_document, target, result.motion, name, /*binary=*/true, &character.glb,
                                      page_copy);
    if (made.ok()) scene->characters.push_back(std::move(character));
    return made;
  });
  if (!status.ok()) return status;
  if (!FLAGS_out_bvh.empty()) {
    status = WriteBvh(FLAGS_out_bvh, target.skeleton, result.motion);
    if (!status.ok()) return status;
  }
  int positions = 0;
  for (const TrackedVertex& t : setup.tracked) positions += t.track_position ? 1 : 0;
  const double ms_per_frame = 1e3 * result.solve_seconds / motion.num_frames();
  if (!FLAGS_quiet) {
    std::fprintf(stderr,
                 "%s -> %s (%s): %d frames, %zu tracked vertices (%d by position), %s: vertex error "
                 "%.4f of height (max %.4f), normal error %.2f deg, foot skating %.4f -> %.4f "
                 "heights/s; foot joints in contact: skating %.2f -> %.2f cm/s (%zu planted); %.3f ms/frame\n",
                 FLAGS_source.c_str(), FLAGS_target.c_str(), retarget.skeleton_only ? "skeleton only" : "mesh",
                 motion.num_frames(), setup.tracked.size(), positions, RetargetSolverName(solve.solver),
                 result.mean_position_error, result.max_position_error, result.mean_normal_error_deg,
                 result.source_foot_skating, result.result_foot_skating, retarget.source_plant_skating_cm_s,
                 retarget.result_plant_skating_cm_s, retarget.plant_joints.size(), ms_per_frame);
  }
  JsonObject report;
  std::vector<JsonValue> position_error, normal_error, plant_joints;
  for (const RetargetFrameFigures& f : result.frames) {
    position_error.push_back(f.position_error);
    normal_error.push_back(f.normal_error_deg);
  }
  for (const std::string& joint : retarget.plant_joints) plant_joints.push_back(joint);
  const Skeleton& source_joints = use_source_mesh ? source_character.skeleton : source_skeleton;
  JsonObject joint_map;
  for (int j = 0; j < source_joints.num_joints(); ++j) {
    const int t = retarget.joint_map.target_of_source[j];
    if (t >= 0) joint_map.Add(source_joints.name(j), target.skeleton.name(t));
  }
  report.Add("command", "retarget")
      .Add("source", FLAGS_source)
      .Add("source_animation", FLAGS_source_animation)
      .Add("source_kind", retarget.skeleton_only ? "skeleton" : "mesh")
      .Add("target", FLAGS_target)
      .Add("animation_only", FLAGS_animation_only)
      .Add("solver", RetargetSolverName(solve.solver))
      .Add("frames", motion.num_frames())
      .Add("frame_rate", motion.frame_rate)
      .Add("iterations", solve.iterations)
      .Add("lambda", solve.lambda)
      .Add("subsample", RetargetSettingsFromFlags().subsample)
      .Add("source_vertices", use_source_mesh ? source_character.mesh.num_vertices() : 0)
      .Add("target_vertices", target.mesh.num_vertices())
      .Add("source_joints", source_joints.num_joints())
      .Add("target_joints", target.skeleton.num_joints())
      .Add("mapped_joints", retarget.joint_map.num_mapped())
      .Add("joint_map", joint_map)
      .Add("rest_alignment_mean_bone_angle_deg", retarget.mean_bone_angle_deg)
      .Add("tracked_vertices", static_cast<int>(setup.tracked.size()))
      .Add("position_tracked", positions)
      .Add("height_ratio", setup.scale)
      .Add("sigma_m", result.sigma)
      .Add("mean_position_error_fraction_of_height", result.mean_position_error)
      .Add("max_position_error_fraction_of_height", result.max_position_error)
      .Add("mean_normal_error_deg", result.mean_normal_error_deg)
      .Add("mean_final_cost", result.mean_final_cost)
      .Add("foot_vertices", result.foot_vertices)
      .Add("foot_contact_pairs", result.contact_pairs)
      .Add("source_foot_skating_heights_per_s", result.source_foot_skating)
      .Add("result_foot_skating_heights_per_s", result.result_foot_skating)
      .Add("plant_joints", plant_joints)
      .Add("plant_weight", options.plant_feet ? solve.plant_weight : 0.0)
      .Add("contact_samples", retarget.contact_samples)
      .Add("plant_contact_pairs", retarget.plant_pairs)
      .Add("source_plant_skating_cm_per_s", retarget.source_plant_skating_cm_s)
      .Add("result_plant_skating_cm_per_s", retarget.result_plant_skating_cm_s)
      .Add("setup_seconds", setup_seconds)
      .Add("solve_seconds", result.solve_seconds)
      .Add("ms_per_frame", ms_per_frame)
      .Add("per_frame_position_error", position_error)
      .Add("per_frame_normal_error_deg", normal_error);
  if (FLAGS_stage_times) report.Add("stages", Stages(result.stages));
  return WriteReport(report);
}

const std::string kRetargetFlags = std::string("target,out,report,quiet,max_frames,skeleton,amc_fps,view,"
                                               "animation_only,") +
                                   "foot_joints";

}  // namespace

extern const Command kRetargetCommand = {
    "retarget", "transfer a motion (glTF, BVH, AMC, FBX) onto a glTF character by meshes (thesis ch. 4)",
    "mocapsolve retarget --source=SRC.glb|.bvh|.amc|.fbx [--skeleton=X.asf] [--source_animation=NAME] --target=TGT.glb "
    "--out=OUT.glb|.gltf|.bvh [--animation_only] [--out_bvh=OUT.bvh] [--animation_name=NAME] [--solver=dls|dls_generic|ceres] [--subsample=128] "
    "[--iterations=10] [--lambda=5] [--blend_mask=auto|FILE.json] [--report=r.json] [--view=PAGE.html]\n\n"
    "Subsamples the source mesh (farthest points, normal check, >= 3 per joint), maps the samples\n"
    "to the nearest target vertices in a height-normalized rest frame, and solves each frame's\n"
    "target pose (root translation and joint rotations) so that the target vertices track the\n"
    "source's: hands, feet and head by position, the rest by normals. The skeletons may differ.\n"
    "A skeleton-only source (BVH, AMC, FBX; or --source_mesh=false) gets the target's mesh bound\n"
    "to its skeleton after aligning the rest poses (joints mapped by name, --joint_map overrides).\n"
    "Feet are planted where the source's foot joints are in contact (--plant_feet).\n"
    "A .glb/.gltf --out is the target file with the result added as a new animation; with\n"
    "--animation_only just the target's skeleton, skin and that animation (no meshes), to play\n"
    "on the target file an application already has (Blender: scripts/apply_animation_gltf.py).\n"
    "--solver: dls (the default here: the lean DLS kernel, eq. 18), dls_generic\n"
    "(solvers/dls_solver.h on the same residual blocks) or ceres (Levenberg-Marquardt).",
    __FILE__, RunRetarget, kRetargetFlags.c_str(), {RetargetSolverOptions().options(), RetargetSettingOptions().options()}};

}  // namespace mocapsolve
