// `convert` between marker formats (issue 17): C3D <-> TRC keeps labels, rate, first frame
// and missing samples; --out_units converts the coordinates; --axes permutes them as for
// solving ((x, y, z)_out = IN's named axes); a marker file never becomes a motion.
#include <cmath>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/marker_file.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

TEST(ConvertMarkers, C3dToTrcAndBackWithUnitsAndAxes) {
  const std::string walk = testing::TempPath("walk.bvh"), c3d = testing::TempPath("walk.c3d");
  std::string output;
  ASSERT_EQ(testing::RunCli("generate --demo_out=" + walk + " --frames=30 --fps=30", &output), 0) << output;
  ASSERT_EQ(testing::RunCli("markers --motion=" + walk + " --skeleton_units=cm --markerset=auto:2 --out=" + c3d +
                            " --write_markerset=" + testing::TempPath("set.json"), &output), 0) << output;
  // A gap, so that missing samples are seen to survive.
  const std::string damaged = testing::TempPath("damaged.c3d");
  ASSERT_EQ(testing::RunCli("corrupt --markers=" + c3d + " --out=" + damaged + " --seed=3 --mask_out=" +
                            testing::TempPath("truth.csv"), &output), 0) << output;
  const std::string trc = testing::TempPath("walk.trc"), back = testing::TempPath("back.c3d");
  ASSERT_EQ(testing::RunCli("convert " + damaged + " " + trc, &output), 0) << output;
  ASSERT_EQ(testing::RunCli("convert " + trc + " " + back + " --out_units=m --axes=y,z,x", &output), 0) << output;

  MarkerTrajectories in, out;
  ASSERT_TRUE(ReadMarkerFile(damaged, &in).ok());
  ASSERT_TRUE(ReadMarkerFile(back, &out).ok());
  ASSERT_GT(in.CountMissing(), 0);
  EXPECT_EQ(out.labels(), in.labels());
  EXPECT_EQ(out.num_frames(), in.num_frames());
  EXPECT_EQ(out.first_frame, in.first_frame);
  EXPECT_DOUBLE_EQ(out.frame_rate, in.frame_rate);
  EXPECT_EQ(out.unit.name, "m");
  EXPECT_EQ(out.CountMissing(), in.CountMissing());
  double worst = 0.0;
  for (int f = 0; f < in.num_frames(); ++f) {
    for (int m = 0; m < in.num_markers(); ++m) {
      ASSERT_EQ(out.valid(f, m), in.valid(f, m)) << f << " " << m;
      if (!in.valid(f, m)) continue;
      const Eigen::Vector3d a = in.position(f, m) / 1000.0;  // mm -> m
      const Eigen::Vector3d expected(a.y(), a.z(), a.x());
      worst = std::max(worst, (out.position(f, m) - expected).norm());
    }
  }
  EXPECT_LT(worst, 1e-6);  // Float32 C3D samples: well under a micrometre at metre scale.

  EXPECT_EQ(testing::RunCli("convert " + trc + " " + testing::TempPath("x.bvh"), &output), 1);
  EXPECT_THAT(output, HasSubstr("marker files convert to marker files"));
  EXPECT_EQ(testing::RunCli("convert " + trc + " " + testing::TempPath("y.c3d") + " --out_units=furlong", &output), 1);
  EXPECT_THAT(output, HasSubstr("--out_units='furlong'"));
  EXPECT_FALSE(testing::FileExists(testing::TempPath("y.c3d")));
}

}  // namespace
}  // namespace mocapsolve
