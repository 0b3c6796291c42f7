// FK agreement of CMU 16_15 read as ASF/AMC (amc/16.asf + amc/16_15.amc) and as the
// MotionBuilder 7.5 BVH conversion of the same take (bvh/16_15.bvh; both from IMUSim's
// test data, shared/data/README.md). This pins the Acclaim conventions of asf_reader.h:
// Euler angles applied in the written order (x first for "XYZ"), W_b = W_p C M C^-1,
// joints at the bone's start. (The opposite multiplication order gives 4.4 cm mean and
// 33 cm max error over all frames, wrong already on the spine, which agrees exactly
// below; numbers for the joints.)
//
// What MotionBuilder did, as measured here:
// - Joints: each BVH joint sits at the start of the ASF bone of the same name (the
//   parent bone's tail); lhipjoint/rhipjoint (no dofs) are folded into the femur
//   offsets; end sites are the leaf bones' tails. The rest pose differs (arms hang
//   along -y in the BVH), which the BVH rotations absorb.
// - Time: consistent with limb rotations plotted at 30 Hz and interpolated to 120 Hz:
//   on every 4th frame (f % 4 == 0) all joints agree to the rounding of the printed
//   values (6 significant digits: +-0.0005 cm on coordinates near 100 cm, +-0.0005 deg on
//   angles above 100 deg), in between by 0.1-0.2 cm on average. The spine rotations
//   (rest frames coincide) agree on every frame. Frames 0-7 are worst: the AMC has a
//   dropout (lhumerus "0 0 0" in AMC frames 1-2, then -39 25 76), which the
//   interpolation turns into a 40 cm excursion of the left hand.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/amc_reader.h"
#include "io/asf_reader.h"
#include "io/bvh_reader.h"
#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

// ASF ":units length 0.45": one unit is 1/0.45 inch; the BVH is in cm.
constexpr double kCmPerAsfUnit = 2.54 / 0.45;

struct ErrorStats {
  double sum = 0.0, max = 0.0;
  long count = 0;
  std::string worst;

  void Add(double error, const std::string& name, int frame) {
    sum += error;
    ++count;
    if (error > max) {
      max = error;
      worst = name + " frame " + std::to_string(frame);
    }
  }
  double mean() const { return count > 0 ? sum / count : 0.0; }
  void Print(const char* what) const {
    std::printf("%-44s mean %.6f cm, max %.6f cm (%s), %ld samples\n", what, mean(), max,
                worst.c_str(), count);
  }
};

TEST(AsfAmcVsBvh, WorldJointPositionsAgree) {
  MOCAPSOLVE_DATA_FILE(asf_path, "amc/16.asf");
  MOCAPSOLVE_DATA_FILE(amc_path, "amc/16_15.amc");
  MOCAPSOLVE_DATA_FILE(bvh_path, "bvh/16_15.bvh");
  Skeleton asf;
  AsfInfo info;
  Motion amc;
  Status status = ReadAsf(asf_path, &asf, &info);
  ASSERT_TRUE(status.ok()) << status.message();
  status = ReadAmc(amc_path, asf, info, 120.0, &amc);
  ASSERT_TRUE(status.ok()) << status.message();
  Skeleton bvh;
  Motion bvh_motion;
  status = ReadBvh(bvh_path, &bvh, &bvh_motion);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(amc.num_frames(), 471);
  ASSERT_EQ(bvh_motion.num_frames(), amc.num_frames());
  EXPECT_NEAR(bvh_motion.frame_rate, amc.frame_rate, 1e-3);

  // Match by name: BVH joints are ASF bones, BVH end sites ASF leaf-bone tails (both
  // readers name an end site "<joint>_End").
  ASSERT_EQ(bvh.num_joints(), 29);
  std::vector<int> asf_joint(bvh.num_joints());
  for (int j = 0; j < bvh.num_joints(); ++j) {
    asf_joint[j] = asf.FindJoint(bvh.name(j));
    ASSERT_GE(asf_joint[j], 0) << bvh.name(j);
  }
  ASSERT_EQ(bvh.end_sites().size(), 7u);
  ASSERT_EQ(asf.end_sites().size(), 7u);
  std::vector<int> asf_site(bvh.end_sites().size(), -1);
  for (size_t s = 0; s < bvh.end_sites().size(); ++s) {
    for (size_t t = 0; t < asf.end_sites().size(); ++t) {
      if (asf.end_sites()[t].name == bvh.end_sites()[s].name) asf_site[s] = static_cast<int>(t);
    }
    ASSERT_GE(asf_site[s], 0) << bvh.end_sites()[s].name;
  }

  ErrorStats plotted, settled, all, end_sites;
  // Rotations: the two rest poses differ, so world_from_joint differs by a constant
  // per-joint rotation D_j = asf^-1 * bvh; its drift from frame 0 checks the twist too,
  // which positions alone do not see.
  ErrorStats rotation_drift_deg;
  QuaternionVector rest_difference(bvh.num_joints());
  FkData asf_fk(asf), bvh_fk(bvh);
  for (int f = 0; f < amc.num_frames(); ++f) {
    ForwardKinematics(asf, amc.frames[f], &asf_fk);
    ForwardKinematics(bvh, bvh_motion.frames[f], &bvh_fk);
    auto add = [&](double error, const std::string& name) {
      all.Add(error, name, f);
      if (f % 4 == 0) plotted.Add(error, name, f);
      if (f >= 8) settled.Add(error, name, f);
    };
    for (int j = 0; j < bvh.num_joints(); ++j) {
      const Eigen::Quaterniond difference =
          asf_fk.world_rotations[asf_joint[j]].conjugate() * bvh_fk.world_rotations[j];
      if (f == 0) rest_difference[j] = difference;
      if (f % 4 == 0) {
        rotation_drift_deg.Add(RadToDeg(AngularDistance(rest_difference[j], difference)),
                               bvh.name(j), f);
      }
      add((kCmPerAsfUnit * asf_fk.world_positions[asf_joint[j]] - bvh_fk.world_positions[j])
              .norm(),
          bvh.name(j));
    }
    const Vector3dVector asf_sites = EndSitePositions(asf, asf_fk);
    const Vector3dVector bvh_sites = EndSitePositions(bvh, bvh_fk);
    for (size_t s = 0; s < bvh_sites.size(); ++s) {
      const double error = (kCmPerAsfUnit * asf_sites[asf_site[s]] - bvh_sites[s]).norm();
      add(error, bvh.end_sites()[s].name);
      end_sites.Add(error, bvh.end_sites()[s].name, f);
    }
  }
  plotted.Print("joints+end sites, plotted frames (f % 4 == 0)");
  settled.Print("joints+end sites, frames 8..470");
  all.Print("joints+end sites, all frames");
  end_sites.Print("end sites only, all frames");
  std::printf("rotation drift (deg), plotted frames: mean %.6f, max %.6f (%s)\n",
              rotation_drift_deg.mean(), rotation_drift_deg.max, rotation_drift_deg.worst.c_str());

  // Tolerances are about twice what was measured (in brackets).
  // The mapping itself: exact up to the BVH's printed rounding [mean 0.00019, max 0.00059 cm;
  // rotations, twist included: mean 0.00027, max 0.0015 deg].
  EXPECT_LT(plotted.mean(), 4e-4);
  EXPECT_LT(plotted.max, 1.2e-3);
  EXPECT_LT(rotation_drift_deg.mean(), 6e-4);
  EXPECT_LT(rotation_drift_deg.max, 3e-3);
  // MotionBuilder's 30 Hz plot + interpolation in between [mean 0.113, max 2.08 cm].
  EXPECT_LT(settled.mean(), 0.23);
  EXPECT_LT(settled.max, 4.2);
  // All frames, including the interpolated dropout at the start [mean 0.150, max 43.9 cm].
  EXPECT_LT(all.mean(), 0.3);
  EXPECT_LT(all.max, 88.0);
}

}  // namespace
}  // namespace mocapsolve
