// BenchRunSettings: what `mocapsolve bench` runs (the problem, its solvers, its input, the
// repeats) and where it writes the records. Declared once; the harness itself and its
// problems: apps/bench_problems.h.
#ifndef MOCAPSOLVE_SETTINGS_BENCH_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_BENCH_SETTINGS_H_

#include <string>

#include "settings/option.h"

namespace mocapsolve {

struct BenchRunSettings {
  std::string problem = "fk";
  std::string solvers;          // Comma-separated; "" = all of the problem's.
  std::string json;             // Every record as JSON to this file.
  int repeats = 5;              // Timed repeats; the median is reported.
  std::string bench_motion;     // The problem's clip ("" = its own).
  std::string bench_skeleton, bench_markers, bench_markerset;  // A real-marker problem's files.
  int bench_frames = 0;         // The first N frames; 0 = all.
  double bench_noise_mm = 0.0;  // Gaussian noise on synthesized markers.
  std::string bench_subject;    // The pipeline problem's subject (with bench_markers).
  std::string bench_character;  // The pipeline problem's characters, comma-separated.
};

const OptionGroup<BenchRunSettings>& BenchRunSettingOptions();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_BENCH_SETTINGS_H_
