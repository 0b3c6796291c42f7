#include "problems/marker_solve/marker_observations.h"

#include <cmath>
#include <sstream>

#include "kinematics/quote_token.h"

namespace mocapsolve {

Status ParseAxes(const std::string& text, Eigen::Matrix3d* rotation) {
  std::stringstream ss(text);
  std::string part;
  Eigen::Matrix3d r = Eigen::Matrix3d::Zero();
  int row = 0;
  bool used[3] = {false, false, false};
  while (std::getline(ss, part, ',')) {
    double sign = 1.0;
    if (!part.empty() && (part[0] == '-' || part[0] == '+')) {
      sign = part[0] == '-' ? -1.0 : 1.0;
      part = part.substr(1);
    }
    const int axis = part == "x" ? 0 : part == "y" ? 1 : part == "z" ? 2 : -1;
    if (row >= 3 || axis < 0 || used[axis]) {
      return Status::Error("--axes: " + QuoteToken(text) + " is not a signed permutation of x,y,z (e.g. x,z,-y)");
    }
    used[axis] = true;
    r(row++, axis) = sign;
  }
  if (row != 3) return Status::Error("--axes: " + QuoteToken(text) + " must name three axes (e.g. x,z,-y)");
  if (r.determinant() < 0.0) {
    return Status::Error("--axes: " + QuoteToken(text) + " is a reflection, not a rotation (flip one sign)");
  }
  *rotation = r;
  return Status::Ok();
}

std::string AxesName(const Eigen::Matrix3d& model_from_file) {
  std::string name;
  for (int row = 0; row < 3; ++row) {
    Eigen::Index col;
    model_from_file.row(row).cwiseAbs().maxCoeff(&col);
    if (row > 0) name += ",";
    if (model_from_file(row, col) < 0.0) name += "-";
    name += static_cast<char>('x' + col);
  }
  return name;
}

std::vector<Eigen::Matrix3d> AllAxisRotations() {
  std::vector<Eigen::Matrix3d> result;
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& p : perms) {
    for (int signs = 0; signs < 8; ++signs) {
      Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
      for (int row = 0; row < 3; ++row) m(row, p[row]) = (signs >> row) & 1 ? -1.0 : 1.0;
      if (m.determinant() > 0.0) result.push_back(m);
    }
  }
  return result;  // perms[0] with signs 0 is the identity: first.
}

Status UnitScale(const LengthUnit& file_unit, const LengthUnit& model_unit, double* scale) {
  if (!file_unit.known() || !model_unit.known()) {
    return Status::Error("cannot convert marker units " + QuoteToken(file_unit.name) + " to skeleton units '" +
                         model_unit.name + "': give --marker_scale");
  }
  *scale = file_unit.metres_per_unit / model_unit.metres_per_unit;
  return Status::Ok();
}

Status GatherObservations(const MarkerSet& markers, const MarkerTrajectories& file,
                          const MarkerFileToModel& transform,
                          std::vector<std::vector<Eigen::Vector3d>>* observed) {
  std::vector<int> column(markers.num_markers());
  std::string missing;
  for (int m = 0; m < markers.num_markers(); ++m) {
    column[m] = file.FindMarker(markers.label(m));
    if (column[m] < 0) missing += (missing.empty() ? "" : ", ") + markers.label(m);
  }
  if (!missing.empty()) {
    return Status::Error("marker file has no column for the marker set's " + missing);
  }
  const Eigen::Vector3d nan = Eigen::Vector3d::Constant(std::nan(""));
  observed->assign(file.num_frames(), std::vector<Eigen::Vector3d>(markers.num_markers(), nan));
  for (int f = 0; f < file.num_frames(); ++f) {
    for (int m = 0; m < markers.num_markers(); ++m) {
      if (file.valid(f, column[m])) (*observed)[f][m] = transform.Apply(file.position(f, column[m]));
    }
  }
  return Status::Ok();
}

}  // namespace mocapsolve
