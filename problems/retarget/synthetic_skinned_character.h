// A synthetic skinned character for tests and benchmarks of the retargeting problem: a
// "cylinder character" over any skeleton (in practice kinematics/demo_character.h's).
//
// Every joint j gets a capped tube from its bind-pose origin toward its first child (or,
// for a leaf, its first end site; a leaf without an end site gets a short tube along the
// bone from its parent). Rings are spaced evenly along the bone; a ring at fraction t of
// the bone is weighted w_j = 1 - b(t), w_parent = b(t) with b(t) = max(0, 0.5 - 2t), so
// vertices near a joint blend across it. Normals point radially outward (cap vertices:
// along the bone). The mesh is bound at the skeleton's rest pose: joint_from_bind_j =
// (world_from_joint_j at rest)^-1, positions in skeleton units, bind space = world.
//
// ScaleSkeleton multiplies every offset (and end-site offset) by `factor`, so a mesh built
// on the scaled skeleton is the uniformly scaled copy of the original one.
#ifndef MOCAPSOLVE_PROBLEMS_RETARGET_SYNTHETIC_SKINNED_CHARACTER_H_
#define MOCAPSOLVE_PROBLEMS_RETARGET_SYNTHETIC_SKINNED_CHARACTER_H_

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/skinned_mesh.h"

namespace mocapsolve {

struct CylinderCharacterOptions {
  int segments = 12;      // Vertices per ring.
  int rings = 8;          // Rings per bone (>= 2).
  double radius = 0.06;   // Tube radius as a fraction of the skeleton's rest height.
};

SkinnedMesh MakeCylinderCharacter(const Skeleton& skeleton,
                                  const CylinderCharacterOptions& options = {});

Skeleton ScaleSkeleton(const Skeleton& skeleton, double factor);

// The same motion on the scaled skeleton: every translation times `factor`.
Motion ScaleMotion(const Motion& motion, double factor);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_SYNTHETIC_SKINNED_CHARACTER_H_
