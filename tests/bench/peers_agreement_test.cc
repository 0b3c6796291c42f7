// The peers benchmark's precondition, as a test: when bench/peers is built (some peer
// kinematics library was found: scripts/setup.sh --with-peers), every peer's model of
// CMU 01_01 (31 joints, 93 synthetic markers) must give the same joint origins and marker
// positions as our FK, within 1e-9 skeleton units, at every 50th frame of the clip. Skips
// when the executable is not built.
#include <gtest/gtest.h>

#include "tests/test_support.h"

namespace mocapsolve {
namespace {

TEST(PeersAgreement, EveryPeerFkMatchesOurs) {
  MOCAPSOLVE_DATA_FILE(path, "bvh/01_01.bvh");
  const std::string program = testing::BuiltProgramPath("mocapsolve_peers_bench");
  if (!testing::FileExists(program)) {
    GTEST_SKIP() << "mocapsolve_peers_bench is not built: no peer kinematics library (KDL, MuJoCo, DART) "
                    "was found at configure time (scripts/setup.sh --with-peers installs them)";
  }
  std::string output;
  // 1e-9: the peers compose the same rigid transforms in another order (KDL through
  // Euler angles); round-off on ~30 unit offsets stays near 1e-13.
  const int code = testing::RunProgram(program, "--check_only --check_stride=50 --tolerance=1e-9 --motion=" + path,
                                       &output);
  EXPECT_EQ(code, 0) << output;
  EXPECT_EQ(output.find("DISAGREE"), std::string::npos) << output;
  EXPECT_NE(output.find(": agree"), std::string::npos) << output;
}

TEST(PeersAgreement, InterleavedHarnessPrintsEveryRatio) {
  // The harness `mocapsolve bench --problem=peers` runs, at a token size (figures
  // meaningless): every case present, every ratio printed, every IK at its target.
  MOCAPSOLVE_DATA_FILE(path, "bvh/01_01.bvh");
  const std::string program = testing::BuiltProgramPath("mocapsolve_peers_bench");
  if (!testing::FileExists(program)) GTEST_SKIP() << "mocapsolve_peers_bench is not built";
  std::string output;
  const int code = testing::RunProgram(program,
                                       "--interleaved --rounds=1 --fk_frames=20 --jac_frames=5 --ik_frames=3 "
                                       "--dart_ik_frames=1 --check_stride=1000 --motion=" + path,
                                       &output);
  ASSERT_EQ(code, 0) << output;
  for (const char* figure : {"PEERS fk_mocapsolve_ratio_to_ours 1", "PEERS jac_mocapsolve_ratio_to_ours 1",
                             "PEERS ik_mocapsolve_dls_ratio_to_ours 1", "PEERS ik_mocapsolve_ceres_ratio_to_ours",
                             "PEERS ik_mocapsolve_dls_generic_mean_rms"}) {
    EXPECT_NE(output.find(figure), std::string::npos) << figure << "\n" << output;
  }
  for (const char* peer : {"kdl", "mujoco", "dart"}) {
    if (output.find(std::string("check ") + peer) == std::string::npos) continue;  // Not built here.
    EXPECT_NE(output.find(std::string("PEERS fk_") + peer + "_ratio_to_ours"), std::string::npos) << output;
    EXPECT_NE(output.find(std::string("PEERS jac_") + peer + "_ratio_to_ours"), std::string::npos) << output;
  }
  // Our three solvers (and KDL, when built) reach the target on all three frames.
  int complete = 0;
  for (size_t at = output.find("3/3 at target"); at != std::string::npos; at = output.find("3/3 at target", at + 1)) {
    ++complete;
  }
  EXPECT_GE(complete, 3) << output;
}

}  // namespace
}  // namespace mocapsolve
