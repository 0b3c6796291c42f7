// Marker association from the data (problems/marker_solve/marker_association.h) on a
// synthetic body: the demo character's walk with 3 markers around every bone
// (synthetic_marker_set.h), labels replaced by meaningless ones, a still point and a rarely
// seen one added, written Z-up or Y-up, in cm or with no unit. The benchmark on the shared
// captures is bench/tools/protocol_association.cc (BENCHMARKS.md).
#include "problems/marker_solve/marker_association.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "kinematics/demo_character.h"
#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
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

// z_up: file axes (x, -z, y) of the demo's (x, y, z) (right-handed, Z up). Markers on the
// joints in `without` are left out (a protocol without them).
Take MakeTakeOf(const Skeleton& skeleton, const Motion& motion, bool z_up, bool unit_known,
                const std::set<std::string>& without = {}) {
  const int frames = static_cast<int>(motion.frames.size());
  const MarkerSet all = MakeSyntheticMarkerSet(skeleton, 3, 7);
  std::vector<int> kept;
  for (int m = 0; m < all.num_markers(); ++m) {
    if (!without.count(skeleton.name(all.marker(m).attachments[0].joint))) kept.push_back(m);
  }
  const int n = static_cast<int>(kept.size());
  std::vector<std::string> labels;
  Take take;
  for (int k = 0; k < n; ++k) {
    labels.push_back("Q" + std::to_string((k * 37) % n));
    take.joint[labels.back()] = skeleton.name(all.marker(kept[k]).attachments[0].joint);
  }
  labels.push_back("still");
  labels.push_back("rare");
  take.trajectories = MarkerTrajectories(labels, frames);
  take.trajectories.frame_rate = motion.frame_rate;
  take.trajectories.unit = unit_known ? Centimetres() : LengthUnit();
  FkData fk(skeleton);
  for (int f = 0; f < frames; ++f) {
    ForwardKinematics(skeleton, motion.frames[f], &fk);
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d x = all.Position(kept[k], fk);
      take.trajectories.SetSample(f, k, z_up ? Eigen::Vector3d(x.x(), -x.z(), x.y()) : x);
    }
    take.trajectories.SetSample(f, n, Eigen::Vector3d(500.0, 0.0, 500.0));
    if (f % 30 == 0) take.trajectories.SetSample(f, n + 1, Eigen::Vector3d(0.0, 100.0, 0.0));
  }
  return take;
}

Take MakeTake(bool z_up, bool unit_known) {
  const Skeleton skeleton = MakeDemoSkeleton();
  return MakeTakeOf(skeleton, MakeDemoWalk(skeleton, 240, 60.0), z_up, unit_known);
}

// Sets a demo joint's rotation as the demo walk does (degrees about x, y, z).
void SetJoint(const Skeleton& skeleton, Pose* pose, const char* joint, double x_deg, double y_deg, double z_deg) {
  const int j = skeleton.FindJoint(joint);
  ASSERT_GE(j, 0) << joint;
  pose->rotations[j] =
      QuaternionFromEuler(Eigen::Vector3d(DegToRad(z_deg), DegToRad(x_deg), DegToRad(y_deg)), EulerOrder::kZXY);
}

// Moves the root so that the lower foot stands on the floor (y = 0) and stays put while it
// is the lower one: the body travels by its strides, as on the ground.
void GroundOnTheLowerFoot(const Skeleton& skeleton, Motion* motion) {
  const int feet[2] = {skeleton.FindJoint("LeftFoot"), skeleton.FindJoint("RightFoot")};  // The ankles.
  FkData fk(skeleton);
  Eigen::Vector3d shift = Eigen::Vector3d::Zero(), previous = Eigen::Vector3d::Zero();
  int stance = -1;
  for (Pose& pose : motion->frames) {
    ForwardKinematics(skeleton, pose, &fk);
    const int lower = fk.world_positions[feet[0]].y() < fk.world_positions[feet[1]].y() ? feet[0] : feet[1];
    const Eigen::Vector3d foot = fk.world_positions[stance < 0 ? lower : stance];
    if (stance >= 0) shift += previous - foot;  // The stance foot does not slide.
    shift.y() = -fk.world_positions[lower].y();
    stance = lower;
    previous = fk.world_positions[lower];
    pose.translations[0] += shift;
  }
}

// A sprint of the demo character, on the ground: a stride of 0.7 s, the thighs swinging 55 degrees
// each way (their markers spread wider fore and aft than the hips are wide) and the knees
// bending to 110 degrees (the feet in the air most of the stride).
Motion MakeSprint(const Skeleton& skeleton, int num_frames, double frame_rate) {
  Motion motion;
  motion.frame_rate = frame_rate;
  for (int f = 0; f < num_frames; ++f) {
    const double t = f / frame_rate, phase = 2.0 * kPi * t / 0.7;
    const double s = std::sin(phase), c = std::cos(phase);
    Pose pose = RestPose(skeleton);
    SetJoint(skeleton, &pose, "Hips", 0, 10 * s, 0);
    SetJoint(skeleton, &pose, "Chest", 8, -8 * s, 0);
    SetJoint(skeleton, &pose, "LeftUpLeg", -20 - 45 * s, 0, 2);
    SetJoint(skeleton, &pose, "LeftLeg", 60 + 50 * c, 0, 0);
    SetJoint(skeleton, &pose, "RightUpLeg", -20 + 45 * s, 0, -2);
    SetJoint(skeleton, &pose, "RightLeg", 60 - 50 * c, 0, 0);
    SetJoint(skeleton, &pose, "LeftArm", 50 * s, 0, -70);
    SetJoint(skeleton, &pose, "LeftForeArm", 0, -80, 0);
    SetJoint(skeleton, &pose, "RightArm", -50 * s, 0, 70);
    SetJoint(skeleton, &pose, "RightForeArm", 0, 80, 0);
    motion.frames.push_back(pose);
  }
  GroundOnTheLowerFoot(skeleton, &motion);
  return motion;
}

// Squats of the demo character with its feet planted: hips flexed a, knees 2a, ankles a
// back (the feet flat), a from 0 to 70 degrees and back every 2 s; the root moved so that
// the left ankle stays put (thigh and shin differ by 1 cm: the right one too, within a cm).
Motion MakeSquats(const Skeleton& skeleton, int num_frames, double frame_rate) {
  Motion motion;
  motion.frame_rate = frame_rate;
  FkData fk(skeleton);
  const int ankle = skeleton.FindJoint("LeftFoot");
  ForwardKinematics(skeleton, RestPose(skeleton), &fk);
  const Eigen::Vector3d planted = fk.world_positions[ankle];
  for (int f = 0; f < num_frames; ++f) {
    const double t = f / frame_rate, a = 35.0 * (1.0 - std::cos(2.0 * kPi * t / 2.0));
    Pose pose = RestPose(skeleton);
    for (const char* side : {"Left", "Right"}) {
      SetJoint(skeleton, &pose, (std::string(side) + "UpLeg").c_str(), -a, 0, 0);
      SetJoint(skeleton, &pose, (std::string(side) + "Leg").c_str(), 2 * a, 0, 0);
      SetJoint(skeleton, &pose, (std::string(side) + "Foot").c_str(), -a, 0, 0);
    }
    SetJoint(skeleton, &pose, "Chest", 0.4 * a, 10 * std::sin(2.0 * kPi * t / 3.0), 0);
    SetJoint(skeleton, &pose, "LeftArm", -a, 0, -70 + 0.5 * a);
    SetJoint(skeleton, &pose, "RightArm", -a, 0, 70 - 0.5 * a);
    SetJoint(skeleton, &pose, "LeftForeArm", 0, -20 - 0.3 * a, 0);
    SetJoint(skeleton, &pose, "RightForeArm", 0, 20 + 0.3 * a, 0);
    ForwardKinematics(skeleton, pose, &fk);
    pose.translations[0] += planted - fk.world_positions[ankle];
    motion.frames.push_back(pose);
  }
  return motion;
}

// One leg standing still the whole take (its hip, knee and ankle unbent, the pelvis
// unturned: every marker from the pelvis down that side is still) while the other leg kicks
// forward to 80 degrees and back every 2 s, the trunk bends and the arms swing: as a real
// squat's planted foot and still shin (squat.c3d), the nearest point that moves is far from
// the still foot.
Motion MakeOneLegStill(const Skeleton& skeleton, int num_frames, double frame_rate) {
  Motion motion;
  motion.frame_rate = frame_rate;
  for (int f = 0; f < num_frames; ++f) {
    const double t = f / frame_rate, a = 45.0 * (1.0 - std::cos(2.0 * kPi * t / 2.0));
    Pose pose = RestPose(skeleton);
    SetJoint(skeleton, &pose, "LeftUpLeg", 0, 0, 15);  // A wide stance, held.
    SetJoint(skeleton, &pose, "RightUpLeg", -a, 0, 0);
    SetJoint(skeleton, &pose, "RightLeg", 0.5 * a, 0, 0);
    SetJoint(skeleton, &pose, "Spine", 0.3 * a, 10 * std::sin(2.0 * kPi * t / 3.0), 0);
    SetJoint(skeleton, &pose, "LeftArm", -a, 0, -70 + 0.5 * a);
    SetJoint(skeleton, &pose, "RightArm", a, 0, 70 - 0.5 * a);
    pose.translations[0] += Eigen::Vector3d(150.0, 0.0, 80.0);  // Away from the file's origin.
    motion.frames.push_back(pose);
  }
  return motion;
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

// A gait set without head markers (the top of the body is C7, not a head: every height
// over the points' extent reads too high) on a sprint (the thighs swing wider than the hips,
// the feet are in the air most of the take): before, the pelvis read as chest, the feet as
// shins, the shoulders as a head (measured before: 9 and 7 of 54 right; now every one).
TEST(MarkerAssociationTest, AGaitSetWithoutHeadMarkersOnASprint) {
  const Skeleton skeleton = MakeDemoSkeleton();
  for (const bool z_up : {false, true}) {
    SCOPED_TRACE(z_up ? "Z up" : "Y up");
    const Take take = MakeTakeOf(skeleton, MakeSprint(skeleton, 150, 100.0), z_up, true, {"Head", "Neck"});
    MarkerAssociation association;
    ASSERT_TRUE(AssociateMarkers(take.trajectories, "sprint.trc", MarkerAssociationOptions(), &association).ok());
    EXPECT_EQ(association.up_axis, z_up ? 2 : 1);
    EXPECT_EQ(association.up_sign, 1);
    std::string wrong;
    const int correct = CountCorrect(take, association, &wrong);
    const int total = static_cast<int>(take.joint.size());
    EXPECT_GE(correct, 0.9 * total) << correct << " of " << total << " correct; wrong:" << wrong;
  }
}

// Squats with the feet planted: the two feet keep their distance (and, the squat being
// symmetric, the shins too), so the rigid clusters join them into one; it is split by side
// (before, both feet took one side's role).
TEST(MarkerAssociationTest, PlantedFeetAreTwoFeet) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const Take take = MakeTakeOf(skeleton, MakeSquats(skeleton, 400, 60.0), false, true);
  MarkerAssociation association;
  ASSERT_TRUE(AssociateMarkers(take.trajectories, "squat.c3d", MarkerAssociationOptions(), &association).ok());
  // Each foot's markers on one side, the two feet on two sides (which is left depends on
  // the forward direction, which a symmetric squat leaves to weak votes).
  std::map<std::string, std::set<std::string>> sides;  // Foot -> the sides its markers took.
  for (const AssociatedMarker& a : association.markers) {
    const std::string joint = take.joint.count(a.label) ? take.joint.at(a.label) : "";
    if (joint != "LeftFoot" && joint != "RightFoot" && joint != "LeftToe" && joint != "RightToe") continue;
    sides[joint.substr(0, joint.find("Foot") == std::string::npos ? joint.find("Toe") : joint.find("Foot"))].insert(
        a.role.substr(0, a.role.find('_')));
  }
  ASSERT_EQ(sides.size(), 2u);
  ASSERT_EQ(sides["Left"].size(), 1u);
  ASSERT_EQ(sides["Right"].size(), 1u);
  EXPECT_NE(*sides["Left"].begin(), *sides["Right"].begin()) << "both feet on the " << *sides["Left"].begin();
}

// A Helen Hayes / Davis trunk: no arm markers, only the shoulders' (acromions) and the
// neck's (C7) above the pelvis, on the demo walk. They are the chest: before, a side's
// shoulder-height points were an "arm" whose farthest point was called a hand or forearm.
TEST(MarkerAssociationTest, ShouldersWithoutArmsAreTheChest) {
  const Skeleton skeleton = MakeDemoSkeleton();
  Motion walk = MakeDemoWalk(skeleton, 240, 60.0);
  // The shoulders shrug and swing with the arms (a walk's acromions move against C7).
  for (size_t f = 0; f < walk.frames.size(); ++f) {
    const double phase = 2.0 * kPi * f / walk.frame_rate / 1.1;
    SetJoint(skeleton, &walk.frames[f], "LeftShoulder", 0, 12 * std::sin(phase), 10 * std::cos(phase));
    SetJoint(skeleton, &walk.frames[f], "RightShoulder", 0, 12 * std::sin(phase), -10 * std::cos(phase));
  }
  const Take take = MakeTakeOf(skeleton, walk, false, true,
                               {"Head", "Chest", "LeftArm", "LeftForeArm", "LeftHand", "RightArm", "RightForeArm",
                                "RightHand"});
  MarkerAssociation association;
  ASSERT_TRUE(AssociateMarkers(take.trajectories, "davis.c3d", MarkerAssociationOptions(), &association).ok());
  int trunk = 0;
  for (const AssociatedMarker& a : association.markers) {
    const std::string joint = take.joint.count(a.label) ? take.joint.at(a.label) : "";
    if (joint != "Neck" && joint != "LeftShoulder" && joint != "RightShoulder") continue;
    ++trunk;
    EXPECT_EQ(a.role, "chest") << joint;
  }
  EXPECT_EQ(trunk, 9);
}

// The whole arms held up in front at shoulder height through the take (a squat's arms
// stretched forward), swinging across and bending at the elbow: every arm point sits above
// the shoulder-height bar, as an acromion-only side's do, but an arm's forearm and hand
// reach beyond a shoulder and it carries more points. They were the chest (every arm
// marker "chest"; the attach rounds then kept the fitted subject's arm empty).
TEST(MarkerAssociationTest, ArmsHeldUpAtShoulderHeightStayArms) {
  const Skeleton skeleton = MakeDemoSkeleton();
  Motion walk = MakeDemoWalk(skeleton, 240, 60.0);
  for (size_t f = 0; f < walk.frames.size(); ++f) {
    const double phase = 2.0 * kPi * f / walk.frame_rate / 1.3;
    SetJoint(skeleton, &walk.frames[f], "LeftArm", 0, -70 + 20 * std::sin(phase), 0);
    SetJoint(skeleton, &walk.frames[f], "RightArm", 0, 70 + 20 * std::sin(phase), 0);
    SetJoint(skeleton, &walk.frames[f], "LeftForeArm", 0, -30 - 30 * std::cos(phase), 0);
    SetJoint(skeleton, &walk.frames[f], "RightForeArm", 0, 30 + 30 * std::cos(phase), 0);
  }
  const Take take = MakeTakeOf(skeleton, walk, false, true);
  MarkerAssociation association;
  ASSERT_TRUE(AssociateMarkers(take.trajectories, "arms_up.c3d", MarkerAssociationOptions(), &association).ok());
  int arm = 0, chest = 0;
  for (const AssociatedMarker& a : association.markers) {
    const std::string joint = take.joint.count(a.label) ? take.joint.at(a.label) : "";
    if (joint != "LeftForeArm" && joint != "LeftHand" && joint != "RightForeArm" && joint != "RightHand") continue;
    ++arm;
    chest += a.role == "chest" || a.role == "head";
  }
  EXPECT_GT(arm, 0);
  EXPECT_EQ(chest, 0) << "of " << arm << " forearm and hand markers";
}

// A lower-body set (no marker above the pelvis) of a child (the demo walk at 0.6 of its
// size), in a file that says cm: its points span 0.5-0.6 m, a whole body in no unit, so the
// file's unit was refused ("a body in no unit"); it is read in the file's unit now.
TEST(MarkerAssociationTest, AChildsLowerBodySetKeepsTheFilesUnit) {
  const Skeleton skeleton = MakeDemoSkeleton();
  Take take = MakeTakeOf(skeleton, MakeDemoWalk(skeleton, 240, 60.0), false, true,
                         {"Spine", "Chest", "Neck", "Head", "LeftShoulder", "LeftArm", "LeftForeArm", "LeftHand",
                          "RightShoulder", "RightArm", "RightForeArm", "RightHand"});
  MarkerTrajectories& points = take.trajectories;
  for (int f = 0; f < points.num_frames(); ++f) {
    for (int m = 0; m < points.num_markers(); ++m) {
      if (points.valid(f, m)) points.SetSample(f, m, 0.6 * points.position(f, m));
    }
  }
  MarkerAssociation association;
  const Status status = AssociateMarkers(points, "child.c3d", MarkerAssociationOptions(), &association);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(association.unit.name, "cm");
  EXPECT_FALSE(association.unit_from_data);
  EXPECT_LT(association.height_m, 0.8);
  EXPECT_EQ(association.up_axis, 1);
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

// A foot still the whole take is part of the body: its markers are far from every point that
// moves (the leg above them is still too) but beside the still shin, beside the moving body
// (before: the foot, shin and thigh were left out as "still, apart from the body" and the
// subject lacked a leg: squat.c3d renamed, `pipeline --subject=auto`). A prop that does not
// move at all, beside the still foot, and a still point far from the body stay out.
TEST(MarkerAssociationTest, AFootStillTheWholeTakeIsKept) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const Take still = MakeTakeOf(skeleton, MakeOneLegStill(skeleton, 400, 60.0), false, true);
  const MarkerTrajectories& in = still.trajectories;
  std::vector<std::string> labels;
  for (int m = 0; m < in.num_markers(); ++m) labels.push_back(in.label(m));
  labels.push_back("prop");
  Take take{MarkerTrajectories(labels, in.num_frames()), still.joint};
  take.trajectories.frame_rate = in.frame_rate;
  take.trajectories.unit = in.unit;
  // A camera's noise, 0.05 cm (the demo is in cm) on every tracked point; the prop is the
  // same numbers in every frame, on the floor beside the still left toe.
  std::mt19937 random(5);
  std::normal_distribution<double> noise(0.0, 0.05);
  for (int f = 0; f < in.num_frames(); ++f) {
    for (int m = 0; m < in.num_markers(); ++m) {
      const Eigen::Vector3d jitter(noise(random), noise(random), noise(random));
      if (in.valid(f, m)) take.trajectories.SetSample(f, m, in.position(f, m) + jitter);
    }
    take.trajectories.SetSample(f, in.num_markers(), Eigen::Vector3d(175.0, 0.0, 92.0));
  }
  MarkerAssociation association;
  ASSERT_TRUE(AssociateMarkers(take.trajectories, "one_leg.c3d", MarkerAssociationOptions(), &association).ok());
  EXPECT_EQ(association.up_axis, 1);
  std::string excluded;
  for (const auto& [label, why] : association.excluded) excluded += " " + label + ": " + why + ";";
  for (const auto& [label, joint] : take.joint) {
    const bool leg = joint.find("Leg") != std::string::npos || joint == "LeftFoot" || joint == "LeftToe";
    if (joint.rfind("Left", 0) == 0 && leg) {
      EXPECT_NE(association.Find(label), nullptr) << joint << " (" << label << ") left out;" << excluded;
    }
  }
  EXPECT_EQ(association.Find("still"), nullptr);
  EXPECT_EQ(association.Find("prop"), nullptr) << "a point that never moves kept as a marker";
  // The still leg's markers on its segments: left and right as found, or mirrored (a take
  // that does not travel leaves forward to weak votes; the side is not what this test is
  // about). Measured: every one of the 9 below the knee; 47 of the 60 markers (0 before: the
  // leg left out, up read upside down; the kicking thigh, up to the hips' height, reads as a
  // hand).
  MarkerAssociation mirrored = association;
  for (AssociatedMarker& a : mirrored.markers) {
    if (a.role.rfind("left_", 0) == 0) a.role = "right_" + a.role.substr(5);
    else if (a.role.rfind("right_", 0) == 0) a.role = "left_" + a.role.substr(6);
  }
  int best = 0;
  for (const MarkerAssociation* found : {&association, &mirrored}) {
    int leg = 0;
    for (const AssociatedMarker& a : found->markers) {
      const std::string joint = take.joint.count(a.label) ? take.joint.at(a.label) : "";
      leg += (joint == "LeftLeg" || joint == "LeftFoot" || joint == "LeftToe") && Accepted(joint).count(a.role);
    }
    std::string wrong;
    const int correct = CountCorrect(take, *found, &wrong);
    if (leg == 9) best = std::max(best, correct);
  }
  EXPECT_GE(best, 0.75 * static_cast<double>(take.joint.size())) << "the still leg below the knee wrong, or "
                                                                  << best << " correct;" << excluded;
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
