#include "kinematics/rotation.h"
#include <gtest/gtest.h>
TEST(Rotation, Builds) { EXPECT_TRUE(true); }
