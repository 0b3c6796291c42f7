#include "apps/pipeline_flags.h"

#include "apps/common_flags.h"
#include "apps/delivery_flags.h"
#include "apps/option_flags.h"
#include "apps/pyramid_flags.h"
#include "apps/repair_flags.h"
#include "apps/retarget_flags.h"
#include "apps/view_flags.h"
#include "io/comma_list.h"
#include "pipeline/quality_gate.h"
#include "settings/delivery_settings.h"
#include "settings/pyramid_settings.h"
#include "settings/repair_settings.h"
#include "settings/retarget_settings.h"
#include "settings/view_page_settings.h"

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

// The take's page, as --view says (TakeViewPath; a PAGE.html must be no input). *path: ""
// for none.
Status ViewPageOfTake(std::string* path) {
  ViewPageSetting view;
  ReadOptionFlags(TakeViewPageOption(), &view);
  if (view.view != "auto" && view.view != "off") {
    std::vector<std::string> inputs = {Files().subject, Files().markers};
    for (const std::string& character : SplitCommaList(Files().character)) inputs.push_back(character);
    Status status = CheckViewFlag(inputs);
    if (!status.ok()) return status;
  }
  std::string warning;
  Status status = TakeViewPath(view.view, Files().out_dir, path, &warning);
  // A warning, not progress: printed with --quiet too.
  if (!warning.empty()) std::fprintf(stderr, "warning: pipeline: %s\n", warning.c_str());
  return status;
}

}  // namespace mocapsolve
