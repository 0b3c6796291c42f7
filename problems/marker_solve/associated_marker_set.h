// The first marker set of a fit from a marker association (marker_association.h): every
// associated marker rides on the template joint that plays its segment's role (humanoid
// roles of the template standing in its rest pose, problems/retarget/humanoid_roles.h),
// at the middle of that joint's longest bone segment (subject_checks.h, BoneSegments) as
// the offset the fit starts from; and the file axes that put the take's detected up on the
// template's (the first axis rotation, in AllAxisRotations' order, that does). The markers
// below `min_confidence` are left out, but for the pelvis' (the root's, which anchor the
// fit), left out below half of it, and a segment's most confident marker when none of its
// markers reaches the bar (a segment round 0 leaves unobserved stays at the template's rest,
// and the first attach round places its markers against that pose).
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_ASSOCIATED_MARKER_SET_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_ASSOCIATED_MARKER_SET_H_

#include <string>
#include <vector>

#include "kinematics/marker_set.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "problems/marker_solve/marker_association.h"

namespace mocapsolve {

struct AssociatedMarkerSet {
  std::vector<MarkerSpec> specs;          // The markers at or above the bar (the pelvis': half), on their joints.
  std::vector<std::string> joints;        // Per spec, its joint's name (for the report).
  std::vector<std::string> left_out;      // Below the bar and not their segment's best, or without a template joint.
  std::vector<std::string> head_labels, pelvis_labels;  // For the torso check.
  std::string axes;                       // File -> template axes ("y,z,x").
};

// Errors: the template is no humanoid (the roles' reason), fewer than 3 markers kept.
Status MakeAssociatedMarkerSet(const Skeleton& templ, const MarkerAssociation& association, double min_confidence,
                               AssociatedMarkerSet* out);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_ASSOCIATED_MARKER_SET_H_
