// `mocapsolve convert IN OUT`: a motion (BVH, ASF/AMC, glTF/GLB, FBX) written as BVH, as
// binary FBX (its skeleton, or a glTF character with its skinned mesh), or as a new clip of
// a glTF character; marker files between C3D and TRC (unit and axes changed, samples kept).
// The motion is cut and resampled first when `delivery` says so. OUT is written atomically
// and may not name an input; every refusal is one line naming the option or the file.
#ifndef MOCAPSOLVE_TASKS_CONVERT_TASK_H_
#define MOCAPSOLVE_TASKS_CONVERT_TASK_H_

#include <string>
#include <vector>

#include "io/json_writer.h"
#include "io/motion_file.h"
#include "kinematics/status.h"
#include "settings/convert_settings.h"
#include "signal/clip_delivery.h"

namespace mocapsolve {

struct ConvertInputs {
  std::string in, out;
  std::string target;          // A glTF character (glTF/FBX output; "" = IN when IN is one).
  MotionFileOptions motion;    // How IN is read (its warnings go to ConvertResult::warnings).
  std::string axes = "x,y,z";  // Marker files: OUT's axes (x, y, z) = IN's axes.
};

struct ConvertResult {
  std::string summary;                // "wrote OUT: ..." (one line).
  JsonObject report;                  // What --report records.
  std::vector<std::string> warnings;  // The motion reader's.
};

Status RunConvert(const ConvertInputs& inputs, const ConvertSettings& settings, const ClipDelivery& delivery,
                  ConvertResult* result);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_TASKS_CONVERT_TASK_H_
