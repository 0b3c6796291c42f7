// Live marker frames: the two framings `mocapsolve live` reads from a stream (stdin or a
// TCP connection), one frame at a time, as a capture system streams them while the actor
// moves (docs/live.md gives both with examples).
//
// JSON lines: one object per line (UTF-8, '\n'-terminated; blank lines are ignored):
//   {"frame": 12, "time": 0.1, "markers": {"LASI": [x, y, z], "RASI": null, ...}}
//   frame    integer >= 0, required: the capture's frame number
//   time     number (seconds), optional: the capture time; default frame / rate
//   markers  object, required: label -> [x, y, z] (finite numbers, the stream's axes and
//            units) or null (missing); a label the subject's marker set lacks is ignored,
//            a marker of the set the frame does not name is missing
//   points   [[x, y, z], ...]: unlabelled points; not read yet (an error naming the frame:
//            label them first)
// Unknown keys are errors (typos surface).
//
// Binary (little-endian), detected by its first 8 bytes:
//   stream header: "MOCAPLV1", uint32 M (markers, 1..10000), then M labels, each a uint8
//                  length (1..255) and that many bytes
//   each frame:    "MSFR", uint32 frame number, float32 time (s), uint32 count (= M),
//                  then count x 3 float32 (x, y, z in the header's label order; NaN = missing)
//
// Errors are one line naming the frame (when known) and the field:
//   frame 12: markers.LASI: expected [x, y, z] (3 finite numbers)
#ifndef MOCAPSOLVE_IO_LIVE_FRAME_H_
#define MOCAPSOLVE_IO_LIVE_FRAME_H_

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "kinematics/status.h"

namespace mocapsolve {

struct LiveFrame {
  long frame = -1;              // The capture's frame number (-1: not known yet).
  double time = -1.0;           // Seconds; < 0: not given.
  // Labels and positions (stream axes and units; NaN = missing), same length.
  std::vector<std::string> labels;
  std::vector<Eigen::Vector3d> positions;
};

// One JSON line into *frame. On error *frame->frame holds the frame number when the line
// gave one (so the caller can name it), and the message names the frame and the field.
Status ParseJsonFrameLine(std::string_view line, LiveFrame* frame);
// The line ParseJsonFrameLine reads (no trailing newline); NaN positions are null.
std::string FormatJsonFrameLine(const LiveFrame& frame);

inline constexpr char kBinaryStreamMagic[] = "MOCAPLV1";  // 8 bytes, no terminator sent.
inline constexpr char kBinaryFrameMagic[] = "MSFR";       // 4 bytes.
inline constexpr uint32_t kMaxBinaryMarkers = 10000;

// The binary stream header for `labels` and one binary frame (positions as float32).
std::string FormatBinaryStreamHeader(const std::vector<std::string>& labels);
std::string FormatBinaryFrame(const LiveFrame& frame);
// The fixed part of a binary frame before its positions: magic, frame, time, count.
inline constexpr size_t kBinaryFrameHeaderBytes = 16;
// Parses a binary frame's fixed part (kBinaryFrameHeaderBytes); *count is the number of
// markers that follow (checked against `markers`).
Status ParseBinaryFrameHeader(std::string_view bytes, size_t markers, LiveFrame* frame);
// Parses the positions that follow (count x 12 bytes) into frame->positions.
Status ParseBinaryFramePositions(std::string_view bytes, LiveFrame* frame);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_LIVE_FRAME_H_
