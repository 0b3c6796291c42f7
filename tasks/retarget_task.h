// `retarget` as one function (thesis chapter 4; problems/retarget/retarget_character.h): a
// source motion (a skinned glTF whose mesh is tracked, or any skeleton motion: BVH, AMC,
// FBX, a glTF without its mesh) onto a skinned glTF character. The CLI
// (apps/retarget_command.cc: flags, files, the page) and Python's retarget() both call it.
#ifndef MOCAPSOLVE_TASKS_RETARGET_TASK_H_
#define MOCAPSOLVE_TASKS_RETARGET_TASK_H_

#include <string>

#include "io/gltf_reader.h"
#include "io/json_writer.h"
#include "kinematics/motion.h"
#include "kinematics/status.h"
#include "pipeline/quality_gate.h"
#include "problems/retarget/retarget_character.h"
#include "settings/retarget_settings.h"
#include "signal/clip_delivery.h"
#include "viewer/view_scene.h"

namespace mocapsolve {

struct RetargetInputs {
  std::string source;            // .glb/.gltf, .bvh, .amc (with skeleton), .fbx.
  std::string target;            // .glb/.gltf.
  std::string skeleton;          // An .amc source's .asf.
  std::string source_animation;  // The source file's clip (name or index; "" = the first).
  std::string source_skin, target_skin;  // Skins by name or index ("" = skin 0).
  bool source_mesh = true;       // Track a skinned glTF source's own mesh.
  double frame_rate = 0.0;       // Resample the source to this rate (0 = its own).
  double amc_fps = 120.0;        // An .amc's frame rate.
  int max_frames = 0;            // Only the first N frames (0 = all).
  int loop = 1;                  // Repeat the source clip N times (timing long clips).
};

struct RetargetConfig {
  RetargetSettings retarget;
  // The written clip (WriteRetargeted; the CLI's --out_bvh): retarget.clip.motion cut and
  // resampled (signal/clip_delivery.h), the range checked once the source is read.
  ClipDelivery delivery;
  bool stage_times = false;  // Time FK, skinning, Jacobian and solve separately (dls only).
  // The retarget checks of the quality gate (pipeline/quality_gate.h: limb directions, skate,
  // penetration, own-skeleton joint error, coverage) for the report's "quality" verdict.
  QualityGate gate;
};

struct RetargetTaskResult {
  GltfDocument target_document;
  GltfCharacter target;
  GltfCharacter source_character;  // A tracked glTF source (source_mesh_used).
  Skeleton source_skeleton;        // Any other source.
  bool source_mesh_used = false;
  Motion source_motion;            // The source clip as retargeted (looped, cut).
  CharacterRetargetResult retarget;  // retarget.clip.motion: the result on the target.
  Motion delivered;                  // It as written: cut and resampled (RetargetConfig::delivery).
  double setup_seconds = 0.0;        // Reading and set-up: the wall time besides the solves.
  // What --report records (errors as fractions of the target's height, cm/s, degrees,
  // seconds; the joint map; per-frame errors).
  JsonObject report;

  const Skeleton& source_joints() const {
    return source_mesh_used ? source_character.skeleton : source_skeleton;
  }
};

// Errors: invalid options (naming the option), unreadable inputs (naming the file), or a
// pair that cannot be retargeted ("SOURCE -> TARGET: ...").
Status RunRetarget(const RetargetInputs& inputs, const RetargetConfig& config,
                   const RetargetProgressCallback& progress, RetargetTaskResult* result);

// The new clip's name in a written glTF: `name`, or "retargeted from <source clip or file>".
std::string RetargetAnimationName(const RetargetInputs& inputs, const std::string& name);

// Writes the delivered result to `out`: a .bvh (the target skeleton), a .glb/.gltf (the target file
// with the result added as a new animation; animation_only: skeleton, skin and animation),
// or a .fbx (io/fbx_writer.h: the target's skeleton, mesh unless animation_only, the result
// as the take named `animation_name`, keys reduced within fbx_key_tolerance_mm).
Status WriteRetargeted(const std::string& out, const RetargetTaskResult& result, const std::string& animation_name,
                       bool animation_only, double fbx_key_tolerance_mm = 0.0);

// The console line after RunRetarget: frames, tracked vertices, the vertex, normal and
// foot-skating errors and the time per frame.
std::string RetargetSummary(const RetargetInputs& inputs, const RetargetConfig& config,
                            const RetargetTaskResult& result);

// The page of `retarget --view`: the source's skeleton beside the target character playing
// the result (its animation `animation_name`).
Status MakeRetargetViewScene(const RetargetInputs& inputs, const RetargetTaskResult& result,
                             const std::string& animation_name, ViewScene* scene);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_TASKS_RETARGET_TASK_H_
