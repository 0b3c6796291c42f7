// The falloff flags (--sigma, --sigma_scale, --eigenpairs, --region, --diffusion_steps,
// --knn, --isomap_knn, --falloff_kernel, --feature_joints, --joint_weights, --temporal_weight), defined
// once in apps/falloff_flags.cc for every command that computes a pose-space falloff
// (problems/edit_propagation/falloff.h): distance, propagate.
#ifndef MOCAPSOLVE_APPS_FALLOFF_FLAGS_H_
#define MOCAPSOLVE_APPS_FALLOFF_FLAGS_H_

#include "kinematics/status.h"
#include "settings/falloff_settings.h"
#include "problems/edit_propagation/falloff.h"

namespace mocapsolve {

// Options from the flags; the message names the bad flag. --region is parsed against
// num_frames ("a:b", either side may be empty; b exclusive).
Status FalloffOptionsFromFlags(int num_frames, FalloffOptions* options);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_APPS_FALLOFF_FLAGS_H_
