#include "kinematics/demo_character.h"

#include <cassert>
#include <cmath>

#include "kinematics/rotation.h"

namespace mocapsolve {

Skeleton MakeDemoSkeleton() {
  struct Row {
    const char* name;
    const char* parent;
    double x, y, z;
  };
  // Preorder; offsets in cm in the parent's frame.
  const Row rows[] = {
      {"Hips", nullptr, 0, 95, 0},        {"Spine", "Hips", 0, 10, 0},
      {"Chest", "Spine", 0, 15, 0},       {"Neck", "Chest", 0, 20, 0},
      {"Head", "Neck", 0, 10, 2},         {"LeftShoulder", "Chest", 4, 16, 0},
      {"LeftArm", "LeftShoulder", 14, 0, 0}, {"LeftForeArm", "LeftArm", 28, 0, 0},
      {"LeftHand", "LeftForeArm", 25, 0, 0}, {"RightShoulder", "Chest", -4, 16, 0},
      {"RightArm", "RightShoulder", -14, 0, 0}, {"RightForeArm", "RightArm", -28, 0, 0},
      {"RightHand", "RightForeArm", -25, 0, 0}, {"LeftUpLeg", "Hips", 9, -5, 0},
      {"LeftLeg", "LeftUpLeg", 0, -42, 0}, {"LeftFoot", "LeftLeg", 0, -41, 0},
      {"LeftToe", "LeftFoot", 0, -6, 13},  {"RightUpLeg", "Hips", -9, -5, 0},
      {"RightLeg", "RightUpLeg", 0, -42, 0}, {"RightFoot", "RightLeg", 0, -41, 0},
  };
  std::vector<JointSpec> joints;
  for (const Row& row : rows) {
    JointSpec spec;
    spec.name = row.name;
    spec.offset = Eigen::Vector3d(row.x, row.y, row.z);
    for (int j = 0; j < static_cast<int>(joints.size()); ++j) {
      if (row.parent != nullptr && joints[j].name == row.parent) spec.parent = j;
    }
    spec.channels = {Channel::kZrotation, Channel::kXrotation, Channel::kYrotation};
    if (row.parent == nullptr) {
      spec.channels.insert(spec.channels.begin(),
                           {Channel::kXposition, Channel::kYposition, Channel::kZposition});
    }
    joints.push_back(spec);
  }
  std::vector<EndSite> end_sites = {{"Head_End", 4, {0, 15, 0}},
                                    {"LeftHand_End", 8, {15, 0, 0}},
                                    {"RightHand_End", 12, {-15, 0, 0}},
                                    {"LeftToe_End", 16, {0, 0, 6}},
                                    {"RightFoot_End", 19, {0, -6, 13}}};
  Skeleton skeleton;
  const Status status = Skeleton::Create(joints, end_sites, Centimetres(), &skeleton);
  assert(status.ok());
  (void)status;
  return skeleton;
}

Motion MakeDemoWalk(const Skeleton& skeleton, int num_frames, double frame_rate) {
  Motion motion;
  motion.frame_rate = frame_rate;
  const double cycle_seconds = 1.1;
  auto set = [&](Pose* pose, const char* joint, double x_deg, double y_deg, double z_deg) {
    const int j = skeleton.FindJoint(joint);
    if (j < 0) return;
    pose->rotations[j] = QuaternionFromEuler(
        Eigen::Vector3d(DegToRad(z_deg), DegToRad(x_deg), DegToRad(y_deg)), EulerOrder::kZXY);
  };
  for (int f = 0; f < num_frames; ++f) {
    const double t = f / frame_rate;
    const double phase = 2.0 * kPi * t / cycle_seconds;
    const double s = std::sin(phase), c = std::cos(phase);
    Pose pose = RestPose(skeleton);
    pose.translations[0] += Eigen::Vector3d(2.0 * s, 2.5 * std::cos(2 * phase), 100.0 * t);
    set(&pose, "Hips", 0, 8 * s, 3 * c);
    set(&pose, "Spine", 3, -4 * s, 0);
    set(&pose, "Chest", 2, -6 * s, -2 * c);
    set(&pose, "Head", -3, 5 * s, 0);
    set(&pose, "LeftUpLeg", -28 * s, 0, 2);
    set(&pose, "LeftLeg", 30 + 30 * c, 0, 0);
    set(&pose, "LeftFoot", -10 * s, 0, 0);
    set(&pose, "RightUpLeg", 28 * s, 0, -2);
    set(&pose, "RightLeg", 30 - 30 * c, 0, 0);
    set(&pose, "RightFoot", 10 * s, 0, 0);
    set(&pose, "LeftArm", 25 * s, 0, -70);
    set(&pose, "LeftForeArm", 0, -20 - 15 * s, 0);
    set(&pose, "RightArm", -25 * s, 0, 70);
    set(&pose, "RightForeArm", 0, 20 - 15 * s, 0);
    motion.frames.push_back(pose);
  }
  return motion;
}

}  // namespace mocapsolve
