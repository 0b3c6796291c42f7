// Marker association from the data (problems/marker_solve/marker_association.h) on a
// synthetic body: the demo character's walk with 3 markers around every bone
// (synthetic_marker_set.h), labels replaced by meaningless ones, a still point and a rarely
// seen one added, written Z-up or Y-up, in cm or with no unit. The benchmark on the shared
// captures is bench/tools/protocol_association.cc (BENCHMARKS.md).
#include "problems/marker_solve/marker_association.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "kinematics/demo_character.h"
#include "kinematics/forward_kinematics.h"
#include "problems/marker_solve/rigid_marker_clusters.h"
#include "problems/marker_solve/synthetic_marker_set.h"

namespace mocapsolve {
namespace {

// The segments a marker on each demo joint may be associated with (neighbours of short
// bones count: a spine marker rides between pelvis and chest).
std::set<std::string> Accepted(const std::string& joint) {
  static const std::map<std::string, std::set<std::string>> table = {
      {"Hips", {"pelvis"}}, {"Spine", {"pelvis", "chest"}}, {"Chest", {"chest"}}, {"Neck", {"chest", "head"}},
      {"Head", {"head"}}};
  if (table.count(joint)) return table.at(joint);
  const std::string side = joint.rfind("Left", 0) == 0 ? "left_" : "right_";
  const std::string part = joint.substr(joint.rfind("Left", 0) == 0 ? 4 : 5);
  if (part == "Shoulder") return {"chest", side + "upper_arm"};
  if (part == "Arm") return {side + "upper_arm"};
  if (part == "ForeArm") return {side + "forearm"};
  if (part == "Hand") return {side + "forearm", side + "hand"};
  if (part == "UpLeg") return {side + "thigh"};
  if (part == "Leg") return {side + "shin"};
  return {side + "foot", side + "shin"};  // Foot, Toe.
}

struct Take {
  MarkerTrajectories trajectories;
  std::map<std::string, std::string> joint;  // Label -> the demo joint it rides on.
};

// z_up: file axes (x, -z, y) of the demo's (x, y, z) (right-handed, Z up).
Take MakeTake(bool z_up, bool unit_known) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const Motion motion = MakeDemoWalk(skeleton, 240, 60.0);
  const MarkerSet markers = MakeSyntheticMarkerSet(skeleton, 3, 7);
  std::vector<std::string> labels;
  Take take;
  for (int m = 0; m < markers.num_markers(); ++m) {
    labels.push_back("Q" + std::to_string((m * 37) % markers.num_markers()));
    take.joint[labels.back()] = skeleton.name(markers.marker(m).attachments[0].joint);
  }
  labels.push_back("still");
  labels.push_back("rare");
  take.trajectories = MarkerTrajectories(labels, 240);
  take.trajectories.frame_rate = 60.0;
  take.trajectories.unit = unit_known ? Centimetres() : LengthUnit();
  FkData fk(skeleton);
  for (int f = 0; f < 240; ++f) {
    ForwardKinematics(skeleton, motion.frames[f], &fk);
    for (int m = 0; m < markers.num_markers(); ++m) {
      const Eigen::Vector3d x = markers.Position(m, fk);
      take.trajectories.SetSample(f, m, z_up ? Eigen::Vector3d(x.x(), -x.z(), x.y()) : x);
    }
    take.trajectories.SetSample(f, markers.num_markers(), Eigen::Vector3d(500.0, 0.0, 500.0));
    if (f % 30 == 0) take.trajectories.SetSample(f, markers.num_markers() + 1, Eigen::Vector3d(0.0, 100.0, 0.0));
  }
  return take;
}

int CountCorrect(const Take& take, const MarkerAssociation& association, std::string* wrong) {
  int correct = 0;
  for (const AssociatedMarker& a : association.markers) {
    if (!take.joint.count(a.label)) continue;
    if (Accepted(take.joint.at(a.label)).count(a.role)) ++correct;
    else *wrong += " " + take.joint.at(a.label) + "->" + a.role;
  }
  return correct;
}

TEST(MarkerAssociationTest, RecoversSegmentsUpAndUnitsOfARenamedSyntheticBody) {
  for (const bool z_up : {false, true}) {
    for (const bool unit_known : {true, false}) {
      SCOPED_TRACE(std::string(z_up ? "Z up" : "Y up") + (unit_known ? ", cm" : ", no unit"));
      const Take take = MakeTake(z_up, unit_known);
      MarkerAssociation association;
      ASSERT_TRUE(AssociateMarkers(take.trajectories, "walk.c3d", MarkerAssociationOptions(), &association).ok());
      EXPECT_EQ(association.up_axis, z_up ? 2 : 1);
      EXPECT_EQ(association.up_sign, 1);
      EXPECT_EQ(association.unit.name, "cm");
      EXPECT_EQ(association.unit_from_data, !unit_known);
      // Both added points are no markers, and reported.
      ASSERT_EQ(association.excluded.size(), 2u);
      EXPECT_EQ(association.Find("still"), nullptr);
      EXPECT_EQ(association.Find("rare"), nullptr);
      std::string wrong;
      const int correct = CountCorrect(take, association, &wrong);
      const int total = static_cast<int>(take.joint.size());
      // Measured: every marker but the ones of segments the walk holds rigid to a
      // neighbour; 90 % is the floor this test keeps.
      EXPECT_GE(correct, 0.9 * total) << correct << " of " << total << " correct; wrong:" << wrong;
      for (const AssociatedMarker& a : association.markers) {
        EXPECT_GE(a.confidence, 0.0);
        EXPECT_LE(a.confidence, 1.0);
      }
    }
  }
}

// A lab's model outputs written as points (Nexus joint angles in degrees, a force in N/kg, a
// power in W/kg, a moment in N mm/kg: numbers, not positions) beside the walk in mm, walked
// on a treadmill at the file's origin: the angle-like points sit among the feet.
TEST(MarkerAssociationTest, ExcludesModelOutputsNearTheOriginBeforeTheUpAxis) {
  for (const bool z_up : {false, true}) {
    SCOPED_TRACE(z_up ? "Z up" : "Y up");
    const Take walk = MakeTake(z_up, true);
    const MarkerTrajectories& in = walk.trajectories;
    const std::vector<std::string> outputs = {"LKneeAngles", "RHipAngles", "LAnkleForce", "LHipPower", "RKneeMoment"};
    std::vector<std::string> labels;
    for (int m = 0; m < in.num_markers(); ++m) labels.push_back(in.label(m));
    for (const std::string& o : outputs) labels.push_back(o);
    MarkerTrajectories take(labels, in.num_frames());
    take.frame_rate = in.frame_rate;
    take.unit = Millimetres();  // The body in mm (the walk is in cm), as Nexus writes it.
    // The walk's middle frame over the file's origin: each take's horizontal median at
    // mid-take moved to 0, so the angle-like points sit among the feet half the take.
    const int up = z_up ? 2 : 1, mid = in.num_frames() / 2;
    Eigen::Vector3d shift;
    for (int k = 0; k < 3; ++k) {
      std::vector<double> c;
      for (int m = 0; m < in.num_markers() - 2; ++m) {
        if (in.valid(mid, m)) c.push_back(in.position(mid, m)[k]);
      }
      std::nth_element(c.begin(), c.begin() + c.size() / 2, c.end());
      shift[k] = k == up ? 0.0 : -c[c.size() / 2];
    }
    for (int f = 0; f < in.num_frames(); ++f) {
      for (int m = 0; m < in.num_markers(); ++m) {
        if (in.valid(f, m)) take.SetSample(f, m, 10.0 * (in.position(f, m) + shift));
      }
      const double w = 2.0 * M_PI * f / in.frame_rate;  // One cycle a second.
      const int n = in.num_markers();
      take.SetSample(f, n + 0, {35.0 + 30.0 * std::sin(w), 3.0 * std::cos(w), 8.0 * std::sin(2 * w)});
      take.SetSample(f, n + 1, {20.0 * std::sin(w + 1.0), -4.0, 6.0 * std::cos(w)});
      take.SetSample(f, n + 2, {2.0 * std::sin(w), 1.0, 9.8 + 3.0 * std::cos(w)});
      take.SetSample(f, n + 3, {0.0, 0.0, 2.5 * std::sin(w + 0.5)});
      take.SetSample(f, n + 4, {900.0 * std::sin(w), 150.0 * std::cos(w), 60.0});
    }
    MarkerAssociation association;
    ASSERT_TRUE(AssociateMarkers(take, "outputs.c3d", MarkerAssociationOptions(), &association).ok());
    EXPECT_EQ(association.up_axis, z_up ? 2 : 1);
    EXPECT_EQ(association.up_sign, 1);
    EXPECT_EQ(association.unit.name, "mm");
    for (const std::string& o : outputs) {
      EXPECT_EQ(association.Find(o), nullptr) << o << " kept as a marker";
      // Surely no marker: a fit by labels cuts it from the take.
      const auto& non = association.non_markers;
      EXPECT_NE(std::find(non.begin(), non.end(), o), non.end()) << o;
    }
    std::string wrong;
    const int correct = CountCorrect(walk, association, &wrong);
    // The same floor as the take without the outputs.
    EXPECT_GE(correct, 0.9 * static_cast<double>(walk.joint.size())) << correct << " correct; wrong:" << wrong;
  }
}

TEST(MarkerAssociationTest, RigidMarkersClusterAndMovingOnesDoNot) {
  // Two rigid triangles, one rotating about a hinge against the other.
  MarkerTrajectories take({"a0", "a1", "a2", "b0", "b1", "b2"}, 100);
  take.unit = Metres();
  for (int f = 0; f < 100; ++f) {
    const double angle = 0.02 * f;
    const Eigen::Vector3d hinge(0.0, 0.0, 1.0);
    take.SetSample(f, 0, hinge + Eigen::Vector3d(0.0, 0.0, 0.1));
    take.SetSample(f, 1, hinge + Eigen::Vector3d(0.1, 0.0, 0.2));
    take.SetSample(f, 2, hinge + Eigen::Vector3d(-0.1, 0.05, 0.3));
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d local(0.05 * k, 0.02, -0.2 - 0.1 * k);
      const Eigen::Vector3d rotated(local.x(), std::cos(angle) * local.y() - std::sin(angle) * local.z(),
                                    std::sin(angle) * local.y() + std::cos(angle) * local.z());
      take.SetSample(f, 3 + k, hinge + rotated);
    }
  }
  const std::vector<int> all = {0, 1, 2, 3, 4, 5};
  const PairwiseSpread pairs = ComputePairwiseSpread(take, all, 1.0, RigidClusterOptions());
  EXPECT_LT(pairs.spread(0, 2), 1e-9);
  EXPECT_GT(pairs.spread(0, 5), 0.01);
  const std::vector<std::vector<int>> clusters = ClusterRigidMarkers(pairs, RigidClusterOptions());
  ASSERT_EQ(clusters.size(), 2u);
  EXPECT_EQ(std::set<int>(clusters[0].begin(), clusters[0].end()).size(), 3u);
}

TEST(MarkerAssociationTest, BadInputIsOneLineNamingTheFile) {
  MarkerAssociation association;
  const Status empty = AssociateMarkers(MarkerTrajectories({"a"}, 0), "empty.c3d", {}, &association);
  ASSERT_FALSE(empty.ok());
  EXPECT_EQ(empty.message().rfind("empty.c3d: ", 0), 0u) << empty.message();
  // A body 10 km tall in any unit.
  Take take = MakeTake(false, false);
  take.trajectories.ScaleLengths(1e6);
  const Status huge = AssociateMarkers(take.trajectories, "huge.trc", {}, &association);
  ASSERT_FALSE(huge.ok());
  EXPECT_NE(huge.message().find("a body in no unit"), std::string::npos) << huge.message();
}

TEST(MarkerAssociationTest, LabelSideReadsSideWords) {
  EXPECT_EQ(LabelSide("LASI"), -1);
  EXPECT_EQ(LabelSide("L_IAS"), -1);
  EXPECT_EQ(LabelSide("r should"), 1);
  EXPECT_EQ(LabelSide("Nick01:RFHD"), 1);
  EXPECT_EQ(LabelSide("LeftKnee"), -1);
  EXPECT_EQ(LabelSide("sacrum"), 0);
  EXPECT_EQ(LabelSide("Lateral"), 0);
  EXPECT_EQ(LabelSide("C7"), 0);
}

}  // namespace
}  // namespace mocapsolve
