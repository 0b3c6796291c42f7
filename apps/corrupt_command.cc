// mocapsolve corrupt: damaged copies of clean marker files, with the ground truth of what
// was damaged, for evaluating repair (signal/marker_corruption.h).
#include <cstdio>
#include <string>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "io/atomic_file.h"
#include "io/marker_file.h"
#include "signal/marker_corruption.h"

DEFINE_string(mask_out, "", "CSV of the damaged samples: frame,marker,kind (gap, fly_off, swap, noise).");
DEFINE_int32(corrupt_seed, 1, "Seed of every random draw.");
DEFINE_int32(gaps, 10, "Gaps on random markers.");
DEFINE_int32(gap_min, 10, "Shortest gap (frames).");
DEFINE_int32(gap_max, 60, "Longest gap (frames).");
DEFINE_int32(cluster_gaps, 2, "Occlusions of a marker and its neighbours together.");
DEFINE_double(cluster_radius_mm, 150.0, "Neighbours within this distance share a cluster gap.");
DEFINE_int32(fly_off_frames, 5, "Frames before each interior gap in which the marker drifts off.");
DEFINE_double(fly_off_mm, 100.0, "How far it drifts (mm) by the gap.");
DEFINE_int32(swaps, 1, "Swaps of a marker with its nearest neighbour.");
DEFINE_int32(swap_length, 30, "Frames each swap lasts.");
DEFINE_double(swap_radius_mm, 200.0, "Only neighbours this close are swapped.");
DEFINE_int32(noisy_markers, 2, "Markers that get high-frequency noise over an interval.");
DEFINE_int32(noise_length, 60, "Frames of that interval.");
DEFINE_double(noise_sigma_mm, 5.0, "Noise per axis (mm).");

namespace mocapsolve {
namespace {

Status RunCorrupt(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  if (FLAGS_markers.empty() || FLAGS_out.empty()) return Status::Error("--markers and --out are required");
  for (const std::string& out : {FLAGS_out, FLAGS_mask_out}) {
    if (out.empty()) continue;
    Status status = CheckNotAnInput(out, FLAGS_markers);
    if (!status.ok()) return status;
  }
  if (FLAGS_gap_min < 1 || FLAGS_gap_max < FLAGS_gap_min) return Status::Error("--gap_min/--gap_max: need 1 <= min <= max");
  MarkerTrajectories markers;
  Status status = ReadMarkerFile(FLAGS_markers, &markers);
  if (!status.ok()) return status;
  if (!markers.unit.known()) return Status::Error(FLAGS_markers + ": unknown length unit");
  const double per_mm = 0.001 / markers.unit.metres_per_unit;
  CorruptionOptions options;
  options.seed = static_cast<uint32_t>(FLAGS_corrupt_seed);
  options.gaps = FLAGS_gaps;
  options.gap_min = FLAGS_gap_min;
  options.gap_max = FLAGS_gap_max;
  options.cluster_gaps = FLAGS_cluster_gaps;
  options.cluster_radius = FLAGS_cluster_radius_mm * per_mm;
  options.fly_off_frames = FLAGS_fly_off_frames;
  options.fly_off_distance = FLAGS_fly_off_mm * per_mm;
  options.swaps = FLAGS_swaps;
  options.swap_length = FLAGS_swap_length;
  options.swap_radius = FLAGS_swap_radius_mm * per_mm;
  options.noisy_markers = FLAGS_noisy_markers;
  options.noise_length = FLAGS_noise_length;
  options.noise_sigma = FLAGS_noise_sigma_mm * per_mm;
  CorruptionMask mask;
  CorruptMarkers(options, &markers, &mask);
  status = WriteMarkerFile(FLAGS_out, markers);
  if (!status.ok()) return status;
  int counts[4] = {0, 0, 0, 0};
  std::string csv = "frame,marker,kind\n";
  for (size_t f = 0; f < mask.size(); ++f) {
    for (size_t m = 0; m < mask[f].size(); ++m) {
      const char kind = mask[f][m];
      if (kind == 0) continue;
      const int k = kind == 'g' ? 0 : kind == 'f' ? 1 : kind == 's' ? 2 : 3;
      ++counts[k];
      static const char* kNames[] = {"gap", "fly_off", "swap", "noise"};
      csv += std::to_string(f) + "," + markers.label(static_cast<int>(m)) + "," + kNames[k] + "\n";
    }
  }
  if (!FLAGS_mask_out.empty()) {
    status = WriteFileAtomically(FLAGS_mask_out, csv);
    if (!status.ok()) return status;
  }
  std::printf("wrote %s: %d gap, %d fly-off, %d swapped, %d noisy samples (seed %d)%s%s\n",
              FLAGS_out.c_str(), counts[0], counts[1], counts[2], counts[3], FLAGS_corrupt_seed,
              FLAGS_mask_out.empty() ? "" : "; mask in ", FLAGS_mask_out.c_str());
  JsonObject report;
  report.Add("markers", FLAGS_markers).Add("out", FLAGS_out).Add("gap_samples", counts[0])
      .Add("fly_off_samples", counts[1]).Add("swap_samples", counts[2]).Add("noise_samples", counts[3]);
  return WriteReport(report);
}

}  // namespace

extern const Command kCorruptCommand = {
    "corrupt", "damage clean markers (gaps, occlusions, fly-offs, swaps, noise) with a truth mask",
    "mocapsolve corrupt --markers=CLEAN.c3d|.trc --out=CORRUPTED.c3d|.trc [--mask_out=mask.csv] "
    "[--corrupt_seed=1] [--gaps=10 ...]\n\n"
    "Writes a corrupted copy and, with --mask_out, which samples were damaged and how.\n"
    "Distances are in mm (converted with the file's unit); frames are frame indices.",
    __FILE__, RunCorrupt, "markers,out,report"};

}  // namespace mocapsolve
