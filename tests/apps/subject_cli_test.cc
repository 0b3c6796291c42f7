// Subject files on the command line: calibrate CMU 02_01 with --out_subject, then solve
// 02_05 with only --subject: the same result as with the explicit mapping flags.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

TEST(SubjectCli, SolveWithSubjectEqualsExplicitFlags) {
  MOCAPSOLVE_DATA_FILE(asf, "amc/02.asf");
  MOCAPSOLVE_DATA_FILE(amc, "amc/02_01.amc");
  MOCAPSOLVE_DATA_FILE(c3d, "c3d/02_01.c3d");
  MOCAPSOLVE_DATA_FILE(take, "c3d/cmu_02_05.c3d");
  const std::string set = testing::TempPath("02.json");
  const std::string subject = testing::TempPath("S02.json");
  std::string output;
  ASSERT_EQ(testing::RunCli("calibrate --quiet --motion=" + amc + " --skeleton=" + asf + " --markers=" + c3d +
                                " --axes=y,z,x --out=" + set + " --out_subject=" + subject, &output), 0)
      << output;
  EXPECT_THAT(testing::ReadTextFile(subject), HasSubstr("\"axes\": \"y,z,x\""));

  const std::string explicit_bvh = testing::TempPath("explicit.bvh");
  const std::string subject_bvh = testing::TempPath("subject.bvh");
  const std::string common = " --quiet --solver=dls --max_frames=40 --markers=" + take;
  const std::string no_rest = " --rest_prior_weight=0";
  ASSERT_EQ(testing::RunCli("solve" + common + no_rest + " --skeleton=" + asf + " --markerset=" + set +
                                " --axes=y,z,x --out=" + explicit_bvh, &output), 0) << output;
  ASSERT_EQ(testing::RunCli("solve" + common + no_rest + " --subject=" + subject + " --out=" + subject_bvh, &output),
            0)
      << output;
  const std::string a = testing::ReadTextFile(explicit_bvh);
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(a, testing::ReadTextFile(subject_bvh));
  // The subject also holds the calibration take's mean pose, the rest prior's reference: with
  // the prior on, the solve through the subject differs from the one toward zero rotations.
  EXPECT_THAT(testing::ReadTextFile(subject), HasSubstr("\"mean_pose\": {"));
  const std::string rest = " --rest_prior_weight=5";
  ASSERT_EQ(testing::RunCli("solve" + common + rest + " --skeleton=" + asf + " --markerset=" + set +
                                " --axes=y,z,x --out=" + explicit_bvh, &output), 0) << output;
  ASSERT_EQ(testing::RunCli("solve" + common + rest + " --subject=" + subject + " --out=" + subject_bvh, &output), 0)
      << output;
  const std::string toward_mean = testing::ReadTextFile(subject_bvh);
  EXPECT_NE(testing::ReadTextFile(explicit_bvh), toward_mean);
  // By default (-1) the prior is on at 5 toward a subject's mean pose, and off without one.
  const std::string default_bvh = testing::TempPath("default.bvh");
  ASSERT_EQ(testing::RunCli("solve" + common + " --subject=" + subject + " --out=" + default_bvh, &output), 0)
      << output;
  EXPECT_EQ(testing::ReadTextFile(default_bvh), toward_mean);
  ASSERT_EQ(testing::RunCli("solve" + common + " --skeleton=" + asf + " --markerset=" + set + " --axes=y,z,x --out=" +
                                default_bvh, &output), 0)
      << output;
  EXPECT_EQ(testing::ReadTextFile(default_bvh), a);
  EXPECT_EQ(testing::RunCli("solve" + common + " --rest_prior_weight=-2 --subject=" + subject + " --out=" +
                                default_bvh, &output), 1);
  EXPECT_THAT(output, HasSubstr("--rest_prior_weight: expected >= 0, or -1 (auto)"));

  // Both ways of naming the model: an error naming both flags, no output.
  const std::string both = testing::TempPath("both.bvh");
  EXPECT_EQ(testing::RunCli("solve" + common + " --subject=" + subject + " --axes=y,z,x --out=" + both, &output),
            1);
  EXPECT_THAT(output, HasSubstr("--subject and --axes"));
  EXPECT_FALSE(testing::FileExists(both));
  // repair and evaluate take it too (parse and load only: a bad flag value stops them after the take).
  EXPECT_EQ(testing::RunCli("repair --quiet --subject=" + subject + " --skeleton=" + asf + " --markers=" + take +
                                " --out_markers=" + testing::TempPath("r.c3d"), &output),
            1);
  EXPECT_THAT(output, HasSubstr("--subject and --skeleton"));
}

// fit_skeleton from a template subject on a take without a skeleton (a few frames and
// iterations: a smoke test of the flow; the measured fit is in the README): it prints the
// checks, writes them in its report, and its subject solves the take with --subject alone.
TEST(SubjectCli, FitSkeletonFromTemplateSubject) {
  MOCAPSOLVE_DATA_FILE(asf, "amc/02.asf");
  MOCAPSOLVE_DATA_FILE(amc, "amc/02_01.amc");
  MOCAPSOLVE_DATA_FILE(c3d, "c3d/02_01.c3d");
  MOCAPSOLVE_DATA_FILE(squat, "c3d/squat.c3d");
  const std::string templ = testing::TempPath("S02.json");
  std::string output;
  ASSERT_EQ(testing::RunCli("calibrate --quiet --motion=" + amc + " --skeleton=" + asf + " --markers=" + c3d +
                                " --axes=y,z,x --out=" + testing::TempPath("02.json") + " --out_subject=" + templ,
                            &output),
            0)
      << output;
  const std::string subject = testing::TempPath("squat.json"), report = testing::TempPath("fit.json");
  ASSERT_EQ(testing::RunCli("fit_skeleton --quiet --solver=dls --template_subject=" + templ + " --markers=" + squat +
                                " --fit_max_frames=40 --fit_iterations=2 --attach_rounds=1 --attach_iterations=1"
                                " --check=warn --out_subject=" + subject + " --report=" + report, &output),
            0)
      << output;
  EXPECT_THAT(output, HasSubstr("checks: marker RMS"));
  EXPECT_THAT(testing::ReadTextFile(report), HasSubstr("\"torso_error_mean_deg\""));
  EXPECT_THAT(testing::ReadTextFile(subject), HasSubstr("\"mean_pose\": {"));
  ASSERT_EQ(testing::RunCli("solve --quiet --solver=dls --max_frames=20 --subject=" + subject + " --markers=" + squat +
                                " --out=" + testing::TempPath("squat.bvh"), &output),
            0)
      << output;
  // The template subject holds the skeleton: --skeleton beside it is an error.
  EXPECT_EQ(testing::RunCli("fit_skeleton --template_subject=" + templ + " --skeleton=" + asf + " --markers=" + squat +
                                " --out_subject=" + testing::TempPath("x.json"), &output),
            1);
  EXPECT_THAT(output, HasSubstr("--template_subject and --skeleton"));
}

}  // namespace
}  // namespace mocapsolve
