#include "settings/live_settings.h"

namespace mocapsolve {

const OptionGroup<LiveSettings>& LiveSettingOptions() {
  using S = LiveSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::input, "input",
           "Where frames come from: - (the standard input), tcp:PORT (one client connecting to 127.0.0.1:PORT) or "
           "replay:TAKE.c3d|.trc (a marker file played at its own rate times --replay_speed). Streams are JSON lines "
           "or the binary framing (docs/live.md), told apart by their first bytes.")
      .Add(&S::output, "output",
           "Where poses go: - (the standard output) or tcp:PORT (one client connecting to 127.0.0.1:PORT; the run "
           "waits --stall_seconds for it).")
      .Add(&S::output_format, "output_format",
           "json: one line per frame (frame, time, root position, each joint's local rotation as a quaternion, "
           "markers used, RMS residual); bvh: the subject skeleton's BVH hierarchy once, then one MOTION line per "
           "frame.",
           {"json", "bvh"})
      .Add(&S::replay_speed, "replay_speed", "",
           "With --input=replay:...: frames are due at the file's rate times this (1 = real time); 0 = as fast as "
           "possible. A frame already 0.1 s late when its turn comes is dropped.",
           0.0, 1000.0)
      .Add(&S::on_bad_frame, "on_bad_frame",
           "A frame that cannot be read (malformed JSON, a bad field): stop (one line naming the frame and field, "
           "exit 1; poses already written stay written) or skip (the same line as a warning; counted as dropped).",
           {"stop", "skip"})
      .Add(&S::stall_seconds, "stall_seconds", "s",
           "An input that sends nothing for this long ends the run (as a closed one does); also how long a TCP "
           "endpoint waits for its client.",
           0.001, 86400.0)
      .Add(&S::stream_units, "stream_units",
           "Unit of streamed positions (a replay uses its file's; a subject's marker scale overrides both).",
           {"mm", "cm", "m"})
      .Add(&S::predict_frames, "predict_frames", "frames",
           "A marker that stops being observed is predicted (from its last two samples, at constant velocity) for "
           "at most this many frames, then left out of the solve until it returns.",
           0, 1000);
  return *group;
}

const OptionGroup<SolverSettings>& LiveSolverOptions() {
  static const OptionGroup<SolverSettings>* const group = new OptionGroup<SolverSettings>(SolverOptions().Without(
      "mode,clip_function_tolerance,clip_solver,smooth_order,smooth_weight,smooth_translation_weight,sparse_library,"
      "num_threads"));
  return *group;
}

}  // namespace mocapsolve
