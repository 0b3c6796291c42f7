// The first marker set of an associated fit (problems/marker_solve/associated_marker_set.h):
// which associated markers round 0 fits, on which template joints.
#include "problems/marker_solve/associated_marker_set.h"

#include <set>
#include <string>

#include <gtest/gtest.h>

#include "kinematics/demo_character.h"

namespace mocapsolve {
namespace {

AssociatedMarker Marker(const std::string& label, const std::string& role, double confidence) {
  AssociatedMarker m;
  m.label = label;
  m.role = role;
  m.confidence = confidence;
  return m;
}

// A walk's pelvis moves nearly rigidly with the chest, so its markers' confidence (their
// cluster's separation) is low: 02_01 renamed (protocol_association seed 2) had its four at
// 0.48-0.58, all under the fit's 0.6, and round 0 placed the root by the limbs and the chest
// alone (torso 19.7 degrees off). The pelvis' markers take half the bar; others keep it.
TEST(AssociatedMarkerSet, ThePelvisMarkersAnchorRoundZeroBelowTheBarAndEverySegmentKeepsOne) {
  const Skeleton demo = MakeDemoSkeleton();
  MarkerAssociation association;
  association.up_axis = 1;
  association.up_sign = 1;
  association.markers = {Marker("P1", "pelvis", 0.58), Marker("P2", "pelvis", 0.52), Marker("P3", "pelvis", 0.48),
                         Marker("P4", "pelvis", 0.2),  Marker("C1", "chest", 0.9),   Marker("C2", "chest", 0.5),
                         Marker("H1", "head", 0.8),    Marker("T1", "left_thigh", 0.55),
                         Marker("T2", "left_thigh", 0.3)};
  AssociatedMarkerSet set;
  ASSERT_TRUE(MakeAssociatedMarkerSet(demo, association, 0.6, &set).ok());
  std::set<std::string> fitted;
  for (const MarkerSpec& spec : set.specs) fitted.insert(spec.label);
  // The thigh has no marker at the bar: its most confident one observes it in round 0.
  EXPECT_EQ(fitted, (std::set<std::string>{"P1", "P2", "P3", "C1", "H1", "T1"}));
  EXPECT_EQ(std::set<std::string>(set.left_out.begin(), set.left_out.end()), (std::set<std::string>{"P4", "C2", "T2"}));
  EXPECT_EQ(set.pelvis_labels.size(), 4u);
  for (size_t i = 0; i < set.specs.size(); ++i) {
    if (set.specs[i].label[0] == 'P') {
      EXPECT_EQ(set.joints[i], "Hips") << set.specs[i].label;
    }
  }
}

}  // namespace
}  // namespace mocapsolve
