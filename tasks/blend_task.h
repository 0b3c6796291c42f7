// `mocapsolve blend`: a transition from clip A to clip B (Huang, Boulic & Thalmann, section
// 3; signal/motion_blend.h) over a window given in frames or seconds of A, and how smooth
// it is: the largest velocity jump (skeleton units per frame) around the window against the
// largest of each input anywhere.
#ifndef MOCAPSOLVE_TASKS_BLEND_TASK_H_
#define MOCAPSOLVE_TASKS_BLEND_TASK_H_

#include <string>

#include "io/json_writer.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "settings/blend_settings.h"
#include "signal/laplacian_pyramid.h"

namespace mocapsolve {

// The two clips (the same joints, by name and order) and their names for messages.
struct BlendInputs {
  const Skeleton* skeleton_a = nullptr;
  const Motion* a = nullptr;
  const Skeleton* skeleton_b = nullptr;
  const Motion* b = nullptr;
  std::string a_name, b_name;
};

struct BlendTaskResult {
  Motion blended;       // On A's skeleton.
  JsonObject report;    // method, window, b_start, frames, velocity jumps, units.
  std::string summary;  // What the CLI prints after "wrote OUT: ".
};

// `method`: multires | weighted; `pyramid`: the kernel (its levels are settings.blend_levels).
Status RunBlend(const BlendInputs& inputs, const std::string& method, const BlendSettings& settings,
                const PyramidOptions& pyramid, BlendTaskResult* result);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_TASKS_BLEND_TASK_H_
