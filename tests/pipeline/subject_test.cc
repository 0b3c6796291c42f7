// Subject files (pipeline/subject.h): a round trip with the skeleton inline, old files by path,
// and bad files whose one-line errors name the file and the field.
#include "pipeline/subject.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/bvh_writer.h"
#include "io/marker_file.h"
#include "kinematics/demo_character.h"
#include "problems/marker_solve/synthetic_marker_set.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

// A demo skeleton with ASF-like extras (dof subsets, limits, a rest rotation).
Skeleton RichSkeleton() {
  const Skeleton demo = MakeDemoSkeleton();
  std::vector<JointSpec> joints;
  for (int j = 0; j < demo.num_joints(); ++j) joints.push_back(demo.joint(j));
  joints[1].rotation_axes = std::vector<int>{2, 0};
  joints[1].rotation_limits = {{-1.5, 0.25}, {-std::numeric_limits<double>::infinity(), 0.5}};
  joints[2].rotation_axes = std::vector<int>{};
  joints[3].rest_rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  joints[4].offset *= 1.0 / 3.0;  // Not a short decimal.
  Skeleton skeleton;
  EXPECT_TRUE(Skeleton::Create(joints, demo.end_sites(), demo.unit(), &skeleton).ok());
  return skeleton;
}

void ExpectSameSkeleton(const Skeleton& a, const Skeleton& b) {
  ASSERT_EQ(a.num_joints(), b.num_joints());
  EXPECT_EQ(a.unit().name, b.unit().name);
  EXPECT_EQ(a.unit().metres_per_unit, b.unit().metres_per_unit);
  for (int j = 0; j < a.num_joints(); ++j) {
    EXPECT_EQ(a.name(j), b.name(j));
    EXPECT_EQ(a.parent(j), b.parent(j));
    EXPECT_EQ(a.offset(j), b.offset(j)) << a.name(j);  // Round-trip exact.
    EXPECT_EQ(a.rest_rotation(j).coeffs(), b.rest_rotation(j).coeffs()) << a.name(j);
    EXPECT_EQ(a.rotation_axes(j), b.rotation_axes(j)) << a.name(j);
    EXPECT_EQ(a.rotation_limits(j), b.rotation_limits(j)) << a.name(j);
    EXPECT_EQ(a.joint(j).channels, b.joint(j).channels) << a.name(j);
  }
  ASSERT_EQ(a.end_sites().size(), b.end_sites().size());
  for (size_t e = 0; e < a.end_sites().size(); ++e) {
    EXPECT_EQ(a.end_sites()[e].name, b.end_sites()[e].name);
    EXPECT_EQ(a.end_sites()[e].offset, b.end_sites()[e].offset);
  }
}

void ExpectSameMarkers(const MarkerSet& a, const MarkerSet& b) {
  ASSERT_EQ(a.num_markers(), b.num_markers());
  for (int m = 0; m < a.num_markers(); ++m) {
    EXPECT_EQ(a.label(m), b.label(m));
    ASSERT_EQ(a.marker(m).attachments.size(), b.marker(m).attachments.size());
    for (size_t k = 0; k < a.marker(m).attachments.size(); ++k) {
      EXPECT_EQ(a.marker(m).attachments[k].joint, b.marker(m).attachments[k].joint);
      EXPECT_EQ(a.marker(m).attachments[k].weight, b.marker(m).attachments[k].weight);
      EXPECT_EQ(a.marker(m).attachments[k].offset, b.marker(m).attachments[k].offset);
    }
  }
}

Subject MakeSubject() {
  Subject subject;
  subject.name = "demo";
  subject.skeleton = RichSkeleton();
  subject.markers = MakeSyntheticMarkerSet(subject.skeleton, 2, 5);
  subject.axes = "y,z,x";
  subject.marker_scale = 0.1;
  subject.label_prefix = "Subject1:";
  subject.amc_fps = 60.0;
  return subject;
}

TEST(Subject, InlineSkeletonRoundTrip) {
  const Subject subject = MakeSubject();
  const std::string path = testing::TempPath("s.json");
  ASSERT_TRUE(WriteSubject(path, subject).ok());
  Subject read;
  const Status status = ReadSubject(path, &read);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(read.name, "demo");
  EXPECT_EQ(read.axes, "y,z,x");
  EXPECT_EQ(read.marker_scale, 0.1);
  EXPECT_EQ(read.label_prefix, "Subject1:");
  EXPECT_EQ(read.amc_fps, 60.0);
  EXPECT_TRUE(read.skeleton_path.empty());
  ExpectSameSkeleton(subject.skeleton, read.skeleton);
  ExpectSameMarkers(subject.markers, read.markers);
  // Written again, byte for byte the same.
  const std::string again = testing::TempPath("s2.json");
  ASSERT_TRUE(WriteSubject(again, read).ok());
  EXPECT_EQ(testing::ReadTextFile(path), testing::ReadTextFile(again));
}

// A take keeps the file's unlabelled points ("*7", in the skeleton's frame and units), and
// the repaired file loses those a repair assigned to markers, the rest as read.
TEST(Subject, TakeKeepsUnlabelledPointsAndTheOutputDropsAssignedOnes) {
  const Subject subject = MakeSubject();
  std::vector<std::string> labels;
  for (int m = 0; m < subject.markers.num_markers(); ++m) labels.push_back("Subject1:" + subject.markers.label(m));
  labels.push_back("*7");
  MarkerTrajectories file(labels, 5);
  file.frame_rate = 60.0;
  file.unit = LengthUnitFromName("mm");
  for (int f = 0; f < 5; ++f) {
    for (int c = 0; c < file.num_markers(); ++c) file.SetSample(f, c, Eigen::Vector3d(c + 1.0, f + 1.0, 10.0 * c + f + 1.0));
  }
  file.SetMissing(4, file.num_markers() - 1);
  const std::string path = testing::TempPath("unlabelled.c3d");
  ASSERT_TRUE(WriteMarkerFile(path, file).ok());
  MarkerTake take;
  const Status status = LoadTakeForSubject(subject, path, &take);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(take.unlabelled.names, std::vector<std::string>{"*7"});
  ASSERT_EQ(take.unlabelled_columns, std::vector<int>{file.num_markers() - 1});
  ASSERT_EQ(take.unlabelled.points.size(), 5u);
  const int column = file.num_markers() - 1;
  for (int f = 0; f < 4; ++f) {
    EXPECT_TRUE(take.unlabelled.points[f][0].isApprox(take.transform.Apply(file.position(f, column)), 1e-6)) << f;
  }
  EXPECT_FALSE(take.unlabelled.present(4, 0));
  // Marker 0 took the point at frames 1-2.
  std::vector<std::vector<Eigen::Vector3d>> repaired = take.observed;
  int rewritten = -1, removed = -1;
  const MarkerTrajectories out = WithRepairedSamples(take, repaired, &rewritten, {{0, 0, 1, 2, 0.0}}, &removed);
  EXPECT_EQ(rewritten, 0);
  EXPECT_EQ(removed, 2);
  EXPECT_TRUE(out.valid(0, column));
  EXPECT_FALSE(out.valid(1, column));
  EXPECT_FALSE(out.valid(2, column));
  EXPECT_TRUE(out.valid(3, column));
}

// The subject text with `from` replaced by `to` (which must occur).
std::string Edited(const std::string& text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at == std::string::npos) return text;
  return text.substr(0, at) + to + text.substr(at + from.size());
}

// A segment none of whose markers (nor any below it) is seen in any frame cannot be solved:
// the take is refused, naming the segment and its labels; a segment seen only through the
// markers below it is solvable and passes.
TEST(Subject, ASegmentNeverObservedIsRefusedByName) {
  const Subject subject = MakeSubject();
  const Skeleton& skeleton = subject.skeleton;
  auto joint_of = [&](int m) { return subject.markers.marker(m).attachments[0].joint; };
  // A leaf joint carrying markers whose parent carries markers too.
  int leaf = -1;
  for (int m = 0; m < subject.markers.num_markers() && leaf < 0; ++m) {
    const int j = joint_of(m);
    bool has_child = false, parent_carries = false;
    for (int k = 0; k < skeleton.num_joints(); ++k) has_child |= skeleton.parent(k) == j;
    for (int n = 0; n < subject.markers.num_markers(); ++n) parent_carries |= joint_of(n) == skeleton.parent(j);
    if (!has_child && parent_carries) leaf = j;
  }
  ASSERT_GE(leaf, 0);
  const int parent = skeleton.parent(leaf);
  auto take_without = [&](const std::vector<int>& blind_joints, MarkerTake* take) {
    std::vector<std::string> labels;
    for (int m = 0; m < subject.markers.num_markers(); ++m) labels.push_back(subject.markers.label(m));
    MarkerTrajectories file(labels, 3);
    file.unit = LengthUnitFromName("mm");
    for (int m = 0; m < file.num_markers(); ++m) {
      if (std::count(blind_joints.begin(), blind_joints.end(), joint_of(m))) continue;
      for (int f = 0; f < 3; ++f) file.SetSample(f, m, Eigen::Vector3d(m, f, 2.0));
    }
    EXPECT_TRUE(TakeForSubject(subject, file, "blind.c3d", take).ok());
    return RequireTakeData("blind.c3d", *take);
  };
  std::string leaf_labels, parent_labels, other_labels;
  for (int m = 0; m < subject.markers.num_markers(); ++m) {
    std::string& labels = joint_of(m) == leaf ? leaf_labels : joint_of(m) == parent ? parent_labels : other_labels;
    labels += (labels.empty() ? "" : ", ") + subject.markers.label(m);
  }
  MarkerTake take;
  EXPECT_TRUE(take_without({}, &take).ok());
  EXPECT_TRUE(take_without({parent}, &take).ok()) << "seen through the markers below it";
  Status status = take_without({leaf}, &take);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), StartsWith("blind.c3d: segments never observed"));
  EXPECT_THAT(status.message(), HasSubstr(": " + skeleton.name(leaf) + " (" + leaf_labels + ") ("));
  status = take_without({leaf, parent}, &take);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr(": " + skeleton.name(parent) + " (" + parent_labels + "); " +
                                          skeleton.name(leaf) + " (" + leaf_labels + ") ("));
  EXPECT_EQ(std::count(status.message().begin(), status.message().end(), '\n'), 0);
}

// A file of two actors with the same marker set: without --subject_prefix the take is read
// as the subject file's own actor (its label prefix), even when the other has more points.
TEST(Subject, ATwoActorFileIsReadAsTheSubjectsOwnActor) {
  const Subject subject = MakeSubject();  // label_prefix "Subject1:".
  std::vector<std::string> labels;
  for (int m = 0; m < subject.markers.num_markers(); ++m) labels.push_back("Other:" + subject.markers.label(m));
  labels.push_back("Other:EXTRA");  // The other actor has the most points.
  for (int m = 0; m < subject.markers.num_markers(); ++m) labels.push_back("Subject1:" + subject.markers.label(m));
  MarkerTrajectories file(labels, 2);
  file.frame_rate = 60.0;
  file.unit = LengthUnitFromName("mm");
  const int own = subject.markers.num_markers() + 1;
  for (int c = 0; c < file.num_markers(); ++c) file.SetSample(0, c, Eigen::Vector3d(c, 1.0, 2.0));
  const std::string path = testing::TempPath("two_actors.c3d");
  ASSERT_TRUE(WriteMarkerFile(path, file).ok());
  MarkerTake take;
  const Status status = LoadTakeForSubject(subject, path, &take);
  ASSERT_TRUE(status.ok()) << status.message();
  // Observations are in the skeleton frame (axes y,z,x, scale 0.1): x_file = c -> z.
  EXPECT_DOUBLE_EQ(take.observed[0][0].z(), 0.1 * own);
  MarkerTrajectories read;
  ASSERT_TRUE(ReadMarkerFile(path, &read).ok());  // Without the subject: the larger actor.
  EXPECT_EQ(read.num_markers(), subject.markers.num_markers() + 1);
}

// A subject written from a skeleton file holds the skeleton inline: copied to another
// folder (without the skeleton file), it still loads.
// A take that lacks some of the subject's markers: one line naming, per segment, the labels
// missing (and how many markers the segment has), nothing else loaded.
TEST(Subject, ATakeLackingMarkersNamesTheirSegmentsAndLabels) {
  const Subject subject = MakeSubject();
  std::vector<std::string> labels;
  std::string message;
  const std::vector<int> dropped = {0, 1, 3};  // Two markers per bone: bone 0 loses both, bone 1 one.
  for (int m = 0; m < subject.markers.num_markers(); ++m) {
    if (std::find(dropped.begin(), dropped.end(), m) == dropped.end()) labels.push_back(subject.markers.label(m));
  }
  MarkerTrajectories file(labels, 2);
  file.unit = LengthUnitFromName("mm");
  for (int c = 0; c < file.num_markers(); ++c) file.SetSample(0, c, Eigen::Vector3d(c, 1.0, 2.0));
  MarkerTake take;
  const Status status = TakeForSubject(subject, file, "short.c3d", &take);
  ASSERT_FALSE(status.ok());
  auto segment = [&](int m) { return subject.skeleton.joint(subject.markers.marker(m).attachments[0].joint).name; };
  ASSERT_EQ(segment(0), segment(1));
  EXPECT_EQ(status.message(), "short.c3d: the subject's marker set does not match the take: no column for 3 of its " +
                                  std::to_string(subject.markers.num_markers()) + " markers, by segment: " + segment(0) +
                                  ": " + subject.markers.label(0) + ", " + subject.markers.label(1) + " (of its 2); " +
                                  segment(3) + ": " + subject.markers.label(3) + " (of its 2)");
}

TEST(Subject, WrittenSkeletonIsInlineSoACopyElsewhereLoads) {
  Subject subject = MakeSubject();
  subject.skeleton = MakeDemoSkeleton();
  subject.markers = MakeSyntheticMarkerSet(subject.skeleton, 2, 5);
  const std::string bvh = testing::TempPath("skel_inline/walk.bvh");
  std::filesystem::create_directories(std::filesystem::path(bvh).parent_path());
  ASSERT_TRUE(WriteBvh(bvh, subject.skeleton, MakeDemoWalk(subject.skeleton, 2, 30.0), BvhWriteOptions()).ok());
  subject.skeleton_path = bvh;  // Where it came from: not written.
  const std::string path = testing::TempPath("subjects_inline/s.json");
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  ASSERT_TRUE(WriteSubject(path, subject).ok());
  const std::string text = testing::ReadTextFile(path);
  EXPECT_THAT(text, HasSubstr("\"skeleton\": {"));
  EXPECT_EQ(text.find("walk.bvh"), std::string::npos);
  EXPECT_EQ(text.find("skeleton_units"), std::string::npos);

  const std::string copy = testing::TempPath("elsewhere/deeper/s.json");
  std::filesystem::create_directories(std::filesystem::path(copy).parent_path());
  std::filesystem::copy_file(path, copy, std::filesystem::copy_options::overwrite_existing);
  std::filesystem::remove(bvh);
  Subject read;
  const Status status = ReadSubject(copy, &read);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_TRUE(read.skeleton_path.empty());
  ExpectSameSkeleton(subject.skeleton, read.skeleton);
  ExpectSameMarkers(subject.markers, read.markers);
}

// Older subject files name their skeleton by a path relative to themselves: still read.
TEST(Subject, SkeletonPathRelativeToTheSubjectFile) {
  Subject subject = MakeSubject();
  subject.skeleton = MakeDemoSkeleton();
  subject.markers = MakeSyntheticMarkerSet(subject.skeleton, 2, 5);
  const std::string bvh = testing::TempPath("skel/walk.bvh");
  std::filesystem::create_directories(std::filesystem::path(bvh).parent_path());
  Motion motion = MakeDemoWalk(subject.skeleton, 2, 30.0);
  ASSERT_TRUE(WriteBvh(bvh, subject.skeleton, motion, BvhWriteOptions()).ok());
  const std::string path = testing::TempPath("subjects/s.json");
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  // The inline skeleton replaced by a path, as older files hold it.
  std::string text = FormatSubject(path, subject);
  const size_t begin = text.find("  \"skeleton\": {");
  const size_t end = text.find("  \"marker_files\"");
  ASSERT_NE(begin, std::string::npos);
  ASSERT_NE(end, std::string::npos);
  text.replace(begin, end - begin, "  \"skeleton\": \"../skel/walk.bvh\",\n  \"skeleton_units\": \"cm\",\n");
  std::ofstream(path) << text;
  Subject read;
  const Status status = ReadSubject(path, &read);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(read.skeleton.unit().metres_per_unit, 0.01);
  EXPECT_EQ(read.skeleton_path, testing::TempPath("subjects/../skel/walk.bvh"));
  ASSERT_EQ(read.skeleton.num_joints(), subject.skeleton.num_joints());
  for (int j = 0; j < read.skeleton.num_joints(); ++j) {
    EXPECT_LT((read.skeleton.offset(j) - subject.skeleton.offset(j)).norm(), 1e-5);  // BVH: 6 digits.
  }
  ExpectSameMarkers(subject.markers, read.markers);
  // Written again: inline.
  const std::string again = testing::TempPath("subjects/again.json");
  ASSERT_TRUE(WriteSubject(again, read).ok());
  EXPECT_EQ(testing::ReadTextFile(again).find("walk.bvh"), std::string::npos);

  // The skeleton file gone: the error names the subject file, the field and the path.
  const std::string moved = Edited(text, "../skel/walk.bvh", "../skel/nowhere.bvh");
  const std::string bad = testing::TempPath("subjects/moved.json");
  std::ofstream(bad) << moved;
  const Status missing = ReadSubject(bad, &read);
  ASSERT_FALSE(missing.ok());
  EXPECT_THAT(missing.message(), StartsWith(bad + ":"));
  EXPECT_THAT(missing.message(), HasSubstr("skeleton: "));
  EXPECT_THAT(missing.message(), HasSubstr("nowhere.bvh"));
}

std::string ReadEdited(const std::string& text, const std::string& name) {
  const std::string path = testing::TempPath(name);
  std::ofstream(path) << text;
  Subject subject;
  const Status status = ReadSubject(path, &subject);
  EXPECT_FALSE(status.ok());
  EXPECT_THAT(status.message(), StartsWith(path + ":"));
  EXPECT_EQ(status.message().find('\n'), std::string::npos) << status.message();
  return status.message();
}

TEST(Subject, BadFilesNameTheFileAndField) {
  const Subject subject = MakeSubject();
  const std::string good = FormatSubject(testing::TempPath("good.json"), subject);
  const std::string first_joint = subject.skeleton.name(subject.markers.marker(0).attachments[0].joint);

  EXPECT_THAT(ReadEdited(Edited(good, "\"amc_fps\"", "\"amc_fsp\""), "typo.json"),
              HasSubstr("unknown key 'amc_fsp'"));
  EXPECT_THAT(ReadEdited(Edited(good, "\"joint\": \"" + first_joint + "\"", "\"joint\": \"nojoint\""),
                         "bad_joint.json"),
              HasSubstr("markerset: markers[0]: '" + subject.markers.label(0) +
                        "': attachments[0].joint: unknown joint 'nojoint'"));
  EXPECT_THAT(ReadEdited(Edited(good, "\"axes\": \"y,z,x\"", "\"axes\": \"y,z\""), "axes.json"),
              HasSubstr("marker_files.axes"));
  EXPECT_THAT(ReadEdited(Edited(good, "\"parent\": null", "\"parent\": \"elsewhere\""), "parent.json"),
              HasSubstr("skeleton.joints[0]"));
  std::string no_skeleton = good;
  const size_t begin = no_skeleton.find("  \"skeleton\": {");
  const size_t end = no_skeleton.find("  \"marker_files\"");
  no_skeleton.erase(begin, end - begin);
  EXPECT_THAT(ReadEdited(no_skeleton, "no_skeleton.json"), HasSubstr("missing \"skeleton\""));
}

// The optional mean pose (the rest prior's reference): round trip to the digit, absent in a
// subject without one (files written before it existed read as before), joints not named
// are the identity, and a bad entry names the field.
TEST(Subject, MeanPoseRoundTripAndErrors) {
  Subject subject = MakeSubject();
  EXPECT_EQ(FormatSubject("old.json", subject).find("mean_pose"), std::string::npos);
  const std::string old_path = testing::TempPath("old.json");
  ASSERT_TRUE(WriteSubject(old_path, subject).ok());
  Subject read;
  ASSERT_TRUE(ReadSubject(old_path, &read).ok());
  EXPECT_TRUE(read.mean_pose.empty());

  for (int j = 0; j < subject.skeleton.num_joints(); ++j) {
    subject.mean_pose.push_back(Eigen::Quaterniond(Eigen::AngleAxisd(0.3 + j / 3.0, Eigen::Vector3d(1, -j, 2).normalized())));
  }
  const std::string path = testing::TempPath("mean.json");
  ASSERT_TRUE(WriteSubject(path, subject).ok());
  Status status = ReadSubject(path, &read);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(read.mean_pose.size(), subject.mean_pose.size());
  for (size_t j = 0; j < read.mean_pose.size(); ++j) {
    EXPECT_EQ(read.mean_pose[j].coeffs(), subject.mean_pose[j].coeffs()) << j;  // 17 digits: exact.
  }
  const std::string again = testing::TempPath("mean2.json");
  ASSERT_TRUE(WriteSubject(again, read).ok());
  EXPECT_EQ(testing::ReadTextFile(path), testing::ReadTextFile(again));

  // The file with another "mean_pose" value.
  const std::string good = testing::ReadTextFile(path);
  const auto with_mean = [&](const std::string& value) {
    return good.substr(0, good.find("  \"mean_pose\"")) + "  \"mean_pose\": " + value + ",\n" +
           good.substr(good.find("  \"markerset\""));
  };
  const std::string joint2 = "\"" + subject.skeleton.name(2) + "\"";
  const std::string partial = testing::TempPath("partial.json");
  std::ofstream(partial) << with_mean("{" + joint2 + ": [0, 1, 0, 0]}");
  status = ReadSubject(partial, &read);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(read.mean_pose.size(), static_cast<size_t>(subject.skeleton.num_joints()));
  EXPECT_EQ(read.mean_pose[0].coeffs(), Eigen::Quaterniond::Identity().coeffs());
  EXPECT_EQ(read.mean_pose[2].coeffs(), Eigen::Quaterniond(0, 1, 0, 0).coeffs());

  EXPECT_THAT(ReadEdited(with_mean("{\"nojoint\": [1, 0, 0, 0]}"), "mean_joint.json"),
              HasSubstr("mean_pose.nojoint: unknown joint"));
  EXPECT_THAT(ReadEdited(with_mean("{" + joint2 + ": [1, 0, 0]}"), "mean_size.json"),
              HasSubstr("mean_pose." + subject.skeleton.name(2) + ": expected [w, x, y, z]"));
  EXPECT_THAT(ReadEdited(with_mean("{" + joint2 + ": [2, 0, 0, 0]}"), "mean_norm.json"),
              HasSubstr("mean_pose." + subject.skeleton.name(2) + ": expected a unit quaternion"));
  EXPECT_THAT(ReadEdited(with_mean("[1, 0, 0, 0]"), "mean_type.json"), HasSubstr("mean_pose: expected an object"));
  Subject wrong = subject;
  wrong.mean_pose.pop_back();
  EXPECT_FALSE(WriteSubject(testing::TempPath("wrong.json"), wrong).ok());
}

}  // namespace
}  // namespace mocapsolve
