#include "problems/marker_solve/marker_frame_solver.h"

#include <cmath>

#include <ceres/problem.h>

#include "kinematics/forward_kinematics.h"
#include "kinematics/quote_token.h"
#include "problems/marker_solve/joint_limit_residual.h"
#include "problems/marker_solve/marker_residual.h"
#include "problems/marker_solve/pose_prior_residual.h"
#include "problems/marker_solve/twist_observability.h"
#include "solvers/right_quaternion_manifold.h"
#include "solvers/tree_dls_solver.h"

namespace mocapsolve {

bool MarkerSolveOptions::IsValid(std::string* error) const {
  // Every weight finite (NaN or inf would reach Ceres, which then logs and fails).
  if (!(marker_weight > 0.0) || !std::isfinite(marker_weight)) {
    return *error = "marker weight must be positive and finite", false;
  }
  if (!(loss_scale > 0.0) || !std::isfinite(loss_scale)) {
    return *error = "loss scale must be positive and finite", false;
  }
  for (const double w : {prior_rotation_weight, rest_rotation_weight, hidden_rotation_weight,
                         twist_rotation_weight, prior_translation_weight, limit_weight}) {
    if (!(w >= 0.0) || !std::isfinite(w)) {
      return *error = "prior and limit weights must be finite and >= 0", false;
    }
  }
  if (solver != SolverKind::kCeres && !dls.IsValid(error)) return false;
  if (solver == SolverKind::kCeres && !ceres.IsValid(error)) return false;
  std::unique_ptr<ceres::LossFunction> loss_function;
  const Status status = MakeLoss(loss, loss_scale, &loss_function);
  if (!status.ok()) return *error = status.message(), false;
  return true;
}

ceres::Solver::Options DefaultFrameCeresOptions() {
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  options.max_num_iterations = 50;
  options.function_tolerance = 1e-10;
  options.gradient_tolerance = 1e-12;
  options.parameter_tolerance = 1e-10;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  return options;
}

Status MakeLoss(const std::string& name, double scale, std::unique_ptr<ceres::LossFunction>* loss) {
  if (name == "none") {
    loss->reset();
  } else if (name == "huber") {
    loss->reset(new ceres::HuberLoss(scale));
  } else if (name == "cauchy") {
    loss->reset(new ceres::CauchyLoss(scale));
  } else {
    return Status::Error("--loss: unknown loss " + QuoteToken(name) + " (none, huber, cauchy)");
  }
  return Status::Ok();
}

double RmsMarkerError(const Skeleton& skeleton, const MarkerSet& markers, const Pose& pose,
                      const std::vector<Eigen::Vector3d>& observed, int* count) {
  FkData fk(skeleton);
  ForwardKinematics(skeleton, pose, &fk);
  double sum = 0.0;
  int n = 0;
  for (int m = 0; m < markers.num_markers(); ++m) {
    if (!observed[m].allFinite()) continue;
    sum += (markers.Position(m, fk) - observed[m]).squaredNorm();
    ++n;
  }
  if (count != nullptr) *count = n;
  return n > 0 ? std::sqrt(sum / n) : 0.0;
}

namespace {

// A marker's residual scale: the solve's marker weight times sqrt of the marker's own
// solve weight (kinematics/marker_set.h), so its cost is weighted by solve_weight.
double RowScale(const MarkerSolveOptions& options, const MarkerSet& markers, int m) {
  const double w = markers.marker(m).solve_weight;
  return w == 1.0 ? options.marker_weight : options.marker_weight * std::sqrt(w);
}

}  // namespace

class MarkerFrameSolver::Impl {
 public:
  Impl(const Skeleton& skeleton, const MarkerSet& markers, const MarkerSolveOptions& options)
      : skeleton_(skeleton), markers_(markers), options_(options),
        observed_(markers.num_markers()), rotations_(4 * skeleton.num_joints()),
        reference_rotations_(4 * skeleton.num_joints()), rest_rotations_(4 * skeleton.num_joints()) {
    (void)MakeLoss(options.loss, options.loss_scale, &loss_);
    std::vector<bool> moves(skeleton.num_joints(), false);
    for (int m = 0; m < markers.num_markers(); ++m) {
      residuals_.emplace_back(new MarkerResidual(&skeleton, &markers, m, &observed_[m],
                                                 RowScale(options, markers, m)));
      for (int j : markers.InfluencingJoints(m)) moves[j] = true;
    }
    // Joints on some marker's chain get a block; those without rotation dofs (an ASF
    // bone with no dof) keep it constant.
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      if (!moves[j]) continue;
      chain_joints_.push_back(j);
      if (skeleton.num_rotation_dofs(j) > 0) solved_joints_.push_back(j);
    }
    if (options.prior_rotation_weight > 0.0) {
      for (int j : solved_joints_) {
        rotation_priors_.emplace_back(new RotationPriorResidual(&reference_rotations_[4 * j],
                                                                options.prior_rotation_weight));
        prior_joints_.push_back(j);
      }
    }
    const int given = static_cast<int>(options.rest_rotations.size());
    rest_size_ok_ = given == 0 || given == skeleton.num_joints();
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      const Eigen::Quaterniond q = given == skeleton.num_joints() ? options.rest_rotations[j].normalized()
                                                                  : Eigen::Quaterniond::Identity();
      for (int i = 0; i < 4; ++i) rest_rotations_[4 * j + i] = q.coeffs()[i];
    }
    // Own markers per joint (a marker with attachments on several joints counts for each).
    own_markers_.resize(skeleton.num_joints());
    for (int m = 0; m < markers.num_markers(); ++m) {
      for (const MarkerAttachment& a : markers.marker(m).attachments) {
        std::vector<int>& own = own_markers_[a.joint];
        if (own.empty() || own.back() != m) own.push_back(m);
      }
    }
    const bool rest_on = options.rest_rotation_weight > 0.0 && (given > 0 || !options.rest_prior_needs_reference);
    const bool hidden_on = options.hidden_rotation_weight > 0.0 && given > 0;
    const bool twist_on = options.twist_rotation_weight > 0.0 && given > 0;
    for (int j : solved_joints_) {
      const bool hideable = (hidden_on && !own_markers_[j].empty()) || (twist_on && own_markers_[j].size() >= 2);
      if (!rest_on && !hideable) continue;
      const double weight = rest_on ? options.rest_rotation_weight : 0.0;
      rotation_priors_.emplace_back(new RotationPriorResidual(&rest_rotations_[4 * j], weight));
      prior_joints_.push_back(j);
      if (!hideable) continue;
      Hideable h{j, rotation_priors_.back().get(), weight, {}};
      // Each own marker's direction from the joint, in the joint's frame (zero: at the origin).
      for (int m : own_markers_[j]) {
        Eigen::Vector3d axis = Eigen::Vector3d::Zero();
        for (const MarkerAttachment& a : markers.marker(m).attachments) {
          if (a.joint == j && a.offset.norm() > 1e-9) axis = a.offset.normalized();
        }
        h.axes.push_back(axis);
      }
      hideable_.push_back(std::move(h));
    }
    if (options.limit_weight > 0.0) {
      for (int j : solved_joints_) {
        if (skeleton.rotation_limits(j).empty()) continue;
        limits_.emplace_back(new JointLimitResidual(skeleton.rotation_axes(j),
                                                    skeleton.rotation_limits(j),
                                                    options.limit_weight));
        limit_joints_.push_back(j);
      }
    }
    if (options.prior_translation_weight > 0.0) {
      translation_prior_.reset(new TranslationPriorResidual(reference_translation_,
                                                            options.prior_translation_weight));
    }
  }

  Status Solve(const std::vector<Eigen::Vector3d>& observed, Pose* pose, FrameSolveReport* report) {
    if (static_cast<int>(observed.size()) != markers_.num_markers()) {
      return Status::Error("observation count differs from the marker set");
    }
    if (!rest_size_ok_) {
      return Status::Error("the rest pose has " + std::to_string(options_.rest_rotations.size()) +
                           " rotations, the skeleton " + std::to_string(skeleton_.num_joints()) + " joints");
    }
    std::vector<bool> visible(markers_.num_markers());
    int num_visible = 0;
    for (int m = 0; m < markers_.num_markers(); ++m) {
      visible[m] = observed[m].allFinite();
      num_visible += visible[m];
      if (visible[m]) observed_[m] = observed[m];
    }
    *report = FrameSolveReport();
    report->markers_used = num_visible;
    // Load the warm start (and the prior's reference) into the parameter blocks.
    for (int i = 0; i < 3; ++i) translation_[i] = reference_translation_[i] = pose->translations[0][i];
    for (int j = 0; j < skeleton_.num_joints(); ++j) {
      for (int i = 0; i < 4; ++i) {
        rotations_[4 * j + i] = reference_rotations_[4 * j + i] = pose->rotations[j].coeffs()[i];
      }
    }
    if (num_visible == 0) return Status::Error("no marker observed");
    for (const Hideable& h : hideable_) {
      int seen = 0, last_seen = -1;
      const std::vector<int>& own = own_markers_[h.joint];
      for (size_t k = 0; k < own.size(); ++k) {
        if (visible[own[k]]) ++seen, last_seen = static_cast<int>(k);
      }
      h.prior->clear_axis();
      h.prior->set_weight(h.seen_weight);
      if (seen == 0 && options_.hidden_rotation_weight > 0.0) {
        h.prior->set_weight(options_.hidden_rotation_weight);
        report->held_joints.push_back(h.joint);
      } else if (seen == 1 && own.size() >= 2 && options_.twist_rotation_weight > 0.0) {
        // Held only where the markers below observe the twist by less than a tenth of the
        // prior's weight at the warm start (a humerus whose forearm hinges on it is left to
        // the forearm: observed at 60 mm/rad, it is better placed by it than by the mean pose).
        const Eigen::Vector3d& axis = h.axes[last_seen];
        if (!axis.isZero() && options_.marker_weight * TwistObservability(skeleton_, markers_, *pose, h.joint, axis,
                                                                          &visible) < kTwistObservedFraction * options_.twist_rotation_weight) {
          h.prior->set_axis(axis.data(), options_.twist_rotation_weight);
          report->twist_held_joints.push_back(h.joint);
        }
      }
    }
    if (options_.solver == SolverKind::kCeres) {
      if (visible != ceres_visible_ || ceres_problem_ == nullptr) BuildCeresProblem(visible);
      ceres::Solver::Summary summary;
      ceres::Solve(options_.ceres, ceres_problem_.get(), &summary);
      report->initial_cost = summary.initial_cost;
      report->final_cost = summary.final_cost;
      report->iterations = static_cast<int>(summary.iterations.size()) - 1;
      report->usable = summary.IsSolutionUsable();
      report->brief = summary.BriefReport();
    } else if (options_.solver == SolverKind::kDlsGeneric) {
      if (visible != dls_visible_ || dls_problem_.num_parameter_blocks() == 0) BuildDlsProblem(visible);
      DlsSummary summary;
      dls_solver_.Solve(options_.dls, &dls_problem_, &summary);
      ReportDls(summary, report);
    } else {
      if (tree_ == nullptr) BuildTreeSolver();
      for (int m = 0; m < markers_.num_markers(); ++m) {
        tree_->SetRowScale(m, visible[m] ? RowScale(options_, markers_, m) : 0.0);
      }
      DlsSummary summary;
      tree_->Solve(options_.dls, &summary);
      ReportDls(summary, report);
    }
    if (!report->usable) return Status::Error("solver failed: " + report->brief);
    for (int i = 0; i < 3; ++i) pose->translations[0][i] = translation_[i];
    for (int j : solved_joints_) {
      Eigen::Quaterniond q(rotations_[4 * j + 3], rotations_[4 * j], rotations_[4 * j + 1],
                           rotations_[4 * j + 2]);
      pose->rotations[j] = q.normalized();
    }
    report->rms_marker_error = RmsMarkerError(skeleton_, markers_, *pose, observed);
    return Status::Ok();
  }

 private:
  static void ReportDls(const DlsSummary& summary, FrameSolveReport* report) {
    report->initial_cost = summary.initial_cost;
    report->final_cost = summary.final_cost;
    report->iterations = summary.iterations;
    report->usable = summary.IsSolutionUsable();
    report->brief = summary.BriefReport();
  }

  // The lean kernel on the same unknowns and residuals: one point row per marker (its
  // attachments; off while the marker is missing), the priors and limits as block costs.
  void BuildTreeSolver() {
    tree_.reset(new TreeDlsSolver(&skeleton_, translation_, rotations_.data()));
    for (int j : chain_joints_) tree_->SetJointManifold(j, RotationManifold(skeleton_.rotation_axes(j)));
    for (int m = 0; m < markers_.num_markers(); ++m) {
      std::vector<TreeAttachment> attachments;
      for (const MarkerAttachment& a : markers_.marker(m).attachments) {
        attachments.push_back({a.joint, a.weight, a.offset});
      }
      tree_->AddPointRow(std::move(attachments), &observed_[m], RowScale(options_, markers_, m));
    }
    tree_->set_loss(loss_.get());
    for (size_t k = 0; k < rotation_priors_.size(); ++k) tree_->AddBlockCost(prior_joints_[k], rotation_priors_[k].get());
    for (size_t k = 0; k < limits_.size(); ++k) tree_->AddBlockCost(limit_joints_[k], limits_[k].get());
    if (translation_prior_) tree_->AddBlockCost(-1, translation_prior_.get());
  }

  void BuildCeresProblem(const std::vector<bool>& visible) {
    ceres::Problem::Options problem_options;
    problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    problem_options.enable_fast_removal = false;
    ceres_problem_.reset(new ceres::Problem(problem_options));
    ceres_problem_->AddParameterBlock(translation_, 3);
    for (int j : chain_joints_) {
      ceres::Manifold* manifold = RotationManifold(skeleton_.rotation_axes(j));
      ceres_problem_->AddParameterBlock(&rotations_[4 * j], 4, manifold);
      if (manifold == nullptr) ceres_problem_->SetParameterBlockConstant(&rotations_[4 * j]);
    }
    std::vector<double*> blocks;
    for (int m = 0; m < markers_.num_markers(); ++m) {
      if (!visible[m]) continue;
      blocks.assign(1, translation_);
      for (int j : residuals_[m]->joints()) blocks.push_back(&rotations_[4 * j]);
      ceres_problem_->AddResidualBlock(residuals_[m].get(), loss_.get(), blocks);
    }
    for (size_t k = 0; k < rotation_priors_.size(); ++k) {
      ceres_problem_->AddResidualBlock(rotation_priors_[k].get(), nullptr, &rotations_[4 * prior_joints_[k]]);
    }
    for (size_t k = 0; k < limits_.size(); ++k) {
      ceres_problem_->AddResidualBlock(limits_[k].get(), nullptr, &rotations_[4 * limit_joints_[k]]);
    }
    if (translation_prior_) ceres_problem_->AddResidualBlock(translation_prior_.get(), nullptr, translation_);
    ceres_visible_ = visible;
  }

  void BuildDlsProblem(const std::vector<bool>& visible) {
    dls_problem_.Clear();
    std::vector<int> block_of_joint(skeleton_.num_joints(), -1);
    const int translation_block = dls_problem_.AddParameterBlock(translation_, 3);
    for (int j : chain_joints_) {
      const ceres::Manifold* manifold = RotationManifold(skeleton_.rotation_axes(j));
      block_of_joint[j] = dls_problem_.AddParameterBlock(&rotations_[4 * j], 4, manifold);
      if (manifold == nullptr) dls_problem_.SetParameterBlockConstant(block_of_joint[j]);
    }
    for (int m = 0; m < markers_.num_markers(); ++m) {
      if (!visible[m]) continue;
      std::vector<int> blocks = {translation_block};
      for (int j : residuals_[m]->joints()) blocks.push_back(block_of_joint[j]);
      dls_problem_.AddResidualBlock(residuals_[m].get(), loss_.get(), blocks);
    }
    for (size_t k = 0; k < rotation_priors_.size(); ++k) {
      dls_problem_.AddResidualBlock(rotation_priors_[k].get(), nullptr, {block_of_joint[prior_joints_[k]]});
    }
    for (size_t k = 0; k < limits_.size(); ++k) {
      dls_problem_.AddResidualBlock(limits_[k].get(), nullptr, {block_of_joint[limit_joints_[k]]});
    }
    if (translation_prior_) dls_problem_.AddResidualBlock(translation_prior_.get(), nullptr, {translation_block});
    dls_visible_ = visible;
  }

  const Skeleton& skeleton_;
  const MarkerSet& markers_;
  MarkerSolveOptions options_;
  std::unique_ptr<ceres::LossFunction> loss_;
  std::vector<Eigen::Vector3d> observed_;
  double translation_[3] = {0, 0, 0};
  double reference_translation_[3] = {0, 0, 0};
  std::vector<double> rotations_;            // 4 per joint, Eigen order.
  std::vector<double> reference_rotations_;  // The prior's reference, 4 per joint.
  std::vector<double> rest_rotations_;       // The rest prior's reference, 4 per joint.
  bool rest_size_ok_ = true;                 // options_.rest_rotations: empty or one per joint.
  std::vector<int> chain_joints_;   // Joints on some marker's chain: a parameter block each.
  std::vector<int> solved_joints_;  // Those of them with rotation dofs.
  std::vector<std::unique_ptr<MarkerResidual>> residuals_;
  // Toward the previous solution, then toward rest_rotations_ (each optional).
  std::vector<std::unique_ptr<RotationPriorResidual>> rotation_priors_;
  std::vector<int> prior_joints_;  // The joint of each rotation prior.
  std::vector<std::vector<int>> own_markers_;  // Per joint, the markers attached to it.
  // A joint whose rest prior rises to hidden_rotation_weight while its own markers are missing
  // (or, about one axis, to twist_rotation_weight while only one of two or more is seen).
  struct Hideable {
    int joint;
    RotationPriorResidual* prior;
    double seen_weight;  // The prior's weight while some own marker is observed.
    // Per own marker (own_markers_ order), its unit direction from the joint in the joint's
    // frame, zero for a marker at the origin: the twist axis while it is the only one seen.
    std::vector<Eigen::Vector3d> axes;
  };
  std::vector<Hideable> hideable_;
  std::unique_ptr<TranslationPriorResidual> translation_prior_;
  std::vector<std::unique_ptr<JointLimitResidual>> limits_;
  std::vector<int> limit_joints_;
  std::unique_ptr<ceres::Problem> ceres_problem_;
  std::vector<bool> ceres_visible_;
  DlsProblem dls_problem_;
  DlsSolver dls_solver_;
  std::vector<bool> dls_visible_;
  std::unique_ptr<TreeDlsSolver> tree_;
};

MarkerFrameSolver::MarkerFrameSolver(const Skeleton& skeleton, const MarkerSet& markers,
                                     const MarkerSolveOptions& options)
    : impl_(new Impl(skeleton, markers, options)) {}
MarkerFrameSolver::~MarkerFrameSolver() = default;

Status MarkerFrameSolver::Solve(const std::vector<Eigen::Vector3d>& observed, Pose* pose,
                                FrameSolveReport* report) {
  return impl_->Solve(observed, pose, report);
}

}  // namespace mocapsolve
