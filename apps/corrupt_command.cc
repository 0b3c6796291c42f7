// mocapsolve corrupt: damaged copies of clean marker files, with the ground truth of what
// was damaged, for evaluating repair (signal/marker_corruption.h).
#include <algorithm>
#include <cstdio>
#include <string>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/corruption_flags.h"
#include "io/atomic_file.h"
#include "io/marker_file.h"
#include "signal/marker_corruption.h"


namespace mocapsolve {
namespace {

Status RunCorrupt(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  if (Files().markers.empty() || Files().out.empty()) return Status::Error("--markers and --out are required");
  for (const std::string& out : {Files().out, Files().mask_out}) {
    if (out.empty()) continue;
    Status status = CheckNotAnInput(out, Files().markers);
    if (!status.ok()) return status;
  }
  MarkerTrajectories markers;
  Status status = ReadMarkerFile(Files().markers, &markers);
  if (status.ok()) status = RequireMarkerData(Files().markers, markers);
  if (!status.ok()) return status;
  CorruptionOptions options;
  status = CorruptionOptionsFromFlags(markers.unit, &options);
  if (!status.ok()) return Status::Error(Files().markers + ": " + status.message());
  CorruptionMask mask;
  UnlabelledDamage unlabelled;
  CorruptMarkers(options, &markers, &mask, &unlabelled);
  // The unlabelled damage's tracks become the output's unlabelled points ("*1", ... after
  // the file's own columns; a label the file already has gets a '*' more).
  std::vector<std::string> labels = markers.labels(), more;
  for (int k = 0; k < unlabelled.tracks.num_markers(); ++k) {
    std::string label = unlabelled.tracks.label(k);
    while (std::find(labels.begin(), labels.end(), label) != labels.end()) label = "*" + label;
    labels.push_back(label);
    more.push_back(label);
  }
  MarkerTrajectories out = more.empty() ? markers : WithMoreMarkers(markers, more);
  for (int f = 0; f < markers.num_frames(); ++f) {
    for (int k = 0; k < unlabelled.tracks.num_markers(); ++k) {
      out.SetSample(f, markers.num_markers() + k, unlabelled.tracks.position(f, k));
    }
  }
  status = WriteMarkerFile(Files().out, out);
  if (!status.ok()) return status;
  // Samples per kind; jitter and ghosts were counted as noise before they had names.
  int counts[kNumDamageKinds] = {};
  std::string csv = "frame,marker,kind\n";
  for (size_t f = 0; f < mask.size(); ++f) {
    for (size_t m = 0; m < mask[f].size(); ++m) {
      const int k = DamageKindIndex(mask[f][m]);
      if (k < 0) continue;
      ++counts[k];
      csv += std::to_string(f) + "," + markers.label(static_cast<int>(m)) + "," + kDamageKindNames[k] + "\n";
    }
  }
  if (!Files().mask_out.empty()) {
    status = WriteFileAtomically(Files().mask_out, csv);
    if (!status.ok()) return status;
  }
  std::string summary;
  for (int k = 0; k < kNumDamageKinds; ++k) {
    if (k < 4 || counts[k] > 0) summary += std::string(summary.empty() ? "" : ", ") + std::to_string(counts[k]) + " " + kDamageKindNames[k];
  }
  std::printf("wrote %s: samples damaged: %s (seed %d)%s%s\n", Files().out.c_str(), summary.c_str(),
              CorruptionSettingsFromFlags().seed, Files().mask_out.empty() ? "" : "; mask in ", Files().mask_out.c_str());
  JsonObject report;
  report.Add("markers", Files().markers).Add("out", Files().out);
  for (int k = 0; k < kNumDamageKinds; ++k) report.Add(std::string(kDamageKindNames[k]) + "_samples", counts[k]);
  std::vector<JsonValue> track_names;
  for (int k = 0; k < unlabelled.tracks.num_markers(); ++k) track_names.push_back(labels[markers.num_markers() + k]);
  report.Add("unlabelled_tracks", track_names);
  return WriteReport(report);
}

}  // namespace

extern const Command kCorruptCommand = {
    "corrupt", "damage clean markers (gaps, occlusions, fly-offs, swaps, noise) with a truth mask",
    "mocapsolve corrupt --markers=CLEAN.c3d|.trc --out=CORRUPTED.c3d|.trc [--mask_out=mask.csv] "
    "[--seed=1] [--gaps=10 ...]\n\n"
    "Writes a corrupted copy and, with --mask_out, which samples were damaged and how.\n"
    "Distances are in mm (converted with the file's unit); frames are frame indices.",
    __FILE__, RunCorrupt,
    {SharedOptions("markers,out,mask_out,report"),
     CorruptionSettingOptions().options()}};

}  // namespace mocapsolve
