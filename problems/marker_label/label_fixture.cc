#include "problems/marker_label/label_fixture.h"

#include <algorithm>
#include <limits>
#include <map>
#include <random>
#include <set>

#include "kinematics/unlabelled_label.h"

namespace mocapsolve {

ScrambledTake ScrambleLabels(const MarkerTrajectories& labelled, const ScrambleOptions& options) {
  std::mt19937 random(options.seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  struct Sample {
    Eigen::Vector3d position;
    std::string truth;
  };
  std::vector<std::vector<Sample>> frames(labelled.num_frames());
  size_t most = 0;
  for (int f = 0; f < labelled.num_frames(); ++f) {
    Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), high = -low;
    for (int c = 0; c < labelled.num_markers(); ++c) {
      if (!labelled.valid(f, c)) continue;
      const Eigen::Vector3d p = labelled.position(f, c);
      low = low.cwiseMin(p), high = high.cwiseMax(p);
      if (uniform(random) < options.dropout) continue;
      const std::string name = SplitSubjectPrefix(labelled.label(c), labelled.subject_prefixes).name;
      const Eigen::Vector3d noise(normal(random), normal(random), normal(random));
      frames[f].push_back({p + options.noise * noise, IsUnlabelledLabel(name) ? std::string() : name});
    }
    for (int g = 0; g < options.ghosts && low.allFinite(); ++g) {
      const Eigen::Vector3d t(uniform(random), uniform(random), uniform(random));
      const Eigen::Vector3d lo = low.array() - options.ghost_margin, span = (high - low).array() + 2 * options.ghost_margin;
      frames[f].push_back({lo + Eigen::Vector3d(t.cwiseProduct(span)), ""});
    }
    std::shuffle(frames[f].begin(), frames[f].end(), random);
    most = std::max(most, frames[f].size());
  }
  std::vector<std::string> names;
  for (size_t c = 0; c < most; ++c) names.push_back("*" + std::to_string(c + 1));
  ScrambledTake out;
  out.points = MarkerTrajectories(names, labelled.num_frames());
  out.points.frame_rate = labelled.frame_rate;
  out.points.unit = labelled.unit;
  out.points.first_frame = labelled.first_frame;
  out.truth.assign(labelled.num_frames(), std::vector<std::string>(most));
  for (int f = 0; f < labelled.num_frames(); ++f) {
    for (size_t c = 0; c < frames[f].size(); ++c) {
      out.points.SetSample(f, static_cast<int>(c), frames[f][c].position);
      out.truth[f][c] = frames[f][c].truth;
    }
  }
  return out;
}

LabelScore ScoreLabels(const std::vector<std::vector<std::string>>& truth,
                       const std::vector<std::vector<std::string>>& labels, const std::vector<std::string>& scored) {
  const std::set<std::string> in_set(scored.begin(), scored.end());
  LabelScore score;
  std::map<std::string, int> wrong_run;  // Current run of wrong frames per label.
  for (size_t f = 0; f < truth.size(); ++f) {
    std::set<std::string> wrong_now;
    for (size_t c = 0; c < truth[f].size(); ++c) {
      const std::string expected = in_set.count(truth[f][c]) ? truth[f][c] : "";
      const std::string& given = c < labels[f].size() ? labels[f][c] : std::string();
      if (!expected.empty()) ++score.truth_samples;
      if (!expected.empty() && given == expected) ++score.correct;
      if (!given.empty() && given != expected) ++score.wrong, wrong_now.insert(given);
      if (!expected.empty() && given.empty()) ++score.unlabelled;
    }
    for (const std::string& label : scored) {
      int& run = wrong_run[label];
      run = wrong_now.count(label) ? run + 1 : 0;
      score.longest_wrong_run = std::max(score.longest_wrong_run, run);
    }
  }
  return score;
}

}  // namespace mocapsolve
