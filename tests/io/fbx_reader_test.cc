#include "io/fbx_reader.h"

#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "io/atomic_file.h"
#include "kinematics/forward_kinematics.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

// The CMU clips (Blender export of the cgspeed BVH): 31 joints from Hips down (the
// armature object '<take>' is keyed but constant, so it is baked into the root), 7 end
// sites, keys at 120 fps. Their UnitScaleFactor says cm, but the values are CMU units
// x 100 (the Blender import kept CMU units and the export scaled metres to cm), so a
// person's height is 2500-3500 "cm": with the CMU FAQ factor (0.05644 m per unit, /100)
// that is 1.4-2.0 m.
struct FbxCase {
  const char* file;
  int frames;
};

class CmuFbx : public ::testing::TestWithParam<FbxCase> {};

TEST_P(CmuFbx, LoadsWithPlausibleSkeletonAndFinitePoses) {
  MOCAPSOLVE_DATA_FILE(path, std::string("fbx/") + GetParam().file);
  Skeleton skeleton;
  Motion motion;
  FbxInfo info;
  const Status status = ReadFbx(path, {}, &skeleton, &motion, &info);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(skeleton.num_joints(), 31);
  EXPECT_EQ(skeleton.name(0), "Hips");
  EXPECT_EQ(skeleton.end_sites().size(), 7u);
  EXPECT_GE(skeleton.FindJoint("LeftUpLeg"), 0);
  EXPECT_EQ(skeleton.unit().name, "cm");
  EXPECT_EQ(info.unit_scale_factor, 1.0);
  EXPECT_EQ(motion.frame_rate, 120.0);
  EXPECT_EQ(motion.num_frames(), GetParam().frames);
  EXPECT_TRUE(ValidateMotion(skeleton, motion).ok());
  const double metres_per_unit = 0.0254 / 0.45 / 100.0;
  FkData fk(skeleton);
  double min_height = 1e300, max_height = 0.0, hips_travel = 0.0;
  Eigen::Vector3d first_hips = Eigen::Vector3d::Zero();
  for (int f = 0; f < motion.num_frames(); ++f) {
    ForwardKinematics(skeleton, motion.frames[f], &fk);
    double lo = 1e300, hi = -1e300;
    for (const Eigen::Vector3d& p : fk.world_positions) {
      ASSERT_TRUE(p.allFinite());
      lo = std::min(lo, p.y());
      hi = std::max(hi, p.y());
    }
    for (const Eigen::Vector3d& p : EndSitePositions(skeleton, fk)) {
      lo = std::min(lo, p.y());
      hi = std::max(hi, p.y());
    }
    min_height = std::min(min_height, (hi - lo) * metres_per_unit);
    max_height = std::max(max_height, (hi - lo) * metres_per_unit);
    if (f == 0) first_hips = fk.world_positions[0];
    hips_travel = std::max(hips_travel, (fk.world_positions[0] - first_hips).norm() * metres_per_unit);
  }
  std::printf("%s: %d joints, %d frames at %g fps, y extent %.3f..%.3f m (CMU units), hips travel %.2f m\n",
              GetParam().file, skeleton.num_joints(), motion.num_frames(), motion.frame_rate, min_height,
              max_height, hips_travel);
  // Y-up (the armature's axis change baked in): a walking/running person's vertical
  // extent stays between 1.2 and 2.0 m, and the hips travel more than a metre.
  EXPECT_GT(min_height, 1.2);
  EXPECT_LT(max_height, 2.0);
  EXPECT_GT(hips_travel, 1.0);
}

INSTANTIATE_TEST_SUITE_P(SharedData, CmuFbx,
                         ::testing::Values(FbxCase{"09_11_cmu.fbx", 166}, FbxCase{"07_01_cmu.fbx", 317},
                                           FbxCase{"08_02_cmu.fbx", 310}),
                         [](const ::testing::TestParamInfo<FbxCase>& info) {
                           std::string name = info.param.file;
                           return "cmu_" + name.substr(0, 5);
                         });

TEST(FbxReader, AnimationByNameAndRate) {
  MOCAPSOLVE_DATA_FILE(path, "fbx/09_11_cmu.fbx");
  Skeleton skeleton;
  Motion motion;
  FbxInfo info;
  ASSERT_TRUE(ReadFbx(path, {}, &skeleton, &motion, &info).ok());
  ASSERT_EQ(info.animation_names.size(), 1u);
  FbxReadOptions options;
  options.animation = info.animation_names[0];
  options.frame_rate = 30.0;
  Motion at30;
  ASSERT_TRUE(ReadFbx(path, options, &skeleton, &at30).ok());
  EXPECT_EQ(at30.num_frames(), 42);  // 1.375 s at 30 fps.
  // Frame k at 30 fps is frame 4k at 120 fps (both on keys).
  for (int k = 0; k < at30.num_frames(); ++k) {
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      EXPECT_LT(at30.frames[k].rotations[j].angularDistance(motion.frames[4 * k].rotations[j]), 1e-9);
    }
  }
  options.animation = "walk";
  const Status status = ReadFbx(path, options, &skeleton, &at30);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("animation 'walk' not found"), std::string::npos) << status.message();
}

TEST(FbxReader, BadFilesFailWithOneLine) {
  MOCAPSOLVE_DATA_FILE(path, "fbx/09_11_cmu.fbx");
  std::string bytes;
  ASSERT_TRUE(ReadFileToString(path, &bytes).ok());
  const std::string truncated = testing::TempPath("truncated.fbx");
  ASSERT_TRUE(WriteFileAtomically(truncated, bytes.substr(0, bytes.size() / 3)).ok());
  const std::string garbage = testing::TempPath("garbage.fbx");
  ASSERT_TRUE(WriteFileAtomically(garbage, "this is not an FBX file\n").ok());
  for (const std::string& file : {truncated, garbage, std::string("/nonexistent/x.fbx")}) {
    Skeleton skeleton;
    Motion motion;
    const Status status = ReadFbx(file, {}, &skeleton, &motion);
    ASSERT_FALSE(status.ok()) << file;
    EXPECT_EQ(status.message().find('\n'), std::string::npos) << status.message();
    EXPECT_EQ(status.message().rfind(file + ": ", 0), 0u) << status.message();
    std::printf("%s\n", status.message().c_str());
  }
}

}  // namespace
}  // namespace mocapsolve
