#include "bench/peers/kdl_tree.h"

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <kdl/frames.hpp>
#include <kdl/jacobian.hpp>
#include <kdl/jntarray.hpp>
#include <kdl/tree.hpp>
#include <kdl/treefksolverpos_recursive.hpp>
#include <kdl/treeiksolverpos_nr_jl.hpp>
#include <kdl/treeiksolvervel_wdls.hpp>
#include <kdl/treejnttojacsolver.hpp>

namespace mocapsolve::peers {
namespace {

KDL::Vector ToKdl(const Eigen::Vector3d& v) { return KDL::Vector(v.x(), v.y(), v.z()); }
KDL::Rotation ToKdl(const Eigen::Quaterniond& q) {
  return KDL::Rotation::Quaternion(q.x(), q.y(), q.z(), q.w());
}
Eigen::Vector3d FromKdl(const KDL::Vector& v) { return {v.x(), v.y(), v.z()}; }

class KdlTree : public PeerModel {
 public:
  KdlTree(const Skeleton& skeleton, const MarkerSet& markers) : skeleton_(skeleton) {
    const int nj = skeleton.num_joints();
    joint_segment_.resize(nj);
    first_q_.resize(nj);
    for (int j = 0; j < nj; ++j) {
      std::string hook = j == 0 ? "root" : joint_segment_[skeleton.parent(j)];
      const std::string base = "j" + std::to_string(j);
      if (j == 0) {
        const KDL::Joint::JointType slides[3] = {KDL::Joint::TransX, KDL::Joint::TransY, KDL::Joint::TransZ};
        for (int k = 0; k < 3; ++k) {
          const std::string name = base + "_t" + std::to_string(k);
          tree_.addSegment(KDL::Segment(name, KDL::Joint(name, slides[k])), hook);
          hook = name;
        }
        tree_.addSegment(KDL::Segment(base + "_rest", KDL::Joint(KDL::Joint::None),
                                      KDL::Frame(ToKdl(skeleton.rest_rotation(0)))), hook);
      } else {
        tree_.addSegment(KDL::Segment(base + "_rest", KDL::Joint(KDL::Joint::None),
                                      KDL::Frame(ToKdl(skeleton.rest_rotation(j)), ToKdl(skeleton.offset(j)))),
                         hook);
      }
      hook = base + "_rest";
      const KDL::Joint::JointType axes[3] = {KDL::Joint::RotX, KDL::Joint::RotY, KDL::Joint::RotZ};
      for (int k = 0; k < 3; ++k) {
        const std::string name = base + "_r" + std::to_string(k);
        tree_.addSegment(KDL::Segment(name, KDL::Joint(name, axes[k])), hook);
        hook = name;
      }
      joint_segment_[j] = hook;
    }
    for (int m = 0; m < markers.num_markers(); ++m) {
      const MarkerAttachment& a = markers.marker(m).attachments[0];
      const std::string name = "m" + std::to_string(m);
      tree_.addSegment(KDL::Segment(name, KDL::Joint(KDL::Joint::None), KDL::Frame(ToKdl(a.offset))),
                       joint_segment_[a.joint]);
      marker_segment_.push_back(name);
    }
    const int nq = tree_.getNrOfJoints();
    q_.resize(nq);
    for (int j = 0; j < nj; ++j) {
      // The q index of the joint's RotX segment (and of TransX for the root).
      first_q_[j] = tree_.getSegment("j" + std::to_string(j) + "_r0")->second.q_nr;
    }
    root_translation_q_ = tree_.getSegment("j0_t0")->second.q_nr;
    // Preorder over segments for the all-frames walk.
    Preorder(tree_.getRootSegment(), -1);
    frames_.resize(order_.size());
    for (int j = 0; j < nj; ++j) joint_index_.push_back(index_of_.at(joint_segment_[j]));
    for (const std::string& name : marker_segment_) marker_index_.push_back(index_of_.at(name));
    jac_solver_ = std::make_unique<KDL::TreeJntToJacSolver>(tree_);
    segment_jacobian_ = KDL::Jacobian(nq);
    jacobian_.setZero(3 * markers.num_markers(), nq);
    // IK.
    fk_solver_ = std::make_unique<KDL::TreeFkSolverPos_recursive>(tree_);
    vel_solver_ = std::make_unique<KDL::TreeIkSolverVel_wdls>(tree_, marker_segment_);
    // TreeIkSolverVel_wdls stacks the endpoints in its own map's (name) order; the weight
    // is the same for each, so the order does not matter.
    Eigen::MatrixXd weight = Eigen::MatrixXd::Zero(6 * markers.num_markers(), 6 * markers.num_markers());
    for (int m = 0; m < markers.num_markers(); ++m) weight.block<3, 3>(6 * m, 6 * m).setIdentity();
    vel_solver_->setWeightTS(weight);
    vel_solver_->setLambda(kLambda);
    q_min_.resize(nq);
    q_max_.resize(nq);
    for (int i = 0; i < nq; ++i) q_min_(i) = -1e9, q_max_(i) = 1e9;
  }

  std::string name() const override { return "kdl"; }
  std::string description() const override {
    return "KDL Tree, " + std::to_string(tree_.getNrOfSegments()) + " segments, " +
           std::to_string(tree_.getNrOfJoints()) +
           " joints (ball = RotX RotY RotZ; markers = fixed end segments)";
  }

  void SetPose(const Pose& pose) override {
    for (int j = 0; j < skeleton_.num_joints(); ++j) {
      const Eigen::Vector3d e = pose.rotations[j].toRotationMatrix().eulerAngles(0, 1, 2);
      for (int k = 0; k < 3; ++k) q_(first_q_[j] + k) = e[k];
    }
    for (int k = 0; k < 3; ++k) q_(root_translation_q_ + k) = pose.translations[0][k];
  }

  void GetCoordinates(Eigen::VectorXd* q) const override { *q = q_.data; }
  void SetCoordinates(const Eigen::VectorXd& q) override { q_.data = q; }

  void ForwardKinematics() override {
    for (size_t s = 0; s < order_.size(); ++s) {
      const KDL::TreeElement& element = order_[s]->second;
      const KDL::Frame local = element.segment.pose(
          element.segment.getJoint().getType() == KDL::Joint::None ? 0.0 : q_(element.q_nr));
      frames_[s] = parent_[s] < 0 ? local : frames_[parent_[s]] * local;
    }
  }

  void FkAndJacobian() override {
    for (size_t m = 0; m < marker_segment_.size(); ++m) {
      jac_solver_->JntToJac(q_, segment_jacobian_, marker_segment_[m]);
      jacobian_.middleRows(3 * m, 3) = segment_jacobian_.data.topRows(3);
    }
  }
  const Eigen::MatrixXd& jacobian() const override { return jacobian_; }

  void JointPositions(std::vector<Eigen::Vector3d>* out) override {
    out->clear();
    for (int s : joint_index_) out->push_back(FromKdl(frames_[s].p));
  }
  void MarkerPositions(std::vector<Eigen::Vector3d>* out) override {
    out->clear();
    for (int s : marker_index_) out->push_back(FromKdl(frames_[s].p));
  }

  bool has_ik() const override { return true; }
  Status SolveIk(const std::vector<Eigen::Vector3d>& observed, const IkTarget& target,
                 IkResult* result) override {
    const double eps = std::sqrt(static_cast<double>(observed.size())) * target.target_rms;
    if (!ik_solver_ || eps != ik_eps_ || target.max_iterations != ik_max_iterations_) {
      // Built once per setting (a benchmark runs one): the solver copies the tree.
      ik_solver_ = std::make_unique<KDL::TreeIkSolverPos_NR_JL>(tree_, marker_segment_, q_min_, q_max_,
                                                               *fk_solver_, *vel_solver_,
                                                               target.max_iterations, eps);
      ik_eps_ = eps;
      ik_max_iterations_ = target.max_iterations;
    }
    for (size_t m = 0; m < observed.size(); ++m) goals_[marker_segment_[m]] = KDL::Frame(ToKdl(observed[m]));
    q_out_ = q_;
    ik_solver_->CartToJnt(q_, goals_, q_out_);
    q_ = q_out_;
    ForwardKinematics();
    std::vector<Eigen::Vector3d> positions;
    MarkerPositions(&positions);
    result->rms = MarkerRms(positions, observed);
    result->reached = result->rms <= target.target_rms;
    result->iterations = -1;  // Not reported by KDL.
    return Status::Ok();
  }

 private:
  static constexpr double kLambda = 1e-6;

  void Preorder(KDL::SegmentMap::const_iterator it, int parent) {
    const int index = static_cast<int>(order_.size());
    order_.push_back(it);
    parent_.push_back(parent);
    index_of_[it->first] = index;
    for (const auto& child : it->second.children) Preorder(child, index);
  }

  const Skeleton& skeleton_;
  KDL::Tree tree_;
  std::vector<std::string> joint_segment_, marker_segment_;
  std::vector<int> first_q_;
  int root_translation_q_ = 0;
  KDL::JntArray q_, q_out_, q_min_, q_max_;
  std::vector<KDL::SegmentMap::const_iterator> order_;
  std::vector<int> parent_;
  std::map<std::string, int> index_of_;
  std::vector<int> joint_index_, marker_index_;
  std::vector<KDL::Frame> frames_;
  std::unique_ptr<KDL::TreeJntToJacSolver> jac_solver_;
  KDL::Jacobian segment_jacobian_;
  Eigen::MatrixXd jacobian_;
  std::unique_ptr<KDL::TreeFkSolverPos_recursive> fk_solver_;
  std::unique_ptr<KDL::TreeIkSolverVel_wdls> vel_solver_;
  std::unique_ptr<KDL::TreeIkSolverPos_NR_JL> ik_solver_;
  double ik_eps_ = -1.0;
  int ik_max_iterations_ = -1;
  KDL::Frames goals_;
};

}  // namespace

std::unique_ptr<PeerModel> MakeKdlTree(const Skeleton& skeleton, const MarkerSet& markers) {
  return std::make_unique<KdlTree>(skeleton, markers);
}

}  // namespace mocapsolve::peers
