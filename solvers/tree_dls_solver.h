// TreeDlsSolver: the lean damped-least-squares kernel of per-frame problems on a kinematic
// tree (per-frame marker IK, the retarget's tracked vertices), problem-agnostic: it knows
// rows of points and directions rigidly attached to joints, not markers or meshes.
//
// Unknowns: the root translation t (3) and the local rotation q_j of every joint given a
// manifold (SetJointManifold; others are held), increments R_j <- R_j Plus(q_j, delta_j)
// (RightQuaternionManifold: q_j exp(delta_j), delta_j in the joint's local frame; an ASF
// joint's DofQuaternionManifold: its Euler angles), t <- t + tau delta_t (tau =
// translation_scale). The caller owns t (3 doubles) and q (4 per joint, x y z w).
//
// Rows (3 residuals each), with p_k = R_{b_k} y_k + o_{b_k} (points) or R_{b_k} y_k
// (directions) for attachments (joint b_k, weight w_k, vector y_k in b_k's frame):
//   r = s (sum_k w_k p_k - goal)            s = the row's scale (0: the row is off)
// optionally robustified by one loss (iteratively reweighted, as DlsSolver: r and its
// Jacobian scaled by sqrt(rho'(|r|^2))). Block costs: any ceres::CostFunction on the
// translation or on one joint's rotation (priors, limits), mapped to the tangent with the
// manifold's PlusJacobian as DlsSolver does. Cost 1/2 sum rho(|r|^2), as Ceres reports.
//
// Jacobian of a row (DESIGN.md): d r/d delta_t = s W tau I (points; W = sum_k w_k; 0 for
// directions) and d r/d delta_j = [u_j]x R_j B_j for the solved joints on the row's chain
// (the ancestors of its attachments), u_j = s (sum_{k in subtree(j)} w_k (o_j - p_k)) for
// points, -s sum_{k in subtree(j)} w_k p_k for directions; B_j = the manifold's local
// increment basis (I for RightQuaternionManifold, 3 x #dofs for an ASF joint).
//
// Normal equations, (J^T J + lambda I) delta = -J^T r, without forming J:
//   (J^T J)_jk = E_j^T X_jk E_k,  X_jk = sum_rows (u_j . u_k) I - u_k u_j^T,  E_j = R_j B_j,
// non-zero only for joints on a common chain: the kinematic tree's ancestor pairs (plus
// pairs of branches a blended row spans). For every joint j above the lowest common
// ancestor of a row's attachments u_j = a o_j - b with per-row a (= s W, 0 for directions)
// and b (= s x), so X_jk for j an ancestor of k is a polynomial in o_j, o_k of the moments
// sum a^2, sum a b, sum b b^T over the rows below k: summed once per joint up the tree,
// expanded once per ancestor pair. A free joint's block is taken in world-frame increments
// omega_j = R_j delta_j (E_j orthogonal, so the damping is unchanged and no rotation is
// applied per pair). The system is factored by solvers/block_sparse_cholesky.h leaves
// first (reverse preorder, the translation last), so a pure tree has no fill; an ASF
// joint's block is padded to 3 x 3 with identity (its step there is exactly 0).
//
// Iterations: solvers/dls_iterations.h (RunDlsIterations), the same damping and stopping
// rules as the generic DlsSolver, so the two stop alike on the same problem. Each
// evaluation does forward kinematics once over the joints that move some row.
#ifndef MOCAPSOLVE_SOLVERS_TREE_DLS_SOLVER_H_
#define MOCAPSOLVE_SOLVERS_TREE_DLS_SOLVER_H_

#include <cstdint>
#include <utility>
#include <vector>

#include <ceres/cost_function.h>
#include <ceres/loss_function.h>
#include <ceres/manifold.h>
#include <Eigen/Core>

#include "kinematics/skeleton.h"
#include "solvers/block_sparse_cholesky.h"
#include "solvers/dls_iterations.h"

namespace mocapsolve {

class DofQuaternionManifold;

struct TreeAttachment {
  int joint = 0;
  double weight = 1.0;
  Eigen::Vector3d local = Eigen::Vector3d::Zero();  // y_k, in the joint's frame.
};

// Seconds per stage of the evaluations and steps (set_time_stages(true)).
struct TreeDlsStageTimes {
  double fk = 0.0;        // Forward kinematics.
  double rows = 0.0;      // Rows' points, residuals and moments; block costs.
  double assembly = 0.0;  // The moments expanded into the blocks of J^T J and J^T r.
  double solve = 0.0;     // Damping, factorization, triangular solves.
  double update = 0.0;    // The retraction.
  int steps = 0;          // Linear solves.
  double total() const { return fk + rows + assembly + solve + update; }
};

class TreeDlsSolver : private DlsModel {
 public:
  // `translation` (3) and `rotations` (4 per joint) are the caller's; the skeleton must
  // outlive the solver. All joints start held.
  TreeDlsSolver(const Skeleton* skeleton, double* translation, double* rotations);

  // Structure (before the first Solve; a change re-analyses it at the next Solve).
  void SetJointManifold(int joint, const ceres::Manifold* manifold);  // nullptr: held.
  void set_translation_scale(double tau) { translation_scale_ = tau; }
  // Rows; `goal` is read at every evaluation. Returns the row's index.
  int AddPointRow(std::vector<TreeAttachment> attachments, const Eigen::Vector3d* goal, double scale);
  int AddDirectionRow(std::vector<TreeAttachment> attachments, const Eigen::Vector3d* goal, double scale);
  // joint -1: the translation. The cost function's one parameter block is that block.
  void AddBlockCost(int joint, const ceres::CostFunction* cost);
  void set_loss(const ceres::LossFunction* loss) { loss_ = loss; }  // Rows only.

  // Between solves.
  void SetRowScale(int row, double scale) { rows_[row].scale = scale; }
  int num_rows() const { return static_cast<int>(rows_.size()); }
  void set_time_stages(bool on) { time_stages_ = on; }
  const TreeDlsStageTimes& stage_times() const { return times_; }
  void ResetStageTimes() { times_ = TreeDlsStageTimes(); }

  void Solve(const DlsOptions& options, DlsSummary* summary);

  // The rows' residuals (3 per row, in order; robust loss not applied) and their Jacobian in
  // the pose tangent layout of kinematics/kinematic_jacobians.h (3 + 3 #J columns: the
  // translation in model units, each joint's local 3-dof increment; held joints zero), at
  // the current parameters. For tests.
  void Linearize(Eigen::VectorXd* residual, Eigen::MatrixXd* jacobian);

  // Blocks of the factor below the diagonal (after fill), for tests.
  int num_factor_blocks();

 private:
  struct Row {
    bool point = true;
    double scale = 1.0;
    const Eigen::Vector3d* goal = nullptr;
    std::vector<TreeAttachment> attachments;
    double total_weight = 0.0;
    // Filled by Analyze: the solved joints on the chain (ascending), the subtree masks and
    // cumulative weights of the partial ones (those below the attachments' lowest common
    // ancestor), and the pair slots they touch.
    std::vector<int> chain;
    int full = 0;           // chain[0, full) hold every attachment in their subtree.
    int moment_joint = -1;  // chain[full - 1], or -1 (translation only).
    std::vector<uint32_t> masks;     // Per partial joint.
    std::vector<double> cumulative;  // Per partial joint.
    std::vector<int> pair_ids;       // Per partial joint a: (a, t), then (a, chain[0..a]).
  };
  struct BlockCost {
    int joint;
    const ceres::CostFunction* cost;
  };
  // Row moments (see the header): a = s W, b = s x (points), a = 0, b = s n (directions).
  struct Moments {
    double s0 = 0, k0 = 0, k1 = 0;
    Eigen::Vector3d s1, k2, g0, g1, g2;
    Eigen::Matrix3d s2;
    void SetZero();
    void Add(const Moments& other);
  };

  int AddRow(bool point, std::vector<TreeAttachment> attachments, const Eigen::Vector3d* goal, double scale);
  void Analyze();
  void ForwardKinematics();
  bool EvaluateRows(bool linearize, double* cost);
  bool EvaluateBlockCosts(bool linearize, double* cost);
  void Assemble();

  // DlsModel.
  bool Evaluate(bool linearize, double* cost) override;
  int num_columns() const override { return num_columns_; }
  double MaxGradient() const override;
  bool ComputeStep(double lambda, Eigen::VectorXd* delta) override;
  void Save() override;
  void Restore() override;
  bool ApplyStep(const Eigen::VectorXd& delta, double* step_norm, double* x_norm) override;

  const Skeleton* skeleton_;
  double* translation_;
  double* rotations_;
  double translation_scale_ = 1.0;
  std::vector<const ceres::Manifold*> manifolds_;  // Per joint; nullptr = held.
  std::vector<Row> rows_;
  std::vector<BlockCost> block_costs_;
  const ceres::LossFunction* loss_ = nullptr;
  bool analyzed_ = false;
  bool time_stages_ = false;
  TreeDlsStageTimes times_;

  // Analysis.
  std::vector<int> block_of_joint_;   // 1.. for solved joints (preorder), -1 held; 0 = t.
  std::vector<int> joint_of_block_;   // -1 for block 0.
  std::vector<int> tangent_size_;     // Per block (3 for the translation).
  std::vector<char> world_frame_;     // Per block: a free joint solved in world increments.
  std::vector<const DofQuaternionManifold*> dof_manifolds_;  // Per block: an ASF joint's, or null.
  std::vector<int> solved_parent_;    // Per block: the nearest solved ancestor's block, 0 if none.
  std::vector<int> fk_joints_;        // Joints some row depends on, ascending.
  std::vector<int> chain_joints_;     // Joints on some row's chain (held or not), for |x|.
  std::vector<std::pair<int, int>> pairs_;  // (a, b) blocks, a <= b: a's row, b's column.
  std::vector<int> pair_slot_;        // Cholesky slot of each off-diagonal pair, -1 diagonal.
  std::vector<std::vector<std::pair<int, int>>> ancestor_pairs_;  // Per block k: (j, pair (j, k)) j ancestor-or-self.
  int num_columns_ = 0;
  BlockSparseCholesky cholesky_;

  // Per evaluation.
  std::vector<Eigen::Matrix3d> world_rotations_;
  std::vector<Eigen::Vector3d> world_positions_;
  std::vector<Eigen::Matrix3d> bases_;         // Per block: E = R B, padded (non-world-frame joints).
  std::vector<Eigen::Matrix<double, 4, 3>> plus_jacobians_;  // Per block with a manifold.
  std::vector<Moments> moments_;               // Per block (0: rows with no solved joint).
  std::vector<Eigen::Matrix3d> accumulators_;  // X per pair.
  std::vector<Eigen::Vector3d> gradient_world_;  // Per block: sum r x u (and costs' J^T r).
  std::vector<Eigen::Vector3d> points_;        // Scratch: a row's p_k.
  std::vector<Eigen::Vector3d> levers_;        // Scratch: a row's partial levers.
  // The linearization (tangent-frame blocks; world frame for world-frame joints) and its
  // saved copy.
  struct Linearization {
    std::vector<Eigen::Matrix3d> blocks;  // Per pair.
    Eigen::VectorXd gradient;             // 3 per block.
    std::vector<Eigen::Matrix3d> frames;  // Per block: R_j (omega = R_j delta).
    std::vector<Eigen::Matrix3d> extra_blocks;    // Per block: the block costs' J^T J.
    std::vector<Eigen::Vector3d> extra_gradient;  // Per block: their J^T r.
    double max_gradient = 0.0;            // max |J^T r| in tangent coordinates.
    std::vector<double> saved_parameters;
  };
  Linearization current_, saved_;
  Eigen::VectorXd rhs_, step_;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SOLVERS_TREE_DLS_SOLVER_H_
