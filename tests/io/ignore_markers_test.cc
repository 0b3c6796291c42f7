// --ignore_markers: the named markers are read as missing in every frame, by their whole
// label or their name after a subject's prefix; a name the file lacks is an error naming it.
#include <gtest/gtest.h>

#include "io/marker_file.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

std::string WriteTake(const std::vector<std::string>& labels) {
  MarkerTrajectories take(labels, 4);
  take.frame_rate = 100.0;
  take.unit = Millimetres();
  for (int f = 0; f < 4; ++f) {
    for (int m = 0; m < static_cast<int>(labels.size()); ++m) take.SetSample(f, m, Eigen::Vector3d(m, f, 1.0));
  }
  const std::string path = testing::TempPath("ignore.trc");
  const Status status = WriteMarkerFile(path, take);
  EXPECT_TRUE(status.ok()) << status.message();
  return path;
}

TEST(IgnoreMarkers, NamedMarkersAreMissingInEveryFrame) {
  const std::string path = WriteTake({"Nick01:RTOE", "Nick01:LTOE", "C7"});
  MarkerReadOptions options;
  options.ignore_markers = "RTOE,C7";
  MarkerTrajectories take;
  const Status status = ReadMarkerFile(path, &take, options);
  ASSERT_TRUE(status.ok()) << status.message();
  for (int f = 0; f < 4; ++f) {
    EXPECT_FALSE(take.valid(f, 0));
    EXPECT_TRUE(take.valid(f, 1));
    EXPECT_FALSE(take.valid(f, 2));
  }
}

TEST(IgnoreMarkers, UnknownNamesAreErrors) {
  const std::string path = WriteTake({"RTOE", "C7"});
  MarkerReadOptions options;
  MarkerTrajectories take;
  options.ignore_markers = "LTOE";
  const Status status = ReadMarkerFile(path, &take, options);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("no marker 'LTOE'"), std::string::npos) << status.message();
}

// A file of two actors is read as one (io/c3d_points.h; a TRC's subjects are its labels'
// prefixes), so a name is that actor's marker, not ambiguous; the other actor's are gone.
TEST(IgnoreMarkers, NamesAreTheActorReadsMarkers) {
  const std::string path = WriteTake({"A:RTOE", "B:RTOE", "A:C7"});
  MarkerReadOptions options;
  std::vector<std::string> warnings;
  options.warnings = &warnings;
  MarkerTrajectories take;
  options.ignore_markers = "RTOE";
  Status status = ReadMarkerFile(path, &take, options);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(take.num_markers(), 2);
  EXPECT_FALSE(take.valid(0, 0));
  EXPECT_TRUE(take.valid(0, 1));
  options.subject_prefix = "B";
  options.ignore_markers = "A:RTOE";
  status = ReadMarkerFile(path, &take, options);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("no marker 'A:RTOE'"), std::string::npos) << status.message();
}

}  // namespace
}  // namespace mocapsolve
