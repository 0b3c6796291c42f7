// `mocapsolve pipeline --subject=auto` (and with no --subject) and `batch --subject=auto`
// on small synthetic takes (tests/auto_subject_takes.h: the shipped template's markers on a
// walk, by their CMU labels or renamed at random; random points): the subject is fitted from
// the take, written as DIR/subject.json and described in the report; a take it cannot fit
// is one line, exit 1 and nothing in DIR.
#include <sys/stat.h>

#include <cstdlib>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/json_reader.h"
#include "io/marker_file.h"
#include "pipeline/subject.h"
#include "tests/auto_subject_takes.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

// A short fit (the take is the template's own body): the fit options are pipeline flags.
const char kShortFit[] = " --fit_iterations=4 --attach_rounds=1 --attach_iterations=3 --view=off";

std::string WriteTake(const MarkerTrajectories& take, const std::string& name) {
  const std::string path = testing::TempPath(name);
  EXPECT_TRUE(WriteMarkerFile(path, take).ok());
  return path;
}

bool Exists(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0;
}

TEST(AutoSubjectCli, PipelineFitsTheSubjectFromATakeWithCmuLabels) {
  const std::string markers = WriteTake(testing::TemplateWalkTake(90, false), "walk.c3d");
  const std::string dir = testing::TempPath("out");
  std::string output;
  ASSERT_EQ(testing::RunCli("pipeline --subject=auto --markers=" + markers + " --out_dir=" + dir + kShortFit, &output),
            0) << output;
  EXPECT_THAT(output, HasSubstr("subject: fitted on 90 frames of the take (labels"));
  EXPECT_THAT(output, HasSubstr("subject.json"));
  Subject subject;
  ASSERT_TRUE(ReadSubject(dir + "/subject.json", &subject).ok());
  EXPECT_EQ(subject.markers.num_markers(), 41);
  JsonNode report;
  ASSERT_TRUE(ReadJsonFile(dir + "/report.json", &report).ok());
  EXPECT_EQ(report.Find("subject")->string, "subject.json");
  const JsonNode* fit = report.Find("subject_fit");
  ASSERT_NE(fit, nullptr);
  EXPECT_EQ(fit->Find("method")->string, "labels");
  EXPECT_TRUE(fit->Find("checks")->Find("passed")->boolean);
  // The written subject runs the take again as a plain --subject.
  const std::string again = testing::TempPath("again");
  ASSERT_EQ(testing::RunCli("pipeline --quiet --view=off --subject=" + dir + "/subject.json --markers=" + markers +
                            " --out_dir=" + again, &output), 0) << output;
  EXPECT_FALSE(Exists(again + "/subject.json"));
}

TEST(AutoSubjectCli, NoSubjectMeansAutoAndRenamedLabelsAssociate) {
  const std::string markers = WriteTake(testing::TemplateWalkTake(90, true), "renamed.c3d");
  const std::string dir = testing::TempPath("out");
  std::string output;
  ASSERT_EQ(testing::RunCli("pipeline --quiet --markers=" + markers + " --out_dir=" + dir + kShortFit, &output), 0)
      << output;
  JsonNode report;
  ASSERT_TRUE(ReadJsonFile(dir + "/report.json", &report).ok());
  EXPECT_EQ(report.Find("subject_fit")->Find("method")->string, "association");
  EXPECT_TRUE(Exists(dir + "/subject.json"));
}

TEST(AutoSubjectCli, RandomPointsExitOneAndWriteNothing) {
  const std::string markers = WriteTake(testing::RandomPointsTake(90, 41), "random.c3d");
  const std::string dir = testing::TempPath("out");
  std::string output;
  EXPECT_EQ(testing::RunCli("pipeline --quiet --subject=auto --markers=" + markers + " --out_dir=" + dir + kShortFit,
                            &output), 1);
  EXPECT_THAT(output, HasSubstr("random.c3d"));
  EXPECT_THAT(output, HasSubstr("--subject=auto"));
  EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
  EXPECT_FALSE(Exists(dir));
}

TEST(AutoSubjectCli, BatchFitsOneSubjectPerTake) {
  const std::string folder = testing::TempPath("takes");
  ASSERT_EQ(std::system(("mkdir -p " + folder).c_str()), 0);
  ASSERT_TRUE(WriteMarkerFile(folder + "/walk.c3d", testing::TemplateWalkTake(60, false)).ok());
  ASSERT_TRUE(WriteMarkerFile(folder + "/walk_renamed.c3d", testing::TemplateWalkTake(60, true)).ok());
  const std::string manifest = folder + "/M.json";
  testing::WriteTextFile(manifest, "{\"defaults\": {\"subject\": \"auto\", \"fit_iterations\": 4, \"attach_rounds\": 1,"
                                   " \"attach_iterations\": 3},\n \"takes\": [{\"markers\": "
                                   "\"walk.c3d\"}, {\"markers\": \"walk_renamed.c3d\"}]}\n");
  const std::string dir = testing::TempPath("batch");
  std::string output;
  ASSERT_EQ(testing::RunCli("batch --quiet --jobs=2 --manifest=" + manifest + " --out_dir=" + dir, &output), 0)
      << output;
  EXPECT_TRUE(Exists(dir + "/walk/subject.json"));
  EXPECT_TRUE(Exists(dir + "/walk_renamed/subject.json"));
  // The same from a glob; a re-run skips both takes (the key needs no subject file).
  const std::string glob_dir = testing::TempPath("glob");
  ASSERT_EQ(testing::RunCli("batch --quiet --markers_glob='" + folder + "/walk.c3d' --subject=auto --out_dir=" +
                            glob_dir, &output), 0) << output;
  EXPECT_TRUE(Exists(glob_dir + "/walk/subject.json"));
  ASSERT_EQ(testing::RunCli("batch --markers_glob='" + folder + "/walk.c3d' --subject=auto --out_dir=" + glob_dir,
                            &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("1 skipped as unchanged"));
}

}  // namespace
}  // namespace mocapsolve
