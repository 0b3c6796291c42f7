// The humanoid role template matched by structure (problems/retarget/humanoid_roles.h) and
// the joint map that uses it (joint_map.h). Fixtures are built here, in memory: the demo
// skeleton, and the shared characters (glTF, BVH, ASF; skipped without MOCAPSOLVE_DATA),
// each also as variants that rename every joint to random names, re-root it under a floor
// bone with IK foot and pole bones, put it under a rotated `Armature` joint in centimetres,
// turn its facing by 90 or 180 degrees, swap its side names (so names lie), or add IK
// copies of the arms. The roles
// must be the same joints on every variant, and the map from the original onto a variant
// must link every role to its counterpart.
#include "problems/retarget/humanoid_roles.h"

#include <cstdio>
#include <functional>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/gltf_reader.h"
#include "io/motion_file.h"
#include "kinematics/demo_character.h"
#include "kinematics/forward_kinematics.h"
#include "problems/retarget/joint_map.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

// A skeleton whose rest pose is `pose` of `skeleton` (so variants work on rest offsets).
struct Fixture {
  Skeleton skeleton;
  std::vector<bool> weighted;   // Empty = unknown.
  std::vector<int> of_original;  // Index of each original joint in this skeleton.
};

Fixture Baked(const Skeleton& skeleton, const Pose& pose, const std::vector<bool>& weighted) {
  std::vector<JointSpec> specs;
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    JointSpec spec;
    spec.name = skeleton.name(j);
    spec.parent = skeleton.parent(j);
    spec.offset = pose.translations[j];
    spec.rest_rotation = (skeleton.rest_rotation(j) * pose.rotations[j]).normalized();
    specs.push_back(spec);
  }
  Fixture out;
  EXPECT_TRUE(Skeleton::Create(specs, {}, skeleton.unit(), &out.skeleton).ok());
  out.weighted = weighted;
  for (int j = 0; j < skeleton.num_joints(); ++j) out.of_original.push_back(j);
  return out;
}

std::vector<JointSpec> Specs(const Skeleton& skeleton) {
  std::vector<JointSpec> specs;
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    JointSpec spec;
    spec.name = skeleton.name(j);
    spec.parent = skeleton.parent(j);
    spec.offset = skeleton.offset(j);
    spec.rest_rotation = skeleton.rest_rotation(j);
    specs.push_back(spec);
  }
  return specs;
}

// `added` joints inserted at the front (new roots/leaves under them): indices shift.
Fixture Rebuild(const Fixture& in, std::vector<JointSpec> specs, int added_before, const std::vector<bool>& added_weighted) {
  Fixture out;
  EXPECT_TRUE(Skeleton::Create(specs, {}, in.skeleton.unit(), &out.skeleton).ok());
  for (int j : in.of_original) out.of_original.push_back(j + added_before);
  if (!in.weighted.empty()) {
    out.weighted.assign(specs.size(), false);
    for (int j = 0; j < in.skeleton.num_joints(); ++j) out.weighted[j + added_before] = in.weighted[j];
    for (size_t k = 0; k < added_weighted.size(); ++k) out.weighted[k] = added_weighted[k];
  }
  return out;
}

Fixture Renamed(const Fixture& in, unsigned seed) {
  std::vector<JointSpec> specs = Specs(in.skeleton);
  std::mt19937 rng(seed);
  std::set<std::string> used;
  for (JointSpec& spec : specs) {
    do {
      spec.name = "j" + std::to_string(10000 + rng() % 90000);  // No side word, no role word.
    } while (!used.insert(spec.name).second);
  }
  return Rebuild(in, specs, 0, {});
}

std::string SwapSides(const std::string& name) {
  std::string out;
  for (size_t i = 0; i < name.size();) {
    auto at = [&](const char* word) { return name.compare(i, std::string(word).size(), word) == 0; };
    const bool word_start = i == 0 || !std::isalpha(static_cast<unsigned char>(name[i - 1])) ||
                            std::islower(static_cast<unsigned char>(name[i - 1]));
    const bool next_not_lower = i + 1 >= name.size() || !std::islower(static_cast<unsigned char>(name[i + 1]));
    if (at("Left")) out += "Right", i += 4;
    else if (at("Right")) out += "Left", i += 5;
    else if (at("left")) out += "right", i += 4;
    else if (at("right")) out += "left", i += 5;
    else if (word_start && next_not_lower && (name[i] == 'L' || name[i] == 'R')) out += name[i] == 'L' ? 'R' : 'L', ++i;
    else if (i == 0 && (name[0] == 'l' || name[0] == 'r') && name.size() > 3) out += name[0] == 'l' ? 'r' : 'l', ++i;
    else out += name[i++];
  }
  return out;
}

Fixture Mirrored(const Fixture& in) {
  std::vector<JointSpec> specs = Specs(in.skeleton);
  for (JointSpec& spec : specs) spec.name = SwapSides(spec.name);
  return Rebuild(in, specs, 0, {});
}

// The root turned by q about the world origin (so the whole figure turns).
Fixture Turned(const Fixture& in, const Eigen::Quaterniond& q) {
  std::vector<JointSpec> specs = Specs(in.skeleton);
  specs[0].offset = q * specs[0].offset;
  specs[0].rest_rotation = (q * specs[0].rest_rotation).normalized();
  return Rebuild(in, specs, 0, {});
}

// A floor bone under the old root (at its ground projection, "up" = +y of the rest
// world), with IK foot and knee pole leaves under it, as game rigs have.
Fixture FloorRooted(const Fixture& in) {
  FkData fk(in.skeleton);
  ForwardKinematics(in.skeleton, RestPose(in.skeleton), &fk);
  double floor = fk.world_positions[0].y();
  int low_a = -1, low_b = -1;  // The lowest joint on each side of x = root x.
  for (int j = 0; j < in.skeleton.num_joints(); ++j) {
    const Eigen::Vector3d& p = fk.world_positions[j];
    floor = std::min(floor, p.y());
    int& low = p.x() > fk.world_positions[0].x() ? low_a : low_b;
    if (low < 0 || p.y() < fk.world_positions[low].y()) low = j;
  }
  const Eigen::Vector3d ground(fk.world_positions[0].x(), floor, fk.world_positions[0].z());
  std::vector<JointSpec> specs;
  JointSpec root;
  root.name = "root_bone";
  root.offset = ground;
  specs.push_back(root);
  for (JointSpec spec : Specs(in.skeleton)) {
    spec.parent = spec.parent < 0 ? 0 : spec.parent + 1;
    if (spec.parent == 0) spec.offset -= ground;
    specs.push_back(spec);
  }
  int k = 0;
  for (int low : {low_a, low_b}) {
    if (low < 0) continue;
    JointSpec ik;
    ik.name = "ik_target_" + std::to_string(k++);
    ik.parent = 0;
    ik.offset = fk.world_positions[low] - ground;
    specs.push_back(ik);
    JointSpec pole = ik;
    pole.name = "pole_" + std::to_string(k);
    pole.offset += Eigen::Vector3d(0, 0.3 * (fk.world_positions[0].y() - floor), 0.4);
    specs.push_back(pole);
  }
  return Rebuild(in, specs, 1, {false});
}

// In centimetres under an `Armature` joint that turns Z up into Y up (Mixamo's FBX).
Fixture UnderArmature(const Fixture& in) {
  const Eigen::Quaterniond r(Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitX()));
  std::vector<JointSpec> specs;
  JointSpec armature;
  armature.name = "Armature";
  armature.rest_rotation = r;
  specs.push_back(armature);
  for (JointSpec spec : Specs(in.skeleton)) {
    spec.offset *= 100.0;
    if (spec.parent < 0) {
      spec.offset = r.inverse() * spec.offset;
      spec.rest_rotation = (r.inverse() * spec.rest_rotation).normalized();
    }
    spec.parent = spec.parent < 0 ? 0 : spec.parent + 1;
    specs.push_back(spec);
  }
  return Rebuild(in, specs, 1, {false});
}

// The subtree of `joint` duplicated under its parent as an IK chain (names "<name>_ik",
// no vertex weight), after the original, as game rigs' IK/FK arms.
Fixture WithIkCopy(const Fixture& in, int joint) {
  std::vector<JointSpec> specs = Specs(in.skeleton);
  std::vector<int> copy_of(in.skeleton.num_joints(), -1);
  for (int j = joint; j < in.skeleton.subtree_end(joint); ++j) {
    JointSpec spec = specs[j];
    spec.name += "_ik";
    spec.parent = j == joint ? specs[j].parent : copy_of[specs[j].parent];
    copy_of[j] = static_cast<int>(specs.size());
    specs.push_back(spec);
  }
  Fixture out = Rebuild(in, specs, 0, {});
  if (!in.weighted.empty()) out.weighted.resize(specs.size(), false);
  return out;
}

HumanoidRoles Roles(const Fixture& f) {
  FkData fk(f.skeleton);
  ForwardKinematics(f.skeleton, RestPose(f.skeleton), &fk);
  return FindHumanoidRoles(f.skeleton, fk.world_positions, f.weighted);
}

JointMapSkeleton Standing(const Fixture& f) {
  JointMapSkeleton out = StandingSkeleton(f.skeleton, Pose(), nullptr);
  out.weighted = f.weighted;
  return out;
}

struct Named {
  const char* name;
  std::function<Fixture(const Fixture&)> make;
};

const std::vector<Named>& Variants() {
  static const auto* variants = new std::vector<Named>{
      {"renamed", [](const Fixture& f) { return Renamed(f, 7); }},
      {"floor root + IK bones", [](const Fixture& f) { return FloorRooted(f); }},
      {"armature cm z-up", [](const Fixture& f) { return UnderArmature(f); }},
      {"facing +90", [](const Fixture& f) { return Turned(f, Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()))); }},
      {"facing 180", [](const Fixture& f) { return Turned(f, Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitY()))); }},
      {"side names swapped", [](const Fixture& f) { return Mirrored(f); }},
      {"IK copies of the arms", [](const Fixture& f) {
         const HumanoidRoles roles = Roles(f);
         Fixture out = WithIkCopy(f, roles.Find("left_upper_arm"));
         return WithIkCopy(out, out.of_original[roles.Find("right_upper_arm")]);
       }},
      {"all of them", [](const Fixture& f) {
         return Mirrored(Renamed(UnderArmature(FloorRooted(
             Turned(f, Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()))))), 11));
       }},
  };
  return *variants;
}

// Every variant: the same roles on the same joints, and the map links them.
void ExpectSameRolesOnVariants(const std::string& what, const Fixture& original) {
  const HumanoidRoles roles = Roles(original);
  ASSERT_TRUE(roles.humanoid) << what << ": " << roles.why_not;
  for (const Named& variant : Variants()) {
    // Where the rest pose cannot tell the facing (feet along the shins), names decide the
    // sides, so names that lie win; that is checked by the caller.
    const std::string kind = variant.name;
    if (roles.side_evidence != "geometry" && (kind == "renamed" || kind == "side names swapped" || kind == "all of them")) {
      continue;
    }
    const Fixture v = variant.make(original);
    const HumanoidRoles got = Roles(v);
    ASSERT_TRUE(got.humanoid) << what << " (" << variant.name << "): " << got.why_not;
    EXPECT_EQ(got.RoleList(), roles.RoleList()) << what << " (" << variant.name << ")";
    for (const auto& [role, joint] : roles.roles) {
      EXPECT_EQ(got.Find(role), v.of_original[joint])
          << what << " (" << variant.name << "): " << role << " is '" << original.skeleton.name(joint) << "', found '"
          << (got.Find(role) >= 0 ? v.skeleton.name(got.Find(role)) : std::string("-")) << "'";
    }
    JointMap map;
    ASSERT_TRUE(BuildJointMap(Standing(original), Standing(v), {}, &map).ok());
    for (const auto& [role, joint] : roles.roles) {
      EXPECT_EQ(map.target_of_source[joint], v.of_original[joint])
          << what << " -> " << variant.name << ": " << role << " ('" << original.skeleton.name(joint) << "') maps to "
          << (map.target_of_source[joint] >= 0 ? v.skeleton.name(map.target_of_source[joint]) : std::string("nothing"));
    }
  }
}

// On names that say the role (Mixamo, CMU, Blender conventions), the structure agrees.
// Returns the disagreements "role: structure 'x', names 'y'".
std::vector<std::string> CompareWithNames(const Skeleton& skeleton, const HumanoidRoles& roles) {
  static const std::map<std::string, std::string> kCanonical = {
      {"pelvis", "hips"}, {"head", "head"}, {"neck", "neck"},
      {"left_clavicle", "leftshoulder"}, {"left_upper_arm", "leftarm"}, {"left_forearm", "leftforearm"},
      {"left_hand", "lefthand"}, {"left_thigh", "leftupleg"}, {"left_shin", "leftleg"},
      {"left_foot", "leftfoot"}, {"left_toes", "lefttoebase"},
      {"right_clavicle", "rightshoulder"}, {"right_upper_arm", "rightarm"}, {"right_forearm", "rightforearm"},
      {"right_hand", "righthand"}, {"right_thigh", "rightupleg"}, {"right_shin", "rightleg"},
      {"right_foot", "rightfoot"}, {"right_toes", "righttoebase"}};
  std::vector<std::string> differences;
  for (const auto& [role, canonical] : kCanonical) {
    int by_name = -1;
    for (int j = 0; j < skeleton.num_joints() && by_name < 0; ++j) {
      if (CanonicalJointName(NormalizeJointName(skeleton.name(j))) == canonical) by_name = j;
    }
    const int by_structure = roles.Find(role);
    if (by_name < 0 || by_name == by_structure) continue;
    differences.push_back(role + ": structure '" + (by_structure >= 0 ? skeleton.name(by_structure) : "-") +
                          "', names '" + skeleton.name(by_name) + "'");
  }
  return differences;
}

TEST(HumanoidRolesTest, DemoSkeletonRolesAndVariants) {
  const Skeleton demo = MakeDemoSkeleton();
  const Fixture original = Baked(demo, RestPose(demo), {});
  const HumanoidRoles roles = Roles(original);
  ASSERT_TRUE(roles.humanoid) << roles.why_not;
  EXPECT_EQ(roles.side_evidence, "geometry");
  EXPECT_EQ(demo.name(roles.Find("pelvis")), "Hips");
  EXPECT_EQ(demo.name(roles.Find("chest")), "Chest");
  EXPECT_EQ(demo.name(roles.Find("spine_1")), "Spine");
  EXPECT_EQ(demo.name(roles.Find("head")), "Head");
  EXPECT_EQ(demo.name(roles.Find("left_forearm")), "LeftForeArm");
  EXPECT_EQ(demo.name(roles.Find("right_thigh")), "RightUpLeg");
  EXPECT_EQ(demo.name(roles.Find("left_toes")), "LeftToe");
  EXPECT_TRUE(CompareWithNames(demo, roles).empty());
  ExpectSameRolesOnVariants("demo", original);
}

TEST(HumanoidRolesTest, NameSideWords) {
  EXPECT_EQ(NameSide("mixamorig:LeftArm"), -1);
  EXPECT_EQ(NameSide("UpperArm.R"), 1);
  EXPECT_EQ(NameSide("leg_joint_L_1"), -1);
  EXPECT_EQ(NameSide("upperarm_r"), 1);
  EXPECT_EQ(NameSide("Bip01 L UpperArm"), -1);
  EXPECT_EQ(NameSide("LHipJoint"), -1);
  EXPECT_EQ(NameSide("lfemur"), -1);
  EXPECT_EQ(NameSide("DEF-upper_arm.L"), -1);
  EXPECT_EQ(NameSide("Hips"), 0);
  EXPECT_EQ(NameSide("leg"), 0);
}

TEST(HumanoidRolesTest, NotAHumanoid) {
  // A chain and a star are no humanoid; the answer says what was missing.
  std::vector<JointSpec> specs(4);
  for (int j = 0; j < 4; ++j) {
    specs[j].name = "b" + std::to_string(j);
    specs[j].parent = j - 1;
    specs[j].offset = Eigen::Vector3d(0, j > 0 ? 1 : 0, 0);
  }
  Skeleton chain;
  ASSERT_TRUE(Skeleton::Create(specs, {}, Metres(), &chain).ok());
  const HumanoidRoles roles = Roles(Baked(chain, RestPose(chain), {}));
  EXPECT_FALSE(roles.humanoid);
  EXPECT_NE(roles.why_not.find("legs"), std::string::npos) << roles.why_not;
}

// --- Shared characters (skipped without the data) ---

// The bind pose, or the node rest pose where only that tells the sides (FindRoles).
Fixture GltfFixture(const std::string& path) {
  GltfCharacter character;
  EXPECT_TRUE(ReadGltfCharacter(path, GltfReadOptions(), &character).ok());
  const Pose bind = character.bind_pose.rotations.empty() ? RestPose(character.skeleton) : character.bind_pose;
  const JointMapSkeleton standing = StandingSkeleton(character.skeleton, bind, &character.mesh, character.rest_pose);
  const HumanoidRoles in_bind = FindHumanoidRoles(character.skeleton, standing.positions, standing.weighted);
  const bool rest = in_bind.humanoid && in_bind.side_evidence != "geometry" &&
                    FindRoles(standing).side_evidence == "geometry";
  return Baked(character.skeleton, rest ? character.rest_pose : bind, standing.weighted);
}

class GltfRolesTest : public ::testing::TestWithParam<const char*> {};

TEST_P(GltfRolesTest, SameRolesAsNamesAndOnVariants) {
  const std::string name = GetParam();
  MOCAPSOLVE_DATA_FILE(path, "gltf/" + name + ".glb");
  const Fixture original = GltfFixture(path);
  const HumanoidRoles roles = Roles(original);
  ASSERT_TRUE(roles.humanoid) << name << ": " << roles.why_not;
  std::string table;
  for (const auto& [role, joint] : roles.roles) table += " " + role + "=" + original.skeleton.name(joint);
  std::printf("%s: %zu roles (sides: %s):%s\n", name.c_str(), roles.roles.size(), roles.side_evidence.c_str(),
              table.c_str());
  std::vector<std::string> differences = CompareWithNames(original.skeleton, roles);
  // RobotExpressive: the legs hang from `Body`, above `Hips` (which carries only the spine),
  // so the structure's pelvis is Body; its feet are IK bones under the floor root.
  std::vector<std::string> expected;
  if (name == "RobotExpressive") {
    expected = {"left_foot: structure '-', names 'Foot.L'", "pelvis: structure 'Body', names 'Hips'",
                "right_foot: structure '-', names 'Foot.R'"};
  }
  EXPECT_EQ(differences, expected);
  EXPECT_EQ(roles.side_evidence, "geometry");
  ExpectSameRolesOnVariants(name, original);
}

INSTANTIATE_TEST_SUITE_P(Characters, GltfRolesTest,
                         ::testing::Values("Xbot", "Ely", "Soldier", "CesiumMan", "RiggedFigure", "RobotExpressive"));

class MotionFileRolesTest : public ::testing::TestWithParam<const char*> {};

TEST_P(MotionFileRolesTest, SameRolesAsNamesAndOnVariants) {
  const std::string relative = GetParam();
  MOCAPSOLVE_DATA_FILE(path, relative);
  MotionFileOptions options;
  if (relative.find(".amc") != std::string::npos) {
    MOCAPSOLVE_DATA_FILE(asf, relative.substr(0, relative.find('_')) + ".asf");
    options.skeleton_path = asf;
  }
  Skeleton skeleton;
  Motion motion;
  ASSERT_TRUE(ReadMotionFile(path, options, &skeleton, &motion).ok());
  const Fixture original = Baked(skeleton, RestPose(skeleton), {});
  const HumanoidRoles roles = Roles(original);
  ASSERT_TRUE(roles.humanoid) << relative << ": " << roles.why_not;
  std::string table;
  for (const auto& [role, joint] : roles.roles) table += " " + role + "=" + skeleton.name(joint);
  std::printf("%s: %zu roles (sides: %s):%s\n", relative.c_str(), roles.roles.size(), roles.side_evidence.c_str(),
              table.c_str());
  EXPECT_EQ(CompareWithNames(skeleton, roles), std::vector<std::string>());
  // 16_15 (a MotionBuilder conversion) rests with its feet pointing down: no facing.
  EXPECT_EQ(roles.side_evidence, relative == "bvh/16_15.bvh" ? "names" : "geometry");
  ExpectSameRolesOnVariants(relative, original);
}

INSTANTIATE_TEST_SUITE_P(Cmu, MotionFileRolesTest,
                         ::testing::Values("bvh/01_01.bvh", "bvh/131_02.bvh", "bvh/16_15.bvh", "amc/02_01.amc"));

TEST(HumanoidRolesTest, FoxIsNoHumanoidAndMapsOntoItselfByTopology) {
  MOCAPSOLVE_DATA_FILE(path, "gltf/Fox.glb");
  const Fixture fox = GltfFixture(path);
  const HumanoidRoles roles = Roles(fox);
  EXPECT_FALSE(roles.humanoid);
  std::printf("Fox: %s\n", roles.why_not.c_str());
  const Fixture renamed = Renamed(fox, 3);
  JointMap map;
  ASSERT_TRUE(BuildJointMap(Standing(fox), Standing(renamed), {}, &map).ok());
  EXPECT_EQ(map.num_mapped(), fox.skeleton.num_joints());
  for (int j = 0; j < fox.skeleton.num_joints(); ++j) EXPECT_EQ(map.target_of_source[j], j);
  EXPECT_EQ(map.how_of_source[1], "topology");
}

}  // namespace
}  // namespace mocapsolve
