#include "apps/falloff_flags.h"

#include <cmath>
#include <cstdlib>
#include <string>

#include <gflags/gflags.h>

DEFINE_double(sigma, 0.0, "Kernel width of eq. 1 in pose-vector units (radians); 0 = auto: "
              "--sigma_scale times the median frame-to-frame pose distance.");
DEFINE_double(sigma_scale, 4.0, "Auto sigma = this times the median frame-to-frame pose distance.");
DEFINE_int32(eigenpairs, 10, "Terms of the Green's function sum (eq. 3): the smallest nonzero "
             "eigenpairs of the pose Laplacian; 0 = all (dense kernel only).");
DEFINE_string(region, "", "Edited region a:b (frames, b exclusive; either side may be empty): "
              "weights are normalized over it and are 0 outside. Empty = the whole clip.");
DEFINE_int32(diffusion_steps, 10, "Diffusion-map steps t for --method=diffusion.");
DEFINE_int32(knn, 30, "Nearest poses per frame in the sparse (kNN) kernel.");
DEFINE_int32(isomap_knn, 10, "Nearest poses per frame in the ISOMAP graph (--method=isomap).");
DEFINE_string(falloff_kernel, "auto", "auto (sparse kNN kernel above 1000 frames), dense or sparse.");
DEFINE_string(feature_joints, "", "Comma-separated joints of the pose vector; empty = every "
              "rotating joint.");
DEFINE_string(joint_weights, "", "Comma-separated weights, one per --feature_joints entry.");
DEFINE_double(temporal_weight, 0.0, "Adds temporal_weight * time (s) to the pose vector "
              "(radians per second; section 3.1's temporal distance term).");

namespace mocapsolve {
namespace {

std::vector<std::string> SplitCommas(const std::string& text) {
  std::vector<std::string> items;
  if (text.empty()) return items;
  size_t begin = 0;
  while (true) {
    const size_t end = text.find(',', begin);
    std::string item = text.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
    // Names pasted from files may carry spaces or a CR; joint names never do.
    const size_t first = item.find_first_not_of(" \t\r\n");
    const size_t last = item.find_last_not_of(" \t\r\n");
    items.push_back(first == std::string::npos ? "" : item.substr(first, last - first + 1));
    if (end == std::string::npos) break;
    begin = end + 1;
  }
  return items;
}

bool ParseInt(const std::string& text, int* value) {
  char* stop = nullptr;
  const long v = std::strtol(text.c_str(), &stop, 10);
  if (text.empty() || *stop != '\0' || v < -1000000000L || v > 1000000000L) return false;
  *value = static_cast<int>(v);
  return true;
}

}  // namespace

const char kFalloffFlagNames[] =
    "sigma,sigma_scale,eigenpairs,region,diffusion_steps,knn,isomap_knn,falloff_kernel,feature_joints,"
    "joint_weights,temporal_weight";

Status FalloffOptionsFromFlags(int num_frames, FalloffOptions* options) {
  options->sigma = FLAGS_sigma;
  options->sigma_scale = FLAGS_sigma_scale;
  options->eigenpairs = FLAGS_eigenpairs;
  options->diffusion_steps = FLAGS_diffusion_steps;
  options->knn = FLAGS_knn;
  options->isomap_knn = FLAGS_isomap_knn;
  if (FLAGS_falloff_kernel == "auto") options->kernel = KernelMode::kAuto;
  else if (FLAGS_falloff_kernel == "dense") options->kernel = KernelMode::kDense;
  else if (FLAGS_falloff_kernel == "sparse") options->kernel = KernelMode::kSparse;
  else return Status::Error("--falloff_kernel: expected auto, dense or sparse, got '" + FLAGS_falloff_kernel + "'");
  options->region_begin = 0;
  options->region_end = -1;
  if (!FLAGS_region.empty()) {
    const size_t colon = FLAGS_region.find(':');
    const std::string a = colon == std::string::npos ? "" : FLAGS_region.substr(0, colon);
    const std::string b = colon == std::string::npos ? "" : FLAGS_region.substr(colon + 1);
    int begin = 0, end = num_frames;
    if (colon == std::string::npos || (!a.empty() && !ParseInt(a, &begin)) ||
        (!b.empty() && !ParseInt(b, &end)) || begin < 0 || end > num_frames || begin >= end) {
      return Status::Error("--region: expected a:b with 0 <= a < b <= " + std::to_string(num_frames) +
                           " (frames, b exclusive), got '" + FLAGS_region + "'");
    }
    options->region_begin = begin;
    options->region_end = end;
  }
  options->features.joints = SplitCommas(FLAGS_feature_joints);
  options->features.joint_weights.clear();
  for (const std::string& item : SplitCommas(FLAGS_joint_weights)) {
    char* stop = nullptr;
    const double w = std::strtod(item.c_str(), &stop);
    if (item.empty() || *stop != '\0' || !std::isfinite(w) || w < 0.0) {
      return Status::Error("--joint_weights: '" + item + "' is not a number >= 0");
    }
    options->features.joint_weights.push_back(w);
  }
  options->features.temporal_weight = FLAGS_temporal_weight;
  std::string error;
  if (!options->IsValid(&error)) return Status::Error("--" + error);
  return Status::Ok();
}

}  // namespace mocapsolve
