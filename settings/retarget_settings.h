// RetargetSettings: the retargeting knobs as the user names them (one field per flag of
// `mocapsolve retarget` / `pipeline`, same names and defaults), and their one conversion
// into CharacterRetargetOptions (problems/retarget/retarget_character.h), reading the
// blend mask and joint map files they name. The command line (apps/retarget_flags.cc)
// and the Python module both call it. Knows nothing of gflags.
#ifndef MOCAPSOLVE_SETTINGS_RETARGET_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_RETARGET_SETTINGS_H_

#include <string>
#include <utility>
#include <vector>

#include "kinematics/status.h"
#include "problems/retarget/retarget_character.h"
#include "settings/option.h"

namespace mocapsolve {

struct RetargetSettings {
  std::string solver = "dls";   // dls | dls_generic | ceres (--solver; dls unless given).
  double limit_weight = 0.0;    // Soft joint limits (--limit_weight), per radian.
  std::string joint_map;        // JSON (ReadJointMapFile); "" = automatic.
  bool plant_feet = true;
  double plant_weight = 30.0;
  double floor_weight = 10.0;   // Per sigma of depth under the floor; 0 = off.
  double plant_height = 0.03;   // Fraction of the source height.
  double plant_speed = 0.15;    // Source heights per second.
  std::string root_motion = "keep";  // keep | root_bone | in_place (problems/retarget/root_motion.h).
  double root_smoothing = 0.15;      // Seconds: the root track's Gaussian standard deviation.
  std::string stride = "height";     // height | legs (problems/retarget/stride_scale.h).
  std::string foot_joints;      // Comma-separated source joints; "" = names with foot/toe/ankle.
  int subsample = 128;
  // 5 iterations at damping 2.5 reach the final cost of 10 at 5 (bench/retarget_quality_table.sh: the
  // same figures on 18 pairs; BENCHMARKS.md, issue 35) in half the time.
  int iterations = 5;
  double lambda = 2.5;
  std::string blend_mask = "auto";  // auto | JSON {"position_joints": [...]}.
  double mapping_normal_weight = 0.0;
  bool transfer_normals = true;
  double normal_weight = 1.0;
  double limb_direction_weight = 2.0;  // Per unit of direction difference; 0 = off.
  double smoothness = 0.0;
  double contact_height = 0.02;
  double ceres_trust_radius = 1.0;
};

// The options, declared once (name, unit, help, check; the defaults are the fields'
// initializers above): the flags of retarget and pipeline, Python's keywords. Not yet
// foot_joints, which propagate also defines (as a gflags flag of its own).
const OptionGroup<RetargetSettings>& RetargetSettingOptions();

// Who solves the retarget and its joint limits, declared once: `retarget`'s --solver and
// --limit_weight. (pipeline reads the marker solver's options of the same names.)
const OptionGroup<RetargetSettings>& RetargetSolverOptions();

// The (source, target) joint pairs of a joint map file: {"joints": {"<source>": "<target>"},
// "roles": {"<role>": {"source": "<joint>", "target": "<joint>"}}} (either object, or
// both; a role with "" on a side is skipped). docs/retarget.md, "Joint map".
Status ReadJointMapFile(const std::string& path, std::vector<std::pair<std::string, std::string>>* pairs);

Status RetargetOptionsFromSettings(const RetargetSettings& settings, CharacterRetargetOptions* options);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_RETARGET_SETTINGS_H_
