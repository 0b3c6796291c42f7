// The shipped subject template (pipeline/shipped_templates.h): it reads, is a humanoid with
// CMU's 41 markers, and fit_skeleton's template loading falls back on it when given none.
#include "pipeline/shipped_templates.h"

#include <gtest/gtest.h>

#include "kinematics/forward_kinematics.h"
#include "kinematics/motion.h"
#include "problems/retarget/humanoid_roles.h"
#include "tasks/fit_skeleton_task.h"

namespace mocapsolve {
namespace {

TEST(ShippedTemplates, DefaultTemplateIsCmuSubject2) {
  Subject subject;
  ASSERT_TRUE(DefaultTemplateSubject(&subject).ok());
  EXPECT_EQ(subject.skeleton.num_joints(), 31);
  EXPECT_EQ(subject.markers.num_markers(), 41);
  EXPECT_TRUE(subject.skeleton.unit().known());
  EXPECT_EQ(subject.mean_pose.size(), 31u);
  FkData fk(subject.skeleton);
  ForwardKinematics(subject.skeleton, RestPose(subject.skeleton), &fk);
  const HumanoidRoles roles = FindHumanoidRoles(subject.skeleton, fk.world_positions);
  EXPECT_TRUE(roles.humanoid) << roles.why_not;
}

TEST(ShippedTemplates, FitSkeletonLoadsItWhenNoTemplateIsGiven) {
  SkeletonFitInputs inputs;
  inputs.markers_path = "take.c3d";
  ASSERT_TRUE(LoadSkeletonFitTemplate("", "", "", "", &inputs).ok());
  EXPECT_TRUE(inputs.from_template_subject);
  EXPECT_EQ(inputs.template_name, DefaultTemplateName());
  EXPECT_EQ(inputs.templ.markers.num_markers(), 41);
  // A skeleton without its marker set is still an error.
  const Status status = LoadSkeletonFitTemplate("", "a.bvh", "", "", &inputs);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("--markers and either --template_subject"), std::string::npos);
}

}  // namespace
}  // namespace mocapsolve
