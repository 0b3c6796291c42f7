// `mocapsolve live` end to end on a tiny synthetic take: the demo clip's markers streamed
// through stdin (JSON lines and the binary framing), replayed from the C3D and sent over
// a TCP loopback; BVH output; malformed frames with skip and stop; a port in use; a sink
// client that disconnects; an input that stalls.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <sstream>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/bvh_reader.h"
#include "io/json_reader.h"
#include "io/live_frame.h"
#include "io/marker_file.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

// A port free at the time of the call (bound to 0, then released).
int FreePort() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address));
  socklen_t size = sizeof(address);
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &size);
  ::close(fd);
  return ntohs(address.sin_port);
}

// Connects to 127.0.0.1:port, retrying for up to 10 s while the command starts.
int Connect(int port) {
  for (int attempt = 0; attempt < 200; ++attempt) {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<uint16_t>(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) == 0) return fd;
    ::close(fd);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return -1;
}

void SendAll(int fd, const std::string& bytes) {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::send(fd, bytes.data() + done, bytes.size() - done, MSG_NOSIGNAL);
    if (n <= 0) return;
    done += static_cast<size_t>(n);
  }
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

class LiveCli : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string demo = testing::TempPath("walk.bvh");
    markers_ = testing::TempPath("walk.c3d");
    const std::string set = testing::TempPath("set.json");
    std::string output;
    ASSERT_EQ(testing::RunCli("generate --demo_out=" + demo + " --frames=40 --fps=30", &output), 0) << output;
    ASSERT_EQ(testing::RunCli("markers --motion=" + demo + " --skeleton_units=cm --markerset=auto:3 "
                              "--write_markerset=" + set + " --out=" + markers_, &output), 0) << output;
    subject_ = testing::TempPath("S.json");
    testing::WriteTextFile(subject_, "{\"format\": \"mocapsolve.subject\", \"version\": 1, \"skeleton\": \"" + demo +
                                         "\", \"skeleton_units\": \"cm\", \"markerset\": " +
                                         testing::ReadTextFile(set) + "}\n");
    MarkerTrajectories take;
    ASSERT_TRUE(ReadMarkerFile(markers_, &take).ok());
    std::string json, binary = FormatBinaryStreamHeader(take.labels());
    for (int f = 0; f < take.num_frames(); ++f) {
      LiveFrame frame;
      frame.frame = f;
      frame.time = f / 30.0;
      frame.labels = take.labels();
      for (int m = 0; m < take.num_markers(); ++m) frame.positions.push_back(take.position(f, m));
      json_lines_.push_back(FormatJsonFrameLine(frame));
      json += json_lines_.back() + "\n";
      binary += FormatBinaryFrame(frame);
    }
    frames_json_ = testing::TempPath("frames.jsonl");
    frames_binary_ = testing::TempPath("frames.bin");
    testing::WriteTextFile(frames_json_, json);
    testing::WriteTextFile(frames_binary_, binary);
  }

  // Runs live with the output to a file; returns the exit code, *poses the output's lines.
  int Live(const std::string& flags, std::vector<std::string>* poses, std::string* messages) {
    const std::string out = testing::TempPath("poses.out");
    // The group's stderr (the messages) goes to RunProgram's pipe, its stdout to `out`.
    const int code = testing::RunProgram("{ " + testing::CliPath(), "live --quiet --subject=" + subject_ + " " +
                                         flags + " > " + out + "; }", messages);
    *poses = Lines(testing::ReadTextFile(out));
    return code;
  }

  std::string markers_, subject_, frames_json_, frames_binary_;
  std::vector<std::string> json_lines_;
};

// The pose lines' root positions, for comparing runs.
std::vector<double> Roots(const std::vector<std::string>& poses) {
  std::vector<double> roots;
  for (const std::string& line : poses) {
    JsonNode node;
    EXPECT_TRUE(ParseJson(line, "pose", &node).ok()) << line;
    const JsonNode* root = node.Find("root");
    if (root == nullptr || root->items.size() != 3) continue;
    for (const JsonNode& x : root->items) roots.push_back(x.number);
  }
  return roots;
}

TEST_F(LiveCli, StdinJsonBinaryAndReplayGiveTheSamePoses) {
  std::vector<std::string> json, binary, replay;
  std::string messages;
  const std::string report = testing::TempPath("r.json");
  ASSERT_EQ(Live("--input=- --report=" + report + " < " + frames_json_, &json, &messages), 0) << messages;
  ASSERT_EQ(json.size(), 40u);
  const std::string text = testing::ReadTextFile(report);
  EXPECT_THAT(text, HasSubstr("\"frames_in\": 40"));
  EXPECT_THAT(text, HasSubstr("\"frames_out\": 40"));
  EXPECT_THAT(text, HasSubstr("\"frames_dropped\": 0"));
  EXPECT_THAT(text, HasSubstr("\"p99\""));
  EXPECT_THAT(json[0], HasSubstr("\"rotations\": {"));
  ASSERT_EQ(Live("--input=- < " + frames_binary_, &binary, &messages), 0) << messages;
  ASSERT_EQ(Live("--input=replay:" + markers_ + " --replay_speed=0", &replay, &messages), 0) << messages;
  const std::vector<double> a = Roots(json), b = Roots(binary), c = Roots(replay);
  ASSERT_EQ(a.size(), 120u);
  ASSERT_EQ(b.size(), a.size());
  ASSERT_EQ(c.size(), a.size());
  for (size_t i = 0; i < a.size(); ++i) {
    // The C3D's float32 mm, printed with 10 digits, and float32 again: well under 0.01 cm.
    EXPECT_NEAR(a[i], b[i], 1e-3) << i;
    EXPECT_NEAR(a[i], c[i], 1e-3) << i;
  }
}

TEST_F(LiveCli, BvhOutputIsAHeaderThenOneMotionLinePerFrame) {
  std::vector<std::string> lines;
  std::string messages;
  ASSERT_EQ(Live("--input=- --output_format=bvh < " + frames_json_, &lines, &messages), 0) << messages;
  std::string bvh;
  int motion_lines = 0;
  for (const std::string& line : lines) {
    if (line.rfind("Frame Time:", 0) == 0) bvh += "Frames: 40\n";
    bvh += line + "\n";
    motion_lines += !line.empty() && (std::isdigit(line[0]) || line[0] == '-');
  }
  EXPECT_EQ(motion_lines, 40);
  const std::string path = testing::TempPath("stream.bvh");
  testing::WriteTextFile(path, bvh);
  Skeleton skeleton;
  Motion motion;
  ASSERT_TRUE(ReadBvh(path, &skeleton, &motion).ok());
  EXPECT_EQ(motion.num_frames(), 40);
}

TEST_F(LiveCli, MalformedFrameSkipOrStop) {
  std::string stream;
  for (size_t f = 0; f < json_lines_.size(); ++f) {
    stream += (f == 5 ? "{\"frame\": 5, \"markers\": {\"Hips_0\": [1, 2]}}" : json_lines_[f]) + "\n";
  }
  const std::string bad = testing::TempPath("bad.jsonl");
  testing::WriteTextFile(bad, stream);
  std::vector<std::string> poses;
  std::string messages;
  const std::string report = testing::TempPath("skip.json");
  ASSERT_EQ(Live("--input=- --on_bad_frame=skip --report=" + report + " < " + bad, &poses, &messages), 0)
      << messages;
  EXPECT_EQ(poses.size(), 39u);
  EXPECT_THAT(messages, HasSubstr("frame 5: markers.Hips_0"));
  EXPECT_THAT(testing::ReadTextFile(report), HasSubstr("\"frames_dropped\": 1"));
  ASSERT_EQ(Live("--input=- < " + bad, &poses, &messages), 1);
  EXPECT_THAT(messages, HasSubstr("frame 5: markers.Hips_0: expected [x, y, z]"));
  EXPECT_EQ(std::count(messages.begin(), messages.end(), '\n'), 1) << messages;
  EXPECT_EQ(poses.size(), 5u);  // Written before the bad frame: kept.
  // Unlabelled points, a missing frame number, not JSON: each named.
  testing::WriteTextFile(bad, json_lines_[0] + "\n{\"frame\": 1, \"points\": [[1, 2, 3]]}\n");
  EXPECT_EQ(Live("--input=- < " + bad, &poses, &messages), 1);
  EXPECT_THAT(messages, HasSubstr("frame 1: points: unlabelled points are not supported"));
  testing::WriteTextFile(bad, "{\"markers\": {}}\n");
  EXPECT_EQ(Live("--input=- < " + bad, &poses, &messages), 1);
  EXPECT_THAT(messages, HasSubstr("line 1: frame: missing"));
  testing::WriteTextFile(bad, json_lines_[0].substr(0, 40) + "\n");
  EXPECT_EQ(Live("--input=- < " + bad, &poses, &messages), 1);
  EXPECT_THAT(messages, HasSubstr("malformed JSON"));
}

TEST_F(LiveCli, MissingMarkersArePredicted) {
  std::string stream;
  for (size_t f = 0; f < json_lines_.size(); ++f) {
    std::string line = json_lines_[f];
    if (f >= 10 && f < 14) {  // Hips_0 occluded for 4 frames.
      const size_t at = line.find("\"Hips_0\": [");
      line.replace(at, line.find(']', at) + 1 - at, "\"Hips_0\": null");
    }
    stream += line + "\n";
  }
  const std::string gaps = testing::TempPath("gaps.jsonl");
  testing::WriteTextFile(gaps, stream);
  std::vector<std::string> poses;
  std::string messages;
  const std::string report = testing::TempPath("gaps.json");
  ASSERT_EQ(Live("--input=- --report=" + report + " < " + gaps, &poses, &messages), 0) << messages;
  EXPECT_EQ(poses.size(), 40u);
  EXPECT_THAT(testing::ReadTextFile(report), HasSubstr("\"predicted_samples\": 4"));
  EXPECT_THAT(poses[11], HasSubstr("\"markers_predicted\": 1"));
}

TEST_F(LiveCli, TcpLoopbackInAndStall) {
  const int port = FreePort();
  std::string messages;
  const std::string out = testing::TempPath("tcp.out");
  const std::string report = testing::TempPath("tcp.json");
  int code = -1;
  std::thread run([&] {
    code = testing::RunCli("live --quiet --subject=" + subject_ + " --input=tcp:" + std::to_string(port) +
                               " --stall_seconds=1 --report=" + report + " > " + out,
                           &messages);
  });
  const int fd = Connect(port);
  ASSERT_GE(fd, 0);
  for (int f = 0; f < 10; ++f) SendAll(fd, json_lines_[f] + "\n");
  // Then silence, the connection left open: the run ends after --stall_seconds.
  run.join();
  ::close(fd);
  ASSERT_EQ(code, 0) << messages;
  EXPECT_EQ(Lines(testing::ReadTextFile(out)).size(), 10u);
  EXPECT_THAT(testing::ReadTextFile(report), HasSubstr("\"end\": \"stalled\""));
}

TEST_F(LiveCli, PortInUseAndDisconnectedClient) {
  const int holder = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(holder, reinterpret_cast<sockaddr*>(&address), sizeof(address)), 0);
  ASSERT_EQ(::listen(holder, 1), 0);
  socklen_t size = sizeof(address);
  ::getsockname(holder, reinterpret_cast<sockaddr*>(&address), &size);
  const int used = ntohs(address.sin_port);
  std::vector<std::string> poses;
  std::string messages;
  EXPECT_EQ(Live("--input=tcp:" + std::to_string(used), &poses, &messages), 1);
  EXPECT_THAT(messages, HasSubstr("tcp:" + std::to_string(used) + ": port in use"));
  EXPECT_EQ(std::count(messages.begin(), messages.end(), '\n'), 1) << messages;
  ::close(holder);
  // No engine connects to the output: one line once --stall_seconds have passed.
  EXPECT_EQ(Live("--input=- --output=tcp:" + std::to_string(FreePort()) + " --stall_seconds=0.3 < " + frames_json_,
                 &poses, &messages), 1);
  EXPECT_THAT(messages, HasSubstr(": no client connected within 0.3 s"));

  // The engine reading the poses goes away after the first: one line, exit 1, no hang.
  const int port = FreePort();
  int code = -1;
  std::thread run([&] {
    code = testing::RunCli("live --quiet --subject=" + subject_ + " --input=replay:" + markers_ +
                               " --output=tcp:" + std::to_string(port) + " --stall_seconds=5",
                           &messages);
  });
  const int fd = Connect(port);
  ASSERT_GE(fd, 0);
  char byte;
  ASSERT_EQ(::recv(fd, &byte, 1, 0), 1);
  ::close(fd);
  run.join();
  EXPECT_EQ(code, 1) << messages;
  EXPECT_THAT(messages, HasSubstr(": the client disconnected"));
  EXPECT_EQ(std::count(messages.begin(), messages.end(), '\n'), 1) << messages;
}

}  // namespace
}  // namespace mocapsolve
