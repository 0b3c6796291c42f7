#include "problems/edit_propagation/foot_contacts.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <memory>

#include <ceres/problem.h>
#include <ceres/solver.h>

#include "kinematics/forward_kinematics.h"
#include "kinematics/marker_set.h"
#include "kinematics/rotation.h"
#include "problems/marker_solve/marker_residual.h"
#include "problems/marker_solve/pose_prior_residual.h"
#include "solvers/right_quaternion_manifold.h"

namespace mocapsolve {

std::vector<int> AutoFootJoints(const Skeleton& skeleton) {
  std::vector<int> joints;
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    std::string name = skeleton.name(j);
    std::transform(name.begin(), name.end(), name.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (name.find("foot") != std::string::npos || name.find("toe") != std::string::npos ||
        name.find("ankle") != std::string::npos) {
      joints.push_back(j);
    }
  }
  return joints;
}

int FootContacts::ContactSamples() const {
  int count = 0;
  for (const auto& flags : in_contact) count += static_cast<int>(std::count(flags.begin(), flags.end(), 1));
  return count;
}

int FootContacts::ContactFrames() const {
  int count = 0;
  for (int f = 0; f < num_frames(); ++f) {
    bool any = false;
    for (const auto& flags : in_contact) any = any || flags[f];
    count += any ? 1 : 0;
  }
  return count;
}

Status DetectFootContacts(const Skeleton& skeleton, const Motion& motion,
                          const FootContactOptions& options, FootContacts* contacts) {
  if (!(options.height_threshold > 0.0) || !std::isfinite(options.height_threshold)) {
    return Status::Error("contact height threshold must be positive");
  }
  if (!(options.speed_threshold > 0.0) || !std::isfinite(options.speed_threshold)) {
    return Status::Error("contact speed threshold must be positive");
  }
  if (!(options.max_gap_seconds >= 0.0) || !(options.min_contact_seconds >= 0.0) ||
      !std::isfinite(options.max_gap_seconds) || !std::isfinite(options.min_contact_seconds)) {
    return Status::Error("contact gap and minimum duration must be >= 0");
  }
  if (options.up_axis < 0 || options.up_axis > 2) return Status::Error("up axis must be 0, 1 or 2");
  if (!(motion.frame_rate > 0.0)) return Status::Error("the motion has no frame rate");
  Status status = ValidateMotion(skeleton, motion);
  if (!status.ok()) return status;
  FootContacts result;
  result.joints = options.joints.empty() ? AutoFootJoints(skeleton) : options.joints;
  if (result.joints.empty()) {
    return Status::Error("no foot joints found by name (foot, toe, ankle); name them with "
                         "--foot_joints");
  }
  for (int j : result.joints) {
    if (j < 0 || j >= skeleton.num_joints()) return Status::Error("foot joint index out of range");
  }
  const int num_frames = motion.num_frames();
  const std::vector<Vector3dVector> clip = ClipJointPositions(skeleton, motion);
  const int num_feet = static_cast<int>(result.joints.size());
  result.in_contact.assign(num_feet, std::vector<char>(num_frames, 0));
  result.positions.assign(num_feet, Vector3dVector(num_frames));
  for (int k = 0; k < num_feet; ++k) {
    const int j = result.joints[k];
    double floor = INFINITY;
    for (int f = 0; f < num_frames; ++f) {
      result.positions[k][f] = clip[f][j];
      floor = std::min(floor, clip[f][j][options.up_axis]);
    }
    for (int f = 0; f < num_frames && num_frames > 1; ++f) {
      const int a = std::max(0, f - 1), b = std::min(num_frames - 1, f + 1);
      const double speed = (clip[b][j] - clip[a][j]).norm() * motion.frame_rate / (b - a);
      const double height = clip[f][j][options.up_axis] - floor;
      result.in_contact[k][f] =
          height <= options.height_threshold && speed <= options.speed_threshold ? 1 : 0;
    }
    // Clean-up: close gaps of at most max_gap frames between contacts, then drop contact
    // runs shorter than min_run frames.
    std::vector<char>& flags = result.in_contact[k];
    const int max_gap = static_cast<int>(std::floor(options.max_gap_seconds * motion.frame_rate));
    const int min_run = static_cast<int>(std::ceil(options.min_contact_seconds * motion.frame_rate));
    for (int f = 0, last = -1; f < num_frames; ++f) {
      if (!flags[f]) continue;
      if (last >= 0 && f - last - 1 <= max_gap) std::fill(flags.begin() + last + 1, flags.begin() + f, 1);
      last = f;
    }
    for (int f = 0; f < num_frames;) {
      if (!flags[f]) {
        ++f;
        continue;
      }
      int end = f;
      while (end < num_frames && flags[end]) ++end;
      if (end - f < min_run) std::fill(flags.begin() + f, flags.begin() + end, 0);
      f = end;
    }
  }
  *contacts = std::move(result);
  return Status::Ok();
}

double MaxContactDrift(const Skeleton& skeleton, const FootContacts& contacts, const Motion& motion) {
  double drift = 0.0;
  FkData fk(skeleton);
  for (int f = 0; f < std::min(contacts.num_frames(), motion.num_frames()); ++f) {
    bool any = false;
    for (const auto& flags : contacts.in_contact) any = any || flags[f];
    if (!any) continue;
    ForwardKinematics(skeleton, motion.frames[f], &fk);
    for (size_t k = 0; k < contacts.joints.size(); ++k) {
      if (!contacts.in_contact[k][f]) continue;
      drift = std::max(drift, (fk.world_positions[contacts.joints[k]] - contacts.positions[k][f]).norm());
    }
  }
  return drift;
}

bool ContactSolveOptions::IsValid(std::string* error) const {
  if (!(contact_weight > 0.0) || !std::isfinite(contact_weight)) {
    *error = "contact weight must be positive";
    return false;
  }
  if (!(prior_weight >= 0.0) || !std::isfinite(prior_weight)) {
    *error = "contact prior weight must be >= 0";
    return false;
  }
  if (!(blend_seconds >= 0.0) || !std::isfinite(blend_seconds)) {
    *error = "contact blend time must be >= 0";
    return false;
  }
  if (max_iterations < 1) {
    *error = "max_iterations must be >= 1";
    return false;
  }
  return true;
}

Status KeepContacts(const Skeleton& skeleton, const FootContacts& contacts,
                    const ContactSolveOptions& options, Motion* motion, ContactSolveReport* report,
                    const std::function<void(int frames_done)>& progress) {
  std::string error;
  if (!options.IsValid(&error)) return Status::Error(error);
  if (contacts.num_frames() != motion->num_frames()) {
    return Status::Error("contacts cover " + std::to_string(contacts.num_frames()) +
                         " frames, the motion has " + std::to_string(motion->num_frames()));
  }
  Status status = ValidateMotion(skeleton, *motion);
  if (!status.ok()) return status;
  const auto start = std::chrono::steady_clock::now();
  ContactSolveReport local;
  local.contact_samples = contacts.ContactSamples();
  local.max_drift_before = MaxContactDrift(skeleton, contacts, *motion);

  // One zero-offset marker per foot joint.
  std::vector<MarkerSpec> specs;
  for (int j : contacts.joints) specs.push_back({skeleton.name(j), {MarkerAttachment{j, 1.0, Eigen::Vector3d::Zero()}}});
  MarkerSet feet;
  status = MarkerSet::Create(skeleton, specs, &feet);
  if (!status.ok()) return status;

  const int num_joints = skeleton.num_joints();
  const int num_feet = static_cast<int>(contacts.joints.size());
  std::vector<double> rotations(4 * num_joints), references(4 * num_joints);
  double translation[3];
  std::vector<Eigen::Vector3d> observed(num_feet);

  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::DENSE_QR;
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.logging_type = ceres::SILENT;
  solver_options.num_threads = 1;

  // solved[j][f]: joint j was an unknown of frame f's re-solve; its correction there is a key.
  const int num_frames = motion->num_frames();
  const Motion propagated = *motion;
  std::vector<std::vector<char>> solved(num_joints, std::vector<char>(num_frames, 0));
  for (int f = 0; f < num_frames; ++f) {
    if (progress) progress(f + 1);
    std::vector<int> active;
    for (int k = 0; k < num_feet; ++k) {
      if (contacts.in_contact[k][f]) active.push_back(k);
    }
    if (active.empty()) continue;
    Pose& pose = motion->frames[f];
    for (int i = 0; i < 3; ++i) translation[i] = pose.translations[0][i];
    for (int j = 0; j < num_joints; ++j) {
      // Temporal coherence: a joint solved at the previous frame starts from, and is pulled
      // toward, this frame's propagated rotation with the previous correction applied.
      Eigen::Quaterniond q = pose.rotations[j].normalized();
      if (f > 0 && solved[j][f - 1]) {
        q = (q * (propagated.frames[f - 1].rotations[j].conjugate() * motion->frames[f - 1].rotations[j]))
                .normalized();
      }
      for (int i = 0; i < 4; ++i) rotations[4 * j + i] = references[4 * j + i] = q.coeffs()[i];
    }
    ceres::Problem::Options problem_options;
    problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem problem(problem_options);
    problem.AddParameterBlock(translation, 3);
    if (options.fix_root) problem.SetParameterBlockConstant(translation);
    std::vector<bool> added(num_joints, false);
    std::vector<double*> blocks;
    for (int k : active) {
      observed[k] = contacts.positions[k][f];
      auto* residual = new MarkerResidual(&skeleton, &feet, k, &observed[k], options.contact_weight);
      blocks.assign(1, translation);
      for (int j : residual->joints()) {
        double* block = &rotations[4 * j];
        if (!added[j]) {
          added[j] = true;
          ceres::Manifold* manifold = RotationManifold(skeleton.rotation_axes(j));
          problem.AddParameterBlock(block, 4, manifold);
          if (manifold == nullptr || (options.fix_root && j == 0)) {
            problem.SetParameterBlockConstant(block);
          } else if (options.prior_weight > 0.0) {
            problem.AddResidualBlock(new RotationPriorResidual(&references[4 * j], options.prior_weight),
                                     nullptr, block);
          }
        }
        blocks.push_back(block);
      }
      problem.AddResidualBlock(residual, nullptr, blocks);
    }
    ceres::Solver::Summary summary;
    ceres::Solve(solver_options, &problem, &summary);
    ++local.frames_solved;
    if (!summary.IsSolutionUsable()) {
      ++local.failed_frames;
      continue;
    }
    for (int i = 0; i < 3; ++i) pose.translations[0][i] = translation[i];
    for (int j = 0; j < num_joints; ++j) {
      if (!added[j] || problem.IsParameterBlockConstant(&rotations[4 * j])) continue;
      pose.rotations[j] = Eigen::Quaterniond(rotations[4 * j + 3], rotations[4 * j],
                                             rotations[4 * j + 1], rotations[4 * j + 2]).normalized();
      solved[j][f] = 1;
    }
  }
  // Blend each joint's correction c(f) = log(q_prop(f)^-1 q(f)) (a local increment) into the
  // frames where it was not solved, so legs do not pop at the ends of contact intervals:
  // between keys a < f < b, c(f) = e(f) ((1 - t) c(a) + t c(b)), t = (f - a) / (b - a), with
  // the envelope e(f) = max(h((f - a) / W), h((b - f) / W)), h the cubic ease 1 -> 0 over
  // W = blend_seconds * frame rate (a missing key contributes nothing).
  const double width = std::max(1.0, options.blend_seconds * motion->frame_rate);
  auto ease = [width](double distance) {
    const double s = distance / width;
    return s >= 1.0 ? 0.0 : 1.0 - s * s * (3.0 - 2.0 * s);
  };
  for (int j = 0; j < num_joints; ++j) {
    std::vector<Eigen::Vector3d> correction(num_frames, Eigen::Vector3d::Zero());
    std::vector<int> keys;
    for (int f = 0; f < num_frames; ++f) {
      if (!solved[j][f]) continue;
      keys.push_back(f);
      correction[f] = LogMap(propagated.frames[f].rotations[j].conjugate() * motion->frames[f].rotations[j]);
    }
    if (keys.empty() || options.blend_seconds <= 0.0) continue;
    size_t next = 0;  // First key > f.
    for (int f = 0; f < num_frames; ++f) {
      while (next < keys.size() && keys[next] <= f) ++next;
      if (solved[j][f]) continue;
      const int a = next > 0 ? keys[next - 1] : -1;
      const int b = next < keys.size() ? keys[next] : -1;
      Eigen::Vector3d c;
      if (a >= 0 && b >= 0) {
        const double t = static_cast<double>(f - a) / (b - a);
        c = std::max(ease(f - a), ease(b - f)) * ((1.0 - t) * correction[a] + t * correction[b]);
      } else if (a >= 0) {
        c = ease(f - a) * correction[a];
      } else {
        c = ease(b - f) * correction[b];
      }
      if (c.squaredNorm() == 0.0) continue;
      motion->frames[f].rotations[j] = (propagated.frames[f].rotations[j] * ExpMap(c)).normalized();
    }
  }
  local.max_drift_after = MaxContactDrift(skeleton, contacts, *motion);
  local.solve_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (report != nullptr) *report = local;
  return Status::Ok();
}

}  // namespace mocapsolve
