// FalloffSettings: the pose-space falloff's knobs as the user names them (one field per
// flag of `mocapsolve distance` / `propagate`: --sigma, --sigma_scale, --eigenpairs,
// --region, --diffusion_steps, --knn, --isomap_knn, --falloff_kernel, --feature_joints,
// --joint_weights, --temporal_weight; same defaults), and their one conversion into
// FalloffOptions (problems/edit_propagation/falloff.h). The distance and propagate tasks
// (tasks/) and Python's falloff() call it. Knows nothing of gflags.
#ifndef MOCAPSOLVE_SETTINGS_FALLOFF_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_FALLOFF_SETTINGS_H_

#include <string>

#include "kinematics/status.h"
#include "problems/edit_propagation/falloff.h"
#include "settings/option.h"

namespace mocapsolve {

struct FalloffSettings {
  double sigma = 0.0;           // Radians; 0 = auto (sigma_scale x median pose step).
  double sigma_scale = 4.0;
  int eigenpairs = 10;          // 0 = all (dense kernel only).
  std::string region;           // "a:b" (frames, b exclusive; a side may be empty); "" = all.
  int diffusion_steps = 10;
  int knn = 30;
  int isomap_knn = 10;
  std::string falloff_kernel = "auto";  // auto | dense | sparse.
  std::string feature_joints;   // Comma-separated; "" = every rotating joint.
  std::string joint_weights;    // Comma-separated, one per feature joint.
  double temporal_weight = 0.0; // Radians per second.
  std::string sweep;            // distance: extra sigmas (comma-separated) whose Green's weights it adds.
};

// The options, declared once (name, unit, help, check; the defaults are the fields'
// initializers above): the flags of distance and propagate, Python's keywords.
const OptionGroup<FalloffSettings>& FalloffSettingOptions();

// The message names the bad flag; region is parsed against num_frames.
Status FalloffOptionsFromSettings(const FalloffSettings& settings, int num_frames, FalloffOptions* options);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_FALLOFF_SETTINGS_H_
