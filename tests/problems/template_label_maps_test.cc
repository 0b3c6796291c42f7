// The shipped template label maps and the rule `--template_labels=auto` picks one by
// (problems/marker_solve/template_label_maps.h), on crafted label sets: no real data needed. Which map
// each real take picks is in tests/tasks/fit_skeleton_task_test.cc.
#include "problems/marker_solve/template_label_maps.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "kinematics/demo_character.h"
#include "problems/marker_solve/synthetic_marker_set.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

TEST(ShippedTemplateLabelMaps, EachParsesAndIsItsFileInTheSourceTree) {
  ASSERT_GE(ShippedTemplateLabelMaps().size(), 2u);
  for (const ShippedTemplateLabels& map : ShippedTemplateLabelMaps()) {
    std::vector<TemplateLabel> labels;
    const Status status = ParseTemplateLabels(map.text, map.name, &labels);
    EXPECT_TRUE(status.ok()) << status.message();
    EXPECT_GE(labels.size(), 3u) << map.name;
    EXPECT_EQ(std::string(map.text), testing::ReadTextFile(testing::SourcePath(map.name))) << map.name;
  }
}

class TemplateLabelsFitTakeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    skeleton_ = MakeDemoSkeleton();
    templ_ = MakeSyntheticMarkerSet(skeleton_, 1, 7);
    ASSERT_GE(templ_.num_markers(), 3);
    a_ = templ_.label(0);
    b_ = templ_.label(1);
    c_ = templ_.label(2);
  }
  bool Fits(const std::vector<TemplateLabel>& labels, const std::vector<std::string>& take_labels) const {
    return TemplateLabelsFitTake(labels, templ_, MarkerTrajectories(take_labels, 1));
  }
  Skeleton skeleton_;
  MarkerSet templ_;
  std::string a_, b_, c_;
};

TEST_F(TemplateLabelsFitTakeTest, TakeOfTheMapsProtocol) {
  // The take names a_ and b_ its own way and shares c_.
  EXPECT_TRUE(Fits({{a_, "TAKE_A"}, {b_, "TAKE_B"}}, {"TAKE_A", "TAKE_B", c_, "OTHER"}));
}

TEST_F(TemplateLabelsFitTakeTest, TakeLackingOneOfTheMapsLabels) {
  EXPECT_FALSE(Fits({{a_, "TAKE_A"}, {b_, "TAKE_B"}}, {"TAKE_A", c_}));
}

TEST_F(TemplateLabelsFitTakeTest, TakeWithTheTemplatesLabels) {
  // A take labelled like the template (a CMU take for a map to CMU): no map, even when it
  // also holds the map's take labels.
  EXPECT_FALSE(Fits({{a_, "TAKE_A"}, {b_, "TAKE_B"}}, {a_, b_, c_}));
  EXPECT_FALSE(Fits({{a_, "TAKE_A"}, {b_, "TAKE_B"}}, {"TAKE_A", "TAKE_B", a_}));
}

TEST_F(TemplateLabelsFitTakeTest, TemplateWithoutTheMapsLabels) {
  EXPECT_FALSE(Fits({{a_, "TAKE_A"}, {"NOT_IN_TEMPLATE", "TAKE_B"}}, {"TAKE_A", "TAKE_B"}));
}

TEST_F(TemplateLabelsFitTakeTest, RenamingOntoAnUnmappedTemplateLabel) {
  // a_ would become c_, which the unmapped template marker c_ holds.
  EXPECT_FALSE(Fits({{a_, c_}}, {c_, "OTHER"}));
  EXPECT_FALSE(Fits({}, {"TAKE_A"}));
}

}  // namespace
}  // namespace mocapsolve
