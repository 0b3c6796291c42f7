#include "problems/retarget/retarget_frame_solver.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <ceres/problem.h>
#include <glog/logging.h>

#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "kinematics/skinning.h"
#include "problems/marker_solve/joint_limit_residual.h"
#include "problems/marker_solve/marker_frame_solver.h"
#include "problems/marker_solve/pose_prior_residual.h"
#include "problems/retarget/floor_residual.h"
#include "problems/retarget/foot_plant_residual.h"
#include "problems/retarget/limb_direction_residual.h"
#include "problems/retarget/tracked_vertex_residual.h"
#include "solvers/dls_solver.h"
#include "solvers/right_quaternion_manifold.h"
#include "solvers/tree_dls_solver.h"

namespace mocapsolve {
namespace {

// The lean kernel's floor: at most this many active-set rounds per frame, and a joint counts
// as under its lowest height when deeper than this share of sigma.
constexpr int kFloorRounds = 3;
constexpr double kFloorSlack = 1e-3;

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

bool RetargetSolveOptions::IsValid(std::string* error) const {
  if (iterations < 1) return *error = "iterations must be >= 1", false;
  if (!(lambda >= 0.0) || !std::isfinite(lambda)) return *error = "lambda must be >= 0", false;
  if (!(position_weight > 0.0) || !(normal_weight >= 0.0)) {
    return *error = "position weight must be > 0 and normal weight >= 0", false;
  }
  if (!(smoothness_weight >= 0.0) || !(limit_weight >= 0.0) || !(plant_weight >= 0.0) ||
      !(limb_direction_weight >= 0.0) || !std::isfinite(limb_direction_weight)) {
    return *error = "smoothness, limit, plant and limb direction weights must be >= 0", false;
  }
  for (const Limb& limb : limbs) {
    if (limb.joint < 0 || !limb.local.allFinite()) return *error = "a limb without a joint or direction", false;
  }
  if (!(floor_weight >= 0.0) || !std::isfinite(floor_weight)) return *error = "floor weight must be >= 0", false;
  if (floor_heights.size() != floor_joints.size()) return *error = "one floor height per floor joint", false;
  for (size_t k = 0; k < floor_joints.size(); ++k) {
    if (floor_joints[k] < 0 || !std::isfinite(floor_heights[k])) return *error = "a floor joint or height", false;
  }
  if (solver == SolverKind::kCeres && !ceres.IsValid(error)) return false;
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
                         double* mean_position_error, double* mean_normal_angle,
                         double* mean_effector_error) {
  FkData fk(skeleton);
  ForwardKinematics(skeleton, pose, &fk);
  std::vector<Eigen::Isometry3d> transforms;
  ComputeSkinningTransforms(mesh, fk, &transforms);
  double position = 0.0, angle = 0.0, effector = 0.0;
  int effectors = 0;
  const int nt = static_cast<int>(setup.tracked.size());
  for (int s = 0; s < nt; ++s) {
    const int v = setup.tracked[s].target_vertex;
    const double distance = (SkinPosition(mesh, transforms, v) - goal_positions.col(s)).norm();
    position += distance;
    if (setup.tracked[s].track_position) effector += distance, ++effectors;
    const Eigen::Vector3d n = SkinNormal(mesh, transforms, v);
    const Eigen::Vector3d m = goal_normals.col(s);
    angle += std::atan2(n.cross(m).norm(), n.dot(m));
  }
  *mean_position_error = nt > 0 ? position / nt : 0.0;
  *mean_normal_angle = nt > 0 ? angle / nt : 0.0;
  if (mean_effector_error != nullptr) *mean_effector_error = effectors > 0 ? effector / effectors : 0.0;
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
    const int nl = options.limb_direction_weight > 0.0 ? static_cast<int>(options.limbs.size()) : 0;
    rotations_.assign(4 * nj, 0.0);
    reference_rotations_.assign(4 * nj, 0.0);
    goals_.assign(nt + np + nl, Eigen::Vector3d::Zero());
    plant_scales_.assign(np, 0.0);
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
    for (int l = 0; l < nl; ++l) {
      const RetargetSolveOptions::Limb& limb = options.limbs[l];
      CHECK(limb.joint < nj) << "limb joint " << limb.joint;
      limb_residuals_.emplace_back(new LimbDirectionResidual(&skeleton, limb.joint, limb.local,
                                                             &goals_[nt + np + l], options.limb_direction_weight));
      for (int j : limb_residuals_.back()->joints()) solved[j] = true;
    }
    const int nf = options.floor_weight > 0.0 ? static_cast<int>(options.floor_joints.size()) : 0;
    floor_scale_ = options.floor_weight / sigma;
    floor_goals_.assign(nf, Eigen::Vector3d::Zero());
    floor_active_.assign(nf, 0);
    floor_plant_.assign(nf, -1);
    for (int k = 0; k < nf; ++k) {
      CHECK(options.floor_joints[k] < nj) << "floor joint " << options.floor_joints[k];
      floor_residuals_.emplace_back(
          new FloorResidual(&skeleton, options.floor_joints[k], &options_.floor_heights[k], &floor_scale_));
      for (int j : floor_residuals_.back()->joints()) solved[j] = true;
      for (int p = 0; p < np; ++p) {
        if (options.plant_joints[p] == options.floor_joints[k]) floor_plant_[k] = p;
      }
    }
    for (int j = 0; j < nj; ++j) {
      if (solved[j]) solved_joints_.push_back(j);
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
    // The lean kernel (solvers/tree_dls_solver.h) on the same unknowns and residuals:
    // a point or direction row per tracked vertex (its skinning influences), a point row
    // per plant (the foot joint, off until SetPlants), the priors and limits as block costs.
    tree_.reset(new TreeDlsSolver(&skeleton, translation_.data(), rotations_.data()));
    tree_->set_translation_scale(sigma);
    for (int j : solved_joints_) tree_->SetJointManifold(j, &manifold_);
    for (int s = 0; s < nt; ++s) {
      const TrackedVertexResidual& residual = *residuals_[s];
      const int v = residual.vertex();
      std::vector<TreeAttachment> attachments;
      for (int k = mesh.weight_begin(v); k < mesh.weight_end(v); ++k) {
        const int b = mesh.weight_joint(k);
        const Eigen::Isometry3d& joint_from_bind = mesh.joint_from_bind(b);
        attachments.push_back({b, mesh.weight(k),
                               residual.track_position()
                                   ? Eigen::Vector3d(joint_from_bind * mesh.rest_positions().col(v))
                                   : Eigen::Vector3d(joint_from_bind.linear() * mesh.rest_normals().col(v))});
      }
      if (residual.track_position()) {
        tree_->AddPointRow(std::move(attachments), &goals_[s], residual.scale());
      } else {
        tree_->AddDirectionRow(std::move(attachments), &goals_[s], residual.scale());
      }
    }
    for (int p = 0; p < np; ++p) {
      tree_->AddPointRow({{plant_residuals_[p]->joint(), 1.0, Eigen::Vector3d::Zero()}}, &goals_[nt + p], 0.0);
    }
    for (int l = 0; l < nl; ++l) {
      const LimbDirectionResidual& limb = *limb_residuals_[l];
      tree_->AddDirectionRow({{limb.joint(), 1.0, limb.local()}}, &goals_[nt + np + l], limb.scale());
    }
    for (int k = 0; k < nf; ++k) {
      floor_rows_.push_back(
          tree_->AddPointRow({{floor_residuals_[k]->joint(), 1.0, Eigen::Vector3d::Zero()}}, &floor_goals_[k], 0.0));
    }
    if (translation_prior_) tree_->AddBlockCost(-1, translation_prior_.get());
    for (const Extra& extra : extras_) tree_->AddBlockCost(extra.joint, extra.cost.get());
    tree_->set_time_stages(options.time_stages);
    if (options.solver == SolverKind::kCeres) BuildCeres();
    if (options.solver == SolverKind::kDlsGeneric) BuildDls();
  }

  void SetPlants(const Eigen::Matrix3Xd& anchors, const std::vector<char>& active) {
    const int nt = static_cast<int>(setup_.tracked.size());
    const int np = static_cast<int>(plant_scales_.size());
    CHECK_EQ(anchors.cols(), np);
    CHECK_EQ(static_cast<int>(active.size()), np);
    for (int p = 0; p < np; ++p) {
      goals_[nt + p] = anchors.col(p);
      plant_scales_[p] = active[p] ? options_.plant_weight / sigma_ : 0.0;
      tree_->SetRowScale(nt + p, plant_scales_[p]);
    }
  }

  void SetLimbGoals(const Eigen::Matrix3Xd& directions) {
    const int nl = static_cast<int>(limb_residuals_.size());
    if (nl == 0) return;
    CHECK_EQ(directions.cols(), nl);
    const size_t first = goals_.size() - nl;
    for (int l = 0; l < nl; ++l) goals_[first + l] = directions.col(l);
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
      case SolverKind::kDls: {
        DlsSummary summary;
        tree_->Solve(DlsIterationOptions(), &summary);
        if (!summary.IsSolutionUsable()) return Status::Error("retarget: the DLS solve failed: " + summary.BriefReport());
        result.initial_cost = summary.initial_cost;
        result.final_cost = summary.final_cost;
        result.iterations = summary.iterations;
        // The floor's active set: rounds of rows toward the lowest heights, each round's goal
        // raised by what the last left under (the other rows pull the joint down a little).
        for (int round = 0; round < kFloorRounds; ++round) {
          const int under = ActivateFloorRows(pose, round > 0);
          if (round == 0) result.floor_contacts = under;
          if (under == 0) break;
          tree_->Solve(DlsIterationOptions(), &summary);
          if (!summary.IsSolutionUsable()) {
            for (int row : floor_rows_) tree_->SetRowScale(row, 0.0);
            std::fill(floor_active_.begin(), floor_active_.end(), 0);
            return Status::Error("retarget: the DLS solve failed: " + summary.BriefReport());
          }
          result.final_cost = summary.final_cost;
          result.iterations += summary.iterations;
        }
        for (int row : floor_rows_) tree_->SetRowScale(row, 0.0);
        std::fill(floor_active_.begin(), floor_active_.end(), 0);
        break;
      }
      case SolverKind::kDlsGeneric: {
        DlsSummary summary;
        dls_solver_.Solve(DlsIterationOptions(), &dls_problem_, &summary);
        if (!summary.IsSolutionUsable()) return Status::Error("retarget: DLS failed: " + summary.BriefReport());
        result.initial_cost = summary.initial_cost;
        result.final_cost = summary.final_cost;
        result.iterations = summary.iterations;
        break;
      }
      case SolverKind::kCeres: {
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
                          &result.mean_position_error, &result.mean_normal_angle, &result.mean_effector_error);
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
    tree_->Linearize(residual, jacobian);
  }

  const RetargetStageTimes& stage_times() {
    const TreeDlsStageTimes& t = tree_->stage_times();
    times_.fk = t.fk;
    times_.skinning = t.rows;
    times_.jacobian = t.assembly;
    times_.solve = t.solve;
    times_.update = t.update;
    times_.iterations = t.steps;
    return times_;
  }
  void ResetStageTimes() { tree_->ResetStageTimes(); }


 private:
  struct Extra {
    std::unique_ptr<ceres::CostFunction> cost;
    int joint;
  };

  // The lean kernel's floor (active set): each floor joint more than kFloorSlack under its
  // lowest height h at the current parameters gets its point row toward (x, h, z), scale
  // floor_weight / sigma; with `raise`, a row already on has its goal raised by the depth
  // left instead. `pose` (the warm start) receives the current parameters. Returns how many
  // joints are under.
  int ActivateFloorRows(Pose* pose, bool raise) {
    if (floor_rows_.empty()) return 0;
    GetParameters(pose);
    if (!floor_fk_) floor_fk_.reset(new FkData(skeleton_));
    ForwardKinematics(skeleton_, *pose, floor_fk_.get());
    int under = 0;
    for (size_t k = 0; k < floor_rows_.size(); ++k) {
      const Eigen::Vector3d& p = floor_fk_->world_positions[floor_residuals_[k]->joint()];
      const double lowest = options_.floor_heights[k];
      const double depth = lowest - p.y();
      if (!(depth > kFloorSlack * sigma_)) continue;
      if (raise && floor_active_[k]) {
        floor_goals_[k].y() += depth;
      } else {
        // A planted joint is held over its anchor (lifted to the floor as well), not where
        // this solve let it slide.
        const int plant = floor_plant_[k];
        const Eigen::Vector3d& at = plant >= 0 && plant_scales_[plant] > 0.0
                                        ? goals_[setup_.tracked.size() + plant] : p;
        floor_goals_[k] = Eigen::Vector3d(at.x(), lowest, at.z());
        tree_->SetRowScale(floor_rows_[k], floor_scale_);
        floor_active_[k] = 1;
      }
      ++under;
    }
    if (!raise && under == 0) std::fill(floor_active_.begin(), floor_active_.end(), 0);
    return under;
  }

  // Both DLS paths: a fixed number of iterations, every step taken (Buss).
  DlsOptions DlsIterationOptions() const {
    DlsOptions dls;
    dls.max_iterations = options_.iterations;
    dls.adaptive_damping = false;
    dls.lambda = options_.lambda;
    dls.function_tolerance = dls.gradient_tolerance = dls.parameter_tolerance = 0.0;
    return dls;
  }

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
    for (const auto& residual : limb_residuals_) {
      std::vector<double*> blocks = {translation_.data()};
      for (int j : residual->joints()) blocks.push_back(&rotations_[4 * j]);
      ceres_problem_->AddResidualBlock(residual.get(), nullptr, blocks);
    }
    for (const auto& residual : floor_residuals_) {
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
    for (const auto& residual : limb_residuals_) {
      std::vector<int> blocks = {translation};
      for (int j : residual->joints()) blocks.push_back(block[j]);
      dls_problem_.AddResidualBlock(residual.get(), nullptr, blocks);
    }
    for (const auto& residual : floor_residuals_) {
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
  std::vector<std::unique_ptr<LimbDirectionResidual>> limb_residuals_;
  std::vector<std::unique_ptr<FloorResidual>> floor_residuals_;
  double floor_scale_ = 0.0;                  // floor_weight / sigma.
  std::vector<Eigen::Vector3d> floor_goals_;  // The lean kernel's active-set goals.
  std::vector<int> floor_rows_;               // Its floor rows (off outside Solve).
  std::vector<char> floor_active_;            // Per floor row: on in this Solve.
  std::vector<int> floor_plant_;              // Per floor row: the plant on its joint, or -1.
  std::unique_ptr<FkData> floor_fk_;
  std::unique_ptr<ceres::CostFunction> translation_prior_;
  std::vector<Extra> extras_;
  std::vector<int> solved_joints_;
  RightQuaternionManifold manifold_;
  ScaledEuclideanManifold translation_manifold_;

  std::unique_ptr<TreeDlsSolver> tree_;
  RetargetStageTimes times_;

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

void RetargetFrameSolver::SetLimbGoals(const Eigen::Matrix3Xd& directions) { impl_->SetLimbGoals(directions); }

const RetargetStageTimes& RetargetFrameSolver::stage_times() const { return impl_->stage_times(); }
void RetargetFrameSolver::ResetStageTimes() { impl_->ResetStageTimes(); }

void RetargetFrameSolver::Linearize(const Eigen::Matrix3Xd& goal_positions,
                                    const Eigen::Matrix3Xd& goal_normals, const Pose& pose,
                                    Eigen::VectorXd* residual, Eigen::MatrixXd* jacobian) {
  impl_->Linearize(goal_positions, goal_normals, pose, residual, jacobian);
}

}  // namespace mocapsolve
