#include "apps/falloff_flags.h"

#include <gflags/gflags.h>

#include "settings/falloff_settings.h"

namespace {
// The flags' defaults are the settings' (settings/falloff_settings.h): one source.
const mocapsolve::FalloffSettings kDefault;
}  // namespace

DEFINE_double(sigma, kDefault.sigma, "Kernel width of eq. 1 in pose-vector units (radians); 0 = auto: "
              "--sigma_scale times the median frame-to-frame pose distance.");
DEFINE_double(sigma_scale, kDefault.sigma_scale, "Auto sigma = this times the median frame-to-frame pose distance.");
DEFINE_int32(eigenpairs, kDefault.eigenpairs, "Terms of the Green's function sum (eq. 3): the smallest nonzero "
             "eigenpairs of the pose Laplacian; 0 = all (dense kernel only).");
DEFINE_string(region, kDefault.region.c_str(), "Edited region a:b (frames, b exclusive; either side may be empty): "
              "weights are normalized over it and are 0 outside. Empty = the whole clip.");
DEFINE_int32(diffusion_steps, kDefault.diffusion_steps, "Diffusion-map steps t for --method=diffusion.");
DEFINE_int32(knn, kDefault.knn, "Nearest poses per frame in the sparse (kNN) kernel.");
DEFINE_int32(isomap_knn, kDefault.isomap_knn, "Nearest poses per frame in the ISOMAP graph (--method=isomap).");
DEFINE_string(falloff_kernel, kDefault.falloff_kernel.c_str(), "auto (sparse kNN kernel above 1000 frames), dense or sparse.");
DEFINE_string(feature_joints, kDefault.feature_joints.c_str(), "Comma-separated joints of the pose vector; empty = every "
              "rotating joint.");
DEFINE_string(joint_weights, kDefault.joint_weights.c_str(), "Comma-separated weights, one per --feature_joints entry.");
DEFINE_double(temporal_weight, kDefault.temporal_weight, "Adds temporal_weight * time (s) to the pose vector "
              "(radians per second; section 3.1's temporal distance term).");

namespace mocapsolve {

Status FalloffOptionsFromFlags(int num_frames, FalloffOptions* options) {
  FalloffSettings s;
  s.sigma = FLAGS_sigma;
  s.sigma_scale = FLAGS_sigma_scale;
  s.eigenpairs = FLAGS_eigenpairs;
  s.region = FLAGS_region;
  s.diffusion_steps = FLAGS_diffusion_steps;
  s.knn = FLAGS_knn;
  s.isomap_knn = FLAGS_isomap_knn;
  s.falloff_kernel = FLAGS_falloff_kernel;
  s.feature_joints = FLAGS_feature_joints;
  s.joint_weights = FLAGS_joint_weights;
  s.temporal_weight = FLAGS_temporal_weight;
  return FalloffOptionsFromSettings(s, num_frames, options);
}

}  // namespace mocapsolve
