#include "io/live_source.h"

#include <chrono>
#include <cstring>
#include <thread>
#include <utility>
#include <vector>

#include "io/marker_file.h"

namespace mocapsolve {

int64_t SteadyNanoseconds() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

namespace {

using Next = LiveFrameSource::Next;

// A JSON line is at most this long (a frame of 10,000 markers fits).
constexpr size_t kMaxLineBytes = 4 << 20;

Next FromReader(StreamReader::Result result) {
  switch (result) {
    case StreamReader::Result::kEnd: return Next::kEnd;
    case StreamReader::Result::kStalled: return Next::kStalled;
    default: return Next::kFatal;
  }
}

class StreamFrameSource : public LiveFrameSource {
 public:
  StreamFrameSource(int fd, const std::string& name, double stall_seconds)
      : reader_(fd, name), stall_seconds_(stall_seconds) {}

  Next Read(LiveFrame* frame, int64_t* arrival_ns, std::string* error) override {
    if (framing_ == Framing::kUnknown) {
      std::string_view head;
      const StreamReader::Result peeked = reader_.Peek(8, stall_seconds_, &head, error);
      if (peeked != StreamReader::Result::kData) return FromReader(peeked);
      if (head.size() == 8 && std::memcmp(head.data(), kBinaryStreamMagic, 8) == 0) {
        const Next header = ReadBinaryHeader(error);
        if (header != Next::kFrame) return header;
        framing_ = Framing::kBinary;
      } else {
        framing_ = Framing::kJson;
      }
    }
    return framing_ == Framing::kJson ? ReadJson(frame, arrival_ns, error) : ReadBinary(frame, arrival_ns, error);
  }

 private:
  enum class Framing { kUnknown, kJson, kBinary };

  Next ReadJson(LiveFrame* frame, int64_t* arrival_ns, std::string* error) {
    while (true) {
      std::string_view line;
      const StreamReader::Result result = reader_.ReadLine(stall_seconds_, kMaxLineBytes, &line, error);
      if (result != StreamReader::Result::kData) return FromReader(result);
      if (line.find_first_not_of(" \t\r") == std::string_view::npos) continue;  // Blank.
      *arrival_ns = SteadyNanoseconds();
      const Status status = ParseJsonFrameLine(line, frame);
      if (status.ok()) return Next::kFrame;
      *error = reader_.name() + ": " + (frame->frame < 0 ? "line " + std::to_string(lines_ + 1) + ": " : "") +
               status.message();
      ++lines_;
      return Next::kBadFrame;
    }
  }

  Next ReadBinaryHeader(std::string* error) {
    std::string_view bytes;
    StreamReader::Result result = reader_.ReadBytes(12, stall_seconds_, &bytes, error);
    if (result != StreamReader::Result::kData) {
      *error = reader_.name() + ": binary stream header: truncated (the stream ended inside it)";
      return Next::kFatal;
    }
    uint32_t count;
    std::memcpy(&count, bytes.data() + 8, 4);
    if (count == 0 || count > kMaxBinaryMarkers) {
      *error = reader_.name() + ": binary stream header: markers: expected 1.." + std::to_string(kMaxBinaryMarkers) +
               ", got " + std::to_string(count);
      return Next::kFatal;
    }
    for (uint32_t m = 0; m < count; ++m) {
      result = reader_.ReadBytes(1, stall_seconds_, &bytes, error);
      const uint8_t size = result == StreamReader::Result::kData ? static_cast<uint8_t>(bytes[0]) : 0;
      if (size > 0) result = reader_.ReadBytes(size, stall_seconds_, &bytes, error);
      if (result != StreamReader::Result::kData || size == 0) {
        if (error->empty()) *error = reader_.name() + ": binary stream header: label " + std::to_string(m) + ": "
                                     "expected a length of 1..255 and that many bytes";
        return Next::kFatal;
      }
      labels_.emplace_back(bytes);
    }
    return Next::kFrame;
  }

  Next ReadBinary(LiveFrame* frame, int64_t* arrival_ns, std::string* error) {
    std::string_view bytes;
    StreamReader::Result result = reader_.ReadBytes(kBinaryFrameHeaderBytes, stall_seconds_, &bytes, error);
    if (result == StreamReader::Result::kError) return Next::kBadFrame;  // Truncated: the stream then ends.
    if (result != StreamReader::Result::kData) return FromReader(result);
    Status status = ParseBinaryFrameHeader(bytes, labels_.size(), frame);
    if (!status.ok()) {  // Framing lost: nothing after it can be trusted.
      *error = reader_.name() + ": " + status.message();
      return Next::kFatal;
    }
    result = reader_.ReadBytes(12 * labels_.size(), stall_seconds_, &bytes, error);
    if (result != StreamReader::Result::kData) {
      if (result == StreamReader::Result::kEnd || result == StreamReader::Result::kError) {
        *error = reader_.name() + ": frame " + std::to_string(frame->frame) + ": positions: truncated (the stream "
                 "ended inside the frame)";
        return Next::kBadFrame;
      }
      return FromReader(result);
    }
    *arrival_ns = SteadyNanoseconds();
    status = ParseBinaryFramePositions(bytes, frame);
    if (!status.ok()) {
      *error = reader_.name() + ": " + status.message();
      return Next::kBadFrame;
    }
    frame->labels = labels_;
    return Next::kFrame;
  }

  StreamReader reader_;
  double stall_seconds_;
  Framing framing_ = Framing::kUnknown;
  std::vector<std::string> labels_;  // Binary: from the stream header.
  long lines_ = 0;                   // Bad lines without a frame number, for messages.
};

// A replayed frame later than this when its turn comes is dropped (0.1 s: 12 frames at 120 Hz).
constexpr int64_t kMaxLateNs = 100000000;

class ReplayFrameSource : public LiveFrameSource {
 public:
  ReplayFrameSource(MarkerTrajectories take, double speed) : take_(std::move(take)), speed_(speed) {}

  Next Read(LiveFrame* frame, int64_t* arrival_ns, std::string*) override {
    const int frames = take_.num_frames();
    const int64_t now = SteadyNanoseconds();
    if (next_ == 0) start_ns_ = now;
    if (speed_ > 0) {
      // Frames queue as they would in a socket; one already kMaxLateNs late is dropped.
      while (next_ + 1 < frames && now - Due(next_) > kMaxLateNs) ++next_, ++dropped_;
    }
    if (next_ >= frames) return Next::kEnd;
    const int f = next_++;
    *arrival_ns = now;
    if (speed_ > 0) {
      const int64_t due = Due(f);
      if (due > now) std::this_thread::sleep_for(std::chrono::nanoseconds(due - now));
      *arrival_ns = std::max(due, now);
    }
    frame->frame = take_.first_frame + f;
    frame->time = take_.frame_rate > 0 ? f / take_.frame_rate : 0.0;
    frame->labels = take_.labels();
    frame->positions.resize(take_.num_markers());
    for (int m = 0; m < take_.num_markers(); ++m) frame->positions[m] = take_.position(f, m);  // NaN: missing.
    return Next::kFrame;
  }
  long dropped() const override { return dropped_; }
  double frame_rate() const override { return take_.frame_rate; }
  LengthUnit unit() const override { return take_.unit; }

 private:
  int64_t Due(int f) const { return start_ns_ + static_cast<int64_t>(f * 1e9 / (take_.frame_rate * speed_)); }

  MarkerTrajectories take_;
  double speed_;
  int next_ = 0;
  int64_t start_ns_ = 0;
  long dropped_ = 0;
};

}  // namespace

std::unique_ptr<LiveFrameSource> MakeStreamFrameSource(int fd, const std::string& name, double stall_seconds) {
  return std::make_unique<StreamFrameSource>(fd, name, stall_seconds);
}

Status MakeReplayFrameSource(const std::string& path, double speed, std::unique_ptr<LiveFrameSource>* source) {
  MarkerTrajectories take;
  Status status = ReadMarkerFile(path, &take);
  if (status.ok()) status = RequireMarkerData(path, take);
  if (!status.ok()) return status;
  if (speed > 0 && !(take.frame_rate > 0)) return Status::Error(path + ": no frame rate to replay at (give --replay_speed=0)");
  *source = std::make_unique<ReplayFrameSource>(std::move(take), speed);
  return Status::Ok();
}

}  // namespace mocapsolve
