// The pipeline's flags (apps/pipeline_command.cc): the names a --config file may set, and
// the TakePipelineOptions made from the parsed flags (repair, retarget, filter, gate,
// delivery), each through its settings' one conversion.
#ifndef MOCAPSOLVE_APPS_PIPELINE_FLAGS_H_
#define MOCAPSOLVE_APPS_PIPELINE_FLAGS_H_

#include <string>

#include <gflags/gflags.h>

#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "pipeline/take_pipeline.h"

namespace mocapsolve {

// The options a config file may set and --print_config prints, comma-separated.
const std::string& PipelineOptionFlags();

// The take's page, as --view says (auto, off or PAGE.html, which must be no input; a
// missing viewer runtime is a warning for auto, an error for a page asked for): "" for none.
Status ViewPageOfTake(std::string* path);

// Every stage's options from the flags; errors name the flag.
Status TakePipelineOptionsFromFlags(const Skeleton& skeleton, TakePipelineOptions* options);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_APPS_PIPELINE_FLAGS_H_
