// mocapsolve distance --motion=IN --frame=I [--method=green|diffusion|isomap[,...]]
// --out=curve.csv [--plot=curve.svg]: the pose-space falloff of an edit at one frame
// (Dean, Lewis & Chalmers 2018). problems/edit_propagation/falloff.h.
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "apps/command.h"
#include "settings/edit_settings.h"
#include "apps/common_flags.h"
#include "apps/option_flags.h"
#include "settings/method_settings.h"
#include "settings/plot_settings.h"
#include "io/atomic_file.h"
#include "io/motion_file.h"
#include "io/svg_plot.h"
#include "tasks/distance_task.h"

namespace mocapsolve {
namespace {

std::vector<double> ToStd(const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

// A curve's line: smoothness at the edit, where the weight ends, the other cycles.
void PrintFigures(const char* format, const FalloffFigures& f, bool with_half, bool phases) {
  std::printf(format, f.name.c_str());
  if (with_half) {
    std::printf(" second difference at the edit %.3g (kink ratio %.2f: 0.67 smooth, 2 corner); weight < 0.5 at frames "
                "%d/%d, < 0.05 at %d/%d (-1: never)", f.second_difference, f.kink_ratio, f.end_before_05,
                f.end_after_05, f.end_before_005, f.end_after_005);
  } else {
    std::printf(" weight < 0.05 at frames %d/%d", f.end_before_005, f.end_after_005);
  }
  if (phases) {
    std::printf("; same phase min weight %.3f, opposite phase max %.3f", f.min_same_phase_weight,
                f.max_opposite_phase_weight);
  }
  std::printf("\n");
}

Status DistanceMain(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  PlotSetting plot_setting;
  ReadOptionFlags(DistancePlotOption(), &plot_setting);
  const std::string& plot = plot_setting.plot;
  EditSettings edit;
  ReadOptionFlags(EditSettingOptions(), &edit);
  if (Files().motion.empty() || Files().out.empty() || edit.frame < 0) {
    return Status::Error("--motion, --frame (>= 0) and --out are required");
  }
  if (!IsTextOutputPath(Files().out, ".csv")) return Status::Error(Files().out + ": expected a .csv");
  Status status = CheckNotAnInput(Files().out, Files().motion);
  if (!status.ok()) return status;
  if (!plot.empty()) {
    if (!IsTextOutputPath(plot, ".svg")) return Status::Error(plot + ": expected a .svg");
    status = CheckNotAnInput(plot, Files().motion);
    if (!status.ok()) return status;
  }
  DistanceConfig config;
  config.frame = edit.frame;
  MethodSetting method;
  ReadOptionFlags(DistanceMethodOption(), &method);
  config.methods = method.method;
  ReadOptionFlags(FalloffSettingOptions(), &config.falloff);
  Skeleton skeleton;
  Motion motion;
  status = LoadMotion(Files().motion, &skeleton, &motion);
  if (status.ok()) status = RequireFrames(Files().motion, motion);
  if (!status.ok()) return status;
  DistanceResult result;
  status = RunDistance(skeleton, motion, Files().motion, config, &result);
  if (!status.ok()) return status;

  status = WriteFileAtomically(Files().out, result.csv);
  if (!status.ok()) return status;
  if (!plot.empty()) {
    std::vector<PlotSeries> series;
    for (size_t k = 0; k < result.methods.size(); ++k) {
      series.push_back({result.method_names[k] + " distance", ToStd(result.methods[k].distance)});
    }
    for (size_t s = 0; s < result.sweep.size(); ++s) {
      std::ostringstream name;
      name << "green distance, sigma " << result.sweep[s];
      series.push_back({name.str(), ToStd(result.swept[s].distance)});
    }
    status = WriteFileAtomically(plot, LinePlotSvg("Pose distance from frame " + std::to_string(result.frame) +
                                                             " (" + Files().motion + ")",
                                                         "frame", "normalized distance", series));
    if (!status.ok()) return status;
  }
  std::printf("%s: %d frames, edit at frame %d, region %d:%d, period %d frames\n", Files().motion.c_str(),
              result.frames, result.frame, result.region_begin, result.region_end, result.period);
  const bool phases = !result.same_phase.empty();
  for (const FalloffFigures& f : result.method_figures) PrintFigures("%-9s", f, true, phases);
  for (size_t s = 0; s < result.sweep_figures.size(); ++s) {
    std::printf("sigma %-7.4g", result.sweep[s]);
    FalloffFigures f = result.sweep_figures[s];
    f.name = "";
    PrintFigures("%s", f, false, phases);
  }
  if (result.spectral) {
    std::printf("sigma %.4g (%s), %d eigenpairs, %s kernel; features %.1f ms, build %.1f ms\n", result.sigma_used,
                config.falloff.sigma > 0.0 ? "given" : "auto", result.eigenpairs_used,
                result.sparse_kernel ? "sparse kNN" : "dense", result.features_ms, result.build_ms);
  }
  std::printf("wrote %s%s%s\n", Files().out.c_str(), plot.empty() ? "" : " and ", plot.c_str());
  return WriteReport(result.report);
}

}  // namespace

extern const Command kDistanceCommand = {
    "distance", "pose-space distance/falloff of an edit at one frame (Green's function, diffusion, ISOMAP)",
    "mocapsolve distance --motion=IN.bvh --frame=I [--method=green|diffusion|isomap[,...]]\n"
    "    [--sigma=S --eigenpairs=M --region=a:b --sweep=s1,s2] --out=curve.csv [--plot=curve.svg]\n\n"
    "The \"magic wand\" falloff (Dean, Lewis & Chalmers 2018): pose vectors are the joints'\n"
    "log-quaternions; a Gaussian kernel of width sigma (default 4x the median frame-to-frame\n"
    "pose distance) gives the normalized pose Laplacian L = I - D^-1/2 K D^-1/2, and row I of\n"
    "its Green's function (the M smallest nonzero eigenpairs, default 10) scaled over the\n"
    "region is the weight (1 at the edit, 0 at the least similar frame); distance = 1 - weight.\n"
    "diffusion: diffusion-map distance after --diffusion_steps; isomap: kNN-graph geodesic\n"
    "distance. Several methods: the first fills distance,weight, the others add columns.\n"
    "Prints the clip's period (if periodic), the weight at the same and opposite phase of the\n"
    "other cycles, the second difference at the edit and where the weight drops below 0.5/0.05.\n"
    "--plot writes the distance curves (1 - weight) of every method and --sweep sigma as SVG.",
    __FILE__, DistanceMain,
    {SharedOptions("motion,out,skeleton,skeleton_units,amc_fps,animation,sample_fps,report"),
     EditSettingOptions().Only("frame").options(), FalloffSettingOptions().options(), DistanceMethodOption().options(),
     DistancePlotOption().options()}};

}  // namespace mocapsolve
