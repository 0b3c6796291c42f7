// CMU 02_01 on real markers, shared by the tests that solve it: the C3D (mm, Z-up) mapped
// into 02.asf's frame by axes "y,z,x" and the units' scale (1/56.444 ASF units per mm); the
// marker set calibrated with auto attach against 02_01.amc (AMC frame k <-> C3D frame
// index k-1, frame_offset 0).
#ifndef MOCAPSOLVE_TESTS_PROBLEMS_CMU0201_TEST_SUPPORT_H_
#define MOCAPSOLVE_TESTS_PROBLEMS_CMU0201_TEST_SUPPORT_H_

#include <string>
#include <vector>

#include "io/asf_reader.h"
#include "io/marker_file.h"
#include "io/motion_file.h"
#include "problems/marker_solve/calibration.h"
#include "problems/marker_solve/marker_observations.h"

namespace mocapsolve {
namespace testing {

// CMU 02_01: skeleton, CMU's solve, the calibrated marker set and the observations.
struct Cmu0201 {
  Skeleton skeleton;
  AsfInfo asf;
  Motion amc;
  MarkerFileToModel transform;
  CalibrationResult calibration;
  std::vector<std::vector<Eigen::Vector3d>> observed;  // Model units, per C3D frame.
  double mm = 0.0;                                     // mm per skeleton unit.
};

inline Status LoadCmu0201(const std::string& c3d, const std::string& asf, const std::string& amc,
                          Cmu0201* data) {
  MotionFileOptions motion_options;
  motion_options.skeleton_path = asf;
  Status status = ReadMotionFile(amc, motion_options, &data->skeleton, &data->amc);
  if (!status.ok()) return status;
  Skeleton again;
  status = ReadSkeletonFile(asf, &again, &data->asf);
  if (!status.ok()) return status;
  MarkerTrajectories file;
  status = ReadMarkerFile(c3d, &file);
  if (!status.ok()) return status;
  status = ParseAxes("y,z,x", &data->transform.rotation);
  if (!status.ok()) return status;
  status = UnitScale(file.unit, data->skeleton.unit(), &data->transform.scale);
  if (!status.ok()) return status;
  data->mm = 1.0 / data->transform.scale;
  MarkerTrajectories model = file;
  TransformMarkers(data->transform, data->skeleton.unit(), &model);
  status = CalibrateMarkers(data->skeleton, data->amc, model, {}, nullptr, &data->calibration);
  if (!status.ok()) return status;
  return GatherObservations(data->calibration.marker_set, file, data->transform, &data->observed);
}

}  // namespace testing
}  // namespace mocapsolve

#endif  // MOCAPSOLVE_TESTS_PROBLEMS_CMU0201_TEST_SUPPORT_H_
