// Shared by the filter, bands, blend and pipeline commands (defined in
// apps/filter_command.cc; --kernel_a and --tension are declared in settings/pyramid_settings.h).
#ifndef MOCAPSOLVE_APPS_PYRAMID_FLAGS_H_
#define MOCAPSOLVE_APPS_PYRAMID_FLAGS_H_

#include <vector>

#include "kinematics/status.h"
#include "settings/pyramid_settings.h"
#include "signal/laplacian_pyramid.h"

namespace mocapsolve {

// Pyramid options from --kernel_a and --tension with `levels` levels (checked: the message
// names the option).
Status PyramidOptionsFromFlags(int levels, PyramidOptions* options);

// Filters --motion (BVH out) or --markers (C3D/TRC out) with the given band weights;
// `levels` 0 means weights.size() - 1. Prints and reports what it did.
Status FilterFromFlags(const char* command, int levels, const std::vector<double>& weights);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_APPS_PYRAMID_FLAGS_H_
