// mocapsolve distance --motion=IN --frame=I [--method=green|diffusion|isomap[,...]]
// --out=curve.csv [--plot=curve.svg]: the pose-space falloff of an edit at one frame
// (Dean, Lewis & Chalmers 2018). problems/edit_propagation/falloff.h.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/falloff_flags.h"
#include "io/atomic_file.h"
#include "io/motion_file.h"
#include "io/svg_plot.h"
#include "problems/edit_propagation/falloff.h"
#include "problems/edit_propagation/falloff_analysis.h"
#include "problems/edit_propagation/isomap_distance.h"
#include "problems/edit_propagation/pose_features.h"
#include "problems/edit_propagation/pose_kernel.h"

DEFINE_int32(frame, -1, "The edited frame (0-based).");
DEFINE_string(sweep, "", "Comma-separated extra sigmas: adds a Green's weight column (and plot "
              "line) per sigma (section 4's sigma sweep).");
DECLARE_string(method);  // apps/blend_command.cc; here green|diffusion|isomap, comma-separated.
DECLARE_string(plot);    // apps/solve_command.cc.

namespace mocapsolve {
namespace {

using Clock = std::chrono::steady_clock;
double MsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

std::vector<std::string> Split(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) items.push_back(item);
  if (!text.empty() && text.back() == ',') items.push_back("");
  return items;
}

std::vector<double> ToStd(const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

std::vector<JsonValue> Ints(const std::vector<int>& values) {
  return std::vector<JsonValue>(values.begin(), values.end());
}

struct MethodResult {
  FalloffMethod method;
  Falloff falloff;
  double ms = 0.0;  // Row/weights (Green, diffusion) or graph + Dijkstra (ISOMAP).
};

Status RunDistance(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  if (FLAGS_motion.empty() || FLAGS_out.empty() || FLAGS_frame < 0) {
    return Status::Error("--motion, --frame (>= 0) and --out are required");
  }
  if (!IsTextOutputPath(FLAGS_out, ".csv")) return Status::Error(FLAGS_out + ": expected a .csv");
  Status status = CheckNotAnInput(FLAGS_out, FLAGS_motion);
  if (!status.ok()) return status;
  if (!FLAGS_plot.empty()) {
    if (!IsTextOutputPath(FLAGS_plot, ".svg")) return Status::Error(FLAGS_plot + ": expected a .svg");
    status = CheckNotAnInput(FLAGS_plot, FLAGS_motion);
    if (!status.ok()) return status;
  }
  const std::string method_text = FLAGS_method;
  std::vector<FalloffMethod> methods;
  for (const std::string& name : Split(method_text)) {
    FalloffMethod m;
    if (!ParseFalloffMethod(name, &m)) {
      return Status::Error("--method: expected green, diffusion or isomap (comma-separated), got '" +
                           name + "'");
    }
    methods.push_back(m);
  }
  if (methods.empty()) return Status::Error("--method: empty");
  std::vector<double> sweep;
  for (const std::string& item : Split(FLAGS_sweep)) {
    char* stop = nullptr;
    const double s = std::strtod(item.c_str(), &stop);
    if (item.empty() || *stop != '\0' || !std::isfinite(s) || !(s > 0.0)) {
      return Status::Error("--sweep: '" + item + "' is not a sigma > 0");
    }
    sweep.push_back(s);
  }

  Skeleton skeleton;
  Motion motion;
  status = LoadMotion(FLAGS_motion, &skeleton, &motion);
  if (status.ok()) status = RequireFrames(FLAGS_motion, motion);
  if (!status.ok()) return status;
  const int n = motion.num_frames();
  if (n < 3) return Status::Error(FLAGS_motion + ": a falloff needs at least 3 frames, got " + std::to_string(n));
  if (FLAGS_frame >= n) {
    return Status::Error("--frame: " + std::to_string(FLAGS_frame) + " is outside " + FLAGS_motion +
                         "'s frames 0.." + std::to_string(n - 1));
  }
  FalloffOptions options;
  status = FalloffOptionsFromFlags(n, &options);
  if (!status.ok()) return status;
  int begin = 0, end = 0;
  status = ResolveRegion(n, FLAGS_frame, options.region_begin, options.region_end, &begin, &end);
  if (!status.ok()) return Status::Error("--region/--frame: " + status.message());
  const int frame = FLAGS_frame;

  auto start = Clock::now();
  Eigen::MatrixXd features;
  status = PoseFeatures(skeleton, motion, options.features, &features);
  if (!status.ok()) return Status::Error("--feature_joints/--joint_weights: " + status.message());
  const double features_ms = MsSince(start);

  GreenFunction green;
  double build_ms = 0.0;
  bool spectral = false;
  for (FalloffMethod m : methods) spectral = spectral || m != FalloffMethod::kIsomap;
  if (spectral) {
    start = Clock::now();
    status = green.Build(features, options);
    if (!status.ok()) return Status::Error("--" + status.message());
    build_ms = MsSince(start);
  }
  std::vector<MethodResult> results;
  for (FalloffMethod m : methods) {
    MethodResult r{m, {}, 0.0};
    start = Clock::now();
    if (m == FalloffMethod::kGreen) {
      green.Weights(frame, begin, end, &r.falloff);
    } else if (m == FalloffMethod::kDiffusion) {
      Eigen::VectorXd d;
      green.DiffusionDistance(frame, options.diffusion_steps, &d);
      FalloffFromDistance(d, frame, begin, end, &r.falloff);
      r.falloff.sigma_used = green.sigma_used();
      r.falloff.eigenpairs_used = green.eigenpairs_used();
      r.falloff.sparse_used = green.sparse_used();
    } else {
      FalloffFromDistance(GeodesicDistances(PoseNeighbourGraph(features, options.isomap_knn), frame), frame,
                          begin, end, &r.falloff);
      r.falloff.sparse_used = true;
    }
    r.ms = MsSince(start);
    results.push_back(std::move(r));
  }
  std::vector<Falloff> swept(sweep.size());
  for (size_t s = 0; s < sweep.size(); ++s) {
    FalloffOptions o = options;
    o.sigma = sweep[s];
    GreenFunction g;
    status = g.Build(features, o);
    if (!status.ok()) return Status::Error("--sweep=" + std::to_string(sweep[s]) + ": " + status.message());
    g.Weights(frame, begin, end, &swept[s]);
  }

  // CSV: frame,distance,weight of the first method, then the others' distances and the
  // sweep's weights.
  std::ostringstream csv;
  csv.precision(9);
  csv << "frame,distance,weight";
  for (size_t k = 1; k < results.size(); ++k) csv << "," << FalloffMethodName(results[k].method) << "_distance";
  for (double s : sweep) csv << ",weight_sigma_" << s;
  csv << "\n";
  for (int j = 0; j < n; ++j) {
    csv << j << "," << results[0].falloff.distance[j] << "," << results[0].falloff.weight[j];
    for (size_t k = 1; k < results.size(); ++k) csv << "," << results[k].falloff.distance[j];
    for (const Falloff& f : swept) csv << "," << f.weight[j];
    csv << "\n";
  }
  status = WriteFileAtomically(FLAGS_out, csv.str());
  if (!status.ok()) return status;
  if (!FLAGS_plot.empty()) {
    std::vector<PlotSeries> series;
    for (const MethodResult& r : results) series.push_back({FalloffMethodName(r.method) + " distance", ToStd(r.falloff.distance)});
    for (size_t s = 0; s < sweep.size(); ++s) {
      std::ostringstream name;
      name << "green distance, sigma " << sweep[s];
      series.push_back({name.str(), ToStd(swept[s].distance)});
    }
    status = WriteFileAtomically(FLAGS_plot, LinePlotSvg("Pose distance from frame " + std::to_string(frame) +
                                                             " (" + FLAGS_motion + ")",
                                                         "frame", "normalized distance", series));
    if (!status.ok()) return status;
  }

  // Figures: cycles, smoothness at the edit, where the falloff ends.
  const int period = DetectPosePeriod(features);
  const PhaseFrames phases = FindPhaseFrames(features, frame, period);
  JsonObject report;
  report.Add("motion", FLAGS_motion).Add("frames", n).Add("frame", frame)
      .Add("region_begin", begin).Add("region_end", end)
      .Add("feature_dims", static_cast<int>(features.cols()))
      .Add("period_frames", period).Add("same_phase_frames", Ints(phases.same))
      .Add("opposite_phase_frames", Ints(phases.opposite));
  if (spectral) {
    report.Add("sigma_used", green.sigma_used()).Add("eigenpairs_used", green.eigenpairs_used())
        .Add("kernel", green.sparse_used() ? "sparse" : "dense")
        .Add("lanczos_restarts", green.eigenpairs().lanczos_iterations);
  }
  report.Add("features_ms", features_ms).Add("build_ms", build_ms);
  std::printf("%s: %d frames, edit at frame %d, region %d:%d, period %d frames\n", FLAGS_motion.c_str(), n,
              frame, begin, end, period);
  std::vector<JsonObject> per_method;
  for (const MethodResult& r : results) {
    const Falloff& f = r.falloff;
    double min_same = 1.0, max_opposite = 0.0;
    std::vector<JsonValue> same_w, opposite_w;
    for (int j : phases.same) same_w.push_back(f.weight[j]), min_same = std::min(min_same, f.weight[j]);
    for (int j : phases.opposite) opposite_w.push_back(f.weight[j]), max_opposite = std::max(max_opposite, f.weight[j]);
    JsonObject m;
    m.Add("method", FalloffMethodName(r.method)).Add("ms", r.ms)
        .Add("second_difference", SecondDifference(f.weight, frame))
        .Add("kink_ratio", KinkRatio(f.weight, frame))
        .Add("slope_before", frame > 0 ? f.weight[frame] - f.weight[frame - 1] : NAN)
        .Add("slope_after", frame + 1 < n ? f.weight[frame + 1] - f.weight[frame] : NAN)
        .Add("end_before_0.5", FalloffEnd(f.weight, frame, -1, 0.5))
        .Add("end_after_0.5", FalloffEnd(f.weight, frame, +1, 0.5))
        .Add("end_before_0.05", FalloffEnd(f.weight, frame, -1, 0.05))
        .Add("end_after_0.05", FalloffEnd(f.weight, frame, +1, 0.05))
        .Add("same_phase_weights", same_w).Add("opposite_phase_weights", opposite_w);
    if (!phases.same.empty()) m.Add("min_same_phase_weight", min_same);
    if (!phases.opposite.empty()) m.Add("max_opposite_phase_weight", max_opposite);
    per_method.push_back(m);
    std::printf("%-9s second difference at the edit %.3g (kink ratio %.2f: 0.67 smooth, 2 corner); weight < 0.5 at frames %d/%d, < 0.05 at %d/%d "
                "(-1: never)",
                FalloffMethodName(r.method).c_str(), SecondDifference(f.weight, frame),
                KinkRatio(f.weight, frame),
                FalloffEnd(f.weight, frame, -1, 0.5), FalloffEnd(f.weight, frame, +1, 0.5),
                FalloffEnd(f.weight, frame, -1, 0.05), FalloffEnd(f.weight, frame, +1, 0.05));
    if (!phases.same.empty()) {
      std::printf("; same phase min weight %.3f, opposite phase max %.3f", min_same, max_opposite);
    }
    std::printf("\n");
  }
  report.Add("methods", per_method);
  std::vector<JsonObject> per_sigma;
  for (size_t s = 0; s < sweep.size(); ++s) {
    const Falloff& f = swept[s];
    double min_same = 1.0, max_opposite = 0.0;
    for (int j : phases.same) min_same = std::min(min_same, f.weight[j]);
    for (int j : phases.opposite) max_opposite = std::max(max_opposite, f.weight[j]);
    JsonObject o;
    o.Add("sigma", sweep[s]).Add("eigenpairs_used", f.eigenpairs_used)
        .Add("second_difference", SecondDifference(f.weight, frame))
        .Add("kink_ratio", KinkRatio(f.weight, frame))
        .Add("end_before_0.05", FalloffEnd(f.weight, frame, -1, 0.05))
        .Add("end_after_0.05", FalloffEnd(f.weight, frame, +1, 0.05));
    if (!phases.same.empty()) o.Add("min_same_phase_weight", min_same);
    if (!phases.opposite.empty()) o.Add("max_opposite_phase_weight", max_opposite);
    per_sigma.push_back(o);
    std::printf("sigma %-7.4g weight < 0.05 at frames %d/%d", sweep[s], FalloffEnd(f.weight, frame, -1, 0.05),
                FalloffEnd(f.weight, frame, +1, 0.05));
    if (!phases.same.empty()) {
      std::printf("; same phase min weight %.3f, opposite phase max %.3f", min_same, max_opposite);
    }
    std::printf("\n");
  }
  if (!sweep.empty()) report.Add("sweep", per_sigma);
  if (spectral) {
    std::printf("sigma %.4g (%s), %d eigenpairs, %s kernel; features %.1f ms, build %.1f ms\n",
                green.sigma_used(), options.sigma > 0.0 ? "given" : "auto", green.eigenpairs_used(),
                green.sparse_used() ? "sparse kNN" : "dense", features_ms, build_ms);
  }
  std::printf("wrote %s%s%s\n", FLAGS_out.c_str(), FLAGS_plot.empty() ? "" : " and ", FLAGS_plot.c_str());
  return WriteReport(report);
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
    __FILE__, RunDistance,
    "motion,out,plot,method,skeleton,skeleton_units,amc_fps,animation,sample_fps,report,quiet",
    {FalloffSettingOptions().options()},
    {{"method", "green",
      "green | diffusion | isomap, comma-separated for several: the distances to compute (the first fills "
      "distance,weight; the others add columns)."},
     {"plot", "", "Write the distance curves (1 - weight) of every method and of --sweep as SVG."}}};

}  // namespace mocapsolve
