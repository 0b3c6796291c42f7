// Issue 3 on real markers: CMU 02_01 solved from its C3D onto 02.asf and compared with
// CMU's own solve (02_01.amc), both solvers' agreement, and the long 02_05 take.
//
// Setup (as calibration_test.cc): the C3D (mm, Z-up) is mapped into the ASF's frame by
// axes "y,z,x" and the units' scale (1/56.444 ASF units per mm); the marker set is
// calibrated with auto attach against 02_01.amc (AMC frame k <-> C3D frame index k-1,
// frame_offset 0). The solves then start from the ASF rest pose (as `mocapsolve solve`
// does): nothing of the AMC is used but the marker offsets. Errors are measured in the
// world, per AMC frame, over every skeleton joint.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/asf_reader.h"
#include "io/marker_file.h"
#include "io/motion_file.h"
#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "problems/marker_solve/calibration.h"
#include "problems/marker_solve/marker_observations.h"
#include "problems/marker_solve/marker_frame_solver.h"
#include "problems/marker_solve/sequence_solver.h"
#include "tests/problems/cmu0201_test_support.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using testing::Cmu0201;
using testing::LoadCmu0201;

MarkerSolveOptions Options(SolverKind kind) {
  MarkerSolveOptions options;
  options.solver = kind;
  options.ceres = DefaultFrameCeresOptions();
  return options;
}

const char* Name(SolverKind kind) { return SolverKindName(kind); }

// Cost of a frame as the solvers report it (1/2 sum |r|^2, marker weight 1, no loss).
double FrameCost(const Skeleton& skeleton, const MarkerSet& markers, const Pose& pose,
                 const std::vector<Eigen::Vector3d>& observed) {
  int count = 0;
  const double rms = RmsMarkerError(skeleton, markers, pose, observed, &count);
  return 0.5 * count * rms * rms;
}

// Angle (radians) by which a local rotation leaves the set the ASF bone's rotation dofs
// span (0 for bones with 3): for one dof, the distance to the nearest rotation about its
// axis; for two, the third Euler angle of the decomposition in the dofs' product order
// (Acclaim applies the first-listed angle first: "rx rz" is M = Rz Rx); for none, the
// angle from identity.
double OffDofAngle(const AsfInfo& asf, int joint, const Eigen::Quaterniond& q) {
  if (joint <= 0 || asf.bone_of_joint.empty()) return 0.0;
  const int bone = asf.bone_of_joint[joint];
  if (bone < 0) return 0.0;
  std::vector<int> axes;  // Product order.
  for (const AsfDof& dof : asf.bones[bone].dofs) {
    if (IsRotationDof(dof.dof)) axes.insert(axes.begin(), AcclaimDofAxis(dof.dof));
  }
  if (axes.size() >= 3) return 0.0;
  if (axes.empty()) return AngularDistance(q, Eigen::Quaterniond::Identity());
  if (axes.size() == 1) {
    Eigen::Quaterniond nearest(q.w(), 0, 0, 0);
    nearest.vec()[axes[0]] = q.vec()[axes[0]];
    if (nearest.norm() < 1e-12) return kPi;
    return AngularDistance(q, nearest.normalized());
  }
  const Eigen::Vector3d e = EulerFromQuaternion(q, EulerOrderFromAxes(axes[0], axes[1], 3 - axes[0] - axes[1]));
  return std::abs(e[2]);
}

struct Comparison {
  double mean_position_mm = 0.0, max_position_mm = 0.0;
  double mean_rotation_deg = 0.0;           // Over every joint.
  double mean_markered_rotation_deg = 0.0;  // Over joints carrying a marker.
  int worst_joint = -1;                     // Largest mean position error.
  double worst_joint_mean_mm = 0.0;
  double rms_residual_mm = 0.0;
  std::vector<double> joint_mean_mm, joint_max_mm, joint_rotation_deg, joint_off_dof_deg;
};

// The solve against CMU's: solved frame f <-> AMC frame f (offset 0).
Comparison Compare(const Cmu0201& data, const Motion& solved, const SequenceSolveReport& report) {
  const Skeleton& skeleton = data.skeleton;
  const int joints = skeleton.num_joints();
  std::vector<bool> markered(joints, false);
  for (int m = 0; m < data.calibration.marker_set.num_markers(); ++m) {
    for (const MarkerAttachment& a : data.calibration.marker_set.marker(m).attachments) markered[a.joint] = true;
  }
  Comparison c;
  c.joint_mean_mm.assign(joints, 0.0);
  c.joint_max_mm.assign(joints, 0.0);
  c.joint_rotation_deg.assign(joints, 0.0);
  c.joint_off_dof_deg.assign(joints, 0.0);
  FkData a(skeleton), b(skeleton);
  const int frames = std::min(solved.num_frames(), data.amc.num_frames());
  double sum_rotation = 0.0, sum_markered_rotation = 0.0;
  int markered_count = 0;
  for (int f = 0; f < frames; ++f) {
    ForwardKinematics(skeleton, solved.frames[f], &a);
    ForwardKinematics(skeleton, data.amc.frames[f], &b);
    for (int j = 0; j < joints; ++j) {
      const double e = (a.world_positions[j] - b.world_positions[j]).norm() * data.mm;
      const double r = RadToDeg(AngularDistance(a.world_rotations[j], b.world_rotations[j]));
      c.joint_mean_mm[j] += e / frames;
      c.joint_max_mm[j] = std::max(c.joint_max_mm[j], e);
      c.joint_rotation_deg[j] += r / frames;
      c.joint_off_dof_deg[j] += RadToDeg(OffDofAngle(data.asf, j, solved.frames[f].rotations[j])) / frames;
      c.mean_position_mm += e;
      c.max_position_mm = std::max(c.max_position_mm, e);
      sum_rotation += r;
      if (markered[j]) sum_markered_rotation += r, ++markered_count;
    }
  }
  c.mean_position_mm /= double(frames) * joints;
  c.mean_rotation_deg = sum_rotation / (double(frames) * joints);
  c.mean_markered_rotation_deg = sum_markered_rotation / std::max(markered_count, 1);
  for (int j = 0; j < joints; ++j) {
    if (c.joint_mean_mm[j] > c.worst_joint_mean_mm) c.worst_joint_mean_mm = c.joint_mean_mm[j], c.worst_joint = j;
  }
  c.rms_residual_mm = report.rms_marker_error * data.mm;
  return c;
}

void PrintComparison(const Cmu0201& data, const char* solver, const Comparison& c,
                     const SequenceSolveReport& report) {
  std::printf("02_01 %s: %d frames in %.2f s (%.0f frames/s), %.1f iterations/frame, unsolved %d, "
              "at limit %d\n",
              solver, report.frames, report.solve_seconds, report.frames / report.solve_seconds,
              double(report.total_iterations) / report.frames, report.unsolved_frames,
              report.unconverged_frames);
  std::printf("02_01 %s vs CMU AMC: joint position error mean %.2f mm, max %.1f mm (worst joint "
              "%s, mean %.1f mm); bone rotation error mean %.2f deg (markered bones %.2f deg); "
              "RMS marker residual %.2f mm (AMC with the same markers: %.2f mm)\n",
              solver, c.mean_position_mm, c.max_position_mm, data.skeleton.name(c.worst_joint).c_str(),
              c.worst_joint_mean_mm, c.mean_rotation_deg, c.mean_markered_rotation_deg, c.rms_residual_mm,
              data.calibration.rms * data.mm);
  std::vector<int> markers_on(data.skeleton.num_joints(), 0);
  for (int m = 0; m < data.calibration.marker_set.num_markers(); ++m) {
    for (const MarkerAttachment& a : data.calibration.marker_set.marker(m).attachments) ++markers_on[a.joint];
  }
  std::printf("  %-10s %7s %8s %8s %8s %8s\n", "joint", "markers", "mean mm", "max mm", "rot deg", "off-dof");
  for (int j = 0; j < data.skeleton.num_joints(); ++j) {
    std::printf("  %-10s %7d %8.2f %8.1f %8.2f %8.2f\n", data.skeleton.name(j).c_str(), markers_on[j],
                c.joint_mean_mm[j], c.joint_max_mm[j], c.joint_rotation_deg[j], c.joint_off_dof_deg[j]);
  }
}

// The full 02_01 solve with one solver, checked against CMU's.
struct Solved0201 {
  Motion motion;
  SequenceSolveReport report;
  Comparison comparison;
};

void Solve0201(const Cmu0201& data, SolverKind kind, Solved0201* out) {
  const Status status = SolveSequence(data.skeleton, data.calibration.marker_set, data.observed,
                                      Options(kind), RestPose(data.skeleton), &out->motion, &out->report);
  ASSERT_TRUE(status.ok()) << status.message();
  out->comparison = Compare(data, out->motion, out->report);
  PrintComparison(data, Name(kind), out->comparison, out->report);
}

#define MOCAPSOLVE_CMU_0201(data)                                          \
  MOCAPSOLVE_DATA_FILE(c3d_path, "c3d/02_01.c3d");                         \
  MOCAPSOLVE_DATA_FILE(asf_path, "amc/02.asf");                            \
  MOCAPSOLVE_DATA_FILE(amc_path, "amc/02_01.amc");                         \
  Cmu0201 data;                                                            \
  {                                                                        \
    const Status load = LoadCmu0201(c3d_path, asf_path, amc_path, &data);  \
    ASSERT_TRUE(load.ok()) << load.message();                              \
  }                                                                        \
  ASSERT_EQ(data.observed.size(), 343u);                                   \
  ASSERT_EQ(data.amc.num_frames(), 343)

// (a) Every frame of 02_01 solved from the C3D and compared with CMU's solve.
//
// Measured with the ASF dofs enforced (1-dof knees, 0-dof hip joints, ...), both solvers
// alike in joint positions: mean 8.69 mm, max 57.3 mm; per joint the knee centres
// (rtibia 22.9 mm, ltibia 20.5 mm mean) and hip centres (femur 11.7 mm) dominate; the
// root is off by 6.4 mm on average (zero-mean over the take: bias < 0.5 mm) and every
// joint inherits that. Bone rotations: mean 15.8 deg (Ceres) / 8.5 deg (DLS) over all
// bones, 12.8 / 10.1 deg over bones that carry markers; the mean is dominated by
// rotations no marker fixes (twist of the marker-less lowerneck, a hand or thumb with one
// marker), where the two solvers drift differently. RMS marker residual 3.92 mm, against
// 11.70 mm for CMU's own solve with the same marker set.
//
// The goal (mean joint position error <= 5 mm) is NOT met and is not asserted.
// What limits it is the reference, not the solver: markers synthesized from the AMC with
// this marker set are solved back to 1.6 mm mean, 0 mm residual (the remainder: the
// fingers of hands with one marker), and CMU's solve itself misses these markers by
// 11.7 mm RMS (18-27 mm at thigh, knee and shin markers), so the two solves place the
// knees and the pelvis differently; CMU's knee and root trajectories are also the
// jerkier ones (mean |second difference| 1.35 vs 0.73 mm at the knee). Neither a Huber
// loss (5 or 10 mm) nor dropping the high-residual leg markers brings the error down.
// Bounds below are the measured values x ~1.5.
void Expect0201Accuracy(const Cmu0201& data, const Solved0201& solved, SolverKind kind) {
  const Comparison& c = solved.comparison;
  EXPECT_EQ(solved.report.unsolved_frames, 0) << Name(kind);
  // Measured 15 (Ceres) and 26 (DLS) of 343 frames stop at the 50-iteration limit: the
  // cost is settled to ~1e-6 relative within 20 iterations, then the step crawls along
  // an ill-conditioned direction (redundant rotations of joints without markers); with
  // 100 iterations Ceres converges on every frame (DLS: 11 left), same cost to 1e-8.
  EXPECT_LE(solved.report.unconverged_frames, 40) << Name(kind);
  EXPECT_LT(c.mean_position_mm, 13.0) << Name(kind);   // Measured 8.69 mm (goal 5 mm: not met).
  EXPECT_LT(c.max_position_mm, 86.0) << Name(kind);    // Measured 57.3 mm (rtibia).
  EXPECT_LT(c.worst_joint_mean_mm, 34.0) << Name(kind);  // Measured 22.9 mm (rtibia).
  EXPECT_LT(c.mean_rotation_deg, 24.0) << Name(kind);  // Measured 15.8 (Ceres), 8.5 (DLS) deg.
  EXPECT_LT(c.mean_markered_rotation_deg, 19.0) << Name(kind);  // 12.8, 10.1 deg.
  EXPECT_LT(c.rms_residual_mm, 5.9) << Name(kind);     // Measured 3.92 mm.
  // The ankles (markers 2.5 mm from CMU's solve in calibration) agree best.
  for (const char* joint : {"lfoot", "rfoot"}) {
    const int j = data.skeleton.FindJoint(joint);
    ASSERT_GE(j, 0) << joint;
    EXPECT_LT(c.joint_mean_mm[j], 8.0) << Name(kind) << " " << joint;  // Measured 5.3, 5.0 mm.
  }
}

TEST(CmuMarkerSolve, Cmu0201CeresAgainstCmuSolve) {
  MOCAPSOLVE_CMU_0201(data);
  Solved0201 solved;
  Solve0201(data, SolverKind::kCeres, &solved);
  Expect0201Accuracy(data, solved, SolverKind::kCeres);
}

TEST(CmuMarkerSolve, Cmu0201DlsAgainstCmuSolve) {
  MOCAPSOLVE_CMU_0201(data);
  Solved0201 solved;
  Solve0201(data, SolverKind::kDls, &solved);
  Expect0201Accuracy(data, solved, SolverKind::kDls);
}

// Control for (a): markers synthesized from CMU's solve with the calibrated set (no
// noise) are solved back to CMU's joint positions, except where no marker decides (a
// hand with one marker swings its fingers). Measured: mean 1.61 mm (all of it the two
// finger joints), residual 0.
TEST(CmuMarkerSolve, Cmu0201MarkersSynthesizedFromCmuSolveAreSolvedBack) {
  MOCAPSOLVE_CMU_0201(data);
  std::vector<std::vector<Eigen::Vector3d>> synthetic;
  FkData fk(data.skeleton);
  for (const Pose& pose : data.amc.frames) {
    ForwardKinematics(data.skeleton, pose, &fk);
    synthetic.emplace_back();
    for (int m = 0; m < data.calibration.marker_set.num_markers(); ++m) {
      synthetic.back().push_back(data.calibration.marker_set.Position(m, fk));
    }
  }
  Motion motion;
  SequenceSolveReport report;
  const Status status = SolveSequence(data.skeleton, data.calibration.marker_set, synthetic,
                                      Options(SolverKind::kCeres), RestPose(data.skeleton), &motion, &report);
  ASSERT_TRUE(status.ok()) << status.message();
  const Comparison c = Compare(data, motion, report);
  std::printf("02_01 synthetic from the AMC: joint error mean %.3f mm, max %.1f mm (worst %s), RMS "
              "residual %.2g mm\n", c.mean_position_mm, c.max_position_mm,
              data.skeleton.name(c.worst_joint).c_str(), c.rms_residual_mm);
  EXPECT_LT(c.rms_residual_mm, 1e-3);
  EXPECT_LT(c.mean_position_mm, 2.5);  // Measured 1.61 mm.
  int markerless_fingers = 0;
  for (int j = 0; j < data.skeleton.num_joints(); ++j) {
    const std::string& name = data.skeleton.name(j);
    if (name == "lfingers" || name == "rfingers") {
      ++markerless_fingers;
      continue;  // Measured up to 55 mm: the hand's rotation about its one marker is free.
    }
    EXPECT_LT(c.joint_max_mm[j], 0.01) << name;  // Measured < 1e-4 mm everywhere else.
  }
  EXPECT_EQ(markerless_fingers, 2);
}

// (b) Ceres and DLS minimize the same residual blocks: on 02_01 their per-frame costs
// agree. Measured (ASF dofs enforced): total 33.99183 vs 33.99198 (4.5e-6 relative),
// worst frame 6.8e-4 relative.
TEST(CmuMarkerSolve, Cmu0201SolversAgreeOnTheCost) {
  MOCAPSOLVE_CMU_0201(data);
  Motion solved[2];
  SequenceSolveReport reports[2];
  for (int k = 0; k < 2; ++k) {
    const Status status = SolveSequence(data.skeleton, data.calibration.marker_set, data.observed,
                                        Options(k == 0 ? SolverKind::kCeres : SolverKind::kDls),
                                        RestPose(data.skeleton), &solved[k], &reports[k]);
    ASSERT_TRUE(status.ok()) << status.message();
  }
  double worst_relative = 0.0, total[2] = {0.0, 0.0};
  int worst_frame = -1;
  for (size_t f = 0; f < data.observed.size(); ++f) {
    double cost[2];
    for (int k = 0; k < 2; ++k) {
      cost[k] = FrameCost(data.skeleton, data.calibration.marker_set, solved[k].frames[f], data.observed[f]);
      total[k] += cost[k];
    }
    const double relative = std::abs(cost[0] - cost[1]) / cost[0];
    if (relative > worst_relative) worst_relative = relative, worst_frame = static_cast<int>(f);
  }
  std::printf("02_01 total cost: ceres %.9g, dls %.9g, relative difference %.3g; worst frame %d: %.3g\n",
              total[0], total[1], std::abs(total[0] - total[1]) / total[0], worst_frame, worst_relative);
  // The reports' totals are the same sums.
  EXPECT_NEAR(reports[0].total_final_cost, total[0], 1e-9 * total[0]);
  EXPECT_NEAR(reports[1].total_final_cost, total[1], 1e-9 * total[1]);
  EXPECT_LT(std::abs(total[0] - total[1]), 0.01 * total[0]);
  EXPECT_LT(worst_relative, 0.01) << "frame " << worst_frame;
}

// (b2) The lean tree kernel and the generic DLS solver on 02_01 with the command line's
// defaults (prior 20 mm/rad, function tolerance 1e-6): the same iterations and poses to
// round-off, so the same RMS residual (BENCHMARKS.md: 3.932 mm with the shoulder markers
// on the thorax; 3.958 mm, 1,397 iterations, since calibration puts them on the clavicles).
TEST(CmuMarkerSolve, Cmu0201LeanAndGenericDlsAgree) {
  MOCAPSOLVE_CMU_0201(data);
  Motion solved[2];
  SequenceSolveReport reports[2];
  for (int k = 0; k < 2; ++k) {
    MarkerSolveOptions options = Options(k == 0 ? SolverKind::kDls : SolverKind::kDlsGeneric);
    options.prior_rotation_weight = 20.0 / data.mm;
    options.dls.function_tolerance = 1e-6;
    options.dls.gradient_tolerance = 1e-10;
    options.dls.parameter_tolerance = 1e-8;
    const Status status = SolveSequence(data.skeleton, data.calibration.marker_set, data.observed, options,
                                        RestPose(data.skeleton), &solved[k], &reports[k]);
    ASSERT_TRUE(status.ok()) << status.message();
  }
  std::printf("02_01 lean / generic DLS: RMS %.4f / %.4f mm, iterations %ld / %ld\n",
              reports[0].rms_marker_error * data.mm, reports[1].rms_marker_error * data.mm,
              reports[0].total_iterations, reports[1].total_iterations);
  EXPECT_EQ(reports[0].total_iterations, reports[1].total_iterations);
  EXPECT_NEAR(reports[0].rms_marker_error * data.mm, reports[1].rms_marker_error * data.mm, 1e-6);
  EXPECT_NEAR(reports[0].rms_marker_error * data.mm, 3.958, 0.0005);
  double worst = 0.0;
  for (size_t f = 0; f < data.observed.size(); ++f) {
    for (int j = 0; j < data.skeleton.num_joints(); ++j) {
      worst = std::max(worst, AngularDistance(solved[0].frames[f].rotations[j], solved[1].frames[f].rotations[j]));
    }
  }
  // Radians. Measured 5.8e-7: round-off carried through 343 warm-started frames, grown
  // along the flat directions the function tolerance leaves unresolved (a marker-less hand).
  EXPECT_LT(worst, 1e-5);
}

// (c) CMU 02_05 (1854 frames, RSHN missing in 3 frames at the start) with the 02_01
// calibration, every frame, both solvers. Measured (ASF dofs enforced, one core): Ceres
// 1.4 s (1350 frames/s), DLS 1.1 s (1600 frames/s); RMS residual 9.19 mm (worst frame
// 14.2 mm); no frame unsolved; at the 50-iteration limit 2 (Ceres) and 1 (DLS) frames,
// the same slow crawl as on 02_01 (cost settled, steps creeping along an ill-conditioned
// direction); with 100 iterations Ceres converges on every frame.
TEST(CmuMarkerSolve, Cmu0205WithThe0201Calibration) {
  MOCAPSOLVE_CMU_0201(data);
  MOCAPSOLVE_DATA_FILE(c3d_0205, "c3d/cmu_02_05.c3d");
  MarkerTrajectories file;
  Status status = ReadMarkerFile(c3d_0205, &file);
  ASSERT_TRUE(status.ok()) << status.message();
  std::vector<std::vector<Eigen::Vector3d>> observed;
  status = GatherObservations(data.calibration.marker_set, file, data.transform, &observed);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(observed.size(), 1854u);
  int missing = 0;
  for (const auto& frame : observed) {
    for (const Eigen::Vector3d& x : frame) missing += !x.allFinite();
  }
  EXPECT_EQ(missing, 3);
  for (SolverKind kind : {SolverKind::kCeres, SolverKind::kDls}) {
    Motion solved;
    SequenceSolveReport report;
    status = SolveSequence(data.skeleton, data.calibration.marker_set, observed, Options(kind),
                           RestPose(data.skeleton), &solved, &report);
    ASSERT_TRUE(status.ok()) << status.message();
    std::printf("02_05 %s: %d frames in %.2f s (%.0f frames/s), %.1f iterations/frame, unsolved %d, at "
                "limit %d, RMS residual %.2f mm, worst frame %.2f mm\n",
                Name(kind), report.frames, report.solve_seconds, report.frames / report.solve_seconds,
                double(report.total_iterations) / report.frames, report.unsolved_frames,
                report.unconverged_frames, report.rms_marker_error * data.mm, report.max_frame_rms * data.mm);
    EXPECT_EQ(report.unsolved_frames, 0) << Name(kind);
    EXPECT_LE(report.unconverged_frames, 5) << Name(kind);           // Measured 2, 1.
    EXPECT_LT(report.rms_marker_error * data.mm, 13.8) << Name(kind);  // Measured 9.19 mm.
    EXPECT_LT(report.max_frame_rms * data.mm, 21.0) << Name(kind);    // Measured 14.2 mm.
  }
  // Converged on every frame given a few more iterations.
  MarkerSolveOptions options = Options(SolverKind::kCeres);
  options.ceres.max_num_iterations = 100;
  Motion solved;
  SequenceSolveReport report;
  status = SolveSequence(data.skeleton, data.calibration.marker_set, observed, options,
                         RestPose(data.skeleton), &solved, &report);
  ASSERT_TRUE(status.ok()) << status.message();
  std::printf("02_05 ceres, 100 iterations: at limit %d, %.2f s\n", report.unconverged_frames, report.solve_seconds);
  EXPECT_EQ(report.unsolved_frames, 0);
  EXPECT_EQ(report.unconverged_frames, 0);
}

}  // namespace
}  // namespace mocapsolve
