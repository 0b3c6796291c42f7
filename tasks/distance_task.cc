#include "tasks/distance_task.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "problems/edit_propagation/falloff_analysis.h"
#include "problems/edit_propagation/isomap_distance.h"
#include "problems/edit_propagation/pose_features.h"
#include "problems/edit_propagation/pose_kernel.h"

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

Status ParseInputs(const DistanceConfig& config, std::vector<FalloffMethod>* methods, std::vector<double>* sweep) {
  for (const std::string& name : Split(config.methods)) {
    FalloffMethod m;
    if (!ParseFalloffMethod(name, &m)) {
      return Status::Error("--method: expected green, diffusion or isomap (comma-separated), got '" + name + "'");
    }
    methods->push_back(m);
  }
  if (methods->empty()) return Status::Error("--method: empty");
  for (const std::string& item : Split(config.falloff.sweep)) {
    char* stop = nullptr;
    const double s = std::strtod(item.c_str(), &stop);
    if (item.empty() || *stop != '\0' || !std::isfinite(s) || !(s > 0.0)) {
      return Status::Error("--sweep: '" + item + "' is not a sigma > 0");
    }
    sweep->push_back(s);
  }
  return Status::Ok();
}

FalloffFigures Figures(const std::string& name, const Eigen::VectorXd& w, int frame, const DistanceResult& r) {
  FalloffFigures f;
  f.name = name;
  const int n = static_cast<int>(w.size());
  f.second_difference = SecondDifference(w, frame);
  f.kink_ratio = KinkRatio(w, frame);
  f.slope_before = frame > 0 ? w[frame] - w[frame - 1] : NAN;
  f.slope_after = frame + 1 < n ? w[frame + 1] - w[frame] : NAN;
  f.end_before_05 = FalloffEnd(w, frame, -1, 0.5);
  f.end_after_05 = FalloffEnd(w, frame, +1, 0.5);
  f.end_before_005 = FalloffEnd(w, frame, -1, 0.05);
  f.end_after_005 = FalloffEnd(w, frame, +1, 0.05);
  for (int j : r.same_phase) f.min_same_phase_weight = std::min(f.min_same_phase_weight, w[j]);
  for (int j : r.opposite_phase) f.max_opposite_phase_weight = std::max(f.max_opposite_phase_weight, w[j]);
  return f;
}

std::string Csv(const DistanceResult& r) {
  std::ostringstream csv;
  csv.precision(9);
  csv << "frame,distance,weight";
  for (size_t k = 1; k < r.methods.size(); ++k) csv << "," << r.method_names[k] << "_distance";
  for (double s : r.sweep) csv << ",weight_sigma_" << s;
  csv << "\n";
  for (int j = 0; j < r.frames; ++j) {
    csv << j << "," << r.methods[0].distance[j] << "," << r.methods[0].weight[j];
    for (size_t k = 1; k < r.methods.size(); ++k) csv << "," << r.methods[k].distance[j];
    for (const Falloff& f : r.swept) csv << "," << f.weight[j];
    csv << "\n";
  }
  return csv.str();
}

JsonObject ReportJson(const std::string& motion_name, const Eigen::MatrixXd& features, const DistanceResult& r) {
  const std::vector<JsonValue> same(r.same_phase.begin(), r.same_phase.end());
  const std::vector<JsonValue> opposite(r.opposite_phase.begin(), r.opposite_phase.end());
  JsonObject report;
  report.Add("motion", motion_name).Add("frames", r.frames).Add("frame", r.frame)
      .Add("region_begin", r.region_begin).Add("region_end", r.region_end)
      .Add("feature_dims", static_cast<int>(features.cols()))
      .Add("period_frames", r.period).Add("same_phase_frames", same).Add("opposite_phase_frames", opposite);
  if (r.spectral) {
    report.Add("sigma_used", r.sigma_used).Add("eigenpairs_used", r.eigenpairs_used)
        .Add("kernel", r.sparse_kernel ? "sparse" : "dense");
  }
  return report;
}

}  // namespace

Status RunDistance(const Skeleton& skeleton, const Motion& motion, const std::string& motion_name,
                   const DistanceConfig& config, DistanceResult* result) {
  *result = DistanceResult();
  DistanceResult& r = *result;
  std::vector<FalloffMethod> methods;
  Status status = ParseInputs(config, &methods, &r.sweep);
  if (!status.ok()) return status;
  if (config.frame < 0) return Status::Error("--frame: expected a frame index >= 0, got " + std::to_string(config.frame));
  const int n = motion.num_frames();
  if (n < 3) return Status::Error(motion_name + ": a falloff needs at least 3 frames, got " + std::to_string(n));
  if (config.frame >= n) {
    return Status::Error("--frame: " + std::to_string(config.frame) + " is outside " + motion_name + "'s frames 0.." +
                         std::to_string(n - 1));
  }
  FalloffOptions options;
  status = FalloffOptionsFromSettings(config.falloff, n, &options);
  if (!status.ok()) return status;
  r.frames = n;
  r.frame = config.frame;
  status = ResolveRegion(n, r.frame, options.region_begin, options.region_end, &r.region_begin, &r.region_end);
  if (!status.ok()) return Status::Error("--region/--frame: " + status.message());

  auto start = Clock::now();
  Eigen::MatrixXd features;
  status = PoseFeatures(skeleton, motion, options.features, &features);
  if (!status.ok()) return Status::Error("--feature_joints/--joint_weights: " + status.message());
  r.features_ms = MsSince(start);
  GreenFunction green;
  for (FalloffMethod m : methods) r.spectral = r.spectral || m != FalloffMethod::kIsomap;
  if (r.spectral) {
    start = Clock::now();
    status = green.Build(features, options);
    if (!status.ok()) return Status::Error("--" + status.message());
    r.build_ms = MsSince(start);
    r.sigma_used = green.sigma_used();
    r.eigenpairs_used = green.eigenpairs_used();
    r.sparse_kernel = green.sparse_used();
  }
  std::vector<double> ms;
  for (FalloffMethod m : methods) {
    Falloff f;
    start = Clock::now();
    if (m == FalloffMethod::kGreen) {
      green.Weights(r.frame, r.region_begin, r.region_end, &f);
    } else if (m == FalloffMethod::kDiffusion) {
      Eigen::VectorXd d;
      green.DiffusionDistance(r.frame, options.diffusion_steps, &d);
      FalloffFromDistance(d, r.frame, r.region_begin, r.region_end, &f);
      f.sigma_used = green.sigma_used();
      f.eigenpairs_used = green.eigenpairs_used();
      f.sparse_used = green.sparse_used();
    } else {
      FalloffFromDistance(GeodesicDistances(PoseNeighbourGraph(features, options.isomap_knn), r.frame), r.frame,
                          r.region_begin, r.region_end, &f);
      f.sparse_used = true;
    }
    ms.push_back(MsSince(start));
    r.methods.push_back(std::move(f));
    r.method_names.push_back(FalloffMethodName(m));
  }
  for (double sigma : r.sweep) {
    FalloffOptions o = options;
    o.sigma = sigma;
    GreenFunction g;
    status = g.Build(features, o);
    if (!status.ok()) return Status::Error("--sweep=" + std::to_string(sigma) + ": " + status.message());
    r.swept.emplace_back();
    g.Weights(r.frame, r.region_begin, r.region_end, &r.swept.back());
  }

  // Figures: cycles, smoothness at the edit, where the falloff ends.
  r.period = DetectPosePeriod(features);
  const PhaseFrames phases = FindPhaseFrames(features, r.frame, r.period);
  r.same_phase = phases.same;
  r.opposite_phase = phases.opposite;
  r.report = ReportJson(motion_name, features, r);
  if (r.spectral) r.report.Add("lanczos_restarts", green.eigenpairs().lanczos_iterations);
  r.report.Add("features_ms", r.features_ms).Add("build_ms", r.build_ms);
  std::vector<JsonObject> per_method, per_sigma;
  for (size_t k = 0; k < r.methods.size(); ++k) {
    const Falloff& f = r.methods[k];
    r.method_figures.push_back(Figures(r.method_names[k], f.weight, r.frame, r));
    FalloffFigures& g = r.method_figures.back();
    g.ms = ms[k];
    std::vector<JsonValue> same_w, opposite_w;
    for (int j : r.same_phase) same_w.push_back(f.weight[j]);
    for (int j : r.opposite_phase) opposite_w.push_back(f.weight[j]);
    JsonObject m;
    m.Add("method", g.name).Add("ms", g.ms).Add("second_difference", g.second_difference)
        .Add("kink_ratio", g.kink_ratio).Add("slope_before", g.slope_before).Add("slope_after", g.slope_after)
        .Add("end_before_0.5", g.end_before_05).Add("end_after_0.5", g.end_after_05)
        .Add("end_before_0.05", g.end_before_005).Add("end_after_0.05", g.end_after_005)
        .Add("same_phase_weights", same_w).Add("opposite_phase_weights", opposite_w);
    if (!r.same_phase.empty()) m.Add("min_same_phase_weight", g.min_same_phase_weight);
    if (!r.opposite_phase.empty()) m.Add("max_opposite_phase_weight", g.max_opposite_phase_weight);
    per_method.push_back(m);
  }
  r.report.Add("methods", per_method);
  for (size_t s = 0; s < r.sweep.size(); ++s) {
    std::ostringstream name;
    name << "sigma " << r.sweep[s];
    r.sweep_figures.push_back(Figures(name.str(), r.swept[s].weight, r.frame, r));
    const FalloffFigures& g = r.sweep_figures.back();
    JsonObject o;
    o.Add("sigma", r.sweep[s]).Add("eigenpairs_used", r.swept[s].eigenpairs_used)
        .Add("second_difference", g.second_difference).Add("kink_ratio", g.kink_ratio)
        .Add("end_before_0.05", g.end_before_005).Add("end_after_0.05", g.end_after_005);
    if (!r.same_phase.empty()) o.Add("min_same_phase_weight", g.min_same_phase_weight);
    if (!r.opposite_phase.empty()) o.Add("max_opposite_phase_weight", g.max_opposite_phase_weight);
    per_sigma.push_back(o);
  }
  if (!r.sweep.empty()) r.report.Add("sweep", per_sigma);
  r.csv = Csv(r);
  return Status::Ok();
}

}  // namespace mocapsolve
