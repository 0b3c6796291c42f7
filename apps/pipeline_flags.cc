#include "apps/pipeline_flags.h"

#include "apps/delivery_flags.h"
#include "apps/option_flags.h"
#include "apps/pyramid_flags.h"
#include "apps/repair_flags.h"
#include "apps/retarget_flags.h"
#include "pipeline/quality_gate.h"
#include "settings/delivery_settings.h"
#include "settings/pyramid_settings.h"
#include "settings/repair_settings.h"
#include "settings/retarget_settings.h"

DEFINE_string(take_name, "", "The take's name: the characters' new animation (default: the marker "
              "file's name without extension).");
DEFINE_int32(filter_levels, 0, "Filter the solved motion: drop the N finest bands of its Laplacian "
             "pyramid (as `filter --levels=N`); 0 = no filtering.");

namespace mocapsolve {

const std::string& PipelineOptionFlags() {
  static const std::string* const names = new std::string(
      std::string("take_name,filter_levels,") + PyramidSettingOptions().Names() + "," + QualityGateOptions().Names() +
      ",animation_only," + DeliverySettingOptions().Names() + "," + RepairSettingOptions().Names() + "," +
      RepairSolverOptions().Names() + "," + RetargetSettingOptions().Names() + ",foot_joints");
  return *names;
}

Status TakePipelineOptionsFromFlags(const Skeleton& skeleton, TakePipelineOptions* options) {
  Status status = RepairOptionsFromFlags(skeleton, &options->repair);
  if (status.ok()) status = RetargetOptionsFromFlags(&options->retarget);
  options->filter_levels = FLAGS_filter_levels;
  if (status.ok()) status = PyramidOptionsFromFlags(FLAGS_filter_levels, &options->filter);
  if (!status.ok()) return status;
  ReadOptionFlags(QualityGateOptions(), &options->gate);
  status = ClipDeliveryFromFlags(&options->delivery);
  if (!status.ok()) return status;
  std::string error;
  if (!options->IsValid(&error)) return Status::Error(error);
  return Status::Ok();
}

}  // namespace mocapsolve
