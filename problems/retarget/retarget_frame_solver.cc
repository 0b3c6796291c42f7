#include "problems/retarget/retarget_frame_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>

#include <ceres/problem.h>
#include <Eigen/Cholesky>
#include <glog/logging.h>

#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "kinematics/skinning.h"
#include "problems/marker_solve/joint_limit_residual.h"
#include "problems/marker_solve/marker_frame_solver.h"
#include "problems/marker_solve/pose_prior_residual.h"
#include "problems/retarget/foot_plant_residual.h"
#include "problems/retarget/tracked_vertex_residual.h"
#include "solvers/block_sparse_cholesky.h"
#include "solvers/dls_solver.h"
#include "solvers/right_quaternion_manifold.h"

namespace mocapsolve {
namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point from, Clock::time_point to) {
  return std::chrono::duration<double>(to - from).count();
}

// The root translation's chart in units of sigma: Plus(t, d) = t + sigma d. With it the
// translation columns of J are on the scale of the (normalized) rotation columns, so a
// fixed damping lambda damps both alike (thesis 4.3.3 normalizes GP_t by sigma).
class ScaledEuclideanManifold : public ceres::Manifold {
 public:
  explicit ScaledEuclideanManifold(double scale) : scale_(scale) {}
  int AmbientSize() const override { return 3; }
  int TangentSize() const override { return 3; }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override {
    for (int i = 0; i < 3; ++i) x_plus_delta[i] = x[i] + scale_ * delta[i];
    return true;
  }
  bool PlusJacobian(const double*, double* jacobian) const override {
    Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> j(jacobian);
    j = scale_ * Eigen::Matrix3d::Identity();
    return true;
  }
  bool Minus(const double* y, const double* x, double* y_minus_x) const override {
    for (int i = 0; i < 3; ++i) y_minus_x[i] = (y[i] - x[i]) / scale_;
    return true;
  }
  bool MinusJacobian(const double*, double* jacobian) const override {
    Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> j(jacobian);
    j = Eigen::Matrix3d::Identity() / scale_;
    return true;
  }

 private:
  double scale_;
};

}  // namespace

bool ParseRetargetSolverKind(const std::string& name, RetargetSolverKind* kind) {
  if (name == "dls") return *kind = RetargetSolverKind::kDls, true;
  if (name == "dls_generic") return *kind = RetargetSolverKind::kDlsGeneric, true;
  if (name == "ceres") return *kind = RetargetSolverKind::kCeres, true;
  return false;
}

const char* RetargetSolverName(RetargetSolverKind kind) {
  switch (kind) {
    case RetargetSolverKind::kDls: return "dls";
    case RetargetSolverKind::kDlsGeneric: return "dls_generic";
    case RetargetSolverKind::kCeres: return "ceres";
  }
  return "?";
}

bool RetargetSolveOptions::IsValid(std::string* error) const {
  if (iterations < 1) return *error = "iterations must be >= 1", false;
  if (!(lambda >= 0.0) || !std::isfinite(lambda)) return *error = "lambda must be >= 0", false;
  if (!(position_weight > 0.0) || !(normal_weight >= 0.0)) {
    return *error = "position weight must be > 0 and normal weight >= 0", false;
  }
  if (!(smoothness_weight >= 0.0) || !(limit_weight >= 0.0) || !(plant_weight >= 0.0)) {
    return *error = "smoothness, limit and plant weights must be >= 0", false;
  }
  if (solver == RetargetSolverKind::kCeres && !ceres.IsValid(error)) return false;
  return true;
}

ceres::Solver::Options DefaultRetargetCeresOptions() {
  // The per-frame marker solve's options (small dense problems), capped at Algorithm 4's
  // 10 iterations.
  ceres::Solver::Options options = DefaultFrameCeresOptions();
  options.max_num_iterations = 10;
  return options;
}

void TrackedVertexErrors(const Skeleton& skeleton, const SkinnedMesh& mesh,
                         const RetargetSetup& setup, const Pose& pose,
                         const Eigen::Matrix3Xd& goal_positions, const Eigen::Matrix3Xd& goal_normals,
                         double* mean_position_error, double* mean_normal_angle) {
  FkData fk(skeleton);
  ForwardKinematics(skeleton, pose, &fk);
  std::vector<Eigen::Isometry3d> transforms;
  ComputeSkinningTransforms(mesh, fk, &transforms);
  double position = 0.0, angle = 0.0;
  const int nt = static_cast<int>(setup.tracked.size());
  for (int s = 0; s < nt; ++s) {
    const int v = setup.tracked[s].target_vertex;
    position += (SkinPosition(mesh, transforms, v) - goal_positions.col(s)).norm();
    const Eigen::Vector3d n = SkinNormal(mesh, transforms, v);
    const Eigen::Vector3d m = goal_normals.col(s);
    angle += std::atan2(n.cross(m).norm(), n.dot(m));
  }
  *mean_position_error = nt > 0 ? position / nt : 0.0;
  *mean_normal_angle = nt > 0 ? angle / nt : 0.0;
}

class RetargetFrameSolver::Impl {
 public:
  Impl(const Skeleton& skeleton, const SkinnedMesh& mesh, const RetargetSetup& setup, double sigma,
       const RetargetSolveOptions& options)
      : skeleton_(skeleton), mesh_(mesh), setup_(setup), sigma_(sigma), options_(options),
        translation_manifold_(sigma) {
    std::string error;
    CHECK(options.IsValid(&error)) << error;
    CHECK_GT(sigma, 0.0);
    const int nj = skeleton.num_joints();
    const int nt = static_cast<int>(setup.tracked.size());
    const int np = static_cast<int>(options.plant_joints.size());
    rotations_.assign(4 * nj, 0.0);
    reference_rotations_.assign(4 * nj, 0.0);
    goals_.assign(nt + np, Eigen::Vector3d::Zero());
    plant_scales_.assign(np, 0.0);
    column_.assign(nj, -1);
    std::vector<bool> solved(nj, false);
    for (int s = 0; s < nt; ++s) {
      const TrackedVertex& t = setup.tracked[s];
      const double scale =
          t.track_position ? options.position_weight / sigma : options.normal_weight;
      residuals_.emplace_back(
          new TrackedVertexResidual(&skeleton, &mesh, t.target_vertex, t.track_position, &goals_[s], scale));
      for (int j : residuals_.back()->joints()) solved[j] = true;
    }
    for (int p = 0; p < np; ++p) {
      const int k = options.plant_joints[p];
      CHECK(k >= 0 && k < nj) << "plant joint " << k;
      plant_residuals_.emplace_back(new FootPlantResidual(&skeleton, k, &goals_[nt + p], &plant_scales_[p]));
      for (int j : plant_residuals_.back()->joints()) solved[j] = true;
    }
    int n = 3;
    for (int j = 0; j < nj; ++j) {
      if (solved[j]) {
        column_[j] = n;
        solved_joints_.push_back(j);
        n += 3;
      }
    }
    // Extra single-block residuals: priors and limits (marker_solve's, reused).
    if (options.smoothness_weight > 0.0) {
      translation_prior_.reset(
          new TranslationPriorResidual(reference_translation_.data(), options.smoothness_weight / sigma));
      for (int j : solved_joints_) {
        extras_.push_back({std::unique_ptr<ceres::CostFunction>(new RotationPriorResidual(
                               &reference_rotations_[4 * j], options.smoothness_weight)),
                           j});
      }
    }
    if (options.limit_weight > 0.0) {
      for (int j : solved_joints_) {
        if (skeleton.rotation_limits(j).empty()) continue;
        extras_.push_back({std::unique_ptr<ceres::CostFunction>(new JointLimitResidual(
                               skeleton.rotation_axes(j), skeleton.rotation_limits(j),
                               options.limit_weight)),
                           j});
      }
    }
    int extra_rows = translation_prior_ ? 3 : 0;
    for (const Extra& extra : extras_) extra_rows += extra.cost->num_residuals();

    // Lean kernel: flattened rows.
    for (int s = 0; s < nt; ++s) {
      const TrackedVertexResidual& residual = *residuals_[s];
      Row row;
      row.track_position = residual.track_position();
      row.scale = residual.scale();
      row.chain = residual.joints();
      const int v = residual.vertex();
      for (int k = mesh.weight_begin(v); k < mesh.weight_end(v); ++k) {
        const int b = mesh.weight_joint(k);
        const Eigen::Isometry3d& joint_from_bind = mesh.joint_from_bind(b);
        row.joints.push_back(b);
        row.weights.push_back(mesh.weight(k));
        row.locals.push_back(row.track_position
                                 ? Eigen::Vector3d(joint_from_bind * mesh.rest_positions().col(v))
                                 : Eigen::Vector3d(joint_from_bind.linear() * mesh.rest_normals().col(v)));
        row.total_weight += mesh.weight(k);
      }
      rows_.push_back(std::move(row));
    }
    // Plants: a position row of weight 1 on the foot joint at zero offset (its scale is
    // switched by SetPlants).
    for (int p = 0; p < np; ++p) {
      Row row;
      row.track_position = true;
      row.scale = 0.0;
      row.chain = plant_residuals_[p]->joints();
      row.joints = {plant_residuals_[p]->joint()};
      row.weights = {1.0};
      row.locals = {Eigen::Vector3d::Zero()};
      row.total_weight = 1.0;
      rows_.push_back(std::move(row));
    }
    const int nr = nt + np;
    jacobian_ = Eigen::MatrixXd::Zero(3 * nr + extra_rows, n);
    if (jacobian_.rows() >= n) BuildNormalPattern();
    residual_.resize(3 * nr + extra_rows);
    world_rotations_.resize(nj);
    world_positions_.resize(nj);

    if (options.solver == RetargetSolverKind::kCeres) BuildCeres();
    if (options.solver == RetargetSolverKind::kDlsGeneric) BuildDls();
  }

  void SetPlants(const Eigen::Matrix3Xd& anchors, const std::vector<char>& active) {
    const int nt = static_cast<int>(setup_.tracked.size());
    const int np = static_cast<int>(plant_scales_.size());
    CHECK_EQ(anchors.cols(), np);
    CHECK_EQ(static_cast<int>(active.size()), np);
    for (int p = 0; p < np; ++p) {
      goals_[nt + p] = anchors.col(p);
      plant_scales_[p] = active[p] ? options_.plant_weight / sigma_ : 0.0;
      rows_[nt + p].scale = plant_scales_[p];
    }
  }

  Status Solve(const Eigen::Matrix3Xd& goal_positions, const Eigen::Matrix3Xd& goal_normals,
               Pose* pose, RetargetFrameReport* report) {
    const int nt = static_cast<int>(setup_.tracked.size());
    if (goal_positions.cols() != nt || goal_normals.cols() != nt) {
      return Status::Error("retarget: goal count differs from the tracked vertex count");
    }
    SetGoals(goal_positions, goal_normals);
    SetParameters(*pose);
    reference_rotations_ = rotations_;
    reference_translation_ = translation_;
    RetargetFrameReport result;
    switch (options_.solver) {
      case RetargetSolverKind::kDls:
        if (!SolveLean(&result)) return Status::Error("retarget: the DLS solve failed (non-finite step)");
        break;
      case RetargetSolverKind::kDlsGeneric: {
        DlsSummary summary;
        DlsOptions dls;
        dls.max_iterations = options_.iterations;
        dls.adaptive_damping = false;
        dls.lambda = options_.lambda;
        dls.function_tolerance = dls.gradient_tolerance = dls.parameter_tolerance = 0.0;
        dls_solver_.Solve(dls, &dls_problem_, &summary);
        if (!summary.IsSolutionUsable()) return Status::Error("retarget: DLS failed: " + summary.BriefReport());
        result.initial_cost = summary.initial_cost;
        result.final_cost = summary.final_cost;
        result.iterations = summary.iterations;
        break;
      }
      case RetargetSolverKind::kCeres: {
        ceres::Solver::Options ceres_options = options_.ceres;
        ceres_options.max_num_iterations = options_.iterations;
        ceres::Solver::Summary summary;
        ceres::Solve(ceres_options, ceres_problem_.get(), &summary);
        if (!summary.IsSolutionUsable()) return Status::Error("retarget: Ceres failed: " + summary.BriefReport());
        result.initial_cost = summary.initial_cost;
        result.final_cost = summary.final_cost;
        result.iterations = static_cast<int>(summary.iterations.size()) - 1;
        break;
      }
    }
    GetParameters(pose);
    if (!translation_.allFinite()) return Status::Error("retarget: the solve produced a non-finite pose");
    if (report != nullptr) {
      TrackedVertexErrors(skeleton_, mesh_, setup_, *pose, goal_positions, goal_normals,
                          &result.mean_position_error, &result.mean_normal_angle);
      *report = result;
    }
    return Status::Ok();
  }

  void Linearize(const Eigen::Matrix3Xd& goal_positions, const Eigen::Matrix3Xd& goal_normals,
                 const Pose& pose, Eigen::VectorXd* residual, Eigen::MatrixXd* jacobian) {
    SetGoals(goal_positions, goal_normals);
    SetParameters(pose);
    reference_rotations_ = rotations_;
    reference_translation_ = translation_;
    Fk();
    SkinAndLinearize(true);
    const int nt = static_cast<int>(rows_.size());  // Tracked vertices, then plants.
    *residual = residual_.head(3 * nt);
    jacobian->setZero(3 * nt, PoseTangentColumns());
    jacobian->leftCols<3>() = jacobian_.topLeftCorner(3 * nt, 3) / sigma_;  // Back to units.
    for (int j : solved_joints_) {
      jacobian->middleCols<3>(3 + 3 * j) = jacobian_.block(0, column_[j], 3 * nt, 3);
    }
  }

  RetargetStageTimes times;

 private:
  struct Row {
    bool track_position = false;
    double scale = 1.0;
    double total_weight = 0.0;
    std::vector<int> chain;
    std::vector<int> joints;
    std::vector<double> weights;
    std::vector<Eigen::Vector3d> locals;
    // Normal-equation kernel: per chain joint, which influences lie in its subtree (bit k
    // = influence k) and their summed weight (the cumulative weight, 4.3.5); the row's
    // blocks (0 = translation, for position rows only) and, for each pair of them
    // (a >= b, a-major), the index of the pair's accumulator.
    std::vector<uint32_t> subtree_masks;
    std::vector<double> cumulative;
    std::vector<int> blocks;
    std::vector<int> pair_index;  // Pairs (a, b) with a a partial block, see AccumulateNormal.
    int full = 0;   // The first `full` chain joints hold all the influences in their subtree.
    int group = -1;  // Group of rows sharing those joints and the mode.
    int term_offset = 0;
  };
  // Rows that share their full chain joints (the ancestors of the influences' lowest common
  // ancestor) and their mode: their contributions to the pairs of those joints are
  // accumulated through moments (AccumulateNormal).
  struct Group {
    bool track_position = false;
    std::vector<int> blocks;      // [0 (translation, positions only)] + the full joints' blocks.
    std::vector<int> joints;      // The joint of each block (-1 for the translation).
    std::vector<int> pair_index;  // (a, b), a >= b over `blocks`, a-major.
    double s0 = 0.0;              // Positions: sum s^2 W^2.
    Eigen::Vector3d s1, g1, g2;   // sum s^2 W x, sum s^2 W (x - g), sum s^2 (x - g) x x.
    Eigen::Matrix3d s2;           // Positions: sum s^2 x x^T; normals: sum s^2 n n^T.
  };
  struct Extra {
    std::unique_ptr<ceres::CostFunction> cost;
    int joint;
  };

  int PoseTangentColumns() const { return 3 + 3 * skeleton_.num_joints(); }

  void SetGoals(const Eigen::Matrix3Xd& goal_positions, const Eigen::Matrix3Xd& goal_normals) {
    for (size_t s = 0; s < setup_.tracked.size(); ++s) {
      goals_[s] = setup_.tracked[s].track_position ? goal_positions.col(s) : goal_normals.col(s);
    }
  }

  void SetParameters(const Pose& pose) {
    translation_ = pose.translations[0];
    for (int j = 0; j < skeleton_.num_joints(); ++j) {
      Eigen::Map<Eigen::Vector4d> q(rotations_.data() + 4 * j);
      q = pose.rotations[j].normalized().coeffs();
    }
  }

  void GetParameters(Pose* pose) const {
    pose->translations[0] = translation_;
    for (int j : solved_joints_) {
      pose->rotations[j].coeffs() = Eigen::Map<const Eigen::Vector4d>(&rotations_[4 * j]).normalized();
    }
  }

  void Fk() {
    for (int j = 0; j < skeleton_.num_joints(); ++j) {
      Eigen::Quaterniond local = Eigen::Map<const Eigen::Quaterniond>(&rotations_[4 * j]);
      if (skeleton_.has_rest_rotation(j)) local = skeleton_.rest_rotation(j) * local;
      const Eigen::Matrix3d local_matrix = local.toRotationMatrix();
      const int p = skeleton_.parent(j);
      if (p < 0) {
        world_rotations_[j] = local_matrix;
        world_positions_[j] = translation_;
      } else {
        world_positions_[j] = world_positions_[p] + world_rotations_[p] * skeleton_.offset(j);
        world_rotations_[j] = world_rotations_[p] * local_matrix;
      }
    }
  }

  // One tracked vertex at the current FK: its residual scale * (x - goal), with x the
  // weighted sum of its influences' terms (p_b = R_b y_b + o_b, or R_b y_b for a normal),
  // which are written to terms[] for the Jacobian.
  Eigen::Vector3d SkinRow(const Row& row, const Eigen::Vector3d& goal, Eigen::Vector3d* terms) const {
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (size_t k = 0; k < row.joints.size(); ++k) {
      const int b = row.joints[k];
      terms[k] = world_rotations_[b] * row.locals[k];
      if (row.track_position) terms[k] += world_positions_[b];
      x += row.weights[k] * terms[k];
    }
    return row.scale * (x - goal);
  }

  // Residual rows of the tracked vertices (and, if `jacobian`, their J blocks).
  void SkinAndLinearize(bool jacobian) {
    Eigen::Vector3d terms[32];
    const int nt = static_cast<int>(rows_.size());
    for (int s = 0; s < nt; ++s) {
      const Row& row = rows_[s];
      const int ni = static_cast<int>(row.joints.size());
      residual_.segment<3>(3 * s) = SkinRow(row, goals_[s], terms);
      if (!jacobian) continue;
      if (row.track_position) {
        jacobian_.block<3, 3>(3 * s, 0) =
            (row.scale * row.total_weight * sigma_) * Eigen::Matrix3d::Identity();
      }
      for (int j : row.chain) {
        Eigen::Vector3d lever = Eigen::Vector3d::Zero();
        for (int k = 0; k < ni; ++k) {
          if (skeleton_.IsAncestorOrSelf(j, row.joints[k])) {
            lever += row.weights[k] *
                     (row.track_position ? Eigen::Vector3d(world_positions_[j] - terms[k])
                                         : Eigen::Vector3d(-terms[k]));
          }
        }
        jacobian_.block<3, 3>(3 * s, column_[j]).noalias() =
            row.scale * SkewSymmetric(lever) * world_rotations_[j];
      }
    }
  }

  // Prior and limit rows after the tracked ones.
  bool LinearizeExtras() {
    int row = 3 * static_cast<int>(rows_.size());
    if (translation_prior_) {
      const double* parameters[] = {translation_.data()};
      Eigen::Matrix<double, 3, 3, Eigen::RowMajor> jt;
      double* jacobians[] = {jt.data()};
      if (!translation_prior_->Evaluate(parameters, residual_.data() + row, jacobians)) return false;
      jacobian_.block<3, 3>(row, 0) = sigma_ * jt;
      row += 3;
    }
    for (const Extra& extra : extras_) {
      const int k = extra.cost->num_residuals();
      const double* parameters[] = {&rotations_[4 * extra.joint]};
      Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor> ambient(k, 4);
      double* jacobians[] = {ambient.data()};
      if (!extra.cost->Evaluate(parameters, residual_.data() + row, jacobians)) return false;
      jacobian_.block(row, column_[extra.joint], k, 3) =
          ambient * QuaternionPlusJacobian(&rotations_[4 * extra.joint]);
      row += k;
    }
    return true;
  }

  bool SolveLean(RetargetFrameReport* report) {
    const int m = static_cast<int>(jacobian_.rows());
    const int n = static_cast<int>(jacobian_.cols());
    if (m >= n) return SolveNormal(report);
    Clock::time_point t0, t1;
    const bool timed = options_.time_stages;
    for (int iteration = 0; iteration <= options_.iterations; ++iteration) {
      const bool last = iteration == options_.iterations;
      if (timed) t0 = Clock::now();
      Fk();
      if (timed) {
        t1 = Clock::now();
        times.fk += Seconds(t0, t1);
        t0 = t1;
      }
      double skinning_seconds = 0.0;
      if (timed && !last) {
        // Skinning alone, timed apart from the Jacobian (the kernel fuses them, so the
        // Jacobian's share is the fused pass minus this one).
        SkinAndLinearize(false);
        t1 = Clock::now();
        skinning_seconds = Seconds(t0, t1);
        times.skinning += skinning_seconds;
        t0 = t1;
      }
      SkinAndLinearize(!last);
      if (!LinearizeExtras()) return false;
      const double cost = 0.5 * residual_.squaredNorm();
      if (iteration == 0) report->initial_cost = cost;
      if (last) {
        report->final_cost = cost;
        break;
      }
      if (timed) {
        t1 = Clock::now();
        times.jacobian += Seconds(t0, t1) - skinning_seconds;
        t0 = t1;
      }
      // delta = J^T (J J^T + lambda I)^-1 e  or  (J^T J + lambda I)^-1 J^T e,  e = -r.
      if (m < n) {
        normal_.setZero(m, m);
        normal_.selfadjointView<Eigen::Lower>().rankUpdate(jacobian_);
        normal_.diagonal().array() += options_.lambda;
        llt_.compute(normal_);
        delta_.noalias() = -(jacobian_.transpose() * llt_.solve(residual_));
      } else {
        normal_.setZero(n, n);
        normal_.selfadjointView<Eigen::Lower>().rankUpdate(jacobian_.transpose());
        normal_.diagonal().array() += options_.lambda;
        llt_.compute(normal_);
        gradient_.noalias() = jacobian_.transpose() * residual_;
        delta_ = -llt_.solve(gradient_);
      }
      if (llt_.info() != Eigen::Success || !delta_.allFinite()) return false;
      if (timed) {
        t1 = Clock::now();
        times.solve += Seconds(t0, t1);
        t0 = t1;
      }
      translation_ += sigma_ * delta_.head<3>();
      for (int j : solved_joints_) {
        Eigen::Map<Eigen::Quaterniond> q(&rotations_[4 * j]);
        q = q * ExpMap(delta_.segment<3>(column_[j]));
        q.normalize();
      }
      ++report->iterations;
      if (timed) {
        times.update += Seconds(t0, Clock::now());
        ++times.iterations;
      }
    }
    return true;
  }

  // The block-sparse normal equations (J^T J + lambda I) delta = -J^T r, assembled without
  // forming J. With J_sp = [u_p]x R_p (u_p = scale * lever, R_p joint p's world rotation)
  // and J_s0 = kappa I for the translation (kappa = scale * total weight * sigma):
  //   (J^T J)_pq = R_p^T (sum_s (u_sp . u_sq) I - u_sq u_sp^T) R_q,
  //   (J^T J)_p0 = R_p^T (sum_s -kappa_s [u_sp]x),  (J^T J)_00 = sum_s kappa_s^2 I,
  //   (J^T r)_p  = R_p^T sum_s r_s x u_sp,          (J^T r)_0  = sum_s kappa_s r_s,
  // so the per-vertex work is a dot and an outer product per pair of chain joints, and the
  // world rotations are applied once per block. Blocks (p, q) are non-zero only when p and
  // q share a tracked vertex's chain (in practice: ancestor pairs), so A is factored by a
  // block sparse Cholesky (solvers/block_sparse_cholesky.h) analysed once, leaves first.
  void BuildNormalPattern() {
    const int nb = 1 + static_cast<int>(solved_joints_.size());
    block_joint_.assign(nb, -1);
    for (int j : solved_joints_) block_joint_[column_[j] / 3] = j;
    std::map<std::pair<int, int>, int> pair_ids;
    auto pair_id = [&](int a, int b) {
      auto it = pair_ids.find({a, b});
      if (it != pair_ids.end()) return it->second;
      const int id = static_cast<int>(pairs_.size());
      pair_ids[{a, b}] = id;
      pairs_.push_back({a, b});
      return id;
    };
    for (int b = 0; b < nb; ++b) pair_id(b, b);
    std::map<std::pair<int, bool>, int> group_ids;
    int terms = 0;
    for (Row& row : rows_) {
      row.term_offset = terms;
      terms += static_cast<int>(row.joints.size());
      CHECK_LE(row.joints.size(), 32u);
      row.blocks.clear();
      if (row.track_position) row.blocks.push_back(0);
      for (int j : row.chain) {
        row.blocks.push_back(column_[j] / 3);
        uint32_t mask = 0;
        double cumulative = 0.0;
        for (size_t k = 0; k < row.joints.size(); ++k) {
          if (skeleton_.IsAncestorOrSelf(j, row.joints[k])) {
            mask |= 1u << k;
            cumulative += row.weights[k];
          }
        }
        row.subtree_masks.push_back(mask);
        row.cumulative.push_back(cumulative);
      }
      const uint32_t all = row.joints.size() >= 32 ? ~0u : (1u << row.joints.size()) - 1;
      row.full = 0;
      while (row.full < static_cast<int>(row.chain.size()) && row.subtree_masks[row.full] == all) ++row.full;
      CHECK_GE(row.full, 1);  // The root holds everything.
      const int first = row.track_position ? 1 : 0;
      const std::pair<int, bool> key(row.chain[row.full - 1], row.track_position);
      auto it = group_ids.find(key);
      if (it == group_ids.end()) {
        Group group;
        group.track_position = row.track_position;
        for (int a = 0; a < first + row.full; ++a) {
          group.blocks.push_back(row.blocks[a]);
          group.joints.push_back(a < first ? -1 : row.chain[a - first]);
        }
        for (size_t a = 0; a < group.blocks.size(); ++a) {
          for (size_t b = 0; b <= a; ++b) group.pair_index.push_back(pair_id(group.blocks[a], group.blocks[b]));
        }
        it = group_ids.emplace(key, static_cast<int>(groups_.size())).first;
        groups_.push_back(group);
      }
      row.group = it->second;
      for (size_t a = first + row.full; a < row.blocks.size(); ++a) {
        for (size_t b = 0; b <= a; ++b) row.pair_index.push_back(pair_id(row.blocks[a], row.blocks[b]));
      }
    }
    terms_.resize(terms);
    accumulators_.resize(pairs_.size());
    gradient_blocks_.resize(nb);
    // The factorization eliminates leaves first: block b of the normal equations is block
    // nb - 1 - b of the factor (joints are in preorder, the translation is block 0).
    std::vector<std::pair<int, int>> lower;
    for (const auto& pair : pairs_) {
      if (pair.first != pair.second) lower.push_back({nb - 1 - pair.second, nb - 1 - pair.first});
    }
    cholesky_.Analyze(nb, lower);
    pair_slot_.assign(pairs_.size(), -1);
    int slot = 0;
    for (size_t i = 0; i < pairs_.size(); ++i) {
      if (pairs_[i].first != pairs_[i].second) pair_slot_[i] = slot++;
    }
    gradient_.resize(3 * nb);
    reordered_.resize(3 * nb);
  }

  // Skinned terms and residual rows of the tracked vertices.
  void SkinRows() {
    const int nt = static_cast<int>(rows_.size());
    for (int s = 0; s < nt; ++s) {
      const Row& row = rows_[s];
      residual_.segment<3>(3 * s) = SkinRow(row, goals_[s], &terms_[row.term_offset]);
    }
  }

  // Per row, u_p = scale * lever_p. For a full joint p (all influences in its subtree)
  // lever_p = W o_p - x (positions; W the total weight, x the skinned point) or -n
  // (normals), so the row's terms on the pairs of full joints are polynomials in o_p, o_q
  // with per-row coefficients; they are summed per group as moments and expanded once per
  // pair (FinishGroups). Pairs with a partial joint (below the influences' common
  // ancestor) are accumulated per row.
  void AccumulateNormal() {
    for (Eigen::Matrix3d& m : accumulators_) m.setZero();
    for (Eigen::Vector3d& g : gradient_blocks_) g.setZero();
    for (Group& g : groups_) {
      g.s0 = 0.0;
      g.s1.setZero();
      g.g1.setZero();
      g.g2.setZero();
      g.s2.setZero();
    }
    Eigen::Vector3d u[kMaxChainBlocks];
    const int nt = static_cast<int>(rows_.size());
    for (int s = 0; s < nt; ++s) {
      const Row& row = rows_[s];
      if (row.scale == 0.0) continue;  // A plant that is off: no rows.
      const Eigen::Vector3d* terms = &terms_[row.term_offset];
      const Eigen::Vector3d r = residual_.segment<3>(3 * s);
      const Eigen::Vector3d x = r / row.scale + goals_[s];  // Skinned point or normal.
      const double s2 = row.scale * row.scale;
      Group& group = groups_[row.group];
      if (row.track_position) {
        const double w = row.total_weight;
        group.s0 += s2 * w * w;
        group.s1 += (s2 * w) * x;
        group.g1 += (s2 * w) * (x - goals_[s]);
        group.g2 += s2 * (x - goals_[s]).cross(x);
        group.s2.noalias() += s2 * x * x.transpose();
      } else {
        group.s2.noalias() += s2 * x * x.transpose();
        group.g2 += s2 * goals_[s].cross(x);
      }
      const int nc = static_cast<int>(row.chain.size());
      if (row.full == nc) continue;  // No partial joints.
      const int first = row.track_position ? 1 : 0;  // Index of the first joint block.
      const double kappa = row.scale * row.total_weight * sigma_;
      DCHECK_LT(nc + first, kMaxChainBlocks);
      for (int c = 0; c < nc; ++c) {
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        for (uint32_t mask = row.subtree_masks[c]; mask != 0; mask &= mask - 1) {
          const int k = __builtin_ctz(mask);
          sum += row.weights[k] * terms[k];
        }
        const Eigen::Vector3d lever =
            row.track_position ? Eigen::Vector3d(row.cumulative[c] * world_positions_[row.chain[c]] - sum)
                               : Eigen::Vector3d(-sum);
        u[first + c] = row.scale * lever;
        if (c >= row.full) gradient_blocks_[row.blocks[first + c]] += r.cross(u[first + c]);
      }
      const int nblocks = first + nc;
      int index = 0;
      for (int a = first + row.full; a < nblocks; ++a) {
        for (int b = 0; b <= a; ++b) {
          Eigen::Matrix3d& acc = accumulators_[row.pair_index[index++]];
          if (b < first) {  // (joint, translation): -kappa [u_a]x.
            acc -= kappa * SkewSymmetric(u[a]);
          } else {
            acc.diagonal().array() += u[a].dot(u[b]);
            acc.noalias() -= u[b] * u[a].transpose();
          }
        }
      }
    }
    FinishGroups();
  }

  // The full-joint pairs from the group moments (see AccumulateNormal):
  //   positions, u_p = s (W o_p - x):
  //     (p, q): (S0 o_p.o_q - (o_p + o_q).S1 + tr S2) I - (S0 o_q o_p^T - o_q S1^T - S1 o_p^T + S2)
  //     (p, 0): -sigma [S0 o_p - S1]x,   (0, 0): sigma^2 S0 I
  //     gradient: h_p += G1 x o_p - G2,  h_0 += sigma G1
  //   normals, u_p = -s n:  (p, q): tr(S2) I - S2;  gradient h_p += sum s^2 m x n.
  void FinishGroups() {
    for (const Group& g : groups_) {
      const int nb = static_cast<int>(g.blocks.size());
      const int first = g.track_position ? 1 : 0;
      int index = 0;
      if (!g.track_position) {
        const Eigen::Matrix3d n2 = g.s2.trace() * Eigen::Matrix3d::Identity() - g.s2;
        for (int a = 0; a < nb; ++a) {
          gradient_blocks_[g.blocks[a]] += g.g2;
          for (int b = 0; b <= a; ++b) accumulators_[g.pair_index[index++]] += n2;
        }
        continue;
      }
      const double trace = g.s2.trace();
      for (int a = 0; a < nb; ++a) {
        const Eigen::Vector3d oa = a < first ? Eigen::Vector3d::Zero() : world_positions_[g.joints[a]];
        if (a < first) {
          gradient_blocks_[0] += sigma_ * g.g1;
        } else {
          gradient_blocks_[g.blocks[a]] += g.g1.cross(oa) - g.g2;
        }
        for (int b = 0; b <= a; ++b) {
          Eigen::Matrix3d& acc = accumulators_[g.pair_index[index++]];
          if (a < first) {
            acc.diagonal().array() += sigma_ * sigma_ * g.s0;
          } else if (b < first) {
            acc -= sigma_ * SkewSymmetric(g.s0 * oa - g.s1);
          } else {
            const Eigen::Vector3d& ob = world_positions_[g.joints[b]];
            acc.diagonal().array() += g.s0 * oa.dot(ob) - (oa + ob).dot(g.s1) + trace;
            acc.noalias() -= g.s0 * ob * oa.transpose() - ob * g.s1.transpose() - g.s1 * oa.transpose();
            acc -= g.s2;
          }
        }
      }
    }
  }

  // Writes lambda I + J^T J into the factor's blocks (reordered, see BuildNormalPattern)
  // and J^T r into gradient_ (normal-equation order).
  void AssembleNormal() {
    const int nb = cholesky_.num_blocks();
    cholesky_.SetZero();  // Fill-in blocks hold the previous factor.
    for (size_t i = 0; i < pairs_.size(); ++i) {
      const int a = pairs_[i].first, b = pairs_[i].second;
      Eigen::Matrix3d block = accumulators_[i];
      if (a > 0) block = world_rotations_[block_joint_[a]].transpose() * block;
      if (b > 0) block = block * world_rotations_[block_joint_[b]];
      if (a == b) {
        cholesky_.Diagonal(nb - 1 - a) = block;
      } else {
        cholesky_.Block(pair_slot_[i]) = block.transpose();  // Row nb-1-b, column nb-1-a.
      }
    }
    for (size_t b = 0; b < gradient_blocks_.size(); ++b) {
      gradient_.segment<3>(3 * b) =
          b == 0 ? gradient_blocks_[0] : Eigen::Vector3d(world_rotations_[block_joint_[b]].transpose() * gradient_blocks_[b]);
    }
    // Prior and limit rows (each on one block), from LinearizeExtras.
    int row = 3 * static_cast<int>(rows_.size());
    auto add_extra = [&](int block, int k) {
      const Eigen::MatrixXd j = jacobian_.block(row, 3 * block, k, 3);
      cholesky_.Diagonal(nb - 1 - block) += j.transpose() * j;
      gradient_.segment<3>(3 * block) += j.transpose() * residual_.segment(row, k);
      row += k;
    };
    if (translation_prior_) add_extra(0, 3);
    for (const Extra& extra : extras_) add_extra(column_[extra.joint] / 3, extra.cost->num_residuals());
    for (int b = 0; b < nb; ++b) cholesky_.Diagonal(b).diagonal().array() += options_.lambda;
    for (int b = 0; b < nb; ++b) reordered_.segment<3>(3 * (nb - 1 - b)) = gradient_.segment<3>(3 * b);
  }

  bool SolveNormal(RetargetFrameReport* report) {
    Clock::time_point t0, t1;
    const bool timed = options_.time_stages;
    auto lap = [&](double* stage) {
      if (!timed) return;
      t1 = Clock::now();
      *stage += Seconds(t0, t1);
      t0 = t1;
    };
    for (int iteration = 0; iteration <= options_.iterations; ++iteration) {
      const bool last = iteration == options_.iterations;
      if (timed) t0 = Clock::now();
      Fk();
      lap(&times.fk);
      SkinRows();
      lap(&times.skinning);
      if (!LinearizeExtras()) return false;
      const double cost = 0.5 * residual_.squaredNorm();
      if (iteration == 0) report->initial_cost = cost;
      if (last) {
        report->final_cost = cost;
        break;
      }
      AccumulateNormal();
      AssembleNormal();
      lap(&times.jacobian);
      if (!cholesky_.Factorize()) return false;
      cholesky_.Solve(reordered_, &reordered_);
      const int nb = cholesky_.num_blocks();
      delta_.resize(3 * nb);
      for (int b = 0; b < nb; ++b) delta_.segment<3>(3 * b) = -reordered_.segment<3>(3 * (nb - 1 - b));
      if (!delta_.allFinite()) return false;
      lap(&times.solve);
      translation_ += sigma_ * delta_.head<3>();
      for (int j : solved_joints_) {
        Eigen::Map<Eigen::Quaterniond> q(rotations_.data() + 4 * j);
        q = q * ExpMap(delta_.segment<3>(column_[j]));
        q.normalize();
      }
      ++report->iterations;
      if (timed) {
        lap(&times.update);
        ++times.iterations;
      }
    }
    return true;
  }

  void BuildCeres() {
    ceres::Problem::Options problem_options;
    problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres_problem_.reset(new ceres::Problem(problem_options));
    ceres_problem_->AddParameterBlock(translation_.data(), 3, &translation_manifold_);
    for (int j : solved_joints_) {
      ceres_problem_->AddParameterBlock(&rotations_[4 * j], 4, &manifold_);
    }
    for (const auto& residual : residuals_) {
      std::vector<double*> blocks = {translation_.data()};
      for (int j : residual->joints()) blocks.push_back(&rotations_[4 * j]);
      ceres_problem_->AddResidualBlock(residual.get(), nullptr, blocks);
    }
    for (const auto& residual : plant_residuals_) {
      std::vector<double*> blocks = {translation_.data()};
      for (int j : residual->joints()) blocks.push_back(&rotations_[4 * j]);
      ceres_problem_->AddResidualBlock(residual.get(), nullptr, blocks);
    }
    if (translation_prior_) {
      ceres_problem_->AddResidualBlock(translation_prior_.get(), nullptr, translation_.data());
    }
    for (const Extra& extra : extras_) {
      ceres_problem_->AddResidualBlock(extra.cost.get(), nullptr, &rotations_[4 * extra.joint]);
    }
  }

  void BuildDls() {
    const int translation = dls_problem_.AddParameterBlock(translation_.data(), 3, &translation_manifold_);
    std::vector<int> block(skeleton_.num_joints(), -1);
    for (int j : solved_joints_) block[j] = dls_problem_.AddParameterBlock(&rotations_[4 * j], 4, &manifold_);
    for (const auto& residual : residuals_) {
      std::vector<int> blocks = {translation};
      for (int j : residual->joints()) blocks.push_back(block[j]);
      dls_problem_.AddResidualBlock(residual.get(), nullptr, blocks);
    }
    for (const auto& residual : plant_residuals_) {
      std::vector<int> blocks = {translation};
      for (int j : residual->joints()) blocks.push_back(block[j]);
      dls_problem_.AddResidualBlock(residual.get(), nullptr, blocks);
    }
    if (translation_prior_) dls_problem_.AddResidualBlock(translation_prior_.get(), nullptr, {translation});
    for (const Extra& extra : extras_) {
      dls_problem_.AddResidualBlock(extra.cost.get(), nullptr, {block[extra.joint]});
    }
  }

  const Skeleton& skeleton_;
  const SkinnedMesh& mesh_;
  const RetargetSetup& setup_;
  double sigma_;
  RetargetSolveOptions options_;

  Eigen::Vector3d translation_ = Eigen::Vector3d::Zero();
  std::vector<double> rotations_;
  Eigen::Vector3d reference_translation_ = Eigen::Vector3d::Zero();
  std::vector<double> reference_rotations_;
  std::vector<Eigen::Vector3d> goals_;
  std::vector<std::unique_ptr<TrackedVertexResidual>> residuals_;
  std::vector<std::unique_ptr<FootPlantResidual>> plant_residuals_;
  std::vector<double> plant_scales_;  // plant_weight / sigma while planted, else 0.
  std::unique_ptr<ceres::CostFunction> translation_prior_;
  std::vector<Extra> extras_;
  std::vector<int> solved_joints_;
  std::vector<int> column_;
  RightQuaternionManifold manifold_;
  ScaledEuclideanManifold translation_manifold_;

  std::vector<Row> rows_;
  std::vector<Eigen::Matrix3d> world_rotations_;
  std::vector<Eigen::Vector3d> world_positions_;
  Eigen::MatrixXd jacobian_;
  Eigen::VectorXd residual_;
  Eigen::MatrixXd normal_;
  Eigen::LLT<Eigen::MatrixXd> llt_;
  // Normal-equation kernel (see BuildNormalPattern).
  static constexpr int kMaxChainBlocks = 130;
  std::vector<int> block_joint_;                 // Joint of each block (-1: translation).
  std::vector<std::pair<int, int>> pairs_;        // (a, b), a >= b.
  std::vector<int> pair_slot_;                    // Off-diagonal pair -> factor slot.
  std::vector<Eigen::Matrix3d> accumulators_;
  std::vector<Eigen::Vector3d> gradient_blocks_;
  std::vector<Eigen::Vector3d> terms_;
  std::vector<Group> groups_;
  BlockSparseCholesky cholesky_;
  Eigen::VectorXd reordered_;  // J^T r, then the step, in the factor's block order.
  Eigen::VectorXd delta_, gradient_;

  std::unique_ptr<ceres::Problem> ceres_problem_;
  DlsProblem dls_problem_;
  DlsSolver dls_solver_;
};

RetargetFrameSolver::RetargetFrameSolver(const Skeleton& skeleton, const SkinnedMesh& mesh,
                                         const RetargetSetup& setup, double sigma,
                                         const RetargetSolveOptions& options)
    : impl_(new Impl(skeleton, mesh, setup, sigma, options)) {}

RetargetFrameSolver::~RetargetFrameSolver() = default;

Status RetargetFrameSolver::Solve(const Eigen::Matrix3Xd& goal_positions,
                                  const Eigen::Matrix3Xd& goal_normals, Pose* pose,
                                  RetargetFrameReport* report) {
  return impl_->Solve(goal_positions, goal_normals, pose, report);
}

void RetargetFrameSolver::SetPlants(const Eigen::Matrix3Xd& anchors, const std::vector<char>& active) {
  impl_->SetPlants(anchors, active);
}

const RetargetStageTimes& RetargetFrameSolver::stage_times() const { return impl_->times; }
void RetargetFrameSolver::ResetStageTimes() { impl_->times = RetargetStageTimes(); }

void RetargetFrameSolver::Linearize(const Eigen::Matrix3Xd& goal_positions,
                                    const Eigen::Matrix3Xd& goal_normals, const Pose& pose,
                                    Eigen::VectorXd* residual, Eigen::MatrixXd* jacobian) {
  impl_->Linearize(goal_positions, goal_normals, pose, residual, jacobian);
}

}  // namespace mocapsolve
