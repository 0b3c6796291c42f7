// Marker observations in the skeleton's frame and units.
//
// A marker file has its own axes (C3D is often Z-up, BVH/ASF Y-up) and unit (mm, m);
// observations enter the solvers as
//   x_model = scale * rotation * x_file + translation
// with rotation a signed axis permutation given as text: "x,z,-y" means
// (x_model, y_model, z_model) = (x_file, z_file, -y_file). CMU's C3D files relate to their
// ASF/AMC skeletons by "y,z,x" (Z-up to Y-up, measured on 02_01; see calibration.h) with
// scale = ASF units per mm.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_MARKER_OBSERVATIONS_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_MARKER_OBSERVATIONS_H_

#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinematics/marker_set.h"
#include "kinematics/marker_trajectories.h"
#include "kinematics/status.h"
#include "kinematics/units.h"

namespace mocapsolve {

struct MarkerFileToModel {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  double scale = 1.0;
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Eigen::Vector3d Apply(const Eigen::Vector3d& x) const { return scale * (rotation * x) + translation; }
  Eigen::Vector3d Invert(const Eigen::Vector3d& x) const {
    return rotation.transpose() * ((x - translation) / scale);
  }
};

// "x,z,-y" -> rotation; must name each axis once and be a proper rotation (det +1).
Status ParseAxes(const std::string& text, Eigen::Matrix3d* rotation);

// model_from_file as text: "x,z,-y" (the inverse of ParseAxes for a signed permutation).
std::string AxesName(const Eigen::Matrix3d& model_from_file);
// The 24 signed permutation matrices with det +1 (the axis-aligned rotations), identity
// first.
std::vector<Eigen::Matrix3d> AllAxisRotations();

// Scale from the file's unit to the skeleton's. Both must be known; otherwise an error
// asking for an explicit scale.
Status UnitScale(const LengthUnit& file_unit, const LengthUnit& model_unit, double* scale);

// observed[f][m] for marker m of the set at frame f (model frame; NaN when missing).
// Every marker of the set must have a column in the file (labels compared without
// subject prefixes); the error lists the ones that do not.
Status GatherObservations(const MarkerSet& markers, const MarkerTrajectories& file,
                          const MarkerFileToModel& transform,
                          std::vector<std::vector<Eigen::Vector3d>>* observed);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_MARKER_OBSERVATIONS_H_
