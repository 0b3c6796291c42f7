#include "signal/marker_corruption.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <limits>
#include <random>

namespace mocapsolve {
namespace {

int Uniform(std::mt19937* rng, int lo, int hi) {  // Inclusive; hi < lo gives lo.
  return hi <= lo ? lo : std::uniform_int_distribution<int>(lo, hi)(*rng);
}

void MakeGap(int m, int first, int length, MarkerTrajectories* markers, CorruptionMask* mask) {
  for (int f = first; f < std::min(markers->num_frames(), first + length); ++f) {
    markers->SetMissing(f, m);
    (*mask)[f][m] = 'g';
  }
}

// The marker nearest to `a` at frame f (within radius) observed there, -1 if none.
int NearestMarker(const MarkerTrajectories& markers, int f, int a, double radius) {
  int b = -1;
  double nearest = std::numeric_limits<double>::infinity();
  for (int m = 0; m < markers.num_markers(); ++m) {
    if (m == a || !markers.valid(f, m)) continue;
    const double d = (markers.position(f, m) - markers.position(f, a)).norm();
    if (d < nearest && d <= radius) nearest = d, b = m;
  }
  return b;
}

// Markers a and b exchange samples over [first, first + length) where both are observed.
void Swap(int a, int b, int first, int length, MarkerTrajectories* markers, CorruptionMask* mask) {
  for (int f = first; f < std::min(markers->num_frames(), first + length); ++f) {
    if (!markers->valid(f, a) || !markers->valid(f, b)) continue;
    const Eigen::Vector3d pa = markers->position(f, a), pb = markers->position(f, b);
    markers->SetSample(f, a, pb);
    markers->SetSample(f, b, pa);
    (*mask)[f][a] = (*mask)[f][b] = 's';
  }
}

}  // namespace

int DamageKindIndex(char letter) {
  for (int k = 0; k < kNumDamageKinds; ++k) {
    if (letter != 0 && kDamageKinds[k] == letter) return k;
  }
  return -1;
}

void CorruptMarkers(const CorruptionOptions& o, MarkerTrajectories* markers, CorruptionMask* mask,
                    UnlabelledDamage* unlabelled) {
  const int nf = markers->num_frames(), nm = markers->num_markers();
  mask->assign(nf, std::vector<char>(nm, 0));
  if (unlabelled != nullptr) *unlabelled = UnlabelledDamage();
  if (nf == 0 || nm == 0) return;
  std::mt19937 rng(o.seed);
  std::normal_distribution<double> normal;
  // Fly-off, then the gap it precedes (the thesis' "markers fly off before disappearing").
  auto gap_with_fly_off = [&](int m, int first, int length) {
    if (first > 0 && o.fly_off_distance > 0.0) {
      const Eigen::Vector3d direction = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
      for (int k = 1; k <= o.fly_off_frames && first - k >= 0; ++k) {
        const int f = first - k;
        if (!markers->valid(f, m) || (*mask)[f][m]) break;
        const double t = 1.0 - (k - 1.0) / o.fly_off_frames;
        markers->SetSample(f, m, markers->position(f, m) + t * o.fly_off_distance * direction);
        (*mask)[f][m] = 'f';
      }
    }
    MakeGap(m, first, length, markers, mask);
  };
  for (int g = 0; g < o.gaps; ++g) {
    const int length = Uniform(&rng, o.gap_min, o.gap_max);
    gap_with_fly_off(Uniform(&rng, 0, nm - 1), Uniform(&rng, 0, std::max(0, nf - length)), length);
  }
  for (int c = 0; c < o.cluster_gaps; ++c) {
    const int length = Uniform(&rng, o.gap_min, o.gap_max);
    const int first = Uniform(&rng, 0, std::max(0, nf - length));
    const int centre = Uniform(&rng, 0, nm - 1);
    if (!markers->valid(first, centre)) continue;
    const Eigen::Vector3d at = markers->position(first, centre);
    for (int m = 0; m < nm; ++m) {
      if (markers->valid(first, m) && (markers->position(first, m) - at).norm() <= o.cluster_radius) {
        gap_with_fly_off(m, first, length);
      }
    }
  }
  for (int s = 0; s < o.swaps; ++s) {
    const int first = Uniform(&rng, 0, std::max(0, nf - o.swap_length));
    const int a = Uniform(&rng, 0, nm - 1);
    if (!markers->valid(first, a)) continue;
    const int b = NearestMarker(*markers, first, a, o.swap_radius);
    if (b >= 0) Swap(a, b, first, o.swap_length, markers, mask);
  }
  for (int n = 0; n < o.noisy_markers && o.noise_sigma > 0.0; ++n) {
    const int m = Uniform(&rng, 0, nm - 1);
    const int first = Uniform(&rng, 0, std::max(0, nf - o.noise_length));
    for (int f = first; f < std::min(nf, first + o.noise_length); ++f) {
      if (!markers->valid(f, m) || (*mask)[f][m]) continue;
      markers->SetSample(f, m, markers->position(f, m) +
                                   o.noise_sigma * Eigen::Vector3d(normal(rng), normal(rng), normal(rng)));
      (*mask)[f][m] = 'n';
    }
  }
  for (int s = 0; s < o.swaps_in_gaps; ++s) {
    const int length = Uniform(&rng, o.gap_min, o.gap_max);
    const int first = Uniform(&rng, 0, std::max(0, nf - length - o.swap_length));
    const int a = Uniform(&rng, 0, nm - 1);
    const int swap_first = first + Uniform(&rng, 1, std::max(1, length - 1));
    if (!markers->valid(first, a)) continue;
    const int b = NearestMarker(*markers, first, a, o.swap_radius);
    if (b < 0) continue;
    MakeGap(a, first, length, markers, mask);
    Swap(a, b, swap_first, o.swap_length, markers, mask);
  }
  auto random_direction = [&] { return Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized(); };
  for (int j = 0; j < o.jitter_markers && o.jitter_distance > 0.0; ++j) {
    const int m = Uniform(&rng, 0, nm - 1);
    const int first = Uniform(&rng, 0, std::max(0, nf - o.jitter_length));
    for (int f = first; f < std::min(nf, first + o.jitter_length); ++f) {
      const double size = o.jitter_distance * std::uniform_real_distribution<double>(0.5, 1.5)(rng);
      const Eigen::Vector3d direction = random_direction();
      if (!markers->valid(f, m) || (*mask)[f][m]) continue;
      markers->SetSample(f, m, markers->position(f, m) + size * direction);
      (*mask)[f][m] = 'j';
    }
  }
  for (int g = 0; g < o.ghosts && o.ghost_distance > 0.0; ++g) {
    const int m = Uniform(&rng, 0, nm - 1);
    const int first = Uniform(&rng, 0, std::max(0, nf - o.ghost_length));
    const Eigen::Vector3d offset = o.ghost_distance * random_direction();
    for (int f = first; f < std::min(nf, first + o.ghost_length); ++f) {
      if (!markers->valid(f, m) || (*mask)[f][m]) continue;
      markers->SetSample(f, m, markers->position(f, m) + offset);
      (*mask)[f][m] = 'h';
    }
  }
  // Unlabelled: drawn last, so the earlier kinds' damage of a seed is as it was.
  std::vector<std::vector<Eigen::Vector3d>> tracks;  // [event][frame].
  std::vector<int> source;
  for (int u = 0; u < o.unlabels; ++u) {
    const int m = Uniform(&rng, 0, nm - 1);
    const int first = Uniform(&rng, 0, std::max(0, nf - o.unlabel_length));
    tracks.emplace_back(nf, Eigen::Vector3d::Constant(std::nan("")));
    source.push_back(m);
    for (int f = first; f < std::min(nf, first + o.unlabel_length); ++f) {
      if (!markers->valid(f, m) || (*mask)[f][m]) continue;
      tracks.back()[f] = markers->position(f, m);
      markers->SetMissing(f, m);
      (*mask)[f][m] = 'u';
    }
  }
  if (unlabelled != nullptr) {
    std::vector<std::string> labels;
    for (size_t k = 0; k < tracks.size(); ++k) labels.push_back("*" + std::to_string(k + 1));
    unlabelled->tracks = MarkerTrajectories(labels, nf);
    unlabelled->tracks.unit = markers->unit;
    unlabelled->tracks.frame_rate = markers->frame_rate;
    unlabelled->tracks.first_frame = markers->first_frame;
    for (size_t k = 0; k < tracks.size(); ++k) {
      for (int f = 0; f < nf; ++f) unlabelled->tracks.SetSample(f, static_cast<int>(k), tracks[k][f]);
    }
    unlabelled->source = std::move(source);
  }
}

}  // namespace mocapsolve
