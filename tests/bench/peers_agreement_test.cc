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

}  // namespace
}  // namespace mocapsolve
