// mocapsolve corrupt: damaged copies of clean marker files, with the ground truth of what
// was damaged, for evaluating repair (signal/marker_corruption.h).
#include <cstdio>
#include <string>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/corruption_flags.h"
#include "io/atomic_file.h"
#include "io/marker_file.h"
#include "signal/marker_corruption.h"

DEFINE_string(mask_out, "", "CSV of the damaged samples: frame,marker,kind (gap, fly_off, swap, noise).");

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
  MarkerTrajectories markers;
  Status status = ReadMarkerFile(FLAGS_markers, &markers);
  if (!status.ok()) return status;
  CorruptionOptions options;
  status = CorruptionOptionsFromFlags(markers.unit, &options);
  if (!status.ok()) return Status::Error(FLAGS_markers + ": " + status.message());
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

const std::string kCorruptFlags = std::string("markers,out,report,") + kCorruptionFlagNames;

}  // namespace

extern const Command kCorruptCommand = {
    "corrupt", "damage clean markers (gaps, occlusions, fly-offs, swaps, noise) with a truth mask",
    "mocapsolve corrupt --markers=CLEAN.c3d|.trc --out=CORRUPTED.c3d|.trc [--mask_out=mask.csv] "
    "[--corrupt_seed=1] [--gaps=10 ...]\n\n"
    "Writes a corrupted copy and, with --mask_out, which samples were damaged and how.\n"
    "Distances are in mm (converted with the file's unit); frames are frame indices.",
    __FILE__, RunCorrupt, kCorruptFlags.c_str()};

}  // namespace mocapsolve
