// Marker labelling (mocapsolve label) on scrambled takes: accuracy against the truth and
// frames per second. Two kinds of take per real capture:
//   real/<take>:      the lab's labelled file with its labels stripped and its points
//                     shuffled every frame (its own unlabelled points stay as ghosts);
//   synthetic/<take>: the subject's markers made by its model from the motion the clip
//                     solve finds on the take (without the samples the lab labelled off
//                     the body), then stripped, shuffled, 2 ghosts per frame, 5 %
//                     dropouts, 1 mm noise per axis.
// Subjects: $MOCAPSOLVE_LABEL_SUBJECTS/<take>.json (bench/label_subjects.sh makes them);
// missing: the case is skipped. Counters: accuracy (correct / samples whose truth is a
// subject marker), wrong (labels given to the wrong point or a ghost), longest_wrong_run
// (frames), fps (labelling only, as the task times it).
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <utility>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_data.h"
#include "io/marker_file.h"
#include "kinematics/forward_kinematics.h"
#include "pipeline/subject.h"
#include "problems/marker_label/label_fixture.h"
#include "problems/marker_label/off_body_samples.h"
#include "tasks/label_task.h"
#include "tasks/solve_task.h"

namespace mocapsolve {
namespace {

std::string SubjectPath(const std::string& take) {
  const char* env = std::getenv("MOCAPSOLVE_LABEL_SUBJECTS");
  return std::string(env != nullptr && *env ? env : "out/label_subjects") + "/" + take + ".json";
}

// Skin and fit errors the off-body check allows (problems/marker_label/off_body_samples.h).
constexpr double kOffBodyToleranceMm = 100.0;

// The subject's markers made by its model from the motion solved on the take, in the
// file's axes and unit: a motion a body can make, so that the take tests the labeller, not
// the lab's file. The motion is the clip solve (--mode=clip, DLS: all frames at once with
// smoothness), from the take without the samples the lab labelled off the body
// (OffBodySamples). The per-frame solve made real nick_freeform_001's body jump: its RTOE
// lies 0.8-1.4 m from its ankle marker in 115 frames from frame 975, and the right leg
// followed it and came back as the point came and went (up to 1.5 m in a frame); a joint
// seen by one marker (LIWR alone on the left hand) went to the prior in each of that
// marker's gaps and snapped back at their ends (30-100 mm in a frame). 317 of its 1,101
// frames had a marker accelerating more than 25 mm per frame^2 (the lab's file: 3); 18
// this way.
Status SyntheticTake(const Subject& subject, const MarkerTake& take, MarkerTrajectories* out) {
  MarkerTake on_body = take;
  const double tolerance = kOffBodyToleranceMm * 0.001 / subject.skeleton.unit().metres_per_unit;
  const std::vector<std::vector<char>> off = OffBodySamples(subject.skeleton, subject.markers, take.observed, tolerance);
  for (size_t f = 0; f < off.size(); ++f) {
    for (size_t m = 0; m < off[f].size(); ++m) {
      if (off[f][m]) on_body.observed[f][m].setConstant(std::numeric_limits<double>::quiet_NaN());
    }
  }
  SolveConfig config;
  config.solver.mode = "clip";
  config.solver.clip_solver = "dls";
  SolveResult solved;
  Status status = RunSolve(on_body, config, SolveProgress{}, &solved);
  if (!status.ok()) return status;
  std::vector<std::string> labels;
  for (int m = 0; m < subject.markers.num_markers(); ++m) labels.push_back(subject.markers.label(m));
  *out = MarkerTrajectories(labels, solved.motion.num_frames());
  out->frame_rate = take.trajectories.frame_rate;
  out->unit = take.trajectories.unit;
  FkData fk(subject.skeleton);
  for (int f = 0; f < solved.motion.num_frames(); ++f) {
    ForwardKinematics(subject.skeleton, solved.motion.frames[f], &fk);
    for (int m = 0; m < subject.markers.num_markers(); ++m) {
      out->SetSample(f, m, take.transform.Invert(subject.markers.Position(m, fk)));
    }
  }
  return Status::Ok();
}

// Per (truth, given) pair of a wrong label: how many samples (stderr).
void PrintConfusions(const std::vector<std::vector<std::string>>& truth,
                     const std::vector<std::vector<std::string>>& labels) {
  std::map<std::pair<std::string, std::string>, std::pair<int, int>> count;  // count, first frame
  for (size_t f = 0; f < truth.size(); ++f) {
    for (size_t c = 0; c < truth[f].size(); ++c) {
      if (labels[f][c] == truth[f][c] || truth[f][c].empty()) continue;
      auto& e = count[{truth[f][c], labels[f][c]}];
      if (e.first++ == 0) e.second = static_cast<int>(f);
    }
  }
  for (const auto& [pair, n] : count) {
    std::fprintf(stderr, "  %s given %s: %d samples from frame %d\n", pair.first.c_str(), pair.second.c_str(),
                 n.first, n.second);
  }
}

void LabelTake(benchmark::State& state, const std::string& take_name, const std::string& file, bool synthetic) {
  Subject subject;
  MarkerTake take;
  Status status = ReadSubject(SubjectPath(take_name), &subject);
  if (status.ok()) status = LoadTakeForSubject(subject, DataFile(file), &take);
  if (!status.ok()) {
    state.SkipWithError(status.message().c_str());
    return;
  }
  MarkerTrajectories source = take.trajectories;
  ScrambleOptions scramble;
  if (synthetic) {
    status = SyntheticTake(subject, take, &source);
    if (!status.ok()) {
      state.SkipWithError(status.message().c_str());
      return;
    }
    const double mm = 0.001 / source.unit.metres_per_unit;
    scramble.ghosts = 2, scramble.ghost_margin = 200 * mm, scramble.dropout = 0.05, scramble.noise = mm;
  }
  const ScrambledTake scrambled = ScrambleLabels(source, scramble);
  LabelResult result;
  for (auto _ : state) {
    status = RunLabel(subject, scrambled.points, take_name, LabelConfig{}, nullptr, &result);
    if (!status.ok()) {
      state.SkipWithError(status.message().c_str());
      return;
    }
  }
  std::vector<std::vector<std::string>> labels(scrambled.truth.size());
  for (size_t f = 0; f < labels.size(); ++f) {
    for (int m : result.marker_of_sample[f]) labels[f].push_back(m >= 0 ? subject.markers.label(m) : "");
  }
  std::vector<std::string> scored;
  for (int m = 0; m < subject.markers.num_markers(); ++m) scored.push_back(subject.markers.label(m));
  const LabelScore score = ScoreLabels(scrambled.truth, labels, scored);
  if (std::getenv("MOCAPSOLVE_LABEL_DEBUG") != nullptr) PrintConfusions(scrambled.truth, labels);
  state.counters["accuracy_pct"] = 100.0 * score.accuracy();
  state.counters["wrong"] = score.wrong;
  state.counters["unlabelled"] = score.unlabelled;
  state.counters["longest_wrong_run"] = score.longest_wrong_run;
  state.counters["fps"] = result.seconds > 0 ? scrambled.points.num_frames() / result.seconds : 0.0;
  state.counters["acquisitions"] = static_cast<double>(result.details.acquisitions.size());
  state.counters["lost_frames"] = result.details.lost_frames;
  int refused = 0;
  for (const MarkerLabelStats& s : result.details.per_marker) refused += s.low_confidence;
  state.counters["low_confidence"] = refused;
  state.counters["truth_samples"] = score.truth_samples;
}

struct Case {
  const char* take;
  const char* file;
};
const Case kCases[] = {{"02_01", "c3d/02_01.c3d"},
                       {"cmu_02_05", "c3d/cmu_02_05.c3d"},
                       {"JA1Gait35", "c3d/JA1Gait35.c3d"},
                       {"squat", "c3d/squat.c3d"},
                       {"nick_freeform_001", "c3d/nick_freeform_001.c3d"}};

const bool kRegistered = [] {
  for (const Case& c : kCases) {
    for (const bool synthetic : {true, false}) {
      const std::string name = std::string("BM_Label/") + (synthetic ? "synthetic/" : "real/") + c.take;
      benchmark::RegisterBenchmark(name.c_str(), [c, synthetic](benchmark::State& state) {
        LabelTake(state, c.take, c.file, synthetic);
      })->Iterations(1)->Unit(benchmark::kMillisecond);
    }
  }
  return true;
}();

}  // namespace
}  // namespace mocapsolve
