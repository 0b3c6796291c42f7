// Which marker labels name no marker. Motion-capture files keep points their labeller could
// not identify beside the labelled markers: C3D (Vicon) names them '*' then the point's
// number ("*52"), other writers leave the label empty. Readers keep them as columns like
// any other (marker_trajectories.h); calibration skips them and marker repair offers them
// to missing markers (problems/marker_repair/unlabelled_assignment.h).
#ifndef MOCAPSOLVE_KINEMATICS_UNLABELLED_LABEL_H_
#define MOCAPSOLVE_KINEMATICS_UNLABELLED_LABEL_H_

#include <string>

namespace mocapsolve {

// `name` is a marker name with its subject prefix stripped (SplitSubjectPrefix).
inline bool IsUnlabelledLabel(const std::string& name) { return name.empty() || name[0] == '*'; }

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_KINEMATICS_UNLABELLED_LABEL_H_
