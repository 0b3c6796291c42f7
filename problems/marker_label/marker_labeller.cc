#include "problems/marker_label/marker_labeller.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>

#include <Eigen/Geometry>

namespace mocapsolve {
namespace {

const Eigen::Vector3d kNan = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
constexpr int kNever = std::numeric_limits<int>::max() / 2;  // `since` of a marker never labelled.
// An exchange of two tracked markers' labels is kept when it lowers the solved cost of the
// track's frames by more than 5 %: continuous tracks are evidence of their own, and
// markers the fit cannot tell apart (one marker on each of two short joints) differ by
// about 1 % either way; a wrong acquisition corrected differs by 20 % (CMU 02_05, S02).
constexpr double kTrackExchangeRatio = 0.95;
// A marker matched in the second pass (SecondPass) needs this confidence: its prediction
// leans on the pose solved from the others, a weaker witness than its own track (0.5 cost
// real nick_freeform_001 and synthetic JA1Gait35 wrong runs of 57-163 frames; 0.7 none).
constexpr double kSecondPassConfidence = 0.7;
// RefindClusters: the rigid fit's RMS residual at most this many `gate`s; the turn of a
// joint in one frame scored against kRefindTurn radians; the best choice taken when the
// next is worse by kRefindMargin.
constexpr double kRefindResidual = 0.4;
constexpr double kRefindTurn = 0.7;
constexpr double kRefindMargin = 0.5;
constexpr double kRefindMaxChoices = 4096;  // A crowd of candidate points: left to SecondPass.

// What tracking carries from frame to frame.
struct TrackState {
  Pose pose;
  std::vector<Eigen::Vector3d> last, before, offset;  // Per marker.
  std::vector<Eigen::Vector3d> model, model_before;   // Model positions at the last two poses.
  std::vector<int> since;          // Frames since last labelled: 1 = the previous frame.
  std::vector<bool> velocity;      // `before` is the frame just before `last`.
  bool lost = false;
  int expected = 0;                // Markers labelled at the latest acquisition.
};

// Finding the body solves each matching round from scratch: no pull toward the previous
// round's pose (the rest prior stays). Its solves compare matchings (placements refined in
// rounds, each warm-started from the last; the checks' moves, each from the frame's pose),
// so they stop at kCompareIterations: of the nick_freeform_001 checks' solves, 10 % ran
// 20-49 iterations and 5 % stopped at the 50 cap, mostly on moves that lose anyway; the
// labeller's CPU time fell 35-50 % on the five real takes, labels unchanged on four and
// nick_freeform_001 97.70 -> 97.78 % (the frame solves, which place the markers, keep 50).
constexpr int kCompareIterations = 12;
MarkerSolveOptions WithoutFramePrior(MarkerSolveOptions options) {
  options.prior_rotation_weight = 0.0;
  options.prior_translation_weight = 0.0;
  options.dls.max_iterations = std::min(options.dls.max_iterations, kCompareIterations);
  return options;
}

class Tracker {
 public:
  Tracker(const Skeleton& skeleton, const MarkerSet& markers, const LabellerOptions& options,
          const std::vector<std::vector<Eigen::Vector3d>>& points, const Pose& start, LabellingResult* result)
      : skeleton_(skeleton), markers_(markers), options_(options), points_(points), start_(start),
        clusters_(RigidClusters(markers)), solver_(skeleton, markers, options.solve),
        acquisition_solver_(skeleton, markers, WithoutFramePrior(options.solve)), result_(result) {}

  // The body in frame f, from scratch.
  Acquisition Find(int f) {
    return AcquireBody(skeleton_, markers_, clusters_, start_, points_[f], options_.acquisition,
                       &acquisition_solver_);
  }
  // Starts (or restarts) tracking from an acquisition at frame f.
  void Start(int f, const Acquisition& acquisition) {
    if (state_.since.empty()) Reset();
    state_.pose = acquisition.pose;
    state_.model.clear();
    state_.model_before.clear();
    GatedAssignment matches = acquisition.matches;
    MatchEmptyMarkers(f, &matches);
    HandOver(f, &matches);
    std::vector<Eigen::Vector3d> observed;
    const int count = TakeMatches(f, matches, false, &observed);
    Advance(observed, count);
    state_.expected = count;
    state_.lost = false;
    result_->acquisitions.push_back(f);
    previous_frame_ = f;
  }
  void Step(int f) {
    StepFrame(f);
    previous_frame_ = f;
  }
  void StepFrame(int f) {
    if (state_.lost) {
      const Acquisition acquisition = Find(f);
      if (acquisition.found) Start(f, acquisition);
      else ++result_->lost_frames;
      return;
    }
    const int num_markers = markers_.num_markers();
    std::vector<Eigen::Vector3d> predicted(num_markers);
    std::vector<double> gate(num_markers);
    Predict(&predicted, &gate);
    GatedAssignment matches;
    AssignGated(predicted, gate, points_[f], &matches);
    if (state_.model_before.empty()) {
      // Just after an acquisition no motion is known: the pose solved from this first
      // match gives the model's step, and the markers without a velocity are matched again
      // from their predictions moved by it.
      std::vector<Eigen::Vector3d> observed(num_markers, kNan);
      for (int m = 0; m < num_markers; ++m) {
        if (matches.point_of_marker[m] >= 0) observed[m] = points_[f][matches.point_of_marker[m]];
      }
      Pose moved = state_.pose;
      FrameSolveReport report;
      if (solver_.Solve(observed, &moved, &report).ok() && report.usable) {
        const std::vector<Eigen::Vector3d> model = ModelMarkerPositions(skeleton_, markers_, moved);
        for (int m = 0; m < num_markers; ++m) {
          if (!(state_.since[m] == 1 && state_.velocity[m])) predicted[m] += model[m] - state_.model[m];
        }
        AssignGated(predicted, gate, points_[f], &matches);
      }
    }
    RefindClusters(f, &matches);
    SecondPass(f, &matches);
    if (options_.polish_every > 0 && ++since_polish_ >= options_.polish_every) Polish(f, &matches);
    if (options_.refill_every > 0 && ++since_refill_ >= options_.refill_every) {
      since_refill_ = 0;
      MatchEmptyMarkers(f, &matches);
    }
    std::vector<Eigen::Vector3d> observed;
    const int count = TakeMatches(f, matches, true, &observed);
    Advance(observed, count);
    if (count < options_.lost_fraction * state_.expected) state_.lost = true;
  }
  // Each marker's prediction and gate for the next frame (see the header).
  void Predict(std::vector<Eigen::Vector3d>* predicted, std::vector<double>* gate) const {
    for (int m = 0; m < markers_.num_markers(); ++m) {
      // The model's step between the last two poses carries predictions made from the model.
      const Eigen::Vector3d step = state_.model_before.empty() ? Eigen::Vector3d::Zero()
                                                              : Eigen::Vector3d(state_.model[m] - state_.model_before[m]);
      if (state_.since[m] == 1 && state_.velocity[m]) {
        (*predicted)[m] = 2.0 * state_.last[m] - state_.before[m];
        (*gate)[m] = options_.gate;
      } else if (state_.since[m] == 1) {
        (*predicted)[m] = state_.last[m] + step;
        (*gate)[m] = options_.reacquire_gate;
      } else {
        (*predicted)[m] =
            state_.model[m] + step + (state_.since[m] < kNever ? state_.offset[m] : Eigen::Vector3d::Zero());
        (*gate)[m] = options_.reacquire_gate;
      }
    }
  }
  // The pose solved from the frame's matched points (`observed`, NaN = none; warm-started
  // at *pose), the model's marker positions there, and the frame's points not `used`, with
  // their indices. False when the solve fails.
  bool PredictFromMatched(int f, const std::vector<Eigen::Vector3d>& observed, const std::vector<char>& used,
                          Pose* pose, std::vector<Eigen::Vector3d>* predicted,
                          std::vector<Eigen::Vector3d>* free_points, std::vector<int>* free_index) {
    FrameSolveReport report;
    if (!solver_.Solve(observed, pose, &report).ok() || !report.usable) return false;
    *predicted = ModelMarkerPositions(skeleton_, markers_, *pose);
    const std::vector<Eigen::Vector3d>& points = points_[f];
    for (size_t k = 0; k < points.size(); ++k) {
      if (!used[k]) free_points->push_back(points[k]), free_index->push_back(static_cast<int>(k));
    }
    return true;
  }
  // A joint's markers that miss their constant-velocity gates together (a kick's onset: a
  // foot's speed jumps by 50-90 mm in a frame) are lost together, and the pose solved
  // without them leaves the joint where it was: the next frames' model predictions miss
  // too, or give a neighbour's point (a toe's three markers held shifted by one for the
  // rest of the take on the demo walk's fast kicks). So a rigid cluster (>= 3 markers on
  // one joint) with three or more markers labelled at f-1, two or more of them tracked and
  // now without a confident point, is placed again as a whole: its markers that kept a
  // point give it back (the first pass may have given a toe marker its mate's point), and
  // each marker's candidates are the free points within `reacquire_gate` of its
  // constant-velocity prediction (its last point without a velocity). Every one-to-one
  // choice (a marker may stay empty while 3 or more are placed) is fitted by the rigid
  // motion of the cluster's points at f-1 onto it (Umeyama without scale), kept when its
  // RMS residual is within kRefindResidual `gate`, and scored by
  //   residual^2 / (kRefindResidual gate)^2 + (turn / kRefindTurn)^2 + empty markers,
  // a joint turning by much less than a third of a turn in a frame (a cyclic relabelling of
  // three markers around a bone fits as well, turned 120 degrees). The best is taken when
  // no other choice scores within kRefindMargin of it; otherwise the matches stand.
  void RefindClusters(int f, GatedAssignment* matches) {
    const std::vector<Eigen::Vector3d>& points = points_[f];
    std::vector<char> used(points.size(), 0);
    const auto confident = [&](int m) {
      return matches->point_of_marker[m] >= 0 && matches->confidence[m] >= options_.min_confidence;
    };
    for (int m = 0; m < markers_.num_markers(); ++m) {
      if (confident(m)) used[matches->point_of_marker[m]] = 1;
    }
    const auto keep = [&](const std::vector<int>& members) {  // Their matches stand.
      for (int m : members) {
        if (confident(m)) used[matches->point_of_marker[m]] = 1;
      }
    };
    for (const RigidCluster& cluster : clusters_) {
      // The cluster's markers tracked at f-1 are all placed again (those that kept a point
      // may hold a lost mate's: the first pass matched a toe marker to its neighbour's).
      std::vector<int> lost;
      int missed = 0;
      for (int m : cluster.markers) {
        if (state_.since[m] != 1) continue;
        lost.push_back(m);
        if (confident(m)) used[matches->point_of_marker[m]] = 0;
        else missed += state_.velocity[m];
      }
      if (missed < 2 || lost.size() < 3) {
        keep(lost);
        continue;
      }
      std::vector<std::vector<int>> candidates(lost.size());
      for (size_t i = 0; i < lost.size(); ++i) {
        const int m = lost[i];
        const Eigen::Vector3d p = state_.velocity[m] ? Eigen::Vector3d(2.0 * state_.last[m] - state_.before[m]) : state_.last[m];
        for (size_t k = 0; k < points.size(); ++k) {
          if (!used[k] && (points[k] - p).norm() < options_.reacquire_gate) candidates[i].push_back(static_cast<int>(k));
        }
      }
      double choices = 1.0;
      for (const std::vector<int>& c : candidates) choices *= static_cast<double>(c.size() + 1);
      if (choices > kRefindMaxChoices) {
        keep(lost);
        continue;
      }
      double best = std::numeric_limits<double>::infinity(), second = best;
      std::vector<int> choice(lost.size(), -1), best_choice;
      const double tolerance = kRefindResidual * options_.gate;
      // Depth-first over the lost markers' candidates (-1: empty).
      std::function<void(size_t)> visit = [&](size_t i) {
        if (i < lost.size()) {
          for (int k : candidates[i]) {
            if (std::find(choice.begin(), choice.begin() + i, k) != choice.begin() + i) continue;
            choice[i] = k;
            visit(i + 1);
          }
          choice[i] = -1;
          visit(i + 1);
          return;
        }
        std::vector<Eigen::Vector3d> from, to;
        int empty = 0;
        for (size_t j = 0; j < lost.size(); ++j) {
          if (choice[j] < 0) ++empty;
          else from.push_back(state_.last[lost[j]]), to.push_back(points[choice[j]]);
        }
        if (from.size() < 3 || empty == static_cast<int>(lost.size())) return;
        Eigen::Matrix3Xd a(3, from.size()), b(3, from.size());
        for (size_t j = 0; j < from.size(); ++j) a.col(j) = from[j], b.col(j) = to[j];
        const Eigen::Matrix4d t = Eigen::umeyama(a, b, false);
        const Eigen::Matrix3d r = t.topLeftCorner<3, 3>();
        const double residual =
            std::sqrt(((r * a).colwise() + t.topRightCorner<3, 1>() - b).colwise().squaredNorm().mean());
        if (residual > tolerance) return;
        const double turn = Eigen::AngleAxisd(r).angle();
        const double score = std::pow(residual / tolerance, 2) + std::pow(turn / kRefindTurn, 2) + empty;
        if (score < best) second = best, best = score, best_choice = choice;
        else second = std::min(second, score);
      };
      visit(0);
      if (best_choice.empty() || second - best < kRefindMargin) {
        keep(lost);
        continue;
      }
      for (size_t j = 0; j < lost.size(); ++j) {
        const int m = lost[j], k = best_choice[j];
        if (k < 0) {
          if (confident(m)) matches->point_of_marker[m] = -1, matches->confidence[m] = 0.0;
          continue;
        }
        if (k != matches->point_of_marker[m] || !confident(m)) {
          matches->point_of_marker[m] = k;
          matches->confidence[m] = std::max(matches->confidence[m], kSecondPassConfidence);
        }
        used[k] = 1;
      }
    }
  }
  // Markers left without a confident point (a dropout broke their velocity, so they were
  // predicted within the wide reacquire_gate, where a neighbour 3 cm away makes any match
  // doubtful) are matched again among the free points, from the pose solved from the
  // frame's confident matches: predicted there with their last offsets, within `gate`,
  // kept at a confidence of at least kSecondPassConfidence.
  void SecondPass(int f, GatedAssignment* matches) {
    const int num_markers = markers_.num_markers();
    const std::vector<Eigen::Vector3d>& points = points_[f];
    std::vector<Eigen::Vector3d> observed(num_markers, kNan);
    std::vector<char> used(points.size(), 0);
    int confident = 0;
    for (int m = 0; m < num_markers; ++m) {
      const int k = matches->point_of_marker[m];
      if (k >= 0 && matches->confidence[m] >= options_.min_confidence) observed[m] = points[k], used[k] = 1, ++confident;
    }
    if (confident == num_markers || confident < 3 || confident == static_cast<int>(points.size())) return;
    Pose pose = state_.pose;
    std::vector<Eigen::Vector3d> predicted, free_points;
    std::vector<int> free_index;
    if (!PredictFromMatched(f, observed, used, &pose, &predicted, &free_points, &free_index)) return;
    for (int m = 0; m < num_markers; ++m) {
      if (observed[m].allFinite()) predicted[m] = kNan;
      else if (state_.since[m] < kNever) predicted[m] += state_.offset[m];
    }
    GatedAssignment found;
    AssignGated(predicted, std::vector<double>(num_markers, options_.gate), free_points, &found);
    for (int m = 0; m < num_markers; ++m) {
      const int k = found.point_of_marker[m];
      if (k < 0 || found.confidence[m] < kSecondPassConfidence) continue;
      matches->point_of_marker[m] = free_index[k];
      matches->confidence[m] = found.confidence[m];
    }
  }
  // Markers without a point take free points near their model positions: matched within
  // 3 acquisition gates of the pose solved from the frame's matches, kept when within one
  // gate of the pose solved with them and with no rival near (match confidence >= 0.5 at
  // the wide gate): a whole lost limb comes back this way.
  void MatchEmptyMarkers(int f, GatedAssignment* matches) {
    const int num_markers = markers_.num_markers();
    const std::vector<Eigen::Vector3d>& points = points_[f];
    int matched = 0;
    for (int m = 0; m < num_markers; ++m) matched += matches->point_of_marker[m] >= 0;
    if (matched == num_markers || matched >= static_cast<int>(points.size())) return;
    std::vector<char> used(points.size(), 0);
    std::vector<Eigen::Vector3d> observed(num_markers, kNan);
    for (int m = 0; m < num_markers; ++m) {
      const int k = matches->point_of_marker[m];
      if (k >= 0) used[k] = 1, observed[m] = points[k];
    }
    Pose pose = state_.pose;
    std::vector<Eigen::Vector3d> predicted, free_points;
    std::vector<int> free_index;
    if (!PredictFromMatched(f, observed, used, &pose, &predicted, &free_points, &free_index)) return;
    for (int m = 0; m < num_markers; ++m) {
      if (matches->point_of_marker[m] >= 0) predicted[m] = kNan;
    }
    GatedAssignment found;
    AssignGated(predicted, std::vector<double>(num_markers, 3.0 * options_.acquisition.gate), free_points, &found);
    std::vector<Eigen::Vector3d> with = observed;
    for (int m = 0; m < num_markers; ++m) {
      if (found.point_of_marker[m] >= 0) with[m] = free_points[found.point_of_marker[m]];
    }
    FrameSolveReport report;
    if (!solver_.Solve(with, &pose, &report).ok() || !report.usable) return;
    const std::vector<Eigen::Vector3d> model = ModelMarkerPositions(skeleton_, markers_, pose);
    for (int m = 0; m < num_markers; ++m) {
      const int k = found.point_of_marker[m];
      if (k < 0 || (with[m] - model[m]).norm() >= options_.acquisition.gate || found.confidence[m] < 0.5) continue;
      matches->point_of_marker[m] = free_index[k];
      matches->confidence[m] = std::max(found.confidence[m], options_.min_confidence);
    }
  }
  // At the start of tracking (acquisition, re-acquisition), a point held by a marker m
  // that an empty marker n explains better goes to n (one frame cannot tell them apart:
  // the track that follows holds whichever got it, cmu_02_05 without LHEE/LTOE/LMT5: LHEE on
  // LANK's point for the first 72 frames). Both
  // are judged from the pose solved without the point, the joints they ride on started
  // again from `start_` (the mean pose): a marker alone on its joint (a heel marker whose
  // foot mates are absent from the take) can hold a neighbour's point (the ankle marker's,
  // on the shin) at any frame, the foot turned to put it there, and the whole-body cost is
  // the same either way (one marker empty); but without the point the shin, held by its
  // other markers, still predicts the ankle marker on it (10 mm off), while the foot at
  // the mean pose puts the heel marker 78 mm away. Handed over when n's prediction (with
  // its last offset) is within `gate` and less than half m's distance; m starts afresh (no offset:
  // its old one would pull it back), the pose becomes the one solved without the point.
  // Candidates: n's model position at the tracked pose within the acquisition gate of a
  // held point. (Applied at the periodic checks too, it handed over 2 points on the five
  // real and synthetic takes, real nick_freeform_001 99.24 -> 99.21 %: left out.)
  void HandOver(int f, GatedAssignment* matches) {
    const int num_markers = markers_.num_markers();
    const std::vector<Eigen::Vector3d>& points = points_[f];
    // Marker i holds its point when it is matched with confidence.
    const auto holds = [&](int i) {
      return matches->point_of_marker[i] >= 0 && matches->confidence[i] >= options_.min_confidence;
    };
    std::vector<int> holder(points.size(), -1);
    for (int m = 0; m < num_markers; ++m) {
      if (holds(m)) holder[matches->point_of_marker[m]] = m;
    }
    const std::vector<Eigen::Vector3d> model = ModelMarkerPositions(skeleton_, markers_, state_.pose);
    const auto offset = [&](int n) { return state_.since[n] < kNever ? state_.offset[n] : Eigen::Vector3d::Zero(); };
    for (int n = 0; n < num_markers; ++n) {
      if (holds(n)) continue;
      const Eigen::Vector3d at = model[n] + offset(n);
      for (size_t k = 0; k < points.size(); ++k) {
        const int m = holder[k];
        if (m < 0 || (points[k] - at).norm() >= options_.acquisition.gate) continue;
        std::vector<Eigen::Vector3d> observed(num_markers, kNan);
        for (int i = 0; i < num_markers; ++i) {
          if (holds(i) && matches->point_of_marker[i] != static_cast<int>(k)) observed[i] = points[matches->point_of_marker[i]];
        }
        Pose pose = state_.pose;
        for (int i : {m, n}) {
          for (const MarkerAttachment& a : markers_.marker(i).attachments) {
            if (a.joint > 0) pose.rotations[a.joint] = start_.rotations[a.joint];
          }
        }
        FrameSolveReport report;
        if (!acquisition_solver_.Solve(observed, &pose, &report).ok() || !report.usable) continue;
        const std::vector<Eigen::Vector3d> without = ModelMarkerPositions(skeleton_, markers_, pose);
        const double d_n = (points[k] - without[n] - offset(n)).norm();
        const double d_m = (points[k] - without[m]).norm();
        if (!(d_n < options_.gate && d_n < 0.5 * d_m)) continue;
        matches->point_of_marker[n] = static_cast<int>(k);
        matches->confidence[n] = std::max(matches->confidence[m], options_.min_confidence);
        matches->point_of_marker[m] = -1;
        matches->confidence[m] = 0.0;
        state_.since[m] = kNever, state_.velocity[m] = false, state_.offset[m].setZero();
        if (state_.since[n] == 1) state_.since[n] = 2;
        state_.pose = pose;
        holder[k] = n;
        break;
      }
    }
  }
  // The periodic check of the labels: PolishMatches on the frame's matches, kept only when
  // the tracked frames before agree (HistoryAgrees); a marker that changes point starts its
  // track again (no velocity; a re-acquisition).
  void Polish(int f, GatedAssignment* matches) {
    since_polish_ = 0;
    const std::vector<int> before = matches->point_of_marker;
    Pose pose = state_.pose;
    if (!PolishMatches(skeleton_, markers_, points_[f], options_.acquisition.gate, false, true, 0.99, &acquisition_solver_, &pose,
                       matches)) {
      return;
    }
    if (!HistoryAgrees(f, before, matches->point_of_marker)) {
      matches->point_of_marker = before;
      return;
    }
    for (int m = 0; m < markers_.num_markers(); ++m) {
      if (matches->point_of_marker[m] == before[m]) continue;
      if (matches->point_of_marker[m] >= 0) matches->confidence[m] = std::max(matches->confidence[m], options_.min_confidence);
      if (state_.since[m] == 1) state_.since[m] = 2;
    }
  }
  // Labels exchanged between tracked markers (marker m given the point marker n had) hold
  // along the whole track, not at one frame: two markers whose fits are alike (a wrist and
  // a thumb marker, each the only one on its joint) can trade places at a single frame by
  // chance. The exchange is applied to up to 6 frames of the track just before f (the
  // side already labelled) and kept when it lowers their summed solved cost by more than
  // kTrackExchangeRatio and does not move the points of markers riding on one joint
  // further from the joint's shape (JointShapeErrors: their distances against the subject's).
  // The shape decides where the solved cost cannot: a marker alone on a free joint (squat's
  // ROHAND on the one-dof fingers) reaches a neighbour's point (ROWR's, one of three on the
  // wrist), and the whole-body fit, limited by the fitted subject's errors elsewhere,
  // preferred that exchange by 2-6 % for 600 frames (real squat, 1,050 frames wrong) while
  // the wrist's distances were 6x further from its shape (1.28 vs 0.20 units). Moves to
  // free points, and frames without a track, are not judged (true).
  bool HistoryAgrees(int f, const std::vector<int>& before, const std::vector<int>& after) {
    const int num_markers = markers_.num_markers();
    std::vector<int> source(num_markers, -1);  // source[m]: the marker whose point m now has.
    bool exchanged = false;
    for (int m = 0; m < num_markers; ++m) {
      if (after[m] < 0 || after[m] == before[m]) continue;
      for (int n = 0; n < num_markers; ++n) {
        if (n != m && before[n] == after[m]) source[m] = n, exchanged = true;
      }
    }
    if (!exchanged || previous_frame_ < 0) return true;
    const int step = previous_frame_ < f ? -1 : 1;  // Toward the frames already labelled.
    std::vector<int> frames;
    std::vector<std::vector<int>> kept_labels, moved_labels;  // Per frame judged: point_of_marker.
    for (int k : {1, 5, 10, 15, 20, 25}) {
      const int g = f + step * k;
      if (g < 0 || g >= static_cast<int>(points_.size())) break;
      std::vector<int> current(num_markers, -1);
      const std::vector<int>& labels = result_->marker_of_point[g];
      for (size_t q = 0; q < labels.size(); ++q) {
        if (labels[q] >= 0) current[labels[q]] = static_cast<int>(q);
      }
      std::vector<int> trial = current;
      for (int m = 0; m < num_markers; ++m) {
        if (source[m] >= 0) trial[m] = current[source[m]];
      }
      // A marker that gave its point away but took none of the others' (a free point, or
      // none) has no known point at g under the move: empty there, and holding its own
      // under the labels kept. (Empty under both, the move always won: one marker given a
      // point against none, a subject marker absent from the take taking its neighbour's
      // point at every check, cmu_02_05 without LHEE/LTOE/LMT5.)
      for (int m = 0; m < num_markers; ++m) {
        const int n = source[m];
        if (n >= 0 && source[n] < 0) trial[n] = -1;
      }
      if (trial == current) continue;
      frames.push_back(g), kept_labels.push_back(std::move(current)), moved_labels.push_back(std::move(trial));
    }
    std::vector<char> involved(num_markers, 0);
    for (int m = 0; m < num_markers; ++m) {
      if (source[m] >= 0) involved[m] = involved[source[m]] = 1;
    }
    std::vector<std::vector<Eigen::Vector3d>> judged_points;
    for (int g : frames) judged_points.push_back(points_[g]);
    double kept_shape = 0.0, moved_shape = 0.0;
    JointShapeErrors(markers_, judged_points, kept_labels, moved_labels, involved, &kept_shape, &moved_shape);
    if (moved_shape > kept_shape) return false;
    double kept = 0.0, moved = 0.0;
    for (size_t i = 0; i < frames.size(); ++i) {
      const std::vector<Eigen::Vector3d>& points = points_[frames[i]];
      Pose pose = state_.pose;
      kept += SolvedCost(skeleton_, markers_, points, kept_labels[i], options_.acquisition.gate, &acquisition_solver_, &pose);
      moved += SolvedCost(skeleton_, markers_, points, moved_labels[i], options_.acquisition.gate, &acquisition_solver_, &pose);
    }
    return frames.empty() || moved < kTrackExchangeRatio * kept;
  }
  const TrackState& state() const { return state_; }
  void set_state(const TrackState& state) { state_ = state; }

 private:
  void Reset() {
    const int n = markers_.num_markers();
    state_.last.assign(n, kNan);
    state_.before.assign(n, kNan);
    state_.offset.assign(n, Eigen::Vector3d::Zero());
    state_.since.assign(n, kNever);
    state_.velocity.assign(n, false);
  }
  // The frame's matches kept (confidence high enough): labels, counts, observed samples.
  int TakeMatches(int f, const GatedAssignment& matches, bool count_conflicts, std::vector<Eigen::Vector3d>* observed) {
    observed->assign(markers_.num_markers(), kNan);
    int count = 0;
    for (int m = 0; m < markers_.num_markers(); ++m) {
      MarkerLabelStats& stats = result_->per_marker[m];
      if (count_conflicts && matches.conflict[m]) ++stats.swaps_avoided;
      const int k = matches.point_of_marker[m];
      if (k < 0) continue;
      if (matches.confidence[m] < options_.min_confidence) {
        ++stats.low_confidence;
        continue;
      }
      result_->marker_of_point[f][k] = m;
      result_->confidence[f][k] = static_cast<float>(matches.confidence[m]);
      ++stats.labelled;
      if (state_.since[m] > 1 && state_.since[m] < kNever) ++stats.reacquisitions;
      (*observed)[m] = points_[f][k];
      ++count;
    }
    return count;
  }
  // Solves the frame's pose and moves every marker's state on by one frame.
  void Advance(const std::vector<Eigen::Vector3d>& observed, int count) {
    if (count >= 3) {
      Pose solved = state_.pose;
      FrameSolveReport report;
      if (solver_.Solve(observed, &solved, &report).ok() && report.usable) state_.pose = solved;
    }
    state_.model_before = std::move(state_.model);
    state_.model = ModelMarkerPositions(skeleton_, markers_, state_.pose);
    const std::vector<Eigen::Vector3d>& model = state_.model;
    for (int m = 0; m < markers_.num_markers(); ++m) {
      if (observed[m].allFinite()) {
        state_.velocity[m] = state_.since[m] == 1;
        state_.before[m] = state_.last[m];
        state_.last[m] = observed[m];
        state_.offset[m] = observed[m] - model[m];
        state_.since[m] = 1;
      } else {
        state_.velocity[m] = false;
        if (state_.since[m] < kNever) ++state_.since[m];
      }
    }
  }

  const Skeleton& skeleton_;
  const MarkerSet& markers_;
  const LabellerOptions& options_;
  const std::vector<std::vector<Eigen::Vector3d>>& points_;
  const Pose start_;
  const std::vector<RigidCluster> clusters_;
  MarkerFrameSolver solver_;
  MarkerFrameSolver acquisition_solver_;  // Without the prior toward the previous solution.
  LabellingResult* result_;
  TrackState state_;
  int since_polish_ = 0;
  int since_refill_ = 0;
  int previous_frame_ = -1;  // The frame stepped before (which side of f is labelled).
};

std::string NotFoundMessage(const Skeleton& skeleton, const MarkerSet& markers, const LabellingResult& result,
                            int tried) {
  const double mm = skeleton.unit().known() ? skeleton.unit().metres_per_unit * 1000.0 : 0.0;
  char text[320];
  std::snprintf(text, sizeof(text),
                "the points match no placement of the subject's markers in the first %d frames with points "
                "(another marker set, another person or wrong units?): best match %d of %d markers (RMS %.3g %s) "
                "at frame %d",
                tried, result.first.matched, markers.num_markers(), mm > 0 ? result.first.rms * mm : result.first.rms,
                mm > 0 ? "mm" : "skeleton units", result.first_frame);
  return text;
}

}  // namespace

Status LabelPointCloud(const Skeleton& skeleton, const MarkerSet& markers, const QuaternionVector& mean_pose,
                       const std::vector<std::vector<Eigen::Vector3d>>& points, const LabellerOptions& options,
                       const LabelProgress& progress, LabellingResult* result) {
  if (!(options.gate > 0.0) || !(options.reacquire_gate > 0.0) || !(options.acquisition.gate > 0.0) ||
      !(options.acquisition.cluster_tolerance > 0.0) || !(options.acquisition.max_rms > 0.0)) {
    return Status::Error("labelling gates and tolerances must be positive");
  }
  const int num_frames = static_cast<int>(points.size());
  *result = LabellingResult();
  result->per_marker.assign(markers.num_markers(), MarkerLabelStats());
  for (const auto& frame : points) {
    result->marker_of_point.emplace_back(frame.size(), -1);
    result->confidence.emplace_back(frame.size(), 0.0f);
  }
  Pose start = RestPose(skeleton);
  if (mean_pose.size() == start.rotations.size()) start.rotations = mean_pose;
  Tracker tracker(skeleton, markers, options, points, start, result);
  int tried = 0;
  for (int f = 0; f < num_frames && tried < options.acquire_frames; ++f) {
    if (points[f].empty()) continue;
    ++tried;
    const Acquisition acquisition = tracker.Find(f);
    if (result->first_frame < 0 || acquisition.matched > result->first.matched) {
      result->first = acquisition, result->first_frame = f;
    }
    if (acquisition.found) {
      result->first = acquisition, result->first_frame = f;
      break;
    }
  }
  if (!result->first.found) return Status::Error(NotFoundMessage(skeleton, markers, *result, tried));
  const int f0 = result->first_frame;
  tracker.Start(f0, result->first);
  const TrackState at_start = tracker.state();
  int done = 1;
  for (int f = f0 + 1; f < num_frames; ++f, ++done) {
    tracker.Step(f);
    if (progress && done % 64 == 0) progress(done, num_frames);
  }
  tracker.set_state(at_start);
  for (int f = f0 - 1; f >= 0; --f, ++done) {
    tracker.Step(f);
    if (progress && done % 64 == 0) progress(done, num_frames);
  }
  if (progress) progress(num_frames, num_frames);
  return Status::Ok();
}

}  // namespace mocapsolve
