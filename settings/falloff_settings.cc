#include "settings/falloff_settings.h"

#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

namespace mocapsolve {

const OptionGroup<FalloffSettings>& FalloffSettingOptions() {
  using S = FalloffSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::sigma, "sigma", "rad",
           "Kernel width of eq. 1 in pose-vector units (radians); 0 = auto: "
           "--sigma_scale times the median frame-to-frame pose distance.")
      .Add(&S::sigma_scale, "sigma_scale", "",
           "Auto sigma = this times the median frame-to-frame pose distance.")
      .Add(&S::eigenpairs, "eigenpairs", "eigenpairs",
           "Terms of the Green's function sum (eq. 3): the smallest nonzero "
           "eigenpairs of the pose Laplacian; 0 = all (dense kernel only).")
      .Add(&S::region, "region",
           "Edited region a:b (frames, b exclusive; either side may be empty): "
           "weights are normalized over it and are 0 outside. Empty = the whole clip.")
      .Add(&S::diffusion_steps, "diffusion_steps", "steps",
           "Diffusion-map steps t for --method=diffusion.")
      .Add(&S::knn, "knn", "poses",
           "Nearest poses per frame in the sparse (kNN) kernel.")
      .Add(&S::isomap_knn, "isomap_knn", "poses",
           "Nearest poses per frame in the ISOMAP graph (--method=isomap).")
      .Add(&S::falloff_kernel, "falloff_kernel",
           "auto (sparse kNN kernel above 1000 frames), dense or sparse.",
           {"auto", "dense", "sparse"})
      .Add(&S::feature_joints, "feature_joints",
           "Comma-separated joints of the pose vector; empty = every "
           "rotating joint.")
      .Add(&S::joint_weights, "joint_weights",
           "Comma-separated weights, one per --feature_joints entry.")
      .Add(&S::temporal_weight, "temporal_weight", "",
           "Adds temporal_weight * time (s) to the pose vector "
           "(radians per second; section 3.1's temporal distance term).")
      .Add(&S::sweep, "sweep",
           "Comma-separated extra sigmas: adds a Green's weight column (and plot line) per sigma (section 4's "
           "sigma sweep).");
  return *group;
}
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

Status FalloffOptionsFromSettings(const FalloffSettings& settings, int num_frames, FalloffOptions* options) {
  Status checked = FalloffSettingOptions().Validate(settings);
  if (!checked.ok()) return checked;
  options->sigma = settings.sigma;
  options->sigma_scale = settings.sigma_scale;
  options->eigenpairs = settings.eigenpairs;
  options->diffusion_steps = settings.diffusion_steps;
  options->knn = settings.knn;
  options->isomap_knn = settings.isomap_knn;
  // One of the declared choices (checked above).
  options->kernel = settings.falloff_kernel == "dense"    ? KernelMode::kDense
                    : settings.falloff_kernel == "sparse" ? KernelMode::kSparse
                                                          : KernelMode::kAuto;
  options->region_begin = 0;
  options->region_end = -1;
  if (!settings.region.empty()) {
    const size_t colon = settings.region.find(':');
    const std::string a = colon == std::string::npos ? "" : settings.region.substr(0, colon);
    const std::string b = colon == std::string::npos ? "" : settings.region.substr(colon + 1);
    int begin = 0, end = num_frames;
    if (colon == std::string::npos || (!a.empty() && !ParseInt(a, &begin)) ||
        (!b.empty() && !ParseInt(b, &end)) || begin < 0 || end > num_frames || begin >= end) {
      return Status::Error("--region: expected a:b with 0 <= a < b <= " + std::to_string(num_frames) +
                           " (frames, b exclusive), got '" + settings.region + "'");
    }
    options->region_begin = begin;
    options->region_end = end;
  }
  options->features.joints = SplitCommas(settings.feature_joints);
  options->features.joint_weights.clear();
  for (const std::string& item : SplitCommas(settings.joint_weights)) {
    char* stop = nullptr;
    const double w = std::strtod(item.c_str(), &stop);
    if (item.empty() || *stop != '\0' || !std::isfinite(w) || w < 0.0) {
      return Status::Error("--joint_weights: '" + item + "' is not a number >= 0");
    }
    options->features.joint_weights.push_back(w);
  }
  options->features.temporal_weight = settings.temporal_weight;
  std::string error;
  if (!options->IsValid(&error)) return Status::Error("--" + error);
  return Status::Ok();
}

}  // namespace mocapsolve
