// The live framings (io/live_frame.h): JSON lines and binary frames round-trip, and each
// malformed frame is one message naming the frame and the field.
#include "io/live_frame.h"

#include <cmath>
#include <cstring>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

LiveFrame SampleFrame() {
  LiveFrame frame;
  frame.frame = 7;
  frame.time = 0.0583;
  frame.labels = {"LASI", "RASI", "Sub:LKNE"};
  frame.positions = {Eigen::Vector3d(1.5, -2.25, 1000.125), Eigen::Vector3d::Constant(std::nan("")),
                     Eigen::Vector3d(0, 1e-3, -7)};
  return frame;
}

TEST(LiveFrame, JsonLineRoundTrip) {
  const LiveFrame frame = SampleFrame();
  LiveFrame read;
  ASSERT_TRUE(ParseJsonFrameLine(FormatJsonFrameLine(frame), &read).ok());
  EXPECT_EQ(read.frame, 7);
  EXPECT_DOUBLE_EQ(read.time, 0.0583);
  ASSERT_EQ(read.labels, frame.labels);
  EXPECT_TRUE(read.positions[0].isApprox(frame.positions[0], 1e-12));
  EXPECT_FALSE(read.positions[1].allFinite());
  EXPECT_TRUE(read.positions[2].isApprox(frame.positions[2], 1e-12));
}

TEST(LiveFrame, JsonErrorsNameFrameAndField) {
  LiveFrame frame;
  auto error = [&](const std::string& line) { return ParseJsonFrameLine(line, &frame).message(); };
  EXPECT_THAT(error("{\"frame\": 3, \"markers\": {\"A\": [1, 2]}}"), HasSubstr("frame 3: markers.A: expected [x, y, z]"));
  EXPECT_THAT(error("{\"frame\": 3, \"markers\": {\"A\": [1, \"x\", 2]}}"), HasSubstr("frame 3: markers.A"));
  EXPECT_THAT(error("{\"frame\": 3, \"markers\": {\"A\": [1, 2, 1e300]}}"), HasSubstr("|value| <= 1e9"));
  EXPECT_THAT(error("{\"frame\": 3, \"marker\": {}}"), HasSubstr("frame 3: marker: unknown key"));
  EXPECT_THAT(error("{\"frame\": 3}"), HasSubstr("frame 3: markers: missing"));
  EXPECT_THAT(error("{\"frame\": 3, \"time\": -1, \"markers\": {}}"), HasSubstr("frame 3: time"));
  EXPECT_THAT(error("{\"frame\": -2, \"markers\": {}}"), HasSubstr("frame: expected an integer >= 0"));
  EXPECT_THAT(error("{\"frame\": 1.5, \"markers\": {}}"), HasSubstr("frame: expected an integer >= 0"));
  EXPECT_THAT(error("{\"frame\": 4, \"points\": [[1, 2, 3]]}"), HasSubstr("frame 4: points: unlabelled"));
  EXPECT_THAT(error("[1, 2, 3]"), HasSubstr("must be a JSON object"));
  EXPECT_THAT(error("{\"frame\": 3, \"markers\": {"), HasSubstr("malformed JSON"));
  // The frame number is kept for the caller's messages once it was read.
  (void)ParseJsonFrameLine("{\"frame\": 9, \"markers\": 5}", &frame);
  EXPECT_EQ(frame.frame, 9);
}

TEST(LiveFrame, BinaryRoundTripAndErrors) {
  const LiveFrame frame = SampleFrame();
  const std::string header = FormatBinaryStreamHeader(frame.labels);
  EXPECT_EQ(header.compare(0, 8, kBinaryStreamMagic), 0);
  EXPECT_EQ(header.size(), 12u + 5 + 5 + 9);
  const std::string bytes = FormatBinaryFrame(frame);
  ASSERT_EQ(bytes.size(), kBinaryFrameHeaderBytes + 12 * 3);
  LiveFrame read;
  ASSERT_TRUE(ParseBinaryFrameHeader(std::string_view(bytes).substr(0, 16), 3, &read).ok());
  EXPECT_EQ(read.frame, 7);
  EXPECT_NEAR(read.time, 0.0583, 1e-7);
  ASSERT_TRUE(ParseBinaryFramePositions(std::string_view(bytes).substr(16), &read).ok());
  EXPECT_TRUE(read.positions[0].isApprox(frame.positions[0], 1e-6));  // float32.
  EXPECT_FALSE(read.positions[1].allFinite());
  EXPECT_THAT(ParseBinaryFrameHeader(std::string_view(bytes).substr(0, 16), 4, &read).message(),
              HasSubstr("frame 7: count: 3 markers, the stream header gave 4"));
  std::string lost = bytes;
  lost[0] = 'X';
  EXPECT_THAT(ParseBinaryFrameHeader(std::string_view(lost).substr(0, 16), 3, &read).message(),
              HasSubstr("lost its framing"));
  std::string infinite = bytes;
  const float inf = INFINITY;
  std::memcpy(&infinite[16 + 12 * 2], &inf, 4);
  ASSERT_TRUE(ParseBinaryFrameHeader(std::string_view(infinite).substr(0, 16), 3, &read).ok());
  EXPECT_THAT(ParseBinaryFramePositions(std::string_view(infinite).substr(16), &read).message(),
              HasSubstr("frame 7: positions[2]"));
}

}  // namespace
}  // namespace mocapsolve
