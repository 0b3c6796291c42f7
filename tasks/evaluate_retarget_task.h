// `evaluate --method=retarget`: one source motion retargeted (tasks/retarget_task.h) onto
// each of a list of characters, and the quality figures that do not trust the solve's
// residual (problems/retarget/retarget_quality.h) measured for each, checked against the
// quality gate's retarget thresholds (pipeline/quality_gate.h): one table row per character.
#ifndef MOCAPSOLVE_TASKS_EVALUATE_RETARGET_TASK_H_
#define MOCAPSOLVE_TASKS_EVALUATE_RETARGET_TASK_H_

#include <functional>
#include <string>
#include <vector>

#include "io/json_writer.h"
#include "kinematics/status.h"
#include "pipeline/quality_gate.h"
#include "problems/retarget/retarget_quality.h"
#include "settings/retarget_settings.h"

namespace mocapsolve {

struct EvaluateRetargetInputs {
  std::string source;                   // .bvh, .amc (with skeleton), .fbx, .glb/.gltf.
  std::string skeleton;                 // An .amc source's .asf.
  double amc_fps = 120.0;
  int max_frames = 0;                   // Only the first N frames (0 = all).
  std::vector<std::string> characters;  // .glb/.gltf.
};

struct EvaluateRetargetRow {
  std::string character;  // File stem.
  RetargetQuality quality;
  QualityVerdict verdict;
  double mean_vertex_error = 0.0;  // The residual's view, for comparison (fraction of height).
  double ms_per_frame = 0.0;
};

struct EvaluateRetargetResult {
  std::vector<EvaluateRetargetRow> rows;
  std::string table;      // The console table.
  std::string table_csv;  // One row per character.
  JsonObject report;
};

// Errors: no character, or a retarget that fails (naming the source and the character).
Status RunEvaluateRetarget(const EvaluateRetargetInputs& inputs, const RetargetSettings& retarget,
                           const QualityGate& gate, const std::function<void(int done, int total)>& progress,
                           EvaluateRetargetResult* result);

// The comma-separated list of `text` ("A.glb,B.glb"); empty entries dropped.
std::vector<std::string> SplitCharacterList(const std::string& text);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_TASKS_EVALUATE_RETARGET_TASK_H_
