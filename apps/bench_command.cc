// mocapsolve bench: the end-to-end solver comparison harness.
#include <cstdio>
#include <sstream>

#include "apps/bench_problems.h"
#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/config_flags.h"
#include "apps/option_flags.h"
#include "apps/solver_flags.h"
#include "io/atomic_file.h"
#include "settings/bench_settings.h"


namespace mocapsolve {
namespace {

Status RunBench(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  BenchRunSettings run;
  ReadOptionFlags(BenchRunSettingOptions(), &run);
  const BenchProblem* problem = nullptr;
  std::string known;
  for (const BenchProblem& p : AllBenchProblems()) {
    if (run.problem == p.name) problem = &p;
    known += std::string(known.empty() ? "" : ", ") + p.name;
  }
  if (problem == nullptr) {
    return Status::Error("--problem: unknown problem '" + run.problem + "' (known: " + known + ")");
  }
  std::vector<std::string> solvers = SplitCommaList(run.solvers);
  if (solvers.empty()) solvers = problem->solvers;
  BenchSettings settings;
  settings.motion_path = run.bench_motion;
  settings.repeats = run.repeats;
  settings.skeleton_path = run.bench_skeleton;
  settings.markers_path = run.bench_markers;
  settings.markerset_path = run.bench_markerset;
  settings.max_frames = run.bench_frames;
  settings.noise_mm = run.bench_noise_mm;
  settings.subject_path = run.bench_subject;
  settings.character_paths = SplitCommaList(run.bench_character);
  std::vector<JsonObject> records;
  std::printf("%-14s %-8s %10s %12s %14s %10s %14s  %s\n", "problem", "solver", "frames",
              "seconds", "frames/s", "iters", "final_cost", "error");
  for (const std::string& solver : solvers) {
    BenchRecord record;
    record.problem = problem->name;
    record.solver = solver;
    Status status = problem->run(solver, settings, &record);
    if (!status.ok()) return status;
    std::printf("%-14s %-8s %10d %12.6f %14.1f %10d %14.6g  %s %.6g\n", record.problem.c_str(),
                record.solver.c_str(), record.frames, record.seconds, record.frames_per_second(),
                record.iterations, record.final_cost, record.error_name.c_str(), record.error);
    for (const auto& [name, value] : record.figures) std::printf("  %s %.6g\n", name.c_str(), value);
    // One machine-readable line per record.
    std::printf("JSON %s\n", record.ToJson().ToString(false).c_str());
    records.push_back(record.ToJson());
  }
  JsonObject all;
  // The settings in force with the records, so a figure can be traced to how it was made.
  all.Add("problem", run.problem).Add("version", Version()).Add("settings", OptionsInForce()).Add("records", records);
  if (!run.json.empty()) {
    Status status = WriteFileAtomically(run.json, all.ToString() + "\n");
    if (!status.ok()) return status;
  }
  return WriteReport(all);
}

std::string BenchUsage() {
  std::string usage =
      "mocapsolve bench --problem=NAME [--solvers=ceres,dls] [--json=OUT.json] "
      "[--bench_motion=FILE]\n\nRuns a problem through each solver and reports time, "
      "frames/s, iterations,\nfinal cost and error (a table and one JSON line per record). "
      "Problems:";
  for (const BenchProblem& p : AllBenchProblems()) {
    usage += std::string("\n  ") + p.name + ": " + p.description;
  }
  return usage;
}

}  // namespace

static const std::string kBenchUsage = BenchUsage();
extern const Command kBenchCommand = {"bench", "the solver comparison harness (time, iterations, "
                                      "cost, error per solver)",
                                      kBenchUsage.c_str(), __FILE__, RunBench,
    {SharedOptions("report,axes,marker_scale,skeleton,skeleton_units,amc_fps,animation,sample_fps"),
     BenchRunSettingOptions().options(),
     SolverOptions().Without("mode").options()}};

}  // namespace mocapsolve
