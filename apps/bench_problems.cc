#include "apps/bench_problems.h"

#include <algorithm>
#include <chrono>

#include "apps/common_flags.h"
#include "kinematics/demo_character.h"
#include "kinematics/forward_kinematics.h"

namespace mocapsolve {

// LoadMotion: apps/common_flags.h.

JsonObject BenchRecord::ToJson() const {
  JsonObject json;
  json.Add("problem", problem).Add("solver", solver).Add("input", input).Add("frames", frames)
      .Add("seconds", seconds).Add("frames_per_second", frames_per_second())
      .Add("iterations", iterations).Add("final_cost", final_cost).Add(error_name.empty() ? "error" : error_name, error);
  return json;
}

namespace {

template <typename Function>
double MedianSeconds(int repeats, Function&& function) {
  std::vector<double> times;
  for (int r = 0; r < std::max(1, repeats); ++r) {
    const auto start = std::chrono::steady_clock::now();
    function();
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

// FK of every frame of a clip: the kinematic core's throughput.
Status RunFkProblem(const std::string& solver, const BenchSettings& settings, BenchRecord* record) {
  if (solver != "fk") return Status::Error("problem fk has one solver, 'fk'");
  Skeleton skeleton;
  Motion motion;
  if (settings.motion_path.empty()) {
    skeleton = MakeDemoSkeleton();
    motion = MakeDemoWalk(skeleton, 2400, 120.0);
    record->input = "procedural demo walk";
  } else {
    Status status = LoadMotion(settings.motion_path, &skeleton, &motion);
    if (!status.ok()) return status;
    record->input = settings.motion_path;
  }
  FkData data(skeleton);
  double checksum = 0.0;
  const int passes = std::max(1, 200000 / std::max(1, motion.num_frames()));
  record->seconds = MedianSeconds(settings.repeats, [&] {
    for (int pass = 0; pass < passes; ++pass) {
      for (const Pose& pose : motion.frames) {
        ForwardKinematics(skeleton, pose, &data);
        checksum += data.world_positions.back().x();
      }
    }
  });
  record->frames = passes * motion.num_frames();
  record->error_name = "checksum";  // Keeps the work observable; not an accuracy figure.
  record->error = checksum;
  return Status::Ok();
}

}  // namespace

const std::vector<BenchProblem>& AllBenchProblems() {
  static const std::vector<BenchProblem> problems = {
      {"fk", "forward kinematics of every frame of a clip (--motion, default: demo walk)",
       {"fk"}, RunFkProblem},
  };
  return problems;
}

}  // namespace mocapsolve
