// The falloff weights of a clip's edits as `mocapsolve propagate` computes them, one field
// w_k (frames,) per edited frame k, for eq. 5's blend R'_f = R_f exp(sum_k w_k(f) log(R_k^-1 R'_k)):
//   green:    the row of the pose-space Green's function at frame k, normalized (falloff.h);
//   harmonic: the harmonic function on the kNN pose graph (Zhu et al. 2003): 1 at edit k,
//             0 at the other edits, at a ground node joined to every frame with weight
//             harmonic_ground x the graph's mean degree, and at the ends of the region where
//             it cuts the clip (or at the clip's ends when harmonic_ground is 0); clamped to [0, 1];
//   spline:   a cubic bump of half-width spline_width frames (spline_falloff.h).
// Also the IK edit's targets from the command line's text. The CLI and the Python module
// both call these. Knows nothing of gflags.
#ifndef MOCAPSOLVE_PIPELINE_EDIT_WEIGHTS_H_
#define MOCAPSOLVE_PIPELINE_EDIT_WEIGHTS_H_

#include <string>
#include <vector>

#include <Eigen/Core>

#include "io/json_writer.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "problems/edit_propagation/falloff.h"
#include "io/edit_file.h"
#include "problems/edit_propagation/ik_edit.h"
#include "problems/edit_propagation/pose_edit.h"
#include "settings/propagate_settings.h"
#include "settings/solver_settings.h"

namespace mocapsolve {

// The options of `mocapsolve propagate` that only these weights read (declared in
// settings/propagate_settings.h and settings/solver_settings.h; the same defaults).
struct EditWeightSettings {
  double harmonic_ground = PropagateSettings().harmonic_ground;  // Fraction of the graph's mean degree.
  double spline_width = PropagateSettings().spline_width;        // Frames.
  std::string sparse_library = SolverSettings().sparse_library;  // eigen_sparse | suite_sparse.
};

struct EditWeights {
  std::vector<Eigen::VectorXd> weights;  // One per edited frame, (frames,) in [0, 1].
  JsonObject report;                     // The method's figures (the CLI report's "falloff").
};

// method: green | harmonic | spline; frames: the edited frames (inside falloff's region).
// Errors name the flag ("--spline_width must be positive").
Status ComputeEditWeights(const std::string& method, const Skeleton& skeleton, const Motion& motion,
                          const FalloffOptions& falloff, const std::vector<int>& frames,
                          const EditWeightSettings& settings, EditWeights* out);

// "JOINT:x,y,z[;JOINT:x,y,z...]" (world, skeleton units) -> targets; errors name --ik_target.
Status ParseIkTargets(const std::string& text, const Skeleton& skeleton, std::vector<IkTarget>* targets);

// The edits of an edit file (io/edit_file.h) applied to the motion's frames; *entries
// (optional) receives the file's entries (their `where` for later messages). Errors name
// the file, line and field (a frame past the motion's end included).
Status ReadPoseEdits(const std::string& path, const Skeleton& skeleton, const Motion& motion,
                     std::vector<PoseEdit>* edits, std::vector<EditFileEntry>* entries = nullptr);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PIPELINE_EDIT_WEIGHTS_H_
