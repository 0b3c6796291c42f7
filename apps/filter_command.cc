// mocapsolve filter --motion=IN|--markers=IN --levels=N --out=OUT: multiresolution data
// filtering (Huang, Boulic & Thalmann, section 5): a Laplacian pyramid of N levels is
// collapsed without its N finest bands, i.e. EXPAND^N(G_N). signal/motion_pyramid.h.
#include <cmath>
#include <cstdio>
#include <string>

#include "apps/command.h"
#include "apps/option_flags.h"
#include "settings/band_settings.h"
#include "apps/common_flags.h"
#include "apps/option_flags.h"
#include "apps/pyramid_flags.h"
#include "io/bvh_writer.h"
#include "io/marker_file.h"
#include "io/motion_file.h"
#include "pipeline/memory_estimate.h"
#include "settings/memory_settings.h"
#include "signal/motion_pyramid.h"

namespace mocapsolve {

Status PyramidOptionsFromFlags(int levels, PyramidOptions* options) {
  PyramidSettings settings;
  ReadOptionFlags(PyramidSettingOptions(), &settings);
  return PyramidOptionsFromSettings(settings, levels, options);
}

Status FilterFromFlags(const char* command, int levels, const std::vector<double>& weights) {
  if (Files().out.empty()) return Status::Error("--out is required");
  if (Files().motion.empty() == Files().markers.empty()) {
    return Status::Error("give exactly one of --motion and --markers");
  }
  const std::string& input = Files().motion.empty() ? Files().markers : Files().motion;
  Status status = CheckNotAnInput(Files().out, input);
  if (!status.ok()) return status;
  PyramidOptions options;
  status = PyramidOptionsFromFlags(levels, &options);
  if (!status.ok()) return status;
  JsonObject report;
  report.Add("command", command).Add("in", input).Add("out", Files().out).Add("levels", levels)
      .Add("kernel_a", options.kernel.a).Add("tension", options.tension);
  if (!Files().motion.empty()) {
    if (!IsTextOutputPath(Files().out, ".bvh")) return Status::Error(Files().out + ": expected a .bvh");
    Skeleton skeleton;
    Motion motion, filtered;
    status = LoadMotion(Files().motion, &skeleton, &motion);
    if (status.ok()) status = RequireFrames(Files().motion, motion);
    MemorySettings memory;
    ReadOptionFlags(MemoryOption(), &memory);
    if (status.ok()) status = CheckMemoryLimit(PyramidFilterMemory(motion.num_frames()), memory.memory_mb, Files().motion);
    if (!status.ok()) return status;
    status = FilterMotion(motion, options, weights, &filtered);
    if (!status.ok()) return Status::Error(Files().motion + ": " + status.message());
    status = WriteBvh(Files().out, skeleton, filtered);
    if (!status.ok()) return status;
    std::printf("wrote %s: %d frames, %d joints, %d levels\n", Files().out.c_str(),
                filtered.num_frames(), skeleton.num_joints(), levels);
    report.Add("frames", filtered.num_frames()).Add("joints", skeleton.num_joints());
  } else {
    if (!IsMarkerFile(Files().out)) return Status::Error(Files().out + ": expected a .c3d or .trc");
    MarkerTrajectories trajectories, filtered;
    status = ReadMarkerFile(Files().markers, &trajectories);
    if (status.ok()) status = RequireMarkerData(Files().markers, trajectories);
    if (!status.ok()) return status;
    status = FilterMarkers(trajectories, options, weights, &filtered);
    if (!status.ok()) return Status::Error(Files().markers + ": " + status.message());
    double sum = 0.0;
    int count = 0;
    for (int f = 0; f < filtered.num_frames(); ++f) {
      for (int m = 0; m < filtered.num_markers(); ++m) {
        if (!trajectories.valid(f, m)) continue;
        sum += (filtered.position(f, m) - trajectories.position(f, m)).squaredNorm();
        ++count;
      }
    }
    const double rms = count > 0 ? std::sqrt(sum / count) : 0.0;
    status = WriteMarkerFile(Files().out, filtered);
    if (!status.ok()) return status;
    std::printf("wrote %s: %d frames, %d markers (%d missing samples kept missing), %d levels, "
                "rms change %.4g %s\n", Files().out.c_str(), filtered.num_frames(),
                filtered.num_markers(), filtered.CountMissing(), levels, rms,
                trajectories.unit.name.c_str());
    report.Add("frames", filtered.num_frames()).Add("markers", filtered.num_markers())
        .Add("rms_change", rms).Add("units", trajectories.unit.name);
  }
  return WriteReport(report);
}

namespace {

Status RunFilter(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  BandSettings bands;
  ReadOptionFlags(BandSettingOptions(), &bands);
  if (bands.levels < 1 || bands.levels > 30) return Status::Error("--levels must be in [1, 30]");
  return FilterFromFlags("filter", bands.levels, DropFinestBands(bands.levels, bands.levels));
}

}  // namespace

extern const Command kFilterCommand = {
    "filter", "multiresolution low-pass filtering of a motion or marker trajectories",
    "mocapsolve filter --motion=IN.bvh|--markers=IN.c3d --levels=N --out=OUT\n\n"
    "Builds a Laplacian pyramid of N levels (5-tap generating kernel, EXPAND by cubic\n"
    "Cardinal splines) and collapses it without its N finest bands (Huang, Boulic &\n"
    "Thalmann, section 5). Rotations are filtered as sign-continuous quaternions and\n"
    "renormalized, positions and markers per channel; missing marker samples stay missing. A\n"
    "motion is written as BVH, markers as C3D or TRC (by --out's extension).",
    __FILE__, RunFilter,
    {SharedOptions("motion,markers,out,skeleton,skeleton_units,amc_fps,animation,sample_fps,report"),
     BandSettingOptions().Only("levels").options(), PyramidSettingOptions().options(), MemoryOption().options()}};

}  // namespace mocapsolve
