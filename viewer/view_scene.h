// What a `mocapsolve view` page shows, already in the viewer's world: metres, +Y up
// (three.js' convention), one frame clock for everything.
//
// Every source is brought into that world by a ViewTransform,
//   x_world = scale * rotation * x_source,
// where `rotation` turns the source's up axis to +Y (a signed axis permutation, so a
// right-handed Z-up capture stays right-handed) and `scale` is the source's metres per
// unit. Marker files carry their unit (C3D POINT:UNITS, TRC Units) and skeletons theirs
// (ASF, glTF; a BVH's from --skeleton_units or, failing that, from its height, with a
// note); the up axis is the caller's (a subject's --axes maps markers onto the skeleton,
// so both then share the skeleton's) or GuessUpAxis'.
//
// Layouts (row-major, frame-major, as MarkerTrajectories):
//   ViewMarkers::positions   #F x #M x 3 floats (world metres), NaN where missing;
//   ViewMarkers::states      #F x #M MarkerState bytes;
//   ViewSkeleton::positions  #F x #J x 3 floats (world metres): FK joint origins;
//   ViewCurve::values        #F floats, NaN where the curve has no value.
// Characters are their .glb files' bytes: the page's GLTFLoader does the skinning and
// plays the named animation (the retargeted take) beside the source.
#ifndef MOCAPSOLVE_VIEWER_VIEW_SCENE_H_
#define MOCAPSOLVE_VIEWER_VIEW_SCENE_H_

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinematics/marker_trajectories.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "kinematics/units.h"

namespace mocapsolve {

// A marker sample's state; the repaired ones by the reason the repair found.
enum class MarkerState : std::uint8_t {
  kObserved = 0,
  kMissing = 1,
  kRepairedGap = 2,
  kRepairedOutlier = 3,
  kRepairedJointDifference = 4,
  kRepairedSwap = 5,
  kRepairedUnlabelled = 6,  // An unlabelled point the repair assigned to the marker.
};
// "observed", "missing", "gap", "outlier", "joint difference", "swap", "unlabelled".
const char* MarkerStateName(MarkerState state);
// A repair report's reason ("missing" and "gap" -> gap, "outlier", "joint difference",
// "swap", "unlabelled"); anything else (a fill method such as "reference") -> gap.
MarkerState RepairedStateForReason(const std::string& reason);

struct ViewTransform {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // Source axes -> world (+Y up).
  double scale = 1.0;                                      // Metres per source unit.
  std::string note;                                        // How the transform was chosen.

  Eigen::Vector3d Apply(const Eigen::Vector3d& x) const { return scale * (rotation * x); }
};

// The up axis of a take's points: the axis along which a frame's points spread most,
// averaged over up to 200 evenly spaced frames (a standing person is taller than wide).
// Returns 0, 1 or 2 (x, y, z); always the positive direction, as capture files use +Y or
// +Z up. frames[f] holds one frame's points; NaN entries are skipped.
int GuessUpAxis(const std::vector<std::vector<Eigen::Vector3d>>& frames);

// The transform for a source whose up axis is `up_axis` (0, 1, 2 for +x, +y, +z) and unit
// `unit`; an unknown unit is an error naming `what` unless `height` (the source's height in
// its own units, > 0) lets one be guessed: metres, centimetres, millimetres or inches,
// whichever makes it 1-2.5 m tall, else a scale making it 1.75 m (noted in `note`).
Status MakeViewTransform(const std::string& what, int up_axis, const LengthUnit& unit, double height,
                         ViewTransform* transform);

// A motion's transform: up_axis 0/1/2, or -1 to guess it from the clip's joints
// (GuessUpAxis); the unit from the skeleton, or guessed from its rest height.
Status MakeMotionViewTransform(const std::string& what, const Skeleton& skeleton, const Motion& motion,
                               int up_axis, ViewTransform* transform);

struct ViewMarkers {
  std::string name;
  std::vector<std::string> labels;
  int num_frames = 0;
  std::vector<float> positions;            // #F x #M x 3.
  std::vector<std::uint8_t> states;        // #F x #M.

  int num_markers() const { return static_cast<int>(labels.size()); }
};

// observed[f][m] (NaN = missing) under `transform`: states observed or missing.
ViewMarkers MakeViewMarkers(const std::string& name, const std::vector<std::string>& labels,
                            const std::vector<std::vector<Eigen::Vector3d>>& observed,
                            const ViewTransform& transform);
// A marker file's trajectories as read (the file's labels, axes and unit).
ViewMarkers MakeViewMarkers(const std::string& name, const MarkerTrajectories& trajectories,
                            const ViewTransform& transform);

struct ViewSkeleton {
  std::string name;
  std::vector<std::string> joint_names;
  std::vector<int> parents;                // -1 for the root.
  int num_frames = 0;
  std::vector<float> positions;            // #F x #J x 3.
  bool ghost = false;                      // Drawn translucent (--compare).
};

ViewSkeleton MakeViewSkeleton(const std::string& name, const Skeleton& skeleton, const Motion& motion,
                              const ViewTransform& transform);

// A repaired interval of markers[0]: frames first..last (inclusive) of marker `marker`.
struct ViewInterval {
  int marker = 0;
  int first = 0, last = 0;
  MarkerState state = MarkerState::kRepairedGap;
};

// Marks the intervals' samples of `markers` with their states (clipped to the take).
void MarkRepairedSamples(const std::vector<ViewInterval>& intervals, ViewMarkers* markers);

struct ViewCurve {
  std::string name;             // "marker residual", "falloff weight", ...
  std::string unit;             // "mm", "" ...
  std::vector<float> values;    // #F, NaN = no value.
};

struct ViewCharacter {
  std::string name;
  std::string glb;              // The .glb file's bytes.
  std::string animation;        // The clip to play; "" = the file's first animation.
};

struct ViewScene {
  std::string title;
  double frame_rate = 30.0;     // Of the scene's frame clock (> 0).
  std::vector<ViewMarkers> markers;      // [0] the take; the others drawn ghosted (--compare).
  std::vector<ViewSkeleton> skeletons;
  std::vector<ViewCharacter> characters;
  std::vector<ViewInterval> intervals;   // Of markers[0].
  std::vector<ViewCurve> curves;
  std::vector<std::string> notes;        // Shown in the page's info panel (units, up axes).

  // The longest source, in frames (characters' clips are timed by frame_rate).
  int num_frames() const;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_VIEWER_VIEW_SCENE_H_
