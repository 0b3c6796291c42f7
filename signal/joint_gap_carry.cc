#include "signal/joint_gap_carry.h"

#include <algorithm>
#include <cassert>
#include <memory>

#include <Eigen/SVD>

#include "kinematics/rotation.h"
#include "signal/joint_gap_template.h"

namespace mocapsolve {
namespace {

constexpr int kMinObservers = 3;
constexpr double kMinLeverMetres = 0.03;

struct HermiteBasis {
  double h10, h01, h11;  // h00 = 1 - h01 multiplies the start value, which is 0 here.
};

HermiteBasis Basis(double t) {
  const double t2 = t * t, t3 = t2 * t;
  return {t3 - 2.0 * t2 + t, -2.0 * t3 + 3.0 * t2, t3 - t2};
}

// The frames [lo, hi] the joint may use for its edge velocities: between its previous run
// (or the take's start) and its next one (or the take's end).
struct FreeSpan {
  int lo, hi;
};

void CarryRotation(const std::vector<Eigen::Quaterniond>& q, int a, int b, int da, int db,
                   std::vector<Eigen::Quaterniond>* out) {
  const Eigen::Quaterniond qa = q[a];
  Eigen::Quaterniond qb = q[b];
  if (qa.dot(qb) < 0.0) qb.coeffs() = -qb.coeffs();
  const Eigen::Vector3d r = LogMap(qa.conjugate() * qb);
  Eigen::Vector3d wa = Eigen::Vector3d::Zero(), wb = Eigen::Vector3d::Zero();
  if (da > 0) wa = LogMap(q[a - da].conjugate() * qa) / da;
  if (db > 0) wb = LogMap(qb.conjugate() * q[b + db]) / db;
  const double n = b - a;
  for (int f = a + 1; f < b; ++f) {
    const HermiteBasis h = Basis((f - a) / n);
    (*out)[f] = (qa * ExpMap(h.h01 * r + n * (h.h10 * wa + h.h11 * wb))).normalized();
  }
}

void CarryTranslation(const std::vector<Eigen::Vector3d>& t, int a, int b, int da, int db,
                      std::vector<Eigen::Vector3d>* out) {
  const Eigen::Vector3d va = da > 0 ? Eigen::Vector3d((t[a] - t[a - da]) / da) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d vb = db > 0 ? Eigen::Vector3d((t[b + db] - t[b]) / db) : Eigen::Vector3d::Zero();
  const double n = b - a;
  for (int f = a + 1; f < b; ++f) {
    const HermiteBasis h = Basis((f - a) / n);
    (*out)[f] = t[a] + h.h01 * (t[b] - t[a]) + n * (h.h10 * va + h.h11 * vb);
  }
}

void CarryRun(const Skeleton& skeleton, const CarriedJointRun& run, const FreeSpan& span, int velocity_frames,
              Motion* motion) {
  const int j = run.joint;
  const int frames = motion->num_frames();
  const int a = run.first - 1, b = run.last + 1;
  const bool animated = skeleton.has_translation_channels(j);
  if (a < 0 || b >= frames) {  // One solved side: hold it.
    if (a < 0 && b >= frames) return;
    const Pose& held = motion->frames[a < 0 ? b : a];
    const Eigen::Quaterniond q = held.rotations[j];
    const Eigen::Vector3d t = held.translations[j];
    for (int f = run.first; f <= run.last; ++f) {
      motion->frames[f].rotations[j] = q;
      if (animated) motion->frames[f].translations[j] = t;
    }
    return;
  }
  const int da = std::min(velocity_frames, a - span.lo), db = std::min(velocity_frames, span.hi - b);
  std::vector<Eigen::Quaterniond> q(frames), q_out(frames);
  std::vector<Eigen::Vector3d> t(frames), t_out(frames);
  const int lo = a - da, hi = b + db;
  for (int f = lo; f <= hi; ++f) {
    q[f] = motion->frames[f].rotations[j];
    t[f] = motion->frames[f].translations[j];
  }
  // Sign-continuous over the velocity frames on each side.
  for (int f = lo + 1; f <= a; ++f) if (q[f].dot(q[f - 1]) < 0.0) q[f].coeffs() = -q[f].coeffs();
  for (int f = b + 1; f <= hi; ++f) if (q[f].dot(q[f - 1]) < 0.0) q[f].coeffs() = -q[f].coeffs();
  CarryRotation(q, a, b, da, db, &q_out);
  if (animated) CarryTranslation(t, a, b, da, db, &t_out);
  for (int f = a + 1; f < b; ++f) {
    motion->frames[f].rotations[j] = q_out[f];
    if (animated) motion->frames[f].translations[j] = t_out[f];
  }
}

// observers[j]: the markers whose position depends on joint j's rotation.
std::vector<std::vector<int>> Observers(const Skeleton& skeleton, const MarkerSet& markers) {
  std::vector<std::vector<int>> observers(skeleton.num_joints());
  for (int m = 0; m < markers.num_markers(); ++m) {
    for (int j : markers.InfluencingJoints(m)) observers[j].push_back(m);
  }
  return observers;
}

// own[j]: the markers attached to joint j alone, with their offsets in its frame.
struct OwnMarker {
  int marker;
  Eigen::Vector3d offset;
};

std::vector<std::vector<OwnMarker>> OwnMarkers(const Skeleton& skeleton, const MarkerSet& markers) {
  std::vector<std::vector<OwnMarker>> own(skeleton.num_joints());
  for (int m = 0; m < markers.num_markers(); ++m) {
    const std::vector<MarkerAttachment>& attachments = markers.marker(m).attachments;
    const int j = attachments.front().joint;
    bool single = true;
    for (const MarkerAttachment& a : attachments) single &= a.joint == j;
    if (!single) continue;
    Eigen::Vector3d offset = Eigen::Vector3d::Zero();
    for (const MarkerAttachment& a : attachments) offset += a.weight * a.offset;
    own[j].push_back({m, offset});
  }
  return own;
}

// True if the present markers of joint j's own bone fix its rotation dofs: the smallest
// singular value of their velocity Jacobian, rows e_k x v_m (v_m the offset, e_k the dof
// axes at zero angles), is at least the lever kMinLeverMetres.
bool OwnMarkersFixDofs(const Skeleton& skeleton, int j, const std::vector<OwnMarker>& own,
                       const MarkerTrajectories& observed, int f, double min_lever) {
  const std::vector<int>& axes = skeleton.rotation_axes(j);
  if (axes.empty() || own.empty() || min_lever <= 0.0) return false;
  Eigen::MatrixXd jacobian(3 * own.size(), axes.size());
  int rows = 0;
  for (const OwnMarker& m : own) {
    if (!observed.valid(f, m.marker)) continue;
    for (size_t k = 0; k < axes.size(); ++k) {
      jacobian.block<3, 1>(rows, k) = Eigen::Vector3d::Unit(axes[k]).cross(m.offset);
    }
    rows += 3;
  }
  if (rows < 3) return false;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(jacobian.topRows(rows));
  return svd.singularValues().minCoeff() >= min_lever;
}

}  // namespace

std::vector<CarriedJointRun> FindUnobservedJointRuns(const Skeleton& skeleton, const MarkerSet& markers,
                                                     const MarkerTrajectories& observed, int min_frames) {
  const int joints = skeleton.num_joints(), frames = observed.num_frames();
  const std::vector<std::vector<int>> observers = Observers(skeleton, markers);
  const std::vector<std::vector<OwnMarker>> own = OwnMarkers(skeleton, markers);
  const double min_lever = skeleton.unit().known() ? kMinLeverMetres / skeleton.unit().metres_per_unit : 0.0;
  // lost[j][f], parents first: the own-marker rule needs the parent observed (a forearm
  // marker on a wrist fixes the wrist's angle only together with the elbow's).
  std::vector<std::vector<char>> lost(joints, std::vector<char>(frames + 1, 0));
  std::vector<CarriedJointRun> runs;
  for (int j = 0; j < joints; ++j) {
    if (observers[j].empty()) continue;
    const int total = static_cast<int>(observers[j].size()), parent = skeleton.parent(j);
    int start = -1;
    for (int f = 0; f <= frames; ++f) {
      int present = 0;
      for (int k = 0; f < frames && k < total; ++k) present += observed.valid(f, observers[j][k]);
      const bool seen = f == frames || present >= kMinObservers || 2 * present >= total || total - present < 2 ||
                        ((parent < 0 || !lost[parent][f]) && OwnMarkersFixDofs(skeleton, j, own[j], observed, f, min_lever));
      lost[j][f] = !seen;
      if (!seen && start < 0) start = f;
      if (seen && start >= 0) {
        if (f - start >= std::max(min_frames, 1)) runs.push_back({j, start, f - 1});
        start = -1;
      }
    }
  }
  return runs;
}

void CarryJoints(const Skeleton& skeleton, const std::vector<CarriedJointRun>& runs, int velocity_frames,
                 Motion* motion) {
  CarryJoints(skeleton, runs, velocity_frames, nullptr, motion);
}

void CarryJoints(const Skeleton& skeleton, const std::vector<CarriedJointRun>& runs, int velocity_frames,
                 const JointTemplateOptions* templates, Motion* motion) {
  assert(velocity_frames >= 1);
  const int frames = motion->num_frames();
  std::vector<std::vector<char>> carried;
  if (templates != nullptr) {
    carried.assign(skeleton.num_joints(), std::vector<char>(frames, 0));
    for (const CarriedJointRun& run : runs) {
      std::fill(carried[run.joint].begin() + run.first, carried[run.joint].begin() + run.last + 1, 1);
    }
  }
  // One table for every run's search: a run's carry writes only carried samples, which no
  // search reads (joint_gap_template.h).
  std::unique_ptr<JointTemplateTable> table;
  if (templates != nullptr && !runs.empty() && frames > 0) {
    table = std::make_unique<JointTemplateTable>(skeleton, *motion, carried, 0, frames - 1);
  }
  for (size_t i = 0; i < runs.size(); ++i) {
    const CarriedJointRun& run = runs[i];
    assert(run.joint >= 0 && run.joint < skeleton.num_joints() && run.first >= 0 && run.last < frames &&
           run.first <= run.last);
    FreeSpan span{0, frames - 1};
    if (i > 0 && runs[i - 1].joint == run.joint) span.lo = runs[i - 1].last + 1;
    if (i + 1 < runs.size() && runs[i + 1].joint == run.joint) span.hi = runs[i + 1].first - 1;
    const int tau = templates != nullptr && !skeleton.has_translation_channels(run.joint)
                        ? FindTemplateShift(skeleton, *motion, carried, *table, run, *templates)
                        : 0;
    if (tau != 0) {
      CarryFromTemplate(run, tau, motion);
    } else {
      CarryRun(skeleton, run, span, velocity_frames, motion);
    }
  }
}

}  // namespace mocapsolve
