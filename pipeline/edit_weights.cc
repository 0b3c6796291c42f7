#include "pipeline/edit_weights.h"

#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "io/comma_list.h"
#include "problems/edit_propagation/harmonic_falloff.h"
#include "problems/edit_propagation/pose_features.h"
#include "problems/edit_propagation/spline_falloff.h"
#include "settings/solver_settings.h"

namespace mocapsolve {
namespace {

bool ParseDouble(const std::string& text, double* value) {
  char* stop = nullptr;
  *value = std::strtod(text.c_str(), &stop);
  return !text.empty() && *stop == '\0' && std::isfinite(*value);
}

}  // namespace

Status ParseIkTargets(const std::string& text, const Skeleton& skeleton, std::vector<IkTarget>* targets) {
  targets->clear();
  for (const std::string& item : SplitFields(text, ';')) {
    const size_t colon = item.rfind(':');
    const std::vector<std::string> xyz =
        colon == std::string::npos ? std::vector<std::string>() : SplitFields(item.substr(colon + 1), ',');
    IkTarget target;
    if (colon == std::string::npos || xyz.size() != 3 || !ParseDouble(xyz[0], &target.position.x()) ||
        !ParseDouble(xyz[1], &target.position.y()) || !ParseDouble(xyz[2], &target.position.z())) {
      return Status::Error("--ik_target: expected JOINT:x,y,z, got '" + item + "'");
    }
    target.joint = skeleton.FindJoint(item.substr(0, colon));
    if (target.joint < 0) {
      return Status::Error("--ik_target: unknown joint '" + item.substr(0, colon) + "'");
    }
    targets->push_back(target);
  }
  return Status::Ok();
}

namespace {

Status HarmonicWeights(const Skeleton& skeleton, const Motion& motion, const FalloffOptions& falloff,
                       const std::vector<int>& frames, const EditWeightSettings& settings, EditWeights* out) {
  Eigen::MatrixXd features;
  Status status = PoseFeatures(skeleton, motion, falloff.features, &features);
  if (!status.ok()) return status;
  const int begin = falloff.region_begin;
  const int end = falloff.region_end < 0 ? motion.num_frames() : falloff.region_end;
  const Eigen::MatrixXd region = features.middleRows(begin, end - begin);
  const double sigma =
      falloff.sigma > 0.0 ? falloff.sigma : falloff.sigma_scale * MedianStepDistance(region);
  if (!(sigma > 0.0)) return Status::Error("--sigma: the auto sigma is 0 (a still clip); give --sigma");
  const std::vector<WeightedEdge> edges = PoseGraphEdges(region, falloff.knn, sigma);
  std::vector<int> local_frames;
  for (int frame : frames) local_frames.push_back(frame - begin);
  std::vector<Eigen::VectorXd> fields;
  HarmonicReport harmonic;
  // The ground edge is a fraction of the mean degree, so --harmonic_ground means the same
  // whatever --knn and --sigma make the degrees.
  double degree_sum = 0.0;
  for (const WeightedEdge& edge : edges) degree_sum += 2.0 * edge.kernel;
  const double mean_degree = degree_sum / (end - begin);
  HarmonicOptions options;
  options.ground_weight = settings.harmonic_ground * mean_degree;
  // The solver's declared --sparse_library (settings/solver_settings.h): its check and message.
  Status checked = SolverOptions().Only("sparse_library").options()[0].Check(settings.sparse_library);
  if (!checked.ok()) return checked;
  if (settings.sparse_library == "suite_sparse") options.sparse_library = ceres::SUITE_SPARSE;
  std::string error;
  if (!options.IsValid(&error)) return Status::Error("--harmonic_ground/--sparse_library: " + error);
  // The region's ends are labelled 0 where the region cuts the clip (so the weights reach 0
  // there, without a step), and at the clip's ends too when no ground node pins the field.
  std::vector<int> anchors;
  if (begin > 0 || options.ground_weight == 0.0) anchors.push_back(0);
  if (end < motion.num_frames() || options.ground_weight == 0.0) anchors.push_back(end - begin - 1);
  status = HarmonicFalloffs(end - begin, edges, local_frames, anchors, options, &fields, &harmonic);
  if (!status.ok()) return status;
  out->weights.clear();
  for (const Eigen::VectorXd& field : fields) {
    Eigen::VectorXd w = Eigen::VectorXd::Zero(motion.num_frames());
    w.segment(begin, end - begin) = field.cwiseMax(0.0).cwiseMin(1.0);
    out->weights.push_back(w);
  }
  out->report.Add("sigma", sigma).Add("knn", falloff.knn).Add("graph_edges", harmonic.edges)
      .Add("harmonic_iterations", harmonic.iterations).Add("harmonic_solve_seconds", harmonic.solve_seconds)
      .Add("harmonic_max_gradient", harmonic.max_gradient)
      .Add("harmonic_ground", settings.harmonic_ground).Add("mean_degree", mean_degree)
      .Add("ground_kernel", options.ground_weight);
  return Status::Ok();
}

Status GreenWeights(const Skeleton& skeleton, const Motion& motion, const FalloffOptions& falloff,
                    const std::vector<int>& frames, EditWeights* out) {
  std::vector<Falloff> falloffs;
  Status status = ComputeFalloffs(skeleton, motion, frames, FalloffMethod::kGreen, falloff, &falloffs);
  if (!status.ok()) return status;
  out->weights.clear();
  for (const Falloff& result : falloffs) out->weights.push_back(result.weight);
  out->report.Add("sigma", falloffs[0].sigma_used).Add("eigenpairs", falloffs[0].eigenpairs_used)
      .Add("sparse_kernel", falloffs[0].sparse_used);
  return Status::Ok();
}

Status SplineWeights(const Motion& motion, const FalloffOptions& falloff, const std::vector<int>& frames,
                     const EditWeightSettings& settings, EditWeights* out) {
  if (!(settings.spline_width > 0.0) || !std::isfinite(settings.spline_width)) {
    return Status::Error("--spline_width must be positive");
  }
  out->weights.clear();
  for (int frame : frames) {
    out->weights.push_back(SplineFalloff(motion.num_frames(), frame, settings.spline_width,
                                         falloff.region_begin, falloff.region_end));
  }
  out->report.Add("spline_width", settings.spline_width);
  return Status::Ok();
}

}  // namespace

Status ComputeEditWeights(const std::string& method, const Skeleton& skeleton, const Motion& motion,
                          const FalloffOptions& falloff, const std::vector<int>& frames,
                          const EditWeightSettings& settings, EditWeights* out) {
  *out = EditWeights();
  if (method == "green") return GreenWeights(skeleton, motion, falloff, frames, out);
  if (method == "harmonic") return HarmonicWeights(skeleton, motion, falloff, frames, settings, out);
  if (method == "spline") return SplineWeights(motion, falloff, frames, settings, out);
  return Status::Error("--method: expected green, harmonic or spline, got '" + method + "'");
}


Status ReadPoseEdits(const std::string& path, const Skeleton& skeleton, const Motion& motion,
                     std::vector<PoseEdit>* edits, std::vector<EditFileEntry>* entries) {
  std::vector<EditFileEntry> read;
  Status status = ReadEditFile(path, skeleton, &read);
  if (!status.ok()) return status;
  edits->clear();
  for (const EditFileEntry& entry : read) {
    if (entry.frame >= motion.num_frames()) {
      return Status::Error(entry.where + ": frame: " + std::to_string(entry.frame) +
                           " is past the motion's last frame " + std::to_string(motion.num_frames() - 1));
    }
    PoseOffsets offsets;
    offsets.frame = entry.frame;
    offsets.rotation_offsets = entry.rotation_offsets_rad;
    offsets.root_translation_offset = entry.root_translation_offset;
    PoseEdit edit;
    status = MakeEdit(motion, offsets, &edit);
    if (!status.ok()) return Status::Error(entry.where + ": " + status.message());
    edits->push_back(std::move(edit));
  }
  if (entries != nullptr) *entries = std::move(read);
  return Status::Ok();
}

}  // namespace mocapsolve
