#include "viewer/view_scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "kinematics/forward_kinematics.h"

namespace mocapsolve {

const char* MarkerStateName(MarkerState state) {
  switch (state) {
    case MarkerState::kObserved: return "observed";
    case MarkerState::kMissing: return "missing";
    case MarkerState::kRepairedGap: return "gap";
    case MarkerState::kRepairedOutlier: return "outlier";
    case MarkerState::kRepairedJointDifference: return "joint difference";
    case MarkerState::kRepairedSwap: return "swap";
    case MarkerState::kRepairedUnlabelled: return "unlabelled";
  }
  return "observed";
}

MarkerState RepairedStateForReason(const std::string& reason) {
  if (reason == "outlier") return MarkerState::kRepairedOutlier;
  if (reason == "joint difference") return MarkerState::kRepairedJointDifference;
  if (reason == "swap") return MarkerState::kRepairedSwap;
  if (reason == "unlabelled") return MarkerState::kRepairedUnlabelled;
  return MarkerState::kRepairedGap;
}

int GuessUpAxis(const std::vector<std::vector<Eigen::Vector3d>>& frames) {
  Eigen::Vector3d spread = Eigen::Vector3d::Zero();
  const int count = static_cast<int>(frames.size());
  const int step = std::max(1, count / 200);
  for (int f = 0; f < count; f += step) {
    Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d high = -low;
    for (const Eigen::Vector3d& p : frames[f]) {
      if (!p.allFinite()) continue;
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
    if (low.allFinite() && high.allFinite()) spread += high - low;
  }
  int axis = 1;
  spread.maxCoeff(&axis);
  return spread.isZero() ? 1 : axis;
}

Status MakeViewTransform(const std::string& what, int up_axis, const LengthUnit& unit, double height,
                         ViewTransform* transform) {
  ViewTransform out;
  if (up_axis == 2) {  // +Z up: (x, y, z) -> (x, z, -y).
    out.rotation << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  } else if (up_axis == 0) {  // +X up: (x, y, z) -> (-y, x, z).
    out.rotation << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  }
  char text[160];
  if (unit.known()) {
    out.scale = unit.metres_per_unit;
    std::snprintf(text, sizeof(text), "%s: %s, +%c up", what.c_str(), unit.name.c_str(), "xyz"[up_axis]);
  } else {
    if (!(height > 0.0) || !std::isfinite(height)) {
      return Status::Error(what + ": its length unit is unknown (give --skeleton_units)");
    }
    static const LengthUnit kCandidates[] = {Metres(), Centimetres(), Millimetres(), {"in", 0.0254}};
    out.scale = 1.75 / height;
    std::string name = "unknown unit, scaled to 1.75 m tall";
    for (const LengthUnit& candidate : kCandidates) {
      const double metres = height * candidate.metres_per_unit;
      if (metres >= 1.0 && metres <= 2.5) {
        out.scale = candidate.metres_per_unit;
        name = candidate.name + " (guessed from its height; --skeleton_units states it)";
        break;
      }
    }
    std::snprintf(text, sizeof(text), "%s: %s, +%c up", what.c_str(), name.c_str(), "xyz"[up_axis]);
  }
  out.note = text;
  *transform = out;
  return Status::Ok();
}

Status MakeMotionViewTransform(const std::string& what, const Skeleton& skeleton, const Motion& motion,
                               int up_axis, ViewTransform* transform) {
  if (up_axis < 0) up_axis = GuessUpAxis(ClipJointPositions(skeleton, motion));
  FkData fk(skeleton);
  ForwardKinematics(skeleton, RestPose(skeleton), &fk);
  Eigen::Vector3d low = fk.world_positions[0], high = low;
  for (const Eigen::Vector3d& p : fk.world_positions) low = low.cwiseMin(p), high = high.cwiseMax(p);
  return MakeViewTransform(what, up_axis, skeleton.unit(), (high - low).maxCoeff(), transform);
}

ViewMarkers MakeViewMarkers(const std::string& name, const std::vector<std::string>& labels,
                            const std::vector<std::vector<Eigen::Vector3d>>& observed,
                            const ViewTransform& transform) {
  ViewMarkers out;
  out.name = name;
  out.labels = labels;
  out.num_frames = static_cast<int>(observed.size());
  const int markers = out.num_markers();
  out.positions.assign(static_cast<size_t>(out.num_frames) * markers * 3, std::nanf(""));
  out.states.assign(static_cast<size_t>(out.num_frames) * markers, static_cast<std::uint8_t>(MarkerState::kMissing));
  for (int f = 0; f < out.num_frames; ++f) {
    for (int m = 0; m < markers && m < static_cast<int>(observed[f].size()); ++m) {
      const Eigen::Vector3d& p = observed[f][m];
      if (!p.allFinite()) continue;
      const Eigen::Vector3d w = transform.Apply(p);
      const size_t i = static_cast<size_t>(f) * markers + m;
      for (int k = 0; k < 3; ++k) out.positions[3 * i + k] = static_cast<float>(w[k]);
      out.states[i] = static_cast<std::uint8_t>(MarkerState::kObserved);
    }
  }
  return out;
}

ViewMarkers MakeViewMarkers(const std::string& name, const MarkerTrajectories& trajectories,
                            const ViewTransform& transform) {
  std::vector<std::vector<Eigen::Vector3d>> observed(trajectories.num_frames());
  for (int f = 0; f < trajectories.num_frames(); ++f) {
    observed[f].resize(trajectories.num_markers());
    for (int m = 0; m < trajectories.num_markers(); ++m) observed[f][m] = trajectories.position(f, m);
  }
  return MakeViewMarkers(name, trajectories.labels(), observed, transform);
}

ViewSkeleton MakeViewSkeleton(const std::string& name, const Skeleton& skeleton, const Motion& motion,
                              const ViewTransform& transform) {
  ViewSkeleton out;
  out.name = name;
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    out.joint_names.push_back(skeleton.name(j));
    out.parents.push_back(skeleton.parent(j));
  }
  out.num_frames = motion.num_frames();
  const int joints = skeleton.num_joints();
  out.positions.resize(static_cast<size_t>(out.num_frames) * joints * 3);
  FkData fk(skeleton);
  for (int f = 0; f < out.num_frames; ++f) {
    ForwardKinematics(skeleton, motion.frames[f], &fk);
    for (int j = 0; j < joints; ++j) {
      const Eigen::Vector3d w = transform.Apply(fk.world_positions[j]);
      const size_t i = 3 * (static_cast<size_t>(f) * joints + j);
      for (int k = 0; k < 3; ++k) out.positions[i + k] = static_cast<float>(w[k]);
    }
  }
  return out;
}

void MarkRepairedSamples(const std::vector<ViewInterval>& intervals, ViewMarkers* markers) {
  const int count = markers->num_markers();
  for (const ViewInterval& interval : intervals) {
    if (interval.marker < 0 || interval.marker >= count) continue;
    const int first = std::max(0, interval.first);
    const int last = std::min(markers->num_frames - 1, interval.last);
    for (int f = first; f <= last; ++f) {
      markers->states[static_cast<size_t>(f) * count + interval.marker] = static_cast<std::uint8_t>(interval.state);
    }
  }
}

int ViewScene::num_frames() const {
  int frames = 0;
  for (const ViewMarkers& m : markers) frames = std::max(frames, m.num_frames);
  for (const ViewSkeleton& s : skeletons) frames = std::max(frames, s.num_frames);
  for (const ViewCurve& c : curves) frames = std::max(frames, static_cast<int>(c.values.size()));
  return frames;
}

}  // namespace mocapsolve
