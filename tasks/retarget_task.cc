#include "tasks/retarget_task.h"

#include <chrono>
#include <vector>

#include "tasks/console_text.h"
#include "io/bvh_writer.h"
#include "io/fbx_writer.h"
#include "io/gltf_writer.h"
#include "io/motion_file.h"
#include "pipeline/retarget_quality_report.h"
#include "tasks/joint_map_task.h"

namespace mocapsolve {
namespace {

JsonObject StagesJson(const RetargetStageTimes& stages) {
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

// The source clip: a skinned glTF's animation (its mesh tracked) or any motion file.
Status ReadSource(const RetargetInputs& inputs, RetargetTaskResult* result, Motion* clip) {
  const std::string extension = FileExtension(inputs.source);
  result->source_mesh_used = (extension == ".glb" || extension == ".gltf") && inputs.source_mesh;
  if (result->source_mesh_used) {
    GltfDocument document;
    Status status = GltfDocument::Read(inputs.source, &document);
    if (!status.ok()) return status;
    GltfReadOptions read_options;
    read_options.skin = inputs.source_skin;
    status = ReadGltfCharacter(document, read_options, &result->source_character);
    if (!status.ok()) return status;
    GltfAnimationOptions animation_options;
    animation_options.animation = inputs.source_animation;
    animation_options.frame_rate = inputs.frame_rate;
    return ReadGltfAnimation(document, result->source_character, animation_options, clip);
  }
  if (!inputs.source_skin.empty()) return Status::Error("--source_skin: applies to a skinned glTF source only");
  MotionFileOptions motion_options;
  motion_options.skeleton_path = inputs.skeleton;
  motion_options.amc_frame_rate = inputs.amc_fps;
  motion_options.animation = inputs.source_animation;
  motion_options.sample_rate = inputs.frame_rate;
  return ReadMotionFile(inputs.source, motion_options, &result->source_skeleton, clip);
}

JsonObject RetargetReportJson(const RetargetInputs& inputs, const CharacterRetargetOptions& options,
                              const RetargetConfig& config, const RetargetTaskResult& task) {
  const CharacterRetargetResult& retarget = task.retarget;
  const RetargetClipResult& result = retarget.clip;
  const RetargetSetup& setup = retarget.setup;
  const RetargetSolveOptions& solve = options.clip.solve;
  const Skeleton& source_joints = task.source_joints();
  const int frames = task.source_motion.num_frames();
  int positions = 0;
  for (const TrackedVertex& t : setup.tracked) positions += t.track_position ? 1 : 0;
  std::vector<JsonValue> position_error, normal_error, plant_joints;
  for (const RetargetFrameFigures& f : result.frames) {
    position_error.push_back(f.position_error);
    normal_error.push_back(f.normal_error_deg);
  }
  for (const std::string& joint : retarget.plant_joints) plant_joints.push_back(joint);
  JsonObject joint_map;
  for (int j = 0; j < source_joints.num_joints(); ++j) {
    const int t = retarget.joint_map.target_of_source[j];
    if (t >= 0) joint_map.Add(source_joints.name(j), task.target.skeleton.name(t));
  }
  const JsonObject joint_roles = JointMapRolesJson(retarget.joint_map, source_joints, task.target.skeleton);
  const std::vector<JsonValue> notes(retarget.notes.begin(), retarget.notes.end());
  QualityVerdict verdict;
  CheckRetargetQuality(config.gate, retarget.quality, FileStem(inputs.target), &verdict);
  JsonObject report;
  report.Add("source", inputs.source)
      .Add("source_animation", inputs.source_animation)
      .Add("source_kind", retarget.skeleton_only ? "skeleton" : "mesh")
      .Add("target", inputs.target)
      .Add("solver", SolverKindName(solve.solver))
      .Add("frames", frames)
      .Add("frame_rate", task.source_motion.frame_rate)
      .Add("iterations", solve.iterations)
      .Add("lambda", solve.lambda)
      .Add("subsample", config.retarget.subsample)
      .Add("source_vertices", task.source_mesh_used ? task.source_character.mesh.num_vertices() : 0)
      .Add("target_vertices", task.target.mesh.num_vertices())
      .Add("source_joints", source_joints.num_joints())
      .Add("target_joints", task.target.skeleton.num_joints())
      .Add("mapped_joints", retarget.joint_map.num_mapped())
      .Add("joint_map", joint_map)
      .Add("joint_map_roles", joint_roles)
      .Add("joint_map_confidence", retarget.joint_map.confidence)
      .Add("rest_alignment_mean_bone_angle_deg", retarget.mean_bone_angle_deg)
      .Add("tracked_vertices", static_cast<int>(setup.tracked.size()))
      .Add("position_tracked", positions)
      .Add("height_ratio", setup.scale)
      .Add("sigma_m", result.sigma)
      .Add("mean_position_error_fraction_of_height", result.mean_position_error)
      .Add("max_position_error_fraction_of_height", result.max_position_error)
      .Add("mean_normal_error_deg", result.mean_normal_error_deg)
      .Add("mean_effector_error_fraction_of_height", result.mean_effector_error)
      .Add("mean_final_cost", result.mean_final_cost)
      .Add("foot_vertices", result.foot_vertices)
      .Add("foot_contact_pairs", result.contact_pairs)
      .Add("source_foot_skating_heights_per_s", result.source_foot_skating)
      .Add("result_foot_skating_heights_per_s", result.result_foot_skating)
      .Add("plant_joints", plant_joints)
      .Add("plant_weight", options.plant_feet ? solve.plant_weight : 0.0)
      .Add("floor_weight", options.floor_weight)
      .Add("contact_samples", retarget.contact_samples)
      .Add("plant_contact_pairs", retarget.plant_pairs)
      .Add("source_plant_skating_cm_per_s", retarget.source_plant_skating_cm_s)
      .Add("result_plant_skating_cm_per_s", retarget.result_plant_skating_cm_s)
      .Add("quality", RetargetQualityJson(retarget.quality, verdict.failures))
      .Add("delivered_frames", task.delivered.num_frames())
      .Add("delivered_frame_rate", task.delivered.frame_rate)
      .Add("setup_seconds", task.setup_seconds)
      .Add("solve_seconds", result.solve_seconds)
      .Add("ms_per_frame", frames > 0 ? 1e3 * result.solve_seconds / frames : 0.0)
      .Add("notes", notes)
      .Add("per_frame_position_error", position_error)
      .Add("per_frame_normal_error_deg", normal_error);
  if (config.stage_times) report.Add("stages", StagesJson(result.stages));
  return report;
}

}  // namespace

Status RunRetarget(const RetargetInputs& inputs, const RetargetConfig& config,
                   const RetargetProgressCallback& progress, RetargetTaskResult* result) {
  CharacterRetargetOptions options;
  Status status = RetargetOptionsFromSettings(config.retarget, &options);
  if (!status.ok()) return status;
  if (inputs.loop < 1 || inputs.loop > 1000) return Status::Error("--loop: must be in [1, 1000]");
  if (inputs.max_frames < 0) return Status::Error("--max_frames: must be >= 0");
  options.clip.solve.time_stages = config.stage_times;

  const auto start = std::chrono::steady_clock::now();
  status = GltfDocument::Read(inputs.target, &result->target_document);
  if (!status.ok()) return status;
  GltfReadOptions target_options;
  target_options.skin = inputs.target_skin;
  status = ReadGltfCharacter(result->target_document, target_options, &result->target);
  if (!status.ok()) return Status::Error("--target: " + status.message());
  Motion clip;
  status = ReadSource(inputs, result, &clip);
  if (!status.ok()) return status;
  if (clip.num_frames() == 0) return Status::Error(inputs.source + ": the animation has no frames");
  Motion& motion = result->source_motion;
  motion = Motion();
  motion.frame_rate = clip.frame_rate;
  for (int l = 0; l < inputs.loop; ++l) {
    for (const Pose& pose : clip.frames) motion.frames.push_back(pose);
  }
  if (inputs.max_frames > 0 && motion.num_frames() > inputs.max_frames) motion.frames.resize(inputs.max_frames);
  int first = 0, last = 0;  // The delivered range, checked before the solve.
  status = ResolveClipRange(config.delivery.range, motion.num_frames(), motion.frame_rate, &first, &last);
  if (!status.ok()) return Status::Error(inputs.source + ": " + status.message());

  RetargetCharacter source_view;
  if (result->source_mesh_used) {
    const GltfCharacter& s = result->source_character;
    source_view = {&s.skeleton, &s.mesh, s.bind_pose, s.rest_pose};
  } else {
    source_view.skeleton = &result->source_skeleton;
  }
  const GltfCharacter& t = result->target;
  const RetargetCharacter target_view = {&t.skeleton, &t.mesh, t.bind_pose, t.rest_pose};
  status = RetargetMotionOntoCharacter(source_view, motion, target_view, options, &result->retarget, progress);
  if (!status.ok()) return Status::Error(inputs.source + " -> " + inputs.target + ": " + status.message());
  // What the reader approximated or made up (normals computed, scales) is part of the answer.
  for (const std::string& warning : t.warnings) result->retarget.notes.push_back(warning);
  result->setup_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() -
                          result->retarget.clip.solve_seconds;
  status = DeliverClip(result->retarget.clip.motion, config.delivery, &result->delivered);
  if (!status.ok()) return Status::Error(inputs.source + ": " + status.message());
  result->report = RetargetReportJson(inputs, options, config, *result);
  return Status::Ok();
}

std::string RetargetAnimationName(const RetargetInputs& inputs, const std::string& name) {
  if (!name.empty()) return name;
  const std::string from = inputs.source_animation.empty()
                               ? inputs.source.substr(inputs.source.find_last_of('/') + 1)
                               : inputs.source_animation;
  return "retargeted from " + from;
}

Status WriteRetargeted(const std::string& out, const RetargetTaskResult& result, const std::string& animation_name,
                       bool animation_only, double fbx_key_tolerance_mm) {
  const Motion& motion = result.delivered;
  if (IsTextOutputPath(out, ".bvh")) return WriteBvh(out, result.target.skeleton, motion);  // "-": stdout.
  if (FileExtension(out) == ".fbx") {
    return WriteFbxCharacter(out, result.target, motion, animation_name, animation_only, fbx_key_tolerance_mm);
  }
  GltfWriteOptions write_options;
  write_options.animation_only = animation_only;
  return WriteGltfWithAnimation(result.target_document, result.target, motion, animation_name, out, write_options);
}

std::string RetargetSummary(const RetargetInputs& inputs, const RetargetConfig& config,
                            const RetargetTaskResult& task) {
  const CharacterRetargetResult& retarget = task.retarget;
  const RetargetClipResult& result = retarget.clip;
  const Motion& motion = task.source_motion;
  int positions = 0;
  for (const TrackedVertex& t : retarget.setup.tracked) positions += t.track_position ? 1 : 0;
  std::string text;
  AppendF(&text,
          "%s -> %s (%s): %d frames, %zu tracked vertices (%d by position), %s: vertex error %.4f of height (max "
          "%.4f), normal error %.2f deg, foot skating %.4f -> %.4f heights/s; foot joints in contact: skating %.2f -> "
          "%.2f cm/s (%zu planted); %.3f ms/frame\n",
          inputs.source.c_str(), inputs.target.c_str(), retarget.skeleton_only ? "skeleton only" : "mesh",
          motion.num_frames(), retarget.setup.tracked.size(), positions, config.retarget.solver.c_str(),
          result.mean_position_error, result.max_position_error, result.mean_normal_error_deg,
          result.source_foot_skating, result.result_foot_skating, retarget.source_plant_skating_cm_s,
          retarget.result_plant_skating_cm_s, retarget.plant_joints.size(),
          1e3 * result.solve_seconds / motion.num_frames());
  QualityVerdict verdict;
  CheckRetargetQuality(config.gate, retarget.quality, FileStem(inputs.target), &verdict);
  text += "quality: " + RetargetQualityLine(retarget.quality) + (verdict.pass ? ": pass\n" : ": FAIL\n");
  for (const std::string& failure : verdict.failures) text += "  " + failure + "\n";
  return text;
}

Status MakeRetargetViewScene(const RetargetInputs& inputs, const RetargetTaskResult& task,
                             const std::string& animation_name, ViewScene* scene) {
  const Skeleton& skeleton = task.source_joints();
  const Motion& motion = task.source_motion;
  ViewTransform transform;
  Status made = MakeMotionViewTransform(inputs.source, skeleton, motion, -1, &transform);
  if (!made.ok()) return made;
  scene->title = "retarget: " + FileStem(inputs.source) + " -> " + FileStem(inputs.target);
  scene->frame_rate = motion.frame_rate > 0 ? motion.frame_rate : 30.0;
  scene->notes.push_back(transform.note);
  scene->skeletons.push_back(MakeViewSkeleton("source: " + FileStem(inputs.source), skeleton, motion, transform));
  ViewCharacter character;
  character.name = FileStem(inputs.target);
  character.animation = animation_name;
  GltfWriteOptions page_copy;
  page_copy.compact = true;  // Int16 rotations, still joints as one key: the page only plays it.
  made = SerializeGltfWithAnimation(task.target_document, task.target, task.retarget.clip.motion, animation_name,
                                    /*binary=*/true, &character.glb, page_copy);
  if (made.ok()) scene->characters.push_back(std::move(character));
  return made;
}

}  // namespace mocapsolve
