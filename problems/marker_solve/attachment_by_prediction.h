// Between two joints that hold a marker nearly equally rigidly, the one with which the
// solve predicts that joint's markers better (issues 31 item 4, 36).
//
// Auto attach (calibration.h) puts marker m on j* = argmin_j rms_mj, the joint in whose
// frame it moves least. When a joint's parent or child holds it almost as well (the
// runner-up's rms within `tolerance` of the best, relative), rigidity does not decide:
// CMU's 02_01 walk puts the fifth metatarsal markers on the toes by 1.5 / 7 % over the
// foot, and a later take's solve then turns the toe joint by that one marker of a foot that
// does not bend there, leaving the foot's pose to its other markers alone. What a subject
// is for is placing a marker where the others put it, so for such a marker m, its joint a
// and the runner-up b, with its offset fitted on each (the caller's calibration):
//   G = {m} and every other marker on a or b;
//   for each n in G, the take (every k-th frame, k = ceil(frames / max_frames)) is solved
//   frame by frame without n (SolveSequence, `solve`, as leave_one_out.h does), and n
//   predicted through its attachment: e_n(f) = |x^_n(f) - y_n(f)|;
//   score(set) = median of e_n(f) over n in G and n's samples,
// once with m on a and once on b; m moves to b when b's score is lower (ties keep a). No
// sample of n reaches its own prediction. A joint that m alone turns, left without it, is
// held by the solve's priors; on the joint whose other markers turn it, m also helps
// place them. Every decision is made against the set as given (one marker's move does
// not feed another's).
//
// Blends over a hinge. A marker over the joint between two bones (a patella over the
// knee, an epicondyle over the elbow) rides neither bone alone: the skin over a hinge
// is pulled partly by each. Its blend candidate is the 50/50 attachment on both,
//   x = 0.5 (p_a + R_a z_a) + 0.5 (p_h + R_h z_h),  a = parent(h),
// offsets fitted by least squares (calibration.h, fixed attachments). With p_h = p_a +
// R_a t_h this is x = p_a + R_a alpha + R_h beta for free alpha, beta: it holds both
// single attachments as special cases (beta = 0: on a; alpha = t_h: on h), and any split
// of the weights spans the same positions, so 50/50 is the only blend worth offering
// (25/75 differs only in how the offsets are scaled). The same test then chooses among
// m's joint, its single alternative and the blend, by the group's held-out median: a
// marker that truly rides one bone predicts its group no better blended (the extra
// freedom is fitted to noise) and keeps its bone.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_ATTACHMENT_BY_PREDICTION_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_ATTACHMENT_BY_PREDICTION_H_

#include <utility>
#include <vector>

#include <Eigen/Core>

#include "kinematics/marker_set.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "problems/marker_solve/calibration.h"
#include "problems/marker_solve/marker_frame_solver.h"

namespace mocapsolve {

struct AttachmentByPredictionOptions {
  // The runner-up's rms within this fraction of the marker's own (0: off). 15 %, a round
  // number set before measuring, above the 1.5-7 % of the metatarsals on 02_01: it only
  // admits candidates; the prediction decides.
  double tolerance = 0.15;
  int max_frames = 240;  // Frames solved per left-out marker (every k-th of the take).
  // A hinge blend is offered to a marker within this fraction of its bone's length of
  // the hinge (HingeBlendCandidates): a quarter, set before measuring (20-25 % asked).
  double hinge_fraction = 0.25;
  // A hinge rotates about at most this many axes: the knee, the elbow, a forearm twist, the
  // toes (CMU's skeleton); blends over ball joints (a shoulder, the spine) changed the solve
  // of markers far from them (JA1Gait35's RFOREARM with LSH blended: BENCHMARKS.md, h36j).
  int hinge_dofs = 1;
  // A hinge bends by at least this much (radians) in the frames the blend's offsets are
  // fitted on (JointBendRange), or it is not offered: x = p_a + R_a alpha + R_h beta tells
  // beta from alpha only through R_a^T R_h's change, which moves beta's end by about
  // |beta| dtheta. 15 degrees, set before measuring: at a patella's or an epicondyle's
  // 4-6 cm from the joint's centre the hinge side's half moves by 5-8 mm over the range,
  // above the 2-5 mm of marker noise and skin slide; a hinge that holds still there (an
  // elbow that bends only late in the take) leaves the blend's six offsets fitted to noise.
  double hinge_min_bend = 15.0 * 3.14159265358979323846 / 180.0;
  // ChooseLimbBlends: a set of blends is refused when it raises any marker's median of the
  // limb by more than this fraction of the limb's median without them. Half, set before
  // measuring: one marker of a limb going wrong moves the limb's median little (cmu_02_05's
  // LWRB, 2.7 -> 68 mm, h36i), its own median by many times the limb's.
  double limb_rise = 0.5;
  // ChooseLimbBlends: a blend is a claim about its own marker's skin, so it must predict that
  // marker at least this fraction better than the marker's bone alone (its left-out median);
  // a blend that only steadies other markers (on noise-free synthetic legs, a knee marker
  // blended held the thigh's twist for its left-out LTHI while predicting itself no better)
  // is not one. A tenth, set before measuring.
  double blend_own_gain = 0.1;
};

// One way to attach a marker: a single joint (weight 1) or a blend of several.
using AttachmentChoice = std::vector<MarkerAttachment>;

struct AttachmentMove {
  int marker = -1;           // Index in the set.
  int from = -1, to = -1;    // Joints (`to`: the best alternative's first joint).
  double from_score = 0.0;   // score(set) with m on `from` and on the best alternative,
  double to_score = 0.0;     // skeleton units.
  AttachmentChoice to_attachments;  // The best alternative.
  bool moved = false;
};

// The candidates of a calibration: for each marker of result.marker_set, its runner-up
// joint when that is the parent or a child of its (single) joint and its rms there within
// (1 + tolerance) of its own; else -1.
std::vector<int> PredictionCandidates(const Skeleton& skeleton, const CalibrationResult& result,
                                      double tolerance);

// The candidates of co-rigidity: markers that keep their mutual distances over a take
// (a rigid cluster, rigid_marker_clusters.h, found from the data alone) ride one body, so
// in a cluster of at least three markers of which more than half ride one joint b (single
// attachments), every other marker of it has b as its candidate. Unlike
// PredictionCandidates this needs no near tie of rigidity under the model: JA1Gait35's
// fifth metatarsal markers move rigidly with the rest of each foot (distance SD 2 mm), but
// the fitted toe joint, turned by them, holds them best; the prediction decides (a wrong
// candidate predicts its group worse and is not moved). clusters: lists of indices into
// `markers`. For each marker, b or -1.
std::vector<int> RigidClusterCandidates(const MarkerSet& markers, const std::vector<std::vector<int>>& clusters);

// The hinge blend candidates (header): for each marker of `markers` on a single joint a,
// the hinges next to its bone are the joint a itself (when it rotates and has a parent)
// and the rotating joints that begin where a's rigid body ends (its children, reached
// through joints without rotation dofs, as BoneSegments walks); the nearest one h to
// the marker's offset, if within max_distance (skeleton units; the skin radius: the
// marker lies over the joint), gives the pair {parent side, h}: {parent(a), a} or {a, h}.
// Else {-1, -1}. Only skin over the joint slides with both bones: a marker whose
// projection on its bone's axis (from a's origin to h for {a, h}; a's longest segment
// from its origin for {parent(a), a}) lies farther than max_fraction of that bone's
// length from the hinge rides its bone (a mid-bone wand), where a blend only adds three
// offset parameters to overfit (BENCHMARKS.md, issue 36, h36j): none. Only joints h of
// at most max_dofs rotation dofs count as hinges.
std::vector<std::pair<int, int>> HingeBlendCandidates(const Skeleton& skeleton, const MarkerSet& markers,
                                                      double max_distance, double max_fraction, int max_dofs);

// How far joint j bends over `motion`: the largest angle (radians) between two of its local
// rotations, over at most max_frames frames evenly spaced (pairwise, O(max_frames^2)). A
// one-dof hinge's angle range; 0 for a motion of fewer than two frames.
double JointBendRange(const Motion& motion, int joint, int max_frames);

// Drops from `pairs` (HingeBlendCandidates') every pair whose hinge bends by less than
// min_bend over `motion` (JointBendRange, max_frames): the frames the blend's offsets are
// fitted on, where a hinge that holds still leaves them unidentified.
void DropHingesThatHoldStill(const Motion& motion, double min_bend, int max_frames,
                             std::vector<std::pair<int, int>>* pairs);

// The blends of a limb decided together (issue 36: two blends on one arm flipped a marker
// that neither decision's group held). A limb is the chain of joints from one that is the
// only child of its parent up from a blend's parent-side joint a, to the first joint whose
// parent has other children (CMU's lclavicle for an elbow or a forearm twist, lhipjoint for
// a knee or the toes), with every joint below it; its group L is every marker on a joint of
// it. With the blends B accepted so far (none at first) and per marker n of L its median
// left-out prediction error e_n(B) (the header's score, per marker), blends[m] (empty: no
// candidate; its offsets fitted) are added one at a time, each time the candidate c of the
// lowest score(L, B + c), accepted while that is below score(L, B), no marker of L rises
// by more than limb_rise * score(L, {}): e_n(B + c) - e_n({}) <= limb_rise * score(L, {}),
// and c itself is predicted better: e_c(B + c) <= (1 - blend_own_gain) e_c({}).
// Limbs are decided against the set as given. `moves` (may be null): one per candidate,
// from_score = score(L, {}), to_score = the lowest score(L, B + m) tried, moved = accepted.
Status ChooseLimbBlends(const Skeleton& skeleton, const std::vector<std::vector<Eigen::Vector3d>>& observed,
                        const std::vector<AttachmentChoice>& blends, const MarkerSolveOptions& solve,
                        const AttachmentByPredictionOptions& options, MarkerSet* markers,
                        std::vector<AttachmentMove>* moves);

// Decides every marker m with alternatives (each a single joint or a blend, its offsets
// fitted) as the header says: its group is m and every other marker on a joint of its
// attachment or of an alternative; m takes the alternative of lowest score when that is
// lower than its own (ties keep it, and the earlier alternative). observed[f][m] in
// skeleton units (NaN: missing), parallel to *markers; alternatives empty or one list per
// marker. `moves` (may be null) gets one entry per candidate decided.
Status ChooseAmongAttachments(const Skeleton& skeleton, const std::vector<std::vector<Eigen::Vector3d>>& observed,
                              const std::vector<std::vector<AttachmentChoice>>& alternatives,
                              const MarkerSolveOptions& solve, const AttachmentByPredictionOptions& options,
                              MarkerSet* markers, std::vector<AttachmentMove>* moves);

// The same with one single-joint alternative per marker (alternative[m].joint < 0: none).
Status ChooseAttachmentsByPrediction(const Skeleton& skeleton, const std::vector<std::vector<Eigen::Vector3d>>& observed,
                                     const std::vector<MarkerAttachment>& alternative, const MarkerSolveOptions& solve,
                                     const AttachmentByPredictionOptions& options, MarkerSet* markers,
                                     std::vector<AttachmentMove>* moves);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_ATTACHMENT_BY_PREDICTION_H_
