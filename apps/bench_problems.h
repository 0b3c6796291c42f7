// The end-to-end benchmark harness (`mocapsolve bench`): each problem runs through each
// of its solvers and reports one BenchRecord. Later problems (marker solving,
// retargeting, edit propagation) register here with solvers "ceres" and "dls" and are
// compared at equal final error.
#ifndef MOCAPSOLVE_APPS_BENCH_PROBLEMS_H_
#define MOCAPSOLVE_APPS_BENCH_PROBLEMS_H_

#include <string>
#include <utility>
#include <vector>

#include "io/json_writer.h"
#include "kinematics/status.h"

namespace mocapsolve {

struct BenchRecord {
  std::string problem;
  std::string solver;
  std::string input;
  int frames = 0;
  double seconds = 0.0;         // Wall time of the measured part (median of repeats).
  int iterations = 0;           // Solver iterations (0 for non-iterative problems).
  double final_cost = 0.0;      // 1/2 sum of squared residuals at the end, if any.
  double error = 0.0;           // The problem's accuracy figure, named by error_name.
  std::string error_name;
  std::string notes;            // Anything a reader of the figures must know.
  // Further named figures of the problem (e.g. a time per frame as a ratio to a reference
  // measured in the same run), printed and written to the JSON in this order.
  std::vector<std::pair<std::string, double>> figures;

  double frames_per_second() const { return seconds > 0.0 ? frames / seconds : 0.0; }
  JsonObject ToJson() const;
};

struct BenchSettings {
  std::string motion_path;  // Input clip ("" = the problem's default).
  int repeats = 5;
  // Marker problems on real markers (else markers are synthesized from the motion).
  std::string skeleton_path, markers_path, markerset_path;
  int max_frames = 0;       // 0 = all.
  double noise_mm = 0.0;    // Gaussian noise on synthesized markers (needs a known unit).
  // The pipeline problem: a subject file, its take (markers_path) and the characters.
  std::string subject_path;
  std::vector<std::string> character_paths;
};

struct BenchProblem {
  const char* name;
  const char* description;
  std::vector<std::string> solvers;
  Status (*run)(const std::string& solver, const BenchSettings& settings, BenchRecord* record);
};

const std::vector<BenchProblem>& AllBenchProblems();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_APPS_BENCH_PROBLEMS_H_
