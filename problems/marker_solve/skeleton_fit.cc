#include "problems/marker_solve/skeleton_fit.h"

#include <algorithm>
#include <cctype>
#include <limits>
#include <string>

#include <Eigen/Cholesky>

#include "kinematics/forward_kinematics.h"
#include "kinematics/kinematic_jacobians.h"
#include "problems/marker_solve/sequence_solver.h"
#include "problems/marker_solve/subject_checks.h"

namespace mocapsolve {
namespace {

using Observations = std::vector<std::vector<Eigen::Vector3d>>;

// Column of each joint's scale: its own, or its left/right twin's.
std::vector<int> ScaleColumns(const Skeleton& skeleton, bool symmetric) {
  std::vector<int> column(skeleton.num_joints());
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    column[j] = j;
    if (!symmetric) continue;
    const std::string key = SideFreeName(skeleton.name(j));
    const char side = static_cast<char>(std::tolower(static_cast<unsigned char>(skeleton.name(j)[0])));
    if (side != 'l' && side != 'r') continue;
    for (int i = 0; i < j; ++i) {
      const char other = static_cast<char>(std::tolower(static_cast<unsigned char>(skeleton.name(i)[0])));
      if (other != side && (other == 'l' || other == 'r') && SideFreeName(skeleton.name(i)) == key) {
        column[j] = column[i];
        break;
      }
    }
  }
  return column;
}

// Step 2: one Gauss-Newton step on the scales (one per scale column) and the marker
// offsets (3 per attachment), with every frame's pose free to first order: per frame the
// pose columns B (root translation + rotation dofs) are eliminated (Schur complement),
//   S += A^T A - A^T B (B^T B + mu I)^-1 B^T A,   g += A^T r - A^T B (B^T B + mu I)^-1 B^T r,
// with A the columns of the globals and r = predicted - observed, so the step accounts
// for how the poses will move when the lengths change (plain alternation, poses held,
// converges linearly and slowly where lengths and offsets trade off).
Status FitLengthsAndOffsets(const Skeleton& skeleton, const MarkerSet& markers, const Observations& observed,
                            const Motion& motion, const SkeletonFitOptions& options, double damping,
                            const std::vector<double>& total_scale, const MarkerSet& prior_markers,
                            std::vector<double>* scales, std::vector<MarkerSpec>* specs) {
  const int joints = skeleton.num_joints();
  const std::vector<int> scale_column = ScaleColumns(skeleton, options.symmetric);
  std::vector<int> z_column(markers.num_markers());
  int unknowns = joints;  // Column a = scale of joint a (column 0, the root, is unused).
  for (int m = 0; m < markers.num_markers(); ++m) {
    z_column[m] = unknowns;
    unknowns += 3 * static_cast<int>(markers.marker(m).attachments.size());
  }
  // The pose columns: the root translation, then each rotation dof (local axis).
  std::vector<int> pose_tangent_column;  // Into the kinematic PoseJacobian.
  for (int c = 0; c < 3; ++c) pose_tangent_column.push_back(c);
  for (int j = 0; j < joints; ++j) {
    for (int axis : skeleton.rotation_axes(j)) pose_tangent_column.push_back(RotationColumn(j) + axis);
  }
  const int pose_columns = static_cast<int>(pose_tangent_column.size());
  Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(unknowns, unknowns);
  Eigen::VectorXd gradient = Eigen::VectorXd::Zero(unknowns);
  FkData fk(skeleton);
  Eigen::MatrixXd a, b;
  Eigen::VectorXd r;
  PoseJacobian point_jacobian(3, PoseTangentSize(skeleton));
  std::vector<BlendTerm> terms;
  int frames_used = 0;
  for (size_t f = 0; f < observed.size(); f += std::max(1, options.frame_step)) {
    std::vector<int> seen;
    for (int m = 0; m < markers.num_markers(); ++m) {
      if (observed[f][m].allFinite()) seen.push_back(m);
    }
    if (seen.size() < 2) continue;
    ++frames_used;
    ForwardKinematics(skeleton, motion.frames[f], &fk);
    a.setZero(3 * seen.size(), unknowns);
    b.resize(3 * seen.size(), pose_columns);
    r.resize(3 * seen.size());
    for (size_t i = 0; i < seen.size(); ++i) {
      const int m = seen[i];
      const MarkerSpec& spec = markers.marker(m);
      for (size_t k = 0; k < spec.attachments.size(); ++k) {
        const MarkerAttachment& at = spec.attachments[k];
        for (int joint = at.joint; joint > 0; joint = skeleton.parent(joint)) {
          const Eigen::Matrix3d parent_rotation = fk.world_rotations[skeleton.parent(joint)].toRotationMatrix();
          a.block<3, 1>(3 * i, scale_column[joint]) += at.weight * parent_rotation * skeleton.offset(joint);
        }
        a.block<3, 3>(3 * i, z_column[m] + 3 * static_cast<int>(k)) +=
            at.weight * fk.world_rotations[at.joint].toRotationMatrix();
      }
      point_jacobian.setZero();
      markers.BlendTerms(m, fk, &terms);
      AccumulateBlendedPointJacobian(skeleton, fk, terms, &point_jacobian);
      for (int c = 0; c < pose_columns; ++c) b.block<3, 1>(3 * i, c) = point_jacobian.col(pose_tangent_column[c]);
      r.segment<3>(3 * i) = markers.Position(m, fk) - observed[f][m];
    }
    Eigen::MatrixXd btb = b.transpose() * b;
    btb.diagonal().array() += 1e-9 * std::max(1.0, btb.diagonal().maxCoeff());
    const Eigen::LDLT<Eigen::MatrixXd> pose_block(btb);
    const Eigen::MatrixXd bta = b.transpose() * a;
    normal.noalias() += a.transpose() * a - bta.transpose() * pose_block.solve(bta);
    gradient.noalias() += a.transpose() * r - bta.transpose() * pose_block.solve(b.transpose() * r);
  }
  // Ridge toward "no change" on the scales (a relative weight), a whisper on the rest,
  // and Levenberg-Marquardt damping on everything.
  const double ridge = options.scale_ridge * std::max(1e-12, normal.diagonal().head(joints).maxCoeff());
  for (int c = 0; c < joints; ++c) normal(c, c) += ridge;
  // Offsets pulled toward the fit's starting ones: w * frames * |z - z_prior|^2.
  if (options.offset_prior_weight > 0.0) {
    const double weight = options.offset_prior_weight * frames_used;
    for (int m = 0; m < markers.num_markers(); ++m) {
      const MarkerSpec& spec = markers.marker(m);
      const MarkerSpec& prior = prior_markers.marker(m);
      for (size_t k = 0; k < spec.attachments.size() && k < prior.attachments.size(); ++k) {
        const int column = z_column[m] + 3 * static_cast<int>(k);
        normal.block<3, 3>(column, column).diagonal().array() += weight;
        gradient.segment<3>(column) += weight * (spec.attachments[k].offset - prior.attachments[k].offset);
      }
    }
  }
  for (int c = 0; c < unknowns; ++c) normal(c, c) += damping * normal(c, c) + 1e-12 * std::max(1.0, normal(c, c));
  const Eigen::VectorXd step = normal.ldlt().solve(-gradient);
  if (!step.allFinite()) return Status::Error("skeleton fit: the length/offset system is singular");
  scales->assign(joints, 1.0);
  for (int joint = 1; joint < joints; ++joint) {
    // Bounded relative to the template: total_scale * step in [min_scale, max_scale].
    (*scales)[joint] = std::clamp(1.0 + step(scale_column[joint]), options.min_scale / total_scale[joint],
                                  options.max_scale / total_scale[joint]);
  }
  specs->clear();
  for (int m = 0; m < markers.num_markers(); ++m) {
    MarkerSpec spec = markers.marker(m);
    for (size_t k = 0; k < spec.attachments.size(); ++k) {
      spec.attachments[k].offset += step.segment<3>(z_column[m] + 3 * static_cast<int>(k));
    }
    specs->push_back(spec);
  }
  return Status::Ok();
}

Status ScaledSkeleton(const Skeleton& skeleton, const std::vector<double>& scales, Skeleton* out) {
  std::vector<JointSpec> joints;
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    joints.push_back(skeleton.joint(j));
    joints.back().offset *= scales[j];
  }
  std::vector<EndSite> sites = skeleton.end_sites();
  for (EndSite& site : sites) {
    double sum = 0.0;
    int children = 0;
    for (int c = site.parent + 1; c < skeleton.num_joints(); ++c) {
      if (skeleton.parent(c) == site.parent) sum += scales[c], ++children;
    }
    site.offset *= children > 0 ? sum / children : scales[site.parent];
  }
  return Skeleton::Create(std::move(joints), std::move(sites), skeleton.unit(), out);
}

// A marker's outlier gate: at least this many times its median residual, so a marker that
// misses by a lot in every frame (a rough fresh attachment: squat.c3d's round 1 starts at
// 59 mm) is fitted, not cut; a ghost or swap misses by many times its marker's median.
constexpr double kOutlierMedianFactor = 5.0;

// The samples of `observed` farther than max(distance, kOutlierMedianFactor x their marker's
// median residual) from their marker on `motion` (frame, marker).
std::vector<std::pair<int, int>> FarSamples(const Skeleton& skeleton, const MarkerSet& markers,
                                            const Observations& observed, const Motion& motion, double distance) {
  const size_t frames = std::min(observed.size(), motion.frames.size());
  std::vector<std::vector<double>> residual(markers.num_markers(), std::vector<double>(frames, -1.0));
  FkData fk(skeleton);
  for (size_t f = 0; f < frames; ++f) {
    ForwardKinematics(skeleton, motion.frames[f], &fk);
    for (int m = 0; m < markers.num_markers(); ++m) {
      if (observed[f][m].allFinite()) residual[m][f] = (markers.Position(m, fk) - observed[f][m]).norm();
    }
  }
  std::vector<std::pair<int, int>> far;
  for (int m = 0; m < markers.num_markers(); ++m) {
    std::vector<double> seen;
    for (double r : residual[m]) {
      if (r >= 0.0) seen.push_back(r);
    }
    if (seen.empty()) continue;
    std::nth_element(seen.begin(), seen.begin() + seen.size() / 2, seen.end());
    const double gate = std::max(distance, kOutlierMedianFactor * seen[seen.size() / 2]);
    for (size_t f = 0; f < frames; ++f) {
      if (residual[m][f] > gate) far.push_back({static_cast<int>(f), m});
    }
  }
  std::sort(far.begin(), far.end());
  return far;
}

}  // namespace

Status FitSkeletonToMarkers(const Skeleton& skeleton, const MarkerSet& markers, const Observations& all_observed,
                            const MarkerSolveOptions& solve_options, const SkeletonFitOptions& options,
                            Skeleton* fitted_skeleton, MarkerSet* fitted_markers, Motion* motion,
                            SkeletonFitReport* report, const SkeletonFitProgress& progress,
                            const std::function<void(int step, int frames_done)>& frame_progress) {
  *report = SkeletonFitReport();
  if (options.iterations < 0 || options.frame_step < 1 || !(options.min_scale > 0.0) ||
      !(options.max_scale >= options.min_scale)) {
    return Status::Error("skeleton fit: bad options");
  }
  Skeleton current = skeleton;
  MarkerSet current_markers = markers;
  std::vector<double> total_scale = options.initial_scales;
  if (total_scale.empty()) total_scale.assign(skeleton.num_joints(), 1.0);
  if (static_cast<int>(total_scale.size()) != skeleton.num_joints()) return Status::Error("skeleton fit: bad options");
  // Each attachment's skin radius: max_bone_distance, or its distance at the start when
  // that is farther (a marker the given set holds outside the tube stays where it is
  // trusted to be, so the first step cannot be worse for a clamp alone).
  const std::vector<bool>& held = options.held_limbs;
  std::vector<std::vector<double>> radius(markers.num_markers());
  for (int m = 0; m < markers.num_markers(); ++m) {
    for (const MarkerAttachment& a : markers.marker(m).attachments) {
      radius[m].push_back(options.max_bone_distance > 0.0
                              ? std::max(options.max_bone_distance, DistanceToBone(skeleton, a.joint, a.offset, held))
                              : 0.0);
    }
  }
  // SolveSequence's progress, told which step its solve belongs to.
  int step = 0;
  const std::function<void(int)> solve_progress =
      frame_progress ? std::function<void(int)>([&](int frames_done) { frame_progress(step, frames_done); })
                     : nullptr;
  SequenceSolveReport solve;
  Observations observed = all_observed;
  Status status = SolveSequence(current, current_markers, observed, solve_options, RestPose(current), motion, &solve,
                                solve_progress, options.root_from_markers);
  if (!status.ok()) return status;
  // Outliers of the first solve are left out and the poses solved again: without the pull of
  // a ghost, more of them stand out (3 passes at most; each is one more pose solve).
  for (int pass = 0; pass < 3 && options.outlier_distance > 0.0; ++pass) {
    const std::vector<std::pair<int, int>> far =
        FarSamples(current, current_markers, observed, *motion, options.outlier_distance);
    if (far.empty()) break;
    for (const auto& [f, m] : far) observed[f][m].setConstant(std::numeric_limits<double>::quiet_NaN());
    report->outliers.insert(report->outliers.end(), far.begin(), far.end());
    status = SolveSequence(current, current_markers, observed, solve_options, RestPose(current), motion, &solve,
                           solve_progress, options.root_from_markers);
    if (!status.ok()) return status;
  }
  double rms = solve.rms_marker_error;
  report->rms.push_back(rms);
  // Levenberg-Marquardt on the globals: a step is kept only if the pose solve on the
  // new skeleton fits better; otherwise the damping grows and the step is retried.
  double damping = 1e-3;
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
    step = iteration + 1;
    std::vector<double> scales;
    std::vector<MarkerSpec> specs;
    status = FitLengthsAndOffsets(current, current_markers, observed, *motion, options, damping, total_scale,
                                  markers, &scales, &specs);
    if (!status.ok()) return status;
    Skeleton next;
    status = ScaledSkeleton(current, scales, &next);
    if (!status.ok()) return status;
    if (options.max_bone_distance > 0.0) {
      for (size_t m = 0; m < specs.size(); ++m) {
        for (size_t k = 0; k < specs[m].attachments.size(); ++k) {
          MarkerAttachment& a = specs[m].attachments[k];
          a.offset = ClampToBone(next, a.joint, a.offset, radius[m][k], held);
        }
      }
    }
    MarkerSet next_markers;
    status = MarkerSet::Create(next, std::move(specs), &next_markers);
    if (!status.ok()) return status;
    Motion next_motion;
    status = SolveSequence(next, next_markers, observed, solve_options, RestPose(next), &next_motion, &solve,
                           solve_progress, options.root_from_markers);
    if (progress) progress(iteration + 1, solve.rms_marker_error);
    if (!status.ok()) return status;
    if (solve.rms_marker_error < rms) {
      current = std::move(next);
      current_markers = std::move(next_markers);
      *motion = std::move(next_motion);
      rms = solve.rms_marker_error;
      for (int j = 0; j < skeleton.num_joints(); ++j) total_scale[j] *= scales[j];
      damping = std::max(1e-12, damping / 10.0);
    } else {
      damping *= 10.0;
    }
    report->rms.push_back(rms);
  }
  *fitted_skeleton = current;
  *fitted_markers = current_markers;
  report->bone_scales = total_scale;
  return Status::Ok();
}

}  // namespace mocapsolve
