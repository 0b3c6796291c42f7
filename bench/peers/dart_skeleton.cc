#include "bench/peers/dart_skeleton.h"

#include <cmath>
#include <limits>
#include <vector>

#include <dart/dynamics/BallJoint.hpp>
#include <dart/dynamics/BodyNode.hpp>
#include <dart/dynamics/EndEffector.hpp>
#include <dart/dynamics/FreeJoint.hpp>
#include <dart/dynamics/HierarchicalIK.hpp>
#include <dart/dynamics/InverseKinematics.hpp>
#include <dart/dynamics/SimpleFrame.hpp>
#include <dart/dynamics/Skeleton.hpp>
#include <dart/optimizer/GradientDescentSolver.hpp>

namespace mocapsolve::peers {
namespace {

using dart::dynamics::BallJoint;
using dart::dynamics::BodyNode;
using dart::dynamics::EndEffector;
using dart::dynamics::FreeJoint;
using dart::dynamics::InverseKinematics;

class DartSkeleton : public PeerModel {
 public:
  DartSkeleton(const Skeleton& skeleton, const MarkerSet& markers, const DartIkSettings& settings)
      : skeleton_(skeleton), settings_(settings) {
    skel_ = dart::dynamics::Skeleton::create("mocapsolve");
    const int nj = skeleton.num_joints();
    for (int j = 0; j < nj; ++j) {
      BodyNode* body;
      if (j == 0) {
        body = skel_->createJointAndBodyNodePair<FreeJoint>(nullptr).second;
      } else {
        auto pair = skel_->createJointAndBodyNodePair<BallJoint>(bodies_[skeleton.parent(j)]);
        Eigen::Isometry3d from_parent = Eigen::Isometry3d::Identity();
        from_parent.translate(skeleton.offset(j));
        from_parent.rotate(skeleton.rest_rotation(j));
        pair.first->setTransformFromParentBodyNode(from_parent);
        body = pair.second;
      }
      body->setName("j" + std::to_string(j));
      body->getParentJoint()->setName("joint" + std::to_string(j));
      bodies_.push_back(body);
      dof_.push_back(static_cast<int>(body->getParentJoint()->getIndexInSkeleton(0)));
    }
    for (int m = 0; m < markers.num_markers(); ++m) {
      const MarkerAttachment& a = markers.marker(m).attachments[0];
      EndEffector* ee = bodies_[a.joint]->createEndEffector("m" + std::to_string(m));
      Eigen::Isometry3d offset = Eigen::Isometry3d::Identity();
      offset.translation() = a.offset;
      ee->setDefaultRelativeTransform(offset, true);
      effectors_.push_back(ee);
    }
    q_ = Eigen::VectorXd::Zero(skel_->getNumDofs());
    jacobian_.setZero(3 * markers.num_markers(), skel_->getNumDofs());
  }

  std::string name() const override { return "dart"; }
  std::string description() const override {
    return "DART Skeleton, " + std::to_string(skel_->getNumBodyNodes()) + " bodies, " +
           std::to_string(skel_->getNumDofs()) + " dofs (FreeJoint root, BallJoints; markers = EndEffectors)";
  }

  void SetPose(const Pose& pose) override {
    for (int j = 0; j < skeleton_.num_joints(); ++j) {
      if (j == 0) {
        Eigen::Isometry3d root = Eigen::Isometry3d::Identity();
        root.translation() = pose.translations[0];
        root.linear() = (skeleton_.rest_rotation(0) * pose.rotations[0]).toRotationMatrix();
        q_.segment<6>(dof_[0]) = FreeJoint::convertToPositions(root);
      } else {
        q_.segment<3>(dof_[j]) = BallJoint::convertToPositions(pose.rotations[j].toRotationMatrix());
      }
    }
    skel_->setPositions(q_);
  }

  void GetCoordinates(Eigen::VectorXd* q) const override { *q = q_; }
  void SetCoordinates(const Eigen::VectorXd& q) override { q_ = q; }

  void ForwardKinematics() override {
    skel_->setPositions(q_);
    for (BodyNode* b : bodies_) sink_ += b->getWorldTransform().translation().x();
    for (EndEffector* e : effectors_) sink_ += e->getWorldTransform().translation().x();
  }

  void FkAndJacobian() override {
    skel_->setPositions(q_);
    for (size_t m = 0; m < effectors_.size(); ++m) {
      jacobian_.middleRows(3 * m, 3) = skel_->getLinearJacobian(effectors_[m]);
    }
  }
  const Eigen::MatrixXd& jacobian() const override { return jacobian_; }

  void JointPositions(std::vector<Eigen::Vector3d>* out) override {
    out->clear();
    for (BodyNode* b : bodies_) out->push_back(b->getWorldTransform().translation());
  }
  void MarkerPositions(std::vector<Eigen::Vector3d>* out) override {
    out->clear();
    for (EndEffector* e : effectors_) out->push_back(e->getWorldTransform().translation());
  }

  bool has_ik() const override { return true; }
  Status SolveIk(const std::vector<Eigen::Vector3d>& observed, const IkTarget& target, IkResult* result) override {
    if (!ik_ready_) SetUpIk();
    skel_->setPositions(q_);
    for (size_t m = 0; m < observed.size(); ++m) targets_[m]->setTranslation(observed[m]);
    std::vector<Eigen::Vector3d> positions;
    int iterations = 0;
    MarkerPositions(&positions);
    result->rms = MarkerRms(positions, observed);
    while (result->rms > target.target_rms && iterations < target.max_iterations) {
      whole_body_->solveAndApply(true);
      iterations += settings_.chunk;
      MarkerPositions(&positions);
      result->rms = MarkerRms(positions, observed);
    }
    q_ = skel_->getPositions();
    result->iterations = iterations;
    result->reached = result->rms <= target.target_rms;
    return Status::Ok();
  }

 private:
  void SetUpIk() {
    const double inf = std::numeric_limits<double>::infinity();
    for (EndEffector* e : effectors_) {
      const std::shared_ptr<InverseKinematics>& ik = e->getIK(true);
      auto frame = dart::dynamics::SimpleFrame::createShared(dart::dynamics::Frame::World());
      ik->setTarget(frame);
      targets_.push_back(frame);
      ik->getErrorMethod().setAngularBounds(Eigen::Vector3d::Constant(-inf), Eigen::Vector3d::Constant(inf));
      ik->getErrorMethod().setLinearBounds(Eigen::Vector3d::Constant(-settings_.linear_bound),
                                           Eigen::Vector3d::Constant(settings_.linear_bound));
      if (settings_.gradient == "transpose") {
        ik->setGradientMethod<InverseKinematics::JacobianTranspose>();
      } else {
        ik->setGradientMethod<InverseKinematics::JacobianDLS>().setDampingCoefficient(settings_.damping);
      }
    }
    whole_body_ = skel_->getIK(true);
    auto solver = std::dynamic_pointer_cast<dart::optimizer::GradientDescentSolver>(whole_body_->getSolver());
    if (solver) {
      solver->setStepSize(settings_.step_size);
      solver->setNumMaxIterations(settings_.chunk);
      solver->setTolerance(0.0);
    }
    ik_ready_ = true;
  }

  const Skeleton& skeleton_;
  DartIkSettings settings_;
  dart::dynamics::SkeletonPtr skel_;
  std::vector<BodyNode*> bodies_;
  std::vector<EndEffector*> effectors_;
  std::vector<int> dof_;
  Eigen::VectorXd q_;
  Eigen::MatrixXd jacobian_;
  double sink_ = 0.0;
  bool ik_ready_ = false;
  std::vector<std::shared_ptr<dart::dynamics::SimpleFrame>> targets_;
  std::shared_ptr<dart::dynamics::WholeBodyIK> whole_body_;
};

}  // namespace

std::unique_ptr<PeerModel> MakeDartSkeleton(const Skeleton& skeleton, const MarkerSet& markers,
                                            const DartIkSettings& ik) {
  return std::make_unique<DartSkeleton>(skeleton, markers, ik);
}

}  // namespace mocapsolve::peers
