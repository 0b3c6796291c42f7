// mocapsolve markers --motion=M --markerset=J|auto:N --out=OUT.c3d|.trc: synthetic marker
// trajectories from a motion and a marker set (thesis eq. 9, x_m = MarkerSet::Position
// after FK), optionally with Gaussian noise.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/progress.h"
#include "io/marker_file.h"
#include "io/marker_set_file.h"
#include "io/motion_file.h"
#include "kinematics/forward_kinematics.h"
#include "kinematics/marker_trajectories.h"
#include "problems/marker_solve/marker_observations.h"
#include "problems/marker_solve/synthetic_marker_set.h"

DEFINE_double(noise_mm, 0.0, "Standard deviation of Gaussian noise added to each coordinate, in mm "
              "(converted into the output unit).");
DEFINE_int32(seed, 1, "Seed of the noise and of --markerset=auto:N (the same output for the same seed).");
DEFINE_string(units, "mm", "Length unit of the written markers (mm, cm, m, in) when the skeleton's "
              "unit is known.");
DEFINE_string(write_markerset, "", "Also write the marker set used (e.g. the auto one) to this .json.");

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

Status RunMarkers(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  if (FLAGS_motion.empty() || FLAGS_markerset.empty() || FLAGS_out.empty()) {
    return Status::Error("--motion, --markerset (FILE.json or auto:N) and --out are required");
  }
  if (!IsMarkerFile(FLAGS_out)) return Status::Error(FLAGS_out + ": expected a .c3d or .trc output");
  const bool auto_set = FLAGS_markerset.compare(0, 5, "auto:") == 0;
  int per_joint = 0;
  uint32_t set_seed = static_cast<uint32_t>(FLAGS_seed);
  if (auto_set && !ParseAutoMarkerSet(FLAGS_markerset, &per_joint, &set_seed)) {
    return Status::Error("--markerset='" + FLAGS_markerset + "': expected auto:N (1 <= N <= 100) or auto:N:SEED");
  }
  if (!FLAGS_write_markerset.empty() && !IsTextOutputPath(FLAGS_write_markerset, ".json")) {
    return Status::Error(FLAGS_write_markerset + ": expected a .json marker set file");
  }
  if (!(FLAGS_noise_mm >= 0.0) || !std::isfinite(FLAGS_noise_mm)) {
    return Status::Error("--noise_mm must be a finite number >= 0");
  }
  for (const std::string& output : {FLAGS_out, FLAGS_write_markerset}) {
    if (output.empty()) continue;
    for (const std::string& input : {FLAGS_motion, FLAGS_skeleton, auto_set ? std::string() : FLAGS_markerset}) {
      if (input.empty()) continue;
      Status status = CheckNotAnInput(output, input);
      if (!status.ok()) return status;
    }
  }
  if (FLAGS_out == FLAGS_write_markerset) return Status::Error("--out and --write_markerset name the same file");

  Skeleton skeleton;
  Motion motion;
  Status status = LoadMotion(FLAGS_motion, &skeleton, &motion);
  if (status.ok()) status = RequireFrames(FLAGS_motion, motion);
  if (!status.ok()) return status;
  MarkerSet marker_set;
  if (auto_set) {
    marker_set = MakeSyntheticMarkerSet(skeleton, per_joint, set_seed);
    if (marker_set.num_markers() == 0) return Status::Error(FLAGS_motion + ": no joint with a bone to put markers on");
  } else {
    status = ReadMarkerSet(FLAGS_markerset, skeleton, &marker_set);
    if (!status.ok()) return status;
  }

  // Output unit and axes: x_file = transform.Invert(x_model).
  MarkerFileToModel transform;
  status = ParseAxes(FLAGS_axes, &transform.rotation);
  if (!status.ok()) return status;
  LengthUnit out_unit = LengthUnitFromName(FLAGS_units);
  if (!out_unit.known()) return Status::Error("--units='" + FLAGS_units + "': expected mm, cm, m or in");
  if (FLAGS_marker_scale > 0.0) {
    transform.scale = FLAGS_marker_scale;
  } else if (FLAGS_marker_scale < 0.0 || !std::isfinite(FLAGS_marker_scale)) {
    return Status::Error("--marker_scale must be positive (or 0: from the units)");
  } else if (skeleton.unit().known()) {
    status = UnitScale(out_unit, skeleton.unit(), &transform.scale);
    if (!status.ok()) return status;
  } else {
    transform.scale = 1.0;
    out_unit = skeleton.unit();
    if (!FLAGS_quiet) {
      std::fprintf(stderr, "warning: %s does not state its length unit: markers are written in its "
                   "units, unlabelled (give --skeleton_units=cm or the like)\n", FLAGS_motion.c_str());
    }
  }
  if (FileExtension(FLAGS_out) == ".trc" && !out_unit.known()) {
    return Status::Error(FLAGS_out + ": TRC needs a known unit; give --skeleton_units (the motion's unit)");
  }
  double sigma = 0.0;  // In output units.
  if (FLAGS_noise_mm > 0.0) {
    if (!out_unit.known()) return Status::Error("--noise_mm needs a known output unit; give --skeleton_units");
    sigma = FLAGS_noise_mm * 0.001 / out_unit.metres_per_unit;
  }

  std::vector<std::string> labels;
  for (int m = 0; m < marker_set.num_markers(); ++m) labels.push_back(marker_set.label(m));
  MarkerTrajectories trajectories(labels, motion.num_frames());
  trajectories.frame_rate = motion.frame_rate;
  trajectories.unit = out_unit;
  trajectories.first_frame = 1;
  NoiseSource noise(static_cast<uint64_t>(static_cast<uint32_t>(FLAGS_seed)));
  FkData fk(skeleton);
  Progress progress("markers", motion.num_frames(), FLAGS_quiet);
  for (int f = 0; f < motion.num_frames(); ++f) {
    ForwardKinematics(skeleton, motion.frames[f], &fk);
    for (int m = 0; m < marker_set.num_markers(); ++m) {
      Eigen::Vector3d x = transform.Invert(marker_set.Position(m, fk));
      if (sigma > 0.0) {
        for (int i = 0; i < 3; ++i) x[i] += sigma * noise.Gaussian();
      }
      trajectories.SetSample(f, m, x);
    }
    progress.Update(f + 1);
  }

  if (!FLAGS_write_markerset.empty()) {
    status = WriteMarkerSet(FLAGS_write_markerset, skeleton, marker_set, FLAGS_motion);
    if (!status.ok()) return status;
  }
  status = WriteMarkerFile(FLAGS_out, trajectories);
  if (!status.ok()) return status;
  std::printf("wrote %s: %d markers x %d frames at %g fps (%s, axes %s, noise %g mm)\n",
              FLAGS_out.c_str(), marker_set.num_markers(), motion.num_frames(), motion.frame_rate,
              out_unit.name.c_str(), FLAGS_axes.c_str(), FLAGS_noise_mm);
  if (!FLAGS_write_markerset.empty()) std::printf("wrote %s\n", FLAGS_write_markerset.c_str());
  JsonObject report;
  report.Add("motion", FLAGS_motion)
      .Add("markerset", FLAGS_markerset)
      .Add("out", FLAGS_out)
      .Add("markers", marker_set.num_markers())
      .Add("frames", motion.num_frames())
      .Add("frame_rate", motion.frame_rate)
      .Add("units", out_unit.name)
      .Add("axes", FLAGS_axes)
      .Add("marker_scale", transform.scale)
      .Add("noise_mm", FLAGS_noise_mm)
      .Add("seed", FLAGS_seed);
  return WriteReport(report);
}

}  // namespace

extern const Command kMarkersCommand = {
    "markers", "synthesize marker trajectories (C3D/TRC) from a motion and a marker set",
    "mocapsolve markers --motion=FILE.bvh|FILE.amc [--skeleton=X.asf] --markerset=SET.json|auto:N[:SEED]\n"
    "          --out=OUT.c3d|OUT.trc [--noise_mm=0 --seed=1] [--units=mm] [--skeleton_units=cm]\n"
    "          [--axes=x,y,z] [--marker_scale=0] [--write_markerset=SET.json]\n\n"
    "Runs FK on every frame and writes each marker's position x_m = sum_k w_k G_j(k) z_k\n"
    "(eq. 9). --markerset=auto:N puts N markers around every bone (deterministic for a\n"
    "seed; --write_markerset saves that set). Positions are converted from the skeleton's\n"
    "unit into --units (default mm) when the skeleton states its unit (ASF does, BVH does\n"
    "not: give --skeleton_units, otherwise positions stay in skeleton units, unlabelled).\n"
    "--axes and --marker_scale mean what they mean for `calibrate` and `solve` (the file\n"
    "from the model): x_file = A^T x_model / scale. --noise_mm adds Gaussian noise of that\n"
    "standard deviation (mm) to each coordinate. Frame rate: the motion's.",
    __FILE__, RunMarkers,
    "motion,markerset,out,skeleton,skeleton_units,amc_fps,animation,sample_fps,axes,marker_scale,report"};

}  // namespace mocapsolve
