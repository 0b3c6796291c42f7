// The viewer scene (viewer/view_scene.h) of one marker take and what was computed from it:
// the markers in the subject skeleton's frame (repaired samples coloured by the reason
// the repair found), the solved skeleton, a per-frame marker residual curve, and the
// characters the take was retargeted onto. Used by `pipeline` (view.html per take) and by
// `repair`, `solve` and `view` (--view, --out).
//
// World: the skeleton's unit (which a subject always knows) to metres; its up axis from
// the solved motion's joints (GuessUpAxis), or from the markers when there is no motion.
// The residual at frame f is the RMS over the markers present (repaired when given, else
// observed) of |x_model(f) - x_marker(f)| in mm, x_model from the marker set on the
// solved pose (RmsMarkerError).
#ifndef MOCAPSOLVE_PIPELINE_TAKE_VIEW_H_
#define MOCAPSOLVE_PIPELINE_TAKE_VIEW_H_

#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinematics/marker_set.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "problems/marker_repair/marker_repair.h"
#include "viewer/view_scene.h"

namespace mocapsolve {

struct TakeViewInputs {
  std::string title;
  const Skeleton* skeleton = nullptr;          // Required.
  const MarkerSet* markers = nullptr;          // Required with observed.
  // [frame][marker of the set], skeleton frame and units, NaN = missing. Optional.
  const std::vector<std::vector<Eigen::Vector3d>>* observed = nullptr;
  // The repaired samples (same layout), shown instead of observed; optional.
  const std::vector<std::vector<Eigen::Vector3d>>* repaired = nullptr;
  std::vector<ViewInterval> intervals;         // Repaired intervals (RepairViewIntervals).
  const Motion* motion = nullptr;              // The solve on *skeleton; optional.
  double frame_rate = 0.0;                     // Of the take (> 0).
  std::vector<ViewCharacter> characters;
};

// The intervals a repair filled, each with the reason it detected (repair_intervals.h).
std::vector<ViewInterval> RepairViewIntervals(const RepairReport& report);

Status MakeTakeViewScene(const TakeViewInputs& inputs, ViewScene* scene);
// The RMS over every marker sample shown (repaired when given, else observed) of
// |x_model - x_marker| in mm, over the frames the motion has, as solve reports it; 0
// without a motion or markers. *samples (optional) counts the samples.
double TakeMarkerRmsMm(const TakeViewInputs& inputs, int* samples = nullptr);
// The take's world (as above), for other files shown with it (--compare).
Status TakeViewTransform(const TakeViewInputs& inputs, ViewTransform* transform);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PIPELINE_TAKE_VIEW_H_
