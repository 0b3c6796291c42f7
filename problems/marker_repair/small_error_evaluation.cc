#include "problems/marker_repair/small_error_evaluation.h"

#include <cmath>
#include <random>

namespace mocapsolve {
namespace {

// The noise generator's seed is the recipe's plus this, so noise and damage draws are
// independent streams.
constexpr uint32_t kNoiseSeedOffset = 0x9E3779B9u;

}  // namespace

SmallErrorRecipe DefaultSmallErrorRecipe(double metres_per_unit, double white_noise_mm) {
  const double cm = 0.01 / metres_per_unit;  // Skeleton units per cm.
  SmallErrorRecipe recipe;
  recipe.jump_min = 1.0 * cm;
  recipe.jump_max = 4.0 * cm;
  recipe.jitter_distance = 2.0 * cm;
  recipe.min_error = 1.0 * cm;
  recipe.white_noise = 0.1 * cm * white_noise_mm;
  return recipe;
}

void AddWhiteNoise(const SmallErrorRecipe& recipe, std::vector<std::vector<Eigen::Vector3d>>* observed) {
  if (recipe.white_noise <= 0.0) return;
  std::mt19937 rng(recipe.seed + kNoiseSeedOffset);
  std::normal_distribution<double> normal(0.0, recipe.white_noise);
  for (std::vector<Eigen::Vector3d>& frame : *observed) {
    for (Eigen::Vector3d& x : frame) {
      if (!x.allFinite()) continue;
      for (int k = 0; k < 3; ++k) x[k] += normal(rng);
    }
  }
}

void AddSmallErrors(const SmallErrorRecipe& recipe, std::vector<std::vector<Eigen::Vector3d>>* observed,
                    SampleFlags* damaged) {
  const int nf = static_cast<int>(observed->size()), nm = nf > 0 ? static_cast<int>((*observed)[0].size()) : 0;
  damaged->assign(nf, std::vector<char>(nm, 0));
  if (nm == 0) return;
  std::mt19937 rng(recipe.seed);
  for (int k = 0; k < recipe.jumps + recipe.jitter_runs; ++k) {
    const int m = std::uniform_int_distribution<int>(0, nm - 1)(rng);
    const bool jitter = k >= recipe.jumps;
    const int length = jitter ? recipe.jitter_frames : std::uniform_int_distribution<int>(1, recipe.jump_max_frames)(rng);
    if (nf < length + 10) continue;  // No room for a run 5 frames from either end.
    const int first = std::uniform_int_distribution<int>(5, nf - length - 5)(rng);
    bool free = true;
    for (int f = first - 5; f < first + length + 5; ++f) free &= !(*damaged)[f][m];
    if (!free) continue;
    const double size = std::uniform_real_distribution<double>(recipe.jump_min, recipe.jump_max)(rng);
    // A fresh distribution per run (it caches a second draw): the draws the test always made.
    std::normal_distribution<double> normal;
    const Eigen::Vector3d direction = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    for (int f = first; f < first + length; ++f) {
      const Eigen::Vector3d step =
          jitter ? Eigen::Vector3d(Eigen::Vector3d(normal(rng), normal(rng), normal(rng)) *
                                   (recipe.jitter_distance / std::sqrt(3.0)))
                 : Eigen::Vector3d(size * direction);
      if (step.norm() < recipe.min_error || !(*observed)[f][m].allFinite()) continue;
      (*observed)[f][m] += step;
      (*damaged)[f][m] = 1;
    }
  }
}

SmallErrorCounts& SmallErrorCounts::operator+=(const SmallErrorCounts& other) {
  damaged += other.damaged;
  flagged += other.flagged;
  true_positive += other.true_positive;
  own += other.own;
  own_damaged += other.own_damaged;
  return *this;
}

SampleFlags FlaggedSamples(const RepairReport& report, int num_frames, int num_markers) {
  SampleFlags flagged(num_frames, std::vector<char>(num_markers, 0));
  for (const RepairInterval& i : report.detected) {
    if (i.what == "missing") continue;
    for (int f = i.first; f <= i.last; ++f) flagged[f][i.marker] = 1;
  }
  return flagged;
}

Status EvaluateSmallErrors(const Skeleton& skeleton, const MarkerSet& markers,
                           const std::vector<std::vector<Eigen::Vector3d>>& clean, const RepairOptions& options,
                           const SmallErrorRecipe& recipe, int num_seeds, SmallErrorScore* score) {
  *score = SmallErrorScore();
  const int nf = static_cast<int>(clean.size()), nm = markers.num_markers();
  auto flag = [&](const std::vector<std::vector<Eigen::Vector3d>>& observed, SampleFlags* flagged) {
    std::vector<std::vector<Eigen::Vector3d>> repaired;
    Motion motion;
    RepairReport report;
    const Status status = RepairMarkers(skeleton, markers, observed, options, &repaired, &motion, &report);
    if (status.ok()) *flagged = FlaggedSamples(report, nf, nm);
    return status;
  };
  SampleFlags own;  // Without noise, the undamaged take is the same for every seed.
  for (int s = 0; s < num_seeds; ++s) {
    SmallErrorRecipe r = recipe;
    r.seed = recipe.seed + static_cast<uint32_t>(s);
    std::vector<std::vector<Eigen::Vector3d>> observed = clean;
    AddWhiteNoise(r, &observed);
    if (own.empty() || r.white_noise > 0.0) {
      const Status status = flag(observed, &own);
      if (!status.ok()) return status;
    }
    SmallErrorSeedScore seed;
    seed.seed = r.seed;
    AddSmallErrors(r, &observed, &seed.damaged_samples);
    SampleFlags& flagged = seed.flagged_samples;
    const Status status = flag(observed, &flagged);
    if (!status.ok()) return status;
    seed.own_samples = own;
    for (int f = 0; f < nf; ++f) {
      for (int m = 0; m < nm; ++m) {
        const bool hurt = seed.damaged_samples[f][m], found = flagged[f][m];
        seed.damaged += hurt;
        seed.flagged += found;
        seed.true_positive += hurt && found;
        seed.own += found && own[f][m];
        seed.own_damaged += hurt && found && own[f][m];
      }
    }
    *score += seed;
    score->seeds.push_back(std::move(seed));
  }
  return Status::Ok();
}

}  // namespace mocapsolve
