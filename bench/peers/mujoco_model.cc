#include "bench/peers/mujoco_model.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include <mujoco/mujoco.h>

namespace mocapsolve::peers {
namespace {

std::string Numbers(std::initializer_list<double> values) {
  std::string text;
  char buffer[32];
  for (double v : values) {
    std::snprintf(buffer, sizeof(buffer), "%.17g", v);
    text += (text.empty() ? "" : " ") + std::string(buffer);
  }
  return text;
}

std::string MakeMjcf(const Skeleton& skeleton, const MarkerSet& markers) {
  const int nj = skeleton.num_joints();
  std::vector<std::vector<int>> children(nj), sites(nj);
  for (int j = 1; j < nj; ++j) children[skeleton.parent(j)].push_back(j);
  for (int m = 0; m < markers.num_markers(); ++m) sites[markers.marker(m).attachments[0].joint].push_back(m);
  std::ostringstream xml;
  xml << "<mujoco model=\"mocapsolve\">\n<worldbody>\n";
  // Bodies in preorder, closed on the way back up.
  std::vector<int> stack = {0};
  std::vector<bool> opened(nj, false);
  while (!stack.empty()) {
    const int j = stack.back();
    if (opened[j]) {
      xml << "</body>\n";
      stack.pop_back();
      continue;
    }
    opened[j] = true;
    const Eigen::Quaterniond& rest = skeleton.rest_rotation(j);
    if (j == 0) {
      xml << "<body name=\"j0\">\n<freejoint name=\"root\"/>\n";
    } else {
      const Eigen::Vector3d& t = skeleton.offset(j);
      xml << "<body name=\"j" << j << "\" pos=\"" << Numbers({t.x(), t.y(), t.z()}) << "\" quat=\""
          << Numbers({rest.w(), rest.x(), rest.y(), rest.z()}) << "\">\n<joint type=\"ball\"/>\n";
    }
    xml << "<inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"1 1 1\"/>\n";
    for (int m : sites[j]) {
      const Eigen::Vector3d& z = markers.marker(m).attachments[0].offset;
      xml << "<site name=\"m" << m << "\" pos=\"" << Numbers({z.x(), z.y(), z.z()}) << "\"/>\n";
    }
    for (auto it = children[j].rbegin(); it != children[j].rend(); ++it) stack.push_back(*it);
  }
  xml << "</worldbody>\n</mujoco>\n";
  return xml.str();
}

class MujocoModel : public PeerModel {
 public:
  MujocoModel(const Skeleton& skeleton, mjModel* model) : skeleton_(skeleton), m_(model), d_(mj_makeData(model)) {
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      const int body = mj_name2id(m_, mjOBJ_BODY, ("j" + std::to_string(j)).c_str());
      body_.push_back(body);
      qpos_address_.push_back(m_->jnt_qposadr[m_->body_jntadr[body]]);
    }
    rows_.assign(3 * m_->nsite * m_->nv, 0.0);
  }
  ~MujocoModel() override {
    mj_deleteData(d_);
    mj_deleteModel(m_);
  }

  std::string name() const override { return "mujoco"; }
  std::string description() const override {
    const int v = mj_version();
    return "MuJoCo " + std::to_string(v / 100) + "." + std::to_string(v / 10 % 10) + "." + std::to_string(v % 10) + " model from MJCF, nq " + std::to_string(m_->nq) + ", nv " +
           std::to_string(m_->nv) + " (free root, ball joints; markers = sites)";
  }

  void SetPose(const Pose& pose) override {
    for (int j = 0; j < skeleton_.num_joints(); ++j) {
      double* q = d_->qpos + qpos_address_[j];
      Eigen::Quaterniond r = pose.rotations[j];
      if (j == 0) {
        for (int k = 0; k < 3; ++k) q[k] = pose.translations[0][k];
        r = skeleton_.rest_rotation(0) * r;
        q += 3;
      }
      q[0] = r.w(), q[1] = r.x(), q[2] = r.y(), q[3] = r.z();
    }
  }

  void GetCoordinates(Eigen::VectorXd* q) const override { *q = Eigen::Map<const Eigen::VectorXd>(d_->qpos, m_->nq); }
  void SetCoordinates(const Eigen::VectorXd& q) override { Eigen::Map<Eigen::VectorXd>(d_->qpos, m_->nq) = q; }

  void ForwardKinematics() override { mj_kinematics(m_, d_); }

  void FkAndJacobian() override {
    mj_kinematics(m_, d_);
    mj_comPos(m_, d_);
    for (int s = 0; s < m_->nsite; ++s) mj_jacSite(m_, d_, rows_.data() + 3 * s * m_->nv, nullptr, s);
  }
  const Eigen::MatrixXd& jacobian() const override {
    // Not timed: MuJoCo's row-major buffer as a matrix. Site s is marker m = s (sites are
    // named m<index> and MuJoCo numbers them in body preorder, so map by name).
    jacobian_.resize(3 * m_->nsite, m_->nv);
    for (int s = 0; s < m_->nsite; ++s) {
      const int m = std::atoi(mj_id2name(m_, mjOBJ_SITE, s) + 1);
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < m_->nv; ++c) jacobian_(3 * m + r, c) = rows_[(3 * s + r) * m_->nv + c];
      }
    }
    return jacobian_;
  }

  void JointPositions(std::vector<Eigen::Vector3d>* out) override {
    out->clear();
    for (int b : body_) out->emplace_back(d_->xpos[3 * b], d_->xpos[3 * b + 1], d_->xpos[3 * b + 2]);
  }
  void MarkerPositions(std::vector<Eigen::Vector3d>* out) override {
    out->assign(m_->nsite, Eigen::Vector3d::Zero());
    for (int s = 0; s < m_->nsite; ++s) {
      const int m = std::atoi(mj_id2name(m_, mjOBJ_SITE, s) + 1);
      (*out)[m] = Eigen::Vector3d(d_->site_xpos[3 * s], d_->site_xpos[3 * s + 1], d_->site_xpos[3 * s + 2]);
    }
  }

 private:
  const Skeleton& skeleton_;
  mjModel* m_;
  mjData* d_;
  std::vector<int> body_, qpos_address_;
  std::vector<double> rows_;
  mutable Eigen::MatrixXd jacobian_;
};

}  // namespace

Status MakeMujocoModel(const Skeleton& skeleton, const MarkerSet& markers, std::unique_ptr<PeerModel>* model) {
  const std::string xml = MakeMjcf(skeleton, markers);
  char path[] = "/tmp/mocapsolve_peers_XXXXXX.xml";
  const int fd = mkstemps(path, 4);
  if (fd < 0) return Status::Error("mujoco: cannot create a temporary MJCF file");
  const bool written = write(fd, xml.data(), xml.size()) == static_cast<ssize_t>(xml.size());
  close(fd);
  char error[1000] = "";
  mjModel* m = written ? mj_loadXML(path, nullptr, error, sizeof(error)) : nullptr;
  unlink(path);
  if (m == nullptr) return Status::Error(std::string("mujoco: mj_loadXML failed: ") + (written ? error : "write failed"));
  *model = std::make_unique<MujocoModel>(skeleton, m);
  return Status::Ok();
}

}  // namespace mocapsolve::peers
