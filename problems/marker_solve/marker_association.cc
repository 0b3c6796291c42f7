#include "problems/marker_solve/marker_association.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <limits>
#include <map>

#include <Eigen/Eigenvalues>

namespace mocapsolve {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Step 1's scale-free thresholds, in units of the body's size (the median point's median
// distance to the per-frame median point, about 0.45 m on an adult):
constexpr double kOriginOfBody = 0.2;      // A point this near the file's origin (about 9 cm).
constexpr double kLoneSpreadOfBody = 0.13;  // A point whose every pair spread is over this (about 6 cm).
// A point whose 10-90 % range of motion is under this does not move at all (about 0.5 um;
// a still foot's markers sway over a millimetre).
constexpr double kConstantOfBody = 1e-6;

double Median(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  if (v.empty()) return kNaN;
  const size_t k = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

double Percentile(std::vector<double> v, double q) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  if (v.empty()) return kNaN;
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

// What the steps share: the take, the kept points, the sampled frames, the vertical.
struct Scene {
  const MarkerTrajectories* take = nullptr;
  std::vector<int> kept;     // Indices into the take.
  std::vector<bool> still;   // Per kept point: moves less than a tenth of the median point.
  std::vector<int> frames;   // Sampled frames.
  int up = 2, sign = 1;      // Vertical file axis and its sign.
  double extent = 0.0;       // Median vertical extent, file units.
  double metres = 1.0;       // Metres per file unit.
  double floor = 0.0;        // File units, along sign * up.
  double stature = 0.0;       // File units: the extent, or more when the top is no head.
  double Height(const Eigen::Vector3d& x) const { return (sign * x[up] - floor) / stature; }
  // Horizontal coordinates (a, b) with (e_a, e_b, e_up) right-handed.
  Eigen::Vector2d Flat(const Eigen::Vector3d& x) const { return {x[(up + 1) % 3], x[(up + 2) % 3]}; }
};

// Step 1, before anything is known about the body (its up axis, its unit): points rarely
// seen, far from it, left at the file's origin, moving rigidly with nothing, or still and
// apart from it.
void ExcludeStrayPoints(Scene* scene, const RigidClusterOptions& options, MarkerAssociation* out) {
  const MarkerTrajectories& take = *scene->take;
  const int n = take.num_markers();
  std::vector<std::vector<double>> dist(n);
  std::vector<int> seen(n, 0);
  std::vector<std::vector<double>> from_origin(n);  // |x_m(f)|, file units.
  std::vector<double> centre_from_origin;           // |median_f|.
  for (int f : scene->frames) {
    Eigen::Vector3d median;
    for (int k = 0; k < 3; ++k) {
      std::vector<double> c;
      for (int m = 0; m < n; ++m) {
        if (take.valid(f, m)) c.push_back(take.position(f, m)[k]);
      }
      median[k] = Median(c);
    }
    if (!median.allFinite()) continue;
    centre_from_origin.push_back(median.norm());
    for (int m = 0; m < n; ++m) {
      if (!take.valid(f, m)) continue;
      dist[m].push_back((take.position(f, m) - median).norm()), ++seen[m];
      from_origin[m].push_back(take.position(f, m).norm());
    }
  }
  std::vector<double> typical(n, kNaN), travel(n, kNaN);
  for (int m = 0; m < n; ++m) {
    typical[m] = Median(dist[m]);
    // How far the point moves over the take: the 10-90 % range of each coordinate.
    Eigen::Vector3d range;
    for (int k = 0; k < 3; ++k) {
      std::vector<double> c;
      for (int f : scene->frames) {
        if (take.valid(f, m)) c.push_back(take.position(f, m)[k]);
      }
      range[k] = Percentile(c, 0.9) - Percentile(c, 0.1);
    }
    travel[m] = range.norm();
  }
  const double body = Median(typical), moves = Median(travel);
  // The body's centre away from the file's origin (over one median point distance).
  const bool body_off_origin = Median(centre_from_origin) > body;
  std::vector<int> candidates;
  for (int m = 0; m < n; ++m) {
    if (seen[m] < 0.1 * static_cast<double>(scene->frames.size())) {
      out->excluded.push_back({take.label(m), "observed in fewer than 10 % of the frames"});
    } else if (typical[m] > 3.5 * body) {
      out->excluded.push_back({take.label(m), "far from the body (not a marker: a model output?)"});
      out->non_markers.push_back(take.label(m));
    } else if (body_off_origin && Median(from_origin[m]) < kOriginOfBody * body) {
      out->excluded.push_back({take.label(m), "stays at the file's origin, the body does not (a model output's values?)"});
      out->non_markers.push_back(take.label(m));
    } else {
      candidates.push_back(m);
    }
  }
  // No rigid partner: every pair spread over kLoneSpreadOfBody times the body's size.
  const PairwiseSpread pairs = ComputePairwiseSpread(take, candidates, 1.0 / body, options);
  for (size_t i = 0; i < candidates.size(); ++i) {
    double lone = kInf;
    for (size_t j = 0; j < candidates.size(); ++j) {
      if (i != j) lone = std::min(lone, pairs.spread(i, j));
    }
    if (candidates.size() > 1 && !(lone <= kLoneSpreadOfBody)) {
      out->excluded.push_back({take.label(candidates[i]), "moves rigidly with no other point (not a marker)"});
      out->non_markers.push_back(take.label(candidates[i]));
    } else {
      scene->kept.push_back(candidates[i]);
      scene->still.push_back(travel[candidates[i]] < 0.1 * moves);
    }
  }
  // Still while the body moves and apart from the body: a still point joins the body when
  // it keeps within 0.75 times the median point's distance to the body (B) of a point that
  // moves, or of a still point that joined it (a squat's planted foot beside its still shin,
  // beside the moving knee: a chain). A point that does not move at all (the same numbers
  // in every frame: no tracked marker, which sways and carries the cameras' noise) joins
  // only beside a moving point.
  std::vector<bool> reached(scene->kept.size(), false);
  std::vector<size_t> frontier;
  for (size_t i = 0; i < scene->kept.size(); ++i) {
    if (!scene->still[i]) reached[i] = true, frontier.push_back(i);
  }
  const auto median_distance = [&](size_t i, size_t j) {
    std::vector<double> d;
    for (int f : scene->frames) {
      if (take.valid(f, scene->kept[i]) && take.valid(f, scene->kept[j])) {
        d.push_back((take.position(f, scene->kept[i]) - take.position(f, scene->kept[j])).norm());
      }
    }
    return Median(d);
  };
  while (!frontier.empty()) {
    std::vector<size_t> next;
    for (size_t i = 0; i < scene->kept.size(); ++i) {
      if (reached[i]) continue;
      const bool constant = !(travel[scene->kept[i]] > kConstantOfBody * body);
      for (size_t j : frontier) {
        if ((constant && scene->still[j]) || !(median_distance(i, j) <= 0.75 * body)) continue;
        reached[i] = true, next.push_back(i);
        break;
      }
    }
    frontier = next;
  }
  std::vector<int> kept;
  std::vector<bool> still;
  for (size_t i = 0; i < scene->kept.size(); ++i) {
    if (!reached[i]) {
      out->excluded.push_back({take.label(scene->kept[i]), "still while the body moves, apart from it (not a marker)"});
    } else {
      kept.push_back(scene->kept[i]);
      still.push_back(scene->still[i]);
    }
  }
  scene->kept = kept;
  scene->still = still;
}

// Step 2: the vertical axis, its sign and the median extent.
void DetectUp(Scene* scene) {
  const MarkerTrajectories& take = *scene->take;
  // Extents between each frame's second lowest and second highest point (one stray point
  // does not stretch the body).
  std::vector<double> extent[3];
  for (int f : scene->frames) {
    for (int k = 0; k < 3; ++k) {
      std::vector<double> c;
      for (int m : scene->kept) {
        if (take.valid(f, m)) c.push_back(take.position(f, m)[k]);
      }
      if (c.size() < 4) continue;
      std::sort(c.begin(), c.end());
      extent[k].push_back(c[c.size() - 2] - c[1]);
    }
  }
  Eigen::Vector3d median;
  for (int k = 0; k < 3; ++k) median[k] = Median(extent[k]);
  median.maxCoeff(&scene->up);
  scene->extent = median[scene->up];
  scene->stature = scene->extent;
  // Sign: feet apart at the bottom, one head at the top; else the steadier floor.
  std::vector<double> spread_low, spread_high, lows, highs;
  const int up = scene->up;
  for (int f : scene->frames) {
    std::vector<double> c;
    for (int m : scene->kept) {
      if (take.valid(f, m)) c.push_back(take.position(f, m)[up]);
    }
    if (c.size() < 4) continue;
    std::sort(c.begin(), c.end());
    const double lo = c[1], hi = c[c.size() - 2];
    lows.push_back(lo), highs.push_back(hi);
    for (int end = 0; end < 2; ++end) {
      std::vector<Eigen::Vector2d> points;
      for (int m : scene->kept) {
        if (!take.valid(f, m)) continue;
        const double z = take.position(f, m)[up];
        if (end == 0 ? z < lo + 0.12 * (hi - lo) : z > hi - 0.12 * (hi - lo)) points.push_back(scene->Flat(take.position(f, m)));
      }
      if (points.size() < 2) continue;
      Eigen::Vector2d c = Eigen::Vector2d::Zero();
      for (const auto& p : points) c += p;
      c /= static_cast<double>(points.size());
      double s = 0.0;
      for (const auto& p : points) s += (p - c).squaredNorm();
      (end == 0 ? spread_low : spread_high).push_back(std::sqrt(s / static_cast<double>(points.size())));
    }
  }
  // The floor first when clear: the lowest point of a frame stands still (a foot on the
  // ground; median speed to the next frame) while the highest moves (walking, squatting),
  // at least twice as fast; else the bottom of a body is two feet apart, its top one head.
  std::vector<double> speed_low, speed_high;
  for (int f : scene->frames) {
    if (f + 1 >= take.num_frames()) continue;
    int m_lo = -1, m_hi = -1;
    for (int m : scene->kept) {
      if (!take.valid(f, m)) continue;
      if (m_lo < 0 || take.position(f, m)[up] < take.position(f, m_lo)[up]) m_lo = m;
      if (m_hi < 0 || take.position(f, m)[up] > take.position(f, m_hi)[up]) m_hi = m;
    }
    if (m_lo >= 0 && take.valid(f + 1, m_lo)) speed_low.push_back((take.position(f + 1, m_lo) - take.position(f, m_lo)).norm());
    if (m_hi >= 0 && take.valid(f + 1, m_hi)) speed_high.push_back((take.position(f + 1, m_hi) - take.position(f, m_hi)).norm());
  }
  const double slow = Median(speed_low), shigh = Median(speed_high);
  const double low = Median(spread_low), high = Median(spread_high);
  if (std::max(slow, shigh) > 2.0 * std::min(slow, shigh)) {
    scene->sign = slow < shigh ? 1 : -1;
  } else if (std::isfinite(low) && std::isfinite(high)) {
    scene->sign = low >= high ? 1 : -1;
  }
  if (std::getenv("MOCAPSOLVE_ASSOCIATION_DEBUG")) {
    std::fprintf(stderr, "up %d: lowest point's speed %.4g highest's %.4g, bottom spread %.4g top spread %.4g\n", up,
                 slow, shigh, low, high);
  }
  std::vector<double> floors;
  for (size_t i = 0; i < lows.size(); ++i) floors.push_back(scene->sign > 0 ? lows[i] : -highs[i]);
  scene->floor = Percentile(floors, 0.02);
}

// Step 3: a body 0.9-2.3 m tall (the file's unit when it gives 0.8-2.5 m).
Status DetectUnit(const std::string& path, Scene* scene, MarkerAssociation* out) {
  const LengthUnit file = scene->take->unit;
  // The file's unit, when it makes the points 0.3-2.5 m tall: a whole body, or part of one
  // (a lower-body set spans pelvis to heels, 0.7-1.0 m for an adult, less for a child or in
  // a sprint's flight; before, such a set was read in inches or refused). A unit wrong by
  // 10x makes 0.17 or 17 m of a body, and is searched for.
  const double in_file = scene->extent * file.metres_per_unit;
  if (file.known() && in_file >= 0.3 && in_file <= 2.5) {
    out->unit = file;
  } else {
    double best = kInf;
    for (const LengthUnit& u : {Millimetres(), Centimetres(), Metres(), LengthUnit{"in", 0.0254}}) {
      const double h = scene->extent * u.metres_per_unit;
      if (h < 0.9 || h > 2.3) continue;
      const double score = std::abs(std::log(h / 1.6));
      if (score < best) best = score, out->unit = u;
    }
    if (!std::isfinite(best)) {
      char line[200];
      std::snprintf(line, sizeof line, ": the points span %.4g file units vertically, a body in no unit (mm, cm, m, in)",
                    scene->extent);
      return Status::Error(path + line);
    }
    out->unit_from_data = true;
  }
  scene->metres = out->unit.metres_per_unit;
  out->height_m = scene->extent * scene->metres;
  out->up_axis = scene->up;
  out->up_sign = scene->sign;
  return Status::Ok();
}

// Per kept point (index into scene.kept): median height, and, in the pelvis' frame, the
// median side (along l x up... see header: side0 = -d.l) and forward (f0 = up x l) coordinates.
// `frame_height[k][i]`: point k's height in sampled frame i (NaN where it is not seen).
struct Layout {
  std::vector<double> height, side, forward;
  std::vector<std::vector<double>> frame_height;
};

void MarkerHeights(const Scene& scene, Layout* layout) {
  layout->height.clear();
  layout->frame_height.clear();
  for (int m : scene.kept) {
    std::vector<double> h;
    for (int f : scene.frames) {
      h.push_back(scene.take->valid(f, m) ? scene.Height(scene.take->position(f, m)) : kNaN);
    }
    layout->height.push_back(Median(h));
    layout->frame_height.push_back(std::move(h));
  }
}

// The stature over the points' extent, when the body's top is no head. The top band: the
// points within kTopBand below the highest one. The top is the base of the neck (C7, a
// gait set without head markers) when two points of that band in different rigid clusters
// (a head's markers share one) keep kShoulderBesideNeck to 0.3 m apart and move nearly
// together (pair spread under 3 cm): an acromion beside C7. A head stands a neck over the
// shoulders, and hands raised to its height move against it. Then the stature is the
// top's height over kNeckOfStature (C7 stands at 0.86 of it). Returns extent / stature.
constexpr double kTopBand = 0.1;
constexpr double kShoulderBesideNeck = 0.12;  // Metres.
constexpr double kNeckOfStature = 0.86;
constexpr double kStance = 0.06;  // Of the stature: a foot on the floor (step 5's legs).
constexpr double kOwnSide = 0.05;  // Metres: a low leg cluster this far off the midline keeps its side.
double StatureScale(const PairwiseSpread& pairs, const std::vector<std::vector<int>>& clusters,
                    const std::vector<double>& height) {
  const size_t n = height.size();
  std::vector<int> cluster_of(n, -1);
  for (size_t c = 0; c < clusters.size(); ++c) {
    for (int i : clusters[c]) cluster_of[i] = static_cast<int>(c);
  }
  double top = -kInf;
  for (double h : height) {
    if (std::isfinite(h)) top = std::max(top, h);
  }
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = i + 1; j < n; ++j) {
      if (!(height[i] > top - kTopBand) || !(height[j] > top - kTopBand) || cluster_of[i] == cluster_of[j]) continue;
      if (pairs.distance(i, j) > kShoulderBesideNeck && pairs.distance(i, j) < 0.3 && pairs.spread(i, j) < 0.03) {
        if (std::getenv("MOCAPSOLVE_ASSOCIATION_DEBUG")) {
          std::fprintf(stderr, "neck: points %zu, %zu at h %.2f, %.2f, %.2f m apart\n", i, j, height[i], height[j],
                       pairs.distance(i, j));
        }
        return std::min(1.0, kNeckOfStature / top);
      }
    }
  }
  return 1.0;
}

double ClusterMedian(const std::vector<int>& cluster, const std::vector<double>& values) {
  std::vector<double> v;
  for (int i : cluster) v.push_back(values[i]);
  return Median(v);
}

// Both feet planted (a squat, a stand) keep their distance: the clustering joins them
// (and, in a symmetric squat, the shins) into one "rigid" cluster. A cluster whose points
// are all below kLowLimb of the stature and whose points on either side of the midline lie
// over kFeetApart apart (their medians across) is split into its two sides (one foot or
// shin is narrower than that; the trunk is never so low).
constexpr double kLowLimb = 0.3;
constexpr double kFeetApart = 0.12;  // Metres.
std::vector<std::vector<int>> SplitFeetAcrossMidline(const std::vector<std::vector<int>>& clusters,
                                                     const Layout& layout, std::vector<bool>* split) {
  std::vector<std::vector<int>> out;
  split->clear();
  for (const std::vector<int>& cluster : clusters) {
    std::vector<int> sides[2];
    bool low = true;
    for (int i : cluster) {
      low = low && layout.height[i] < kLowLimb;
      sides[layout.side[i] > 0.0 ? 0 : 1].push_back(i);
    }
    if (low && !sides[0].empty() && !sides[1].empty() &&
        ClusterMedian(sides[0], layout.side) - ClusterMedian(sides[1], layout.side) > kFeetApart) {
      out.push_back(sides[0]), out.push_back(sides[1]);
      split->push_back(true), split->push_back(true);
    } else {
      out.push_back(cluster);
      split->push_back(false);
    }
  }
  return out;
}

// Side (side0 = -d.l) and forward (f0 = up x l) coordinates of every kept point, medians
// over frames, in the hip band's frame: origin the middle of the points at heights
// [0.4, 0.7] in that frame. Its forward is the band's heading where the body travels (over
// kTravelSpeed, the band's displacement over kHeadingWindow: a walk, a run) and l = f0 x
// up; elsewhere l is the band's principal horizontal axis (kept continuous). A sprint's
// thighs swing wider fore and aft than the hips are wide, so the principal axis alone
// turns the frame by 90 degrees there. Also `travel`: the band's displacement along f0
// over the path length (walking is forward).
constexpr double kTravelSpeed = 0.5;     // Metres per second.
constexpr double kHeadingWindow = 0.5;   // Seconds.
constexpr double kStraight = 0.8;
void BodyFrameCoordinates(const Scene& scene, Layout* layout, double* travel) {
  const MarkerTrajectories& take = *scene.take;
  const size_t n = scene.kept.size();
  // The band's points and centroid per sampled frame.
  std::vector<std::vector<Eigen::Vector2d>> band(scene.frames.size());
  std::vector<Eigen::Vector2d> centroid(scene.frames.size(), Eigen::Vector2d::Constant(kNaN));
  for (size_t s = 0; s < scene.frames.size(); ++s) {
    for (int m : scene.kept) {
      if (!take.valid(scene.frames[s], m)) continue;
      const double h = scene.Height(take.position(scene.frames[s], m));
      if (h >= 0.4 && h <= 0.7) band[s].push_back(scene.Flat(take.position(scene.frames[s], m)));
    }
    if (band[s].size() < 3) continue;
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    for (const auto& p : band[s]) c += p;
    centroid[s] = c / static_cast<double>(band[s].size());
  }
  const double rate = take.frame_rate > 0.0 ? take.frame_rate : 100.0;
  auto heading = [&](size_t s) -> Eigen::Vector2d {
    size_t a = s, b = s;
    const double t = scene.frames[s] / rate;
    while (a > 0 && t - scene.frames[a - 1] / rate <= 0.5 * kHeadingWindow) --a;
    while (b + 1 < scene.frames.size() && scene.frames[b + 1] / rate - t <= 0.5 * kHeadingWindow) ++b;
    const double dt = (scene.frames[b] - scene.frames[a]) / rate;
    if (dt <= 0.0 || !centroid[a].allFinite() || !centroid[b].allFinite()) return Eigen::Vector2d::Zero();
    const Eigen::Vector2d d = centroid[b] - centroid[a];
    return d.norm() * scene.metres / dt > kTravelSpeed ? Eigen::Vector2d(d.normalized()) : Eigen::Vector2d::Zero();
  };
  // Straight travel: over kTravelSpeed in at least a quarter of the sampled frames, and
  // their headings' sum over kStraight of its terms' lengths.
  Eigen::Vector2d net = Eigen::Vector2d::Zero();
  double length = 0.0;
  for (size_t s = 0; s < scene.frames.size(); ++s) {
    const Eigen::Vector2d ahead = heading(s);
    net += ahead, length += ahead.norm();
  }
  const bool straight = length >= 0.25 * static_cast<double>(scene.frames.size()) && net.norm() > kStraight * length;
  if (std::getenv("MOCAPSOLVE_ASSOCIATION_DEBUG")) {
    std::fprintf(stderr, "travel: %.0f sampled frames over %.1f m/s, straightness %.2f\n", length,
                 kTravelSpeed, length > 0.0 ? net.norm() / length : 0.0);
  }
  std::vector<std::vector<double>> side(n), forward(n);
  Eigen::Vector2d last = Eigen::Vector2d::Zero(), previous = Eigen::Vector2d::Constant(kNaN);
  double along = 0.0, path = 0.0;
  for (size_t s = 0; s < scene.frames.size(); ++s) {
    const int f = scene.frames[s];
    const std::vector<Eigen::Vector2d>& points = band[s];
    if (points.size() < 3) continue;
    Eigen::Vector2d c = centroid[s];
    Eigen::Vector2d l;
    const Eigen::Vector2d ahead = straight ? heading(s) : Eigen::Vector2d::Zero();
    if (ahead.squaredNorm() > 0.0) {
      l = scene.sign * Eigen::Vector2d(ahead.y(), -ahead.x());  // f0 = sign (-l.y, l.x) = ahead.
    } else {
      Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
      for (const auto& p : points) cov += (p - c) * (p - c).transpose();
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
      l = eig.eigenvectors().col(1);
      if (last.squaredNorm() > 0.0 && l.dot(last) < 0.0) l = -l;
      if (last.squaredNorm() == 0.0 && l.x() + l.y() < 0.0) l = -l;  // Any fixed start.
    }
    last = l;
    const Eigen::Vector2d f0 = scene.sign * Eigen::Vector2d(-l.y(), l.x());  // up x l.
    // Across, the middle of the band's extremes (a missing marker on one side does not
    // shift it as it shifts the centroid).
    double lo = kInf, hi = -kInf;
    for (const auto& p : points) lo = std::min(lo, (p - c).dot(l)), hi = std::max(hi, (p - c).dot(l));
    c += 0.5 * (lo + hi) * l;
    if (previous.allFinite()) along += (c - previous).dot(f0), path += (c - previous).norm();
    previous = c;
    for (size_t k = 0; k < n; ++k) {
      if (!take.valid(f, scene.kept[k])) continue;
      const Eigen::Vector2d d = (scene.Flat(take.position(f, scene.kept[k])) - c) * scene.metres;
      side[k].push_back(-d.dot(l));
      forward[k].push_back(d.dot(f0));
    }
  }
  layout->side.resize(n);
  layout->forward.resize(n);
  for (size_t k = 0; k < n; ++k) layout->side[k] = Median(side[k]), layout->forward[k] = Median(forward[k]);
  *travel = path > 0.0 ? along / path : 0.0;
}


// A leg's roles from its heights in its stance: the sampled frames where the side's lowest
// leg point (group 1, side of that sign) is within kStance of the floor (a sprint's feet
// are in the air most of the take, so their median heights are a shin's); the medians when
// fewer than a tenth of the frames are stance. Per kept point; the median height off legs.
std::vector<double> StanceHeights(const Layout& layout, const std::vector<std::vector<int>>& clusters,
                                  const std::vector<int>& group, const std::vector<double>& side) {
  std::vector<double> leg_height = layout.height;
  for (const double sign : {1.0, -1.0}) {
    std::vector<int> leg;
    for (size_t c = 0; c < clusters.size(); ++c) {
      if (group[c] == 1 && side[c] * sign > 0.0) leg.insert(leg.end(), clusters[c].begin(), clusters[c].end());
    }
    if (leg.empty()) continue;
    const size_t frames = layout.frame_height[leg[0]].size();
    std::vector<bool> stance(frames, false);
    size_t count = 0;
    for (size_t f = 0; f < frames; ++f) {
      double lowest = kInf;
      for (int i : leg) {
        if (std::isfinite(layout.frame_height[i][f])) lowest = std::min(lowest, layout.frame_height[i][f]);
      }
      stance[f] = lowest < kStance, count += stance[f];
    }
    if (static_cast<double>(count) < 0.1 * static_cast<double>(frames)) continue;
    for (int i : leg) {
      std::vector<double> h;
      for (size_t f = 0; f < frames; ++f) {
        if (stance[f]) h.push_back(layout.frame_height[i][f]);
      }
      if (std::isfinite(Median(h))) leg_height[i] = Median(h);
    }
  }
  return leg_height;
}

// A side whose "arm" points all sit at a shoulder (median h above 0.72, a walk's elbows sit
// near 0.62, its wrists near 0.48; and within kShoulderReach of the trunk's axis across
// the floor, an acromion 0.15-0.22 m off it) is no arm: a Helen Hayes / Davis set puts
// only an acromion there, beside C7 (BTS DAVIS: "l should", "c7"). Its clusters join the
// trunk (the chest), or the arm roles would call one of two shoulder-height points a hand.
// A whole arm held up (a squat's arms stretched forward, a free-form take's raised arm)
// sits as high, but its forearm and hand reach beyond a shoulder, and it carries more points
// than a shoulder (squat: 8-10 a side, 0.4-0.6 m out; nick_freeform_001: 10, 0.16-0.35 m):
// it stays an arm.
void ShoulderOnlyArmsToTrunk(const std::vector<std::vector<int>>& clusters, const Layout& layout,
                             std::vector<int>* group) {
  constexpr double kShoulderHeight = 0.72;
  constexpr double kShoulderReach = 0.35;  // Metres.
  constexpr size_t kShoulderPoints = 3;    // A shoulder's markers; an arm's upper arm, forearm and hand hold more.
  for (const int k : {0, 1}) {
    bool any = false, arm = false;
    size_t points = 0;
    for (size_t c = 0; c < clusters.size(); ++c) {
      if ((*group)[c] != 2 || (ClusterMedian(clusters[c], layout.side) > 0.0 ? 0 : 1) != k) continue;
      any = true;
      points += clusters[c].size();
      for (int i : clusters[c]) {
        const double reach = std::hypot(layout.side[i], layout.forward[i]);
        arm = arm || !(layout.height[i] > kShoulderHeight) || !(reach < kShoulderReach);
      }
    }
    if (!any || arm || points > kShoulderPoints) continue;
    for (size_t c = 0; c < clusters.size(); ++c) {
      if ((*group)[c] == 2 && (ClusterMedian(clusters[c], layout.side) > 0.0 ? 0 : 1) == k) (*group)[c] = 0;
    }
  }
}

// Step 5's roles per marker, sides as "a_" (side0 > 0) and "b_" until forward is known.
// Each cluster is a group: central (trunk), leg (a point below h 0.34, none above 0.6),
// arm, or, below 0.6 and off centre, the group of the cluster it moves most rigidly with
// (the trunk's counts as a leg: the hip); within a group each marker takes its role from its own height
// (trunk: pelvis below 0.66, head above 0.91, chest between; leg: foot below 0.1, shin below
// 0.29, thigh) or, on an arm, its distance from the side's shoulder (the arm's highest
// point): upper arm within 0.5 of the farthest, forearm within 0.85, hand.
struct RoleFinder {
  const PairwiseSpread& pairs;
  const std::vector<std::vector<int>>& clusters;
  const std::vector<bool>& split;  // Per cluster: one side of a cluster split at the midline.
  const Layout& layout;
  std::vector<std::string> roles;    // Per kept point.
  std::vector<double> certainty;     // Per kept point.
  void Run();
};

void RoleFinder::Run() {
  const size_t n = layout.height.size();
  roles.assign(n, "");
  certainty.assign(n, 1.0);
  std::vector<int> group(clusters.size(), 0);  // 0 trunk, 1 leg, 2 arm.
  for (size_t c = 0; c < clusters.size(); ++c) {
    double lo = kInf, hi = -kInf, side_lo = kInf, side_hi = -kInf;
    for (int i : clusters[c]) {
      lo = std::min(lo, layout.height[i]), hi = std::max(hi, layout.height[i]);
      side_lo = std::min(side_lo, layout.side[i]), side_hi = std::max(side_hi, layout.side[i]);
    }
    // Central: the middle of its extremes across (a pelvis missing a marker on one side
    // is still central), or spanning both sides.
    const double mid = 0.5 * (side_lo + side_hi);
    const bool central = std::abs(mid) < 0.07 || (side_lo < -0.05 && side_hi > 0.05);
    if (central && !(lo < 0.3)) group[c] = 0;
    else if (lo < 0.34 && hi < 0.6) group[c] = 1;
    else if (hi < 0.6 && !central) group[c] = 3;  // Thigh or hand: decided below.
    else group[c] = central ? 0 : 2;
  }
  // A cluster between the hips and the hands' height joins the group of the cluster it
  // moves most rigidly with (a thigh with its shin or the pelvis, a hand with its forearm).
  for (size_t c = 0; c < clusters.size(); ++c) {
    if (group[c] != 3) continue;
    double best = kInf;
    int best_group = 1;
    for (size_t o = 0; o < clusters.size(); ++o) {
      if (o == c || group[o] == 3) continue;
      const double spread = MinClusterSpread(pairs, clusters[c], clusters[o]);
      if (spread < best) best = spread, best_group = group[o] == 0 ? 1 : group[o];
    }
    group[c] = best_group;
  }
  ShoulderOnlyArmsToTrunk(clusters, layout, &group);
  // A limb cluster's side is its median's; a shin or foot (below h 0.3) takes the side of
  // the leg cluster above it that it moves most rigidly with (a walk's feet pass under the
  // body's midline, the thighs do not), unless it is one side of a split cluster (planted
  // feet: the other foot is as rigid with the shin as its own).
  std::vector<double> side(clusters.size());
  std::vector<size_t> order(clusters.size());
  for (size_t c = 0; c < clusters.size(); ++c) side[c] = ClusterMedian(clusters[c], layout.side), order[c] = c;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return ClusterMedian(clusters[a], layout.height) > ClusterMedian(clusters[b], layout.height);
  });
  std::vector<bool> sided(clusters.size(), false), linked(clusters.size(), false);
  for (size_t c : order) {
    if (group[c] != 1) continue;
    if (ClusterMedian(clusters[c], layout.height) >= 0.3 || std::abs(side[c]) >= 0.1 || split[c]) {
      sided[c] = true;
      continue;
    }
    // A cluster 5 cm or more off the midline is not taken across it (its own leg's thigh
    // may be missing: a dropped marker).
    const double own = side[c];
    double best = 0.05;
    for (size_t o : order) {
      if (o == c || group[o] != 1 || !sided[o] || (std::abs(own) >= kOwnSide && side[o] * own < 0.0)) continue;
      const double spread = MinClusterSpread(pairs, clusters[c], clusters[o]);
      if (spread < best) {
        best = spread, linked[c] = true;
        side[c] = side[o] > 0.0 ? std::abs(side[c]) + 1e-6 : -std::abs(side[c]) - 1e-6;
      }
    }
    sided[c] = true;
  }
  const std::vector<double> leg_height = StanceHeights(layout, clusters, group, side);
  // Shoulders: per side, the arm point nearest the upper trunk (points of the trunk group
  // above h 0.66; the whole trunk when none is).
  std::vector<int> upper_trunk, trunk;
  for (size_t c = 0; c < clusters.size(); ++c) {
    if (group[c] != 0) continue;
    for (int i : clusters[c]) {
      trunk.push_back(i);
      if (layout.height[i] > 0.66) upper_trunk.push_back(i);
    }
  }
  if (upper_trunk.empty()) upper_trunk = trunk;
  int shoulder[2] = {-1, -1};
  double shoulder_distance[2] = {kInf, kInf};
  for (size_t c = 0; c < clusters.size(); ++c) {
    if (group[c] != 2) continue;
    const int k = side[c] > 0.0 ? 0 : 1;
    for (int i : clusters[c]) {
      for (int t : upper_trunk) {
        if (pairs.distance(i, t) < shoulder_distance[k]) shoulder_distance[k] = pairs.distance(i, t), shoulder[k] = i;
      }
    }
  }
  double reach[2] = {0.0, 0.0};
  for (size_t c = 0; c < clusters.size(); ++c) {
    if (group[c] != 2) continue;
    for (int i : clusters[c]) {
      const int k = side[c] > 0.0 ? 0 : 1;
      if (shoulder[k] >= 0 && std::isfinite(pairs.distance(i, shoulder[k]))) reach[k] = std::max(reach[k], pairs.distance(i, shoulder[k]));
    }
  }
  for (size_t c = 0; c < clusters.size(); ++c) {
    for (int i : clusters[c]) {
      const double h = layout.height[i];
      const std::string prefix = (clusters[c].size() > 1 ? side[c] : layout.side[i]) > 0.0 ? "a_" : "b_";
      if (group[c] == 0) {
        roles[i] = h < 0.66 ? "pelvis" : h > 0.91 ? "head" : "chest";
      } else if (group[c] == 1) {
        roles[i] = prefix + (leg_height[i] < 0.1 ? "foot" : leg_height[i] < 0.29 ? "shin" : "thigh");
      } else {
        const int k = side[c] > 0.0 ? 0 : 1;
        const double d = shoulder[k] < 0 ? 0.0 : pairs.distance(i, shoulder[k]) / std::max(reach[k], 1e-9);
        roles[i] = prefix + (!(d >= 0.5) ? "upper_arm" : d < 0.85 ? "forearm" : "hand");
      }
      // Side unclear: near the midline, unless a joint links it to a sided leg cluster.
      if (group[c] != 0 && std::abs(side[c]) < 0.03 && !linked[c]) certainty[i] = 0.7;
    }
  }
}

// Forward's sign: +1 when f0 is forward. Votes: the take walks forward (|travel| > 0.3);
// the pelvis' front markers (ahead of its median) are wider apart than its back ones; the
// feet reach ahead of the shins; side words in labels (half a vote).
int ForwardSign(const Layout& layout, const std::vector<std::string>& roles, double travel,
                const std::vector<std::string>& labels) {
  double vote = std::abs(travel) > 0.3 ? (travel > 0.0 ? 1.0 : -1.0) : 0.0;
  std::vector<double> pelvis_forward;
  for (size_t i = 0; i < roles.size(); ++i) {
    if (roles[i] == "pelvis") pelvis_forward.push_back(layout.forward[i]);
  }
  double middle = 0.0;
  if (!pelvis_forward.empty()) {
    middle = 0.5 * (*std::min_element(pelvis_forward.begin(), pelvis_forward.end()) +
                    *std::max_element(pelvis_forward.begin(), pelvis_forward.end()));
  }
  double front_lo = kInf, front_hi = -kInf, back_lo = kInf, back_hi = -kInf;
  for (size_t i = 0; i < roles.size(); ++i) {
    if (roles[i] != "pelvis") continue;
    const double s = layout.side[i];
    if (layout.forward[i] > middle + 0.02) front_lo = std::min(front_lo, s), front_hi = std::max(front_hi, s);
    if (layout.forward[i] < middle - 0.02) back_lo = std::min(back_lo, s), back_hi = std::max(back_hi, s);
  }
  const double front = front_hi - front_lo, back = back_hi - back_lo;
  if (std::isfinite(front) && std::isfinite(back) && std::abs(front - back) > 0.04) vote += front > back ? 1.0 : -1.0;
  for (const char* side : {"a_", "b_"}) {
    std::vector<double> foot, shin;
    for (size_t i = 0; i < roles.size(); ++i) {
      if (roles[i] == std::string(side) + "foot") foot.push_back(layout.forward[i]);
      if (roles[i] == std::string(side) + "shin") shin.push_back(layout.forward[i]);
    }
    double reach = -kInf;
    for (double f : foot) reach = std::abs(f - Median(shin)) > std::abs(reach) ? f - Median(shin) : reach;
    if (std::isfinite(reach) && std::abs(reach) > 0.05) vote += reach > 0.0 ? 1.0 : -1.0;
  }
  // Knees bulge forward of the hip-ankle line, and hands work ahead of the shoulders.
  auto role_forward = [&](const std::string& role) {
    std::vector<double> v;
    for (size_t i = 0; i < roles.size(); ++i) {
      if (roles[i] == role) v.push_back(layout.forward[i]);
    }
    return Median(v);
  };
  const double pelvis = role_forward("pelvis");
  for (const char* side : {"a_", "b_"}) {
    const std::string p(side);
    const double knee = 0.5 * (role_forward(p + "thigh") + role_forward(p + "shin"));
    const double bulge = knee - 0.5 * (pelvis + role_forward(p + "foot"));
    if (std::isfinite(bulge) && std::abs(bulge) > 0.03) vote += bulge > 0.0 ? 1.0 : -1.0;
    const double ahead = role_forward(p + "hand") - role_forward(p + "upper_arm");
    if (std::isfinite(ahead) && std::abs(ahead) > 0.05) vote += ahead > 0.0 ? 0.5 : -0.5;
  }
  double names = 0.0;
  for (size_t i = 0; i < labels.size(); ++i) {
    const int word = LabelSide(labels[i]);
    if (word != 0 && std::abs(layout.side[i]) > 0.03) names += (layout.side[i] > 0.0) == (word < 0) ? 1.0 : -1.0;
  }
  if (names != 0.0) vote += 0.5 * (names > 0.0 ? 1.0 : -1.0);
  if (std::getenv("MOCAPSOLVE_ASSOCIATION_DEBUG")) {
    std::fprintf(stderr, "forward vote %.1f (travel %.2f, pelvis front %.2f back %.2f, names %.0f)\n", vote, travel,
                 front, back, names);
  }
  return vote >= 0.0 ? 1 : -1;
}

std::string FinalRole(const std::string& role, int forward) {
  if (role.rfind("a_", 0) == 0) return (forward > 0 ? "left_" : "right_") + role.substr(2);
  if (role.rfind("b_", 0) == 0) return (forward > 0 ? "right_" : "left_") + role.substr(2);
  return role;
}

// Step 6: each marker's confidence.
double MembershipConfidence(const PairwiseSpread& pairs, const std::vector<std::vector<int>>& clusters, int c,
                            int i) {
  if (clusters[c].size() < 2) return 0.6;
  double own = 0.0;
  int count = 0;
  for (int j : clusters[c]) {
    if (j != i && std::isfinite(pairs.spread(i, j))) own += pairs.spread(i, j), ++count;
  }
  own = count > 0 ? own / count : 0.0;
  double other = kInf;
  for (size_t o = 0; o < clusters.size(); ++o) {
    if (static_cast<int>(o) != c) other = std::min(other, MeanClusterSpread(pairs, {i}, clusters[o]));
  }
  if (!std::isfinite(other)) return 1.0;
  return std::clamp(1.0 - own / std::max(other, 1e-9), 0.0, 1.0);
}

}  // namespace

int LabelSide(const std::string& raw) {
  std::string label = raw.substr(raw.find(':') == std::string::npos ? 0 : raw.find(':') + 1);
  std::string lower;
  for (char ch : label) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (lower.rfind("left", 0) == 0) return -1;
  if (lower.rfind("right", 0) == 0) return 1;
  if (label.size() >= 2 && (label[0] == 'L' || label[0] == 'l' || label[0] == 'R' || label[0] == 'r')) {
    const char next = label[1];
    // LASI, L_IAS, "r should", LeftKnee: an upper-case letter, separator or space after the side letter.
    if (std::isupper(static_cast<unsigned char>(next)) || next == '_' || next == ' ' || next == '.' || next == '-') {
      return (label[0] == 'L' || label[0] == 'l') ? -1 : 1;
    }
  }
  return 0;
}

const AssociatedMarker* MarkerAssociation::Find(const std::string& label) const {
  for (const AssociatedMarker& m : markers) {
    if (m.label == label) return &m;
  }
  return nullptr;
}

std::string MarkerAssociation::UpName() const {
  return std::string(up_sign > 0 ? "+" : "-") + "xyz"[up_axis];
}

Status AssociateMarkers(const MarkerTrajectories& take, const std::string& path,
                        const MarkerAssociationOptions& options, MarkerAssociation* out) {
  *out = MarkerAssociation();
  if (take.num_frames() == 0 || take.num_markers() == 0) return Status::Error(path + ": no frames or no points");
  Scene scene;
  scene.take = &take;
  const int step = std::max(1, take.num_frames() / std::max(1, options.clusters.max_frames));
  for (int f = 0; f < take.num_frames(); f += step) scene.frames.push_back(f);
  ExcludeStrayPoints(&scene, options.clusters, out);
  if (scene.kept.size() < 6) return Status::Error(path + ": fewer than 6 points observed often enough to be markers");
  DetectUp(&scene);
  Status status = DetectUnit(path, &scene, out);
  if (!status.ok()) return status;
  PairwiseSpread pairs = ComputePairwiseSpread(take, scene.kept, scene.metres, options.clusters);
  // Points that move rigidly with nothing are no skin markers.
  std::vector<int> kept;
  for (size_t i = 0; i < scene.kept.size(); ++i) {
    double lone = kInf;
    for (size_t j = 0; j < scene.kept.size(); ++j) {
      if (i != j) lone = std::min(lone, pairs.spread(i, j));
    }
    if (lone > options.max_lone_spread) {
      out->excluded.push_back({take.label(scene.kept[i]), "moves rigidly with no other point (not a skin marker)"});
      out->non_markers.push_back(take.label(scene.kept[i]));
    } else {
      kept.push_back(scene.kept[i]);
    }
  }
  if (kept.size() != scene.kept.size()) {
    scene.kept = kept;
    pairs = ComputePairwiseSpread(take, scene.kept, scene.metres, options.clusters);
  }
  const std::vector<std::vector<int>> rigid = ClusterRigidMarkers(pairs, options.clusters);
  Layout layout;
  MarkerHeights(scene, &layout);
  scene.stature = scene.extent / StatureScale(pairs, rigid, layout.height);
  if (scene.stature != scene.extent) MarkerHeights(scene, &layout);
  double travel = 0.0;
  BodyFrameCoordinates(scene, &layout, &travel);
  std::vector<bool> split;
  const std::vector<std::vector<int>> clusters = SplitFeetAcrossMidline(rigid, layout, &split);
  RoleFinder finder{pairs, clusters, split, layout, {}, {}};
  finder.Run();
  std::vector<std::string> labels;
  // Without the subject prefix ("Nick01:"), as the fit's marker sets name them.
  for (int m : scene.kept) labels.push_back(SplitSubjectPrefix(take.label(m), take.subject_prefixes).name);
  const int forward = ForwardSign(layout, finder.roles, travel, labels);
  for (size_t c = 0; c < clusters.size(); ++c) {
    std::vector<std::string> names;
    for (int i : clusters[c]) {
      AssociatedMarker a;
      a.label = labels[i];
      a.role = FinalRole(finder.roles[i], forward);
      a.cluster = static_cast<int>(c);
      a.height = layout.height[i];
      a.side_m = forward * layout.side[i];
      a.confidence = MembershipConfidence(pairs, clusters, static_cast<int>(c), i) * finder.certainty[i];
      const int word = LabelSide(a.label);
      const bool lateral = a.role.rfind("left_", 0) == 0 || a.role.rfind("right_", 0) == 0;
      if (word != 0 && lateral && (word < 0) != (a.role.rfind("left_", 0) == 0)) a.confidence *= 0.5;
      out->markers.push_back(a);
      names.push_back(a.label);
    }
    out->clusters.push_back(names);
  }
  std::stable_sort(out->markers.begin(), out->markers.end(), [&](const AssociatedMarker& a, const AssociatedMarker& b) {
    return take.FindMarker(a.label) < take.FindMarker(b.label);
  });
  return Status::Ok();
}

}  // namespace mocapsolve
