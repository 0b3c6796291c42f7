#include "tasks/markers_task.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "io/marker_set_file.h"
#include "kinematics/forward_kinematics.h"
#include "problems/marker_solve/marker_observations.h"
#include "problems/marker_solve/synthetic_marker_set.h"

namespace mocapsolve {
namespace {

// SplitMix64 and Box-Muller: the same noise on every platform for a given seed.
class NoiseSource {
 public:
  explicit NoiseSource(uint64_t seed) : state_(seed ^ 0x6A09E667F3BCC909ull) {}
  double Gaussian() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double u1 = (static_cast<double>(Next() >> 11) + 0.5) * (1.0 / 9007199254740992.0);
    const double u2 = static_cast<double>(Next() >> 11) * (1.0 / 9007199254740992.0);
    const double radius = std::sqrt(-2.0 * std::log(u1));
    const double angle = 2.0 * 3.14159265358979323846 * u2;
    spare_ = radius * std::sin(angle);
    has_spare_ = true;
    return radius * std::cos(angle);
  }

 private:
  uint64_t Next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  uint64_t state_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

// "auto:N" or "auto:N:SEED" -> per_joint, seed.
bool ParseAutoMarkerSet(const std::string& text, int* per_joint, uint32_t* seed) {
  if (text.compare(0, 5, "auto:") != 0) return false;
  const char* begin = text.c_str() + 5;
  char* end = nullptr;
  const long n = std::strtol(begin, &end, 10);
  if (end == begin || n < 1 || n > 100) return false;
  *per_joint = static_cast<int>(n);
  if (*end == ':') {
    const char* seed_begin = end + 1;
    const unsigned long s = std::strtoul(seed_begin, &end, 10);
    if (end == seed_begin || s > 0xFFFFFFFFul) return false;
    *seed = static_cast<uint32_t>(s);
  }
  return *end == '\0';
}

// The marker set: N per bone, or the file's.
Status MarkerSetFor(const Skeleton& skeleton, const std::string& motion_name, const MarkersConfig& config,
                    MarkerSet* marker_set) {
  if (config.markerset.compare(0, 5, "auto:") != 0) return ReadMarkerSet(config.markerset, skeleton, marker_set);
  int per_joint = 0;
  uint32_t set_seed = static_cast<uint32_t>(config.markers.seed);
  if (!ParseAutoMarkerSet(config.markerset, &per_joint, &set_seed)) {
    return Status::Error("--markerset='" + config.markerset + "': expected auto:N (1 <= N <= 100) or auto:N:SEED");
  }
  *marker_set = MakeSyntheticMarkerSet(skeleton, per_joint, set_seed);
  if (marker_set->num_markers() == 0) return Status::Error(motion_name + ": no joint with a bone to put markers on");
  return Status::Ok();
}

}  // namespace

Status RunMarkers(const Skeleton& skeleton, const Motion& motion, const std::string& motion_name,
                  const MarkersConfig& config, const std::function<void(int frames_done)>& progress,
                  MarkersResult* result) {
  *result = MarkersResult();
  const SyntheticMarkerSettings& s = config.markers;
  Status status = SyntheticMarkerOptions().Validate(s);
  if (!status.ok()) return status;
  if (config.markerset.empty()) return Status::Error("--markerset: expected FILE.json or auto:N");
  status = MarkerSetFor(skeleton, motion_name, config, &result->marker_set);
  if (!status.ok()) return status;

  // Output unit and axes: x_file = transform.Invert(x_model).
  MarkerFileToModel transform;
  status = ParseAxes(config.axes, &transform.rotation);
  if (!status.ok()) return status;
  LengthUnit out_unit = LengthUnitFromName(s.units);
  if (config.marker_scale > 0.0) {
    transform.scale = config.marker_scale;
  } else if (config.marker_scale < 0.0 || !std::isfinite(config.marker_scale)) {
    return Status::Error("--marker_scale must be positive (or 0: from the units)");
  } else if (skeleton.unit().known()) {
    status = UnitScale(out_unit, skeleton.unit(), &transform.scale);
    if (!status.ok()) return status;
  } else {
    transform.scale = 1.0;
    out_unit = skeleton.unit();
    result->warning = motion_name + " does not state its length unit: markers are written in its units, unlabelled "
                      "(give --skeleton_units=cm or the like)";
  }
  double sigma = 0.0;  // In output units.
  if (s.noise_mm > 0.0) {
    if (!out_unit.known()) return Status::Error("--noise_mm needs a known output unit; give --skeleton_units");
    sigma = s.noise_mm * 0.001 / out_unit.metres_per_unit;
  }
  const MarkerSet& marker_set = result->marker_set;
  std::vector<std::string> labels;
  for (int m = 0; m < marker_set.num_markers(); ++m) labels.push_back(marker_set.label(m));
  MarkerTrajectories& trajectories = result->trajectories;
  trajectories = MarkerTrajectories(labels, motion.num_frames());
  trajectories.frame_rate = motion.frame_rate;
  trajectories.unit = out_unit;
  trajectories.first_frame = 1;
  NoiseSource noise(static_cast<uint64_t>(static_cast<uint32_t>(s.seed)));
  FkData fk(skeleton);
  for (int f = 0; f < motion.num_frames(); ++f) {
    ForwardKinematics(skeleton, motion.frames[f], &fk);
    for (int m = 0; m < marker_set.num_markers(); ++m) {
      Eigen::Vector3d x = transform.Invert(marker_set.Position(m, fk));
      if (sigma > 0.0) {
        for (int i = 0; i < 3; ++i) x[i] += sigma * noise.Gaussian();
      }
      trajectories.SetSample(f, m, x);
    }
    if (progress) progress(f + 1);
  }
  result->scale = transform.scale;
  result->report.Add("markers", marker_set.num_markers()).Add("frames", motion.num_frames())
      .Add("frame_rate", motion.frame_rate).Add("units", out_unit.name).Add("axes", config.axes)
      .Add("marker_scale", transform.scale).Add("noise_mm", s.noise_mm).Add("seed", s.seed);
  return Status::Ok();
}

}  // namespace mocapsolve
