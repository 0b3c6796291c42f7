#include "settings/bench_settings.h"

namespace mocapsolve {

const OptionGroup<BenchRunSettings>& BenchRunSettingOptions() {
  using S = BenchRunSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::problem, "problem", "Problem to run (see the list in --help).")
      .Add(&S::solvers, "solvers", "Comma-separated solvers (default: all of the problem's).")
      .Add(&S::json, "json", "Write all records as JSON to this file.")
      .Add(&S::repeats, "repeats", "", "Timed repeats; the median is reported.", 1)
      .Add(&S::bench_motion, "bench_motion", "Input clip for the problem (default: the problem's own).")
      .Add(&S::bench_skeleton, "bench_skeleton", "Skeleton (.asf/.bvh) of a real-marker problem.")
      .Add(&S::bench_markers, "bench_markers", "Marker file (.c3d/.trc) of a real-marker problem.")
      .Add(&S::bench_markerset, "bench_markerset", "Marker set (.json) of a real-marker problem.")
      .Add(&S::bench_frames, "bench_frames", "frames", "Use only the first N frames (0 = all).", 0)
      .Add(&S::bench_noise_mm, "bench_noise_mm", "mm", "Gaussian noise (mm) added to synthesized markers.", 0)
      .Add(&S::bench_subject, "bench_subject", "Subject file (.json) of the pipeline problem (with --bench_markers).")
      .Add(&S::bench_character, "bench_character", "Characters (.glb), comma-separated, of the pipeline problem.");
  return *group;
}

}  // namespace mocapsolve
