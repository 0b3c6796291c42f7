// The template label map (problems/marker_solve/template_labels.h): inline pairs and files with comments,
// one-line errors naming the flag or the file and line, and the renaming of a template's
// markers against a take's labels.
#include "problems/marker_solve/template_labels.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "kinematics/demo_character.h"
#include "problems/marker_solve/synthetic_marker_set.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

std::string ErrorOf(const std::string& value) {
  std::vector<TemplateLabel> labels;
  const Status status = ReadTemplateLabels(value, &labels);
  EXPECT_FALSE(status.ok()) << value;
  return status.message();
}

TEST(ReadTemplateLabels, InlinePairsInOrder) {
  std::vector<TemplateLabel> labels;
  ASSERT_TRUE(ReadTemplateLabels("RFWT:RASI, LFWT:LASI,LKNE:LLEPI", &labels).ok());
  ASSERT_EQ(labels.size(), 3u);
  EXPECT_EQ(labels[0].templ, "RFWT");
  EXPECT_EQ(labels[0].take, "RASI");
  EXPECT_EQ(labels[2].templ, "LKNE");
  EXPECT_EQ(labels[2].take, "LLEPI");
}

TEST(ReadTemplateLabels, EachBadPairNamesItself) {
  EXPECT_EQ(ErrorOf("RFWT:RASI,LFWT"), "--template_labels: 'LFWT': expected TEMPLATE:TAKE");
  EXPECT_EQ(ErrorOf("RFWT:RASI,LFWT:"), "--template_labels: 'LFWT:': expected TEMPLATE:TAKE");
  EXPECT_EQ(ErrorOf(":RASI"), "--template_labels: ':RASI': expected TEMPLATE:TAKE");
  EXPECT_EQ(ErrorOf("A:B:C"), "--template_labels: 'A:B:C': expected TEMPLATE:TAKE");
  EXPECT_EQ(ErrorOf("A:B,A:C"), "--template_labels: template label A mapped twice");
  EXPECT_EQ(ErrorOf("A:B C:B"), "--template_labels: take label B named twice");
}

TEST(ReadTemplateLabels, FileWithCommentsAndLineNumbers) {
  const std::string path = testing::TempPath("labels.txt");
  testing::WriteTextFile(path, "# pelvis\nLFWT:LASI  RFWT:RASI  # the ASIS\n\nLKNE:LLEPI,\n");
  std::vector<TemplateLabel> labels;
  ASSERT_TRUE(ReadTemplateLabels(path, &labels).ok());
  ASSERT_EQ(labels.size(), 3u);
  EXPECT_EQ(labels[1].templ, "RFWT");
  EXPECT_EQ(labels[1].take, "RASI");

  testing::WriteTextFile(path, "LFWT:LASI\n# a comment: with a colon\nRKNE:LASI\n");
  EXPECT_EQ(ErrorOf(path), path + ":3: take label LASI named twice");
  testing::WriteTextFile(path, "# nothing but comments\n\n");
  EXPECT_EQ(ErrorOf(path), path + ": no TEMPLATE:TAKE pairs");
  const std::string absent = testing::TempPath("absent.txt");
  const std::string message = ErrorOf(absent);
  EXPECT_EQ(message.rfind("--template_labels: ", 0), 0u) << message;
  EXPECT_NE(message.find(absent), std::string::npos) << message;
}

class RenameTemplateMarkersTest : public ::testing::Test {
 protected:
  void SetUp() override {
    skeleton_ = MakeDemoSkeleton();
    markers_ = MakeSyntheticMarkerSet(skeleton_, 1, 7);
    ASSERT_GE(markers_.num_markers(), 3);
    a_ = markers_.label(0);
    b_ = markers_.label(1);
    take_ = MarkerTrajectories({"TAKE_A", "TAKE_B", b_}, 1);
  }
  std::string Error(const std::vector<TemplateLabel>& labels) {
    MarkerSet markers = markers_;
    const Status status = RenameTemplateMarkers(labels, skeleton_, take_, "take.trc", &markers);
    EXPECT_FALSE(status.ok());
    return status.message();
  }
  Skeleton skeleton_;
  MarkerSet markers_;
  MarkerTrajectories take_;
  std::string a_, b_;
};

TEST_F(RenameTemplateMarkersTest, RenamedMarkersKeepTheirAttachments) {
  MarkerSet markers = markers_;
  ASSERT_TRUE(RenameTemplateMarkers({{a_, "TAKE_A"}}, skeleton_, take_, "take.trc", &markers).ok());
  ASSERT_EQ(markers.num_markers(), markers_.num_markers());
  EXPECT_EQ(markers.label(0), "TAKE_A");
  EXPECT_EQ(markers.label(1), b_);
  EXPECT_EQ(markers.FindMarker(a_), -1);
  EXPECT_EQ(markers.marker(0).attachments[0].joint, markers_.marker(0).attachments[0].joint);
  EXPECT_EQ(markers.marker(0).attachments[0].offset, markers_.marker(0).attachments[0].offset);
  // Two markers may trade labels: each is mapped.
  markers = markers_;
  ASSERT_TRUE(RenameTemplateMarkers({{a_, b_}, {b_, "TAKE_A"}}, skeleton_, take_, "take.trc", &markers).ok());
  EXPECT_EQ(markers.label(0), b_);
  EXPECT_EQ(markers.label(1), "TAKE_A");
}

TEST_F(RenameTemplateMarkersTest, ErrorsNameTheLabel) {
  EXPECT_EQ(Error({{"NOPE", "TAKE_A"}}), "--template_labels: NOPE is not a label of the template's marker set");
  EXPECT_EQ(Error({{a_, "NOPE"}}), "--template_labels: NOPE (for " + a_ + ") is not in take.trc");
  // b_ is the take's label of the template's own b_ too.
  EXPECT_EQ(Error({{a_, b_}}),
            "--template_labels: two template markers would be labelled " + b_ + " (map the template's own " + b_ +
                " too)");
}

}  // namespace
}  // namespace mocapsolve
