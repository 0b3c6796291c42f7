// LiveSettings: `mocapsolve live`'s stream options (where frames come from and go to, the
// output's format, what a bad frame does, how long a silent input may stall, the stream's
// unit and how long a missing marker is predicted). Declared once. The solver's options are
// settings/solver_settings.h's per-frame ones (LiveSolverOptions: live solves frame by frame).
#ifndef MOCAPSOLVE_SETTINGS_LIVE_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_LIVE_SETTINGS_H_

#include <string>

#include "settings/option.h"
#include "settings/solver_settings.h"

namespace mocapsolve {

struct LiveSettings {
  std::string input;                 // - | tcp:PORT | replay:TAKE.c3d|.trc
  std::string output = "-";          // - | tcp:PORT
  std::string output_format = "json";  // json | bvh
  double replay_speed = 1.0;         // x the file's rate; 0 = as fast as possible.
  std::string on_bad_frame = "stop";   // stop | skip
  double stall_seconds = 5.0;        // An input silent this long ends the run.
  std::string stream_units = "mm";   // Positions of a streamed frame (not a replay).
  int predict_frames = 12;           // A missing marker is predicted for at most this many frames.
};

const OptionGroup<LiveSettings>& LiveSettingOptions();
// The per-frame solver's options (SolverOptions without the whole-clip ones and --mode).
const OptionGroup<SolverSettings>& LiveSolverOptions();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_LIVE_SETTINGS_H_
