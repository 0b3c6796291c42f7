// Where `mocapsolve live` takes its frames from: a stream (stdin or a TCP client) in one
// of the two framings of io/live_frame.h (detected from its first bytes), or a marker
// file (C3D/TRC) replayed at its own rate times a speed (0: as fast as it is read).
//
// Each frame carries its arrival time on the steady clock (ns): when its bytes were
// complete (a stream), or when it was due (a replay at a rate), so a latency measured
// from it includes any wait the consumer caused.
#ifndef MOCAPSOLVE_IO_LIVE_SOURCE_H_
#define MOCAPSOLVE_IO_LIVE_SOURCE_H_

#include <cstdint>
#include <memory>
#include <string>

#include "io/live_frame.h"
#include "io/live_stream.h"
#include "kinematics/marker_trajectories.h"
#include "kinematics/status.h"
#include "kinematics/units.h"

namespace mocapsolve {

// Steady-clock nanoseconds (the arrival and output times of live frames).
int64_t SteadyNanoseconds();

class LiveFrameSource {
 public:
  enum class Next {
    kFrame,     // *frame holds a frame.
    kBadFrame,  // A frame that could not be read (*error names it); the next may be fine.
    kEnd,       // The stream closed (or the file ended).
    kStalled,   // No byte for the stall timeout: the run ends as at kEnd.
    kFatal,     // The stream cannot go on (I/O error, lost binary framing): *error.
  };
  virtual ~LiveFrameSource() = default;
  virtual Next Read(LiveFrame* frame, int64_t* arrival_ns, std::string* error) = 0;
  // Frames a replay skipped because the consumer fell more than a frame behind.
  virtual long dropped() const { return 0; }
  // The frame rate when the source knows it (a replay), else 0.
  virtual double frame_rate() const { return 0.0; }
  // The unit of the positions when the source knows it (a replay), else unknown.
  virtual LengthUnit unit() const { return LengthUnit(); }
};

// Frames from a descriptor it does not own (stdin or an accepted connection); `name`
// labels messages. A read waits at most stall_seconds.
std::unique_ptr<LiveFrameSource> MakeStreamFrameSource(int fd, const std::string& name, double stall_seconds);

// A marker file's frames (labels as the file spells them) at frame_rate * speed frames a
// second (speed 0: as fast as they are asked for). Frames wait for the consumer as they
// would in a socket's buffer, but one already 0.1 s late when its turn comes is skipped
// (dropped()): a consumer that falls that far behind catches up with the newest frames.
Status MakeReplayFrameSource(const std::string& path, double speed, std::unique_ptr<LiveFrameSource>* source);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_LIVE_SOURCE_H_
