// Fitting a subject to a take's markers alone (`mocapsolve fit_skeleton`, the Python
// module's fit_skeleton()): the round logic around FitSkeletonToMarkers
// (problems/marker_solve/skeleton_fit.h), so the command line and Python run one code path.
//
// Without labels to go by (fewer than 3 template labels in the take, no map given; or
// settings.associate "always"), the take's markers are associated with body segments from
// the data (marker_association.h; points that are no markers left out) and round 0 fits each
// on its segment's template joint (associated_marker_set.h), in the detected axes and units.
// Round 0 fits the template's bone-length scales s_j in [min_bone_scale, max_bone_scale]
// (left = right) and marker offsets (each within max_skin_cm of its bone) on the markers
// the take shares with the template by label (after renaming template markers to the take's
// labels by settings.template_labels, template_labels.h; by default a shipped map that fits
// the take, template_label_maps.h), alternating per-frame pose solves (the first
// frame's root from the markers' geometry) with a damped Gauss-Newton step on (s, offsets).
// Rounds r = 1..R then attach every marker of the take to the joint it moves least with
// (CalibrateMarkers; the template's markers keep their joints and fitted offsets, so a
// round starts where the round it comes from ended; a marker attached in an earlier round
// keeps that attachment unless the new one fits the best round's motion better) and fit
// again for attach_iterations,
// each from the best round so far (by marker RMS), stopping when a round does not improve
// the best marker RMS by 1 % (a round that improves it less is kept, then the rounds stop).
// Round 0 competes too when the attach finds no marker it lacks (the template has the
// take's whole set: round 0 is then a complete fit). A joint one marker alone constrains (no
// other marker on it or below it) is then re-expressed to rest at its mean fitted pose
// (lone_joint_gauge.h: the same fit, but a solve that lacks the marker predicts it). The
// kept model is then checked by measures that
// do not trust the residual (subject_checks.h). Knows nothing of flags or printing: the
// caller formats the progress events.
#ifndef MOCAPSOLVE_TASKS_FIT_SKELETON_TASK_H_
#define MOCAPSOLVE_TASKS_FIT_SKELETON_TASK_H_

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "io/json_writer.h"
#include "kinematics/marker_set.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "pipeline/subject.h"
#include "problems/marker_solve/held_segments.h"
#include "problems/marker_solve/marker_association.h"
#include "problems/marker_solve/template_label_maps.h"
#include "problems/marker_solve/template_labels.h"
#include "settings/skeleton_fit_settings.h"
#include "problems/marker_solve/marker_frame_solver.h"
#include "problems/marker_solve/marker_weights.h"
#include "problems/marker_solve/skeleton_fit.h"
#include "problems/marker_solve/subject_checks.h"

namespace mocapsolve {

// Every option's check (settings/skeleton_fit_settings.h), then what one option cannot check
// alone: min_bone_scale > 0, and a given template label map that reads. One-line messages
// naming the option.
Status ValidateSkeletonFitSettings(const SkeletonFitSettings& settings);

// What the fit reports while it runs, for a progress display.
struct SkeletonFitEvent {
  enum Kind {
    kTemplateLabels, // text: the label map applied (its file, "inline" or, for auto, the shipped file); markers: pairs.
    kAbsentMarkers,  // text: the template's labels the take lacks (left out).
    kNotMarkers,     // text: the take's points found to be no markers (left out), with the reasons.
    kRoundStart,     // round, rounds, markers, frames, iterations.
    kFrames,         // round, iteration (the pose solve's step: 0 before the first step, outlier passes included;
                     // k the solve of step k), frames_done of frames.
    kIteration,      // round, iteration, rms (skeleton units).
    kRoundDone,      // round, markers, rms_first, rms (skeleton units).
    kStopped,        // round: it did not improve (rms = 0) or by less than 1 % (rms: the kept one); the rounds stop.
    kKept,           // round (the kept one), rms: the last round was not the best.
    kBlended,        // markers: how many the kept round blended over a hinge; text: which, on which joints.
    kFreeingAxes,    // text: the joints given their locked axis; the second fit's rounds follow (its round,
                     // frames and iteration events, not the take's labels again).
    kFreedAxes,      // text: the joints given their locked axis in a second fit; markers: 1 if that fit is kept;
                     // rms: the first fit's held-out score, rms_first: the second's (skeleton units; -1: none).
  };
  Kind kind = kRoundStart;
  int round = 0, rounds = 0, markers = 0, frames = 0, iterations = 0, iteration = 0, frames_done = 0;
  double rms_first = 0.0, rms = 0.0;
  double seconds = 0.0;  // Since FitSubjectToTake started.
  std::string text;
};
using SkeletonFitCallback = std::function<void(const SkeletonFitEvent&)>;

// SkeletonFitInputs::axes: from the take's data.
inline constexpr char kAxesFromData[] = "auto";

struct SkeletonFitInputs {
  Subject templ;                    // Skeleton + marker set to start from.
  bool from_template_subject = true;  // Picks the -1 defaults (a subject file vs --skeleton/--markerset).
  std::string template_name;        // The template's file, for the report.
  std::string markers_path;         // The take's .c3d/.trc (named in errors).
  // The take in memory (file axes and units, as read), used instead of reading markers_path
  // (which then only names it): a part of a take (evaluate's time split).
  const MarkerTrajectories* trajectories = nullptr;
  // Take's file -> skeleton axes; kAxesFromData: the rotation that puts the take's up,
  // detected from its points as the marker association detects it (the feet lowest), on the
  // template's (as an association always does).
  std::string axes = "x,y,z";
  double marker_scale = 0.0;        // Take's units -> skeleton units; 0: from the units.
  double amc_fps = 120.0;           // Recorded in the subject.
};

struct SkeletonFitRound {
  int round = 0;
  int markers = 0;
  std::vector<double> rms;  // Before and after each iteration, skeleton units.
  int outlier_samples = 0;  // Left out of the round's fit (--fit_outlier_mm): round 0's, in every round.
  // Held-out score (problems/marker_solve/held_out_round.h), skeleton units; negative for a
  // round that was no candidate (round 0 without every marker of the take).
  double held_out = -1.0;
};

// A marker the fit attached 50/50 on the two bones of a hinge (attachment_by_prediction.h).
struct SkeletonFitBlend {
  std::string marker, parent_joint, joint;  // joint: the hinge; parent_joint: the bone above it.
};

struct SkeletonFitResult {
  Subject subject;          // The fitted subject (skeleton inline, marker set, axes, scale).
  Motion motion;            // The kept round's solved motion (frames fitted).
  SkeletonFitReport report; // The kept round's fit (rms by iteration, bone scales).
  SubjectChecks checks;
  std::vector<SkeletonFitRound> rounds;
  std::vector<std::string> absent;  // Template labels the take lacks.
  // Fitting by labels: the take's points the association found to be no markers (model
  // outputs, points at the file's origin, nothing rigid with them), left out: (label, reason).
  std::vector<std::pair<std::string, std::string>> not_markers;
  std::vector<TemplateLabel> template_labels;  // The map applied (settings.template_labels).
  std::string template_labels_map;  // Where it came from: its file, "inline", or "" (none applied).
  // With settings.associate: the take's markers associated with segments from the data,
  // and per associated marker the template joint round 0 fitted it on ("" left out).
  bool associated = false;
  MarkerAssociation association;
  std::vector<std::string> association_joints;
  int frames = 0;           // Frames fitted.
  int frame_stride = 1;     // They are every frame_stride-th frame of the take (FitFrameStride).
  int attach_rounds = 0;    // Rounds asked for (after the -1 default).
  int kept_round = -1;
  int outlier_samples = 0;  // Samples of the template's markers left out (--fit_outlier_mm).
  double seconds = 0.0;
  double mm_per_unit = 1.0; // 1 when the skeleton's unit is unknown.
  bool unit_known = false;
  LearnedMarkerWeights weights;  // With --learn_weights (else empty).
  std::vector<SkeletonFitBlend> hinge_blends;  // The kept round's markers blended over a hinge.
  // The template joints whose locked rotation axis the kept fit frees (locked_axes.h; empty: the template's
  // axes), and the held-out scores of the fits without and with them freed (skeleton units; empty: no second fit).
  std::vector<std::string> freed_axes;
  std::vector<double> locked_axes_held_out;
  // The joints no marker of the fitted subject observes (a sparse protocol's upper body):
  // at the template's rest in the fit; the subject keeps the template's mean pose for them,
  // where its solves start and hold them.
  HeldSegments held;
};

// The stride of the frames a fit uses: every frame (1) with max_frames 0 or a take of at
// most max_frames frames, else ceil(frames / max_frames), the smallest that keeps within
// max_frames: frames spread over the whole take (--fit_max_frames).
int FitFrameStride(int max_frames, int frames);

// Which inputs were given: a template subject, or a skeleton and a marker set (not both), or
// none of them (the shipped template), and the take's markers; else the one-line error every
// front end prints.
Status CheckSkeletonFitInputsGiven(bool template_subject, bool skeleton, bool markerset, bool skeleton_units,
                                   bool markers);

// The template from files: a subject file, or a skeleton file (with `skeleton_units` when
// it states none) and a marker set, or, with none of them, the shipped template
// (pipeline/shipped_templates.h) (CheckSkeletonFitInputsGiven first; set
// inputs->markers_path before).
Status LoadSkeletonFitTemplate(const std::string& template_subject, const std::string& skeleton,
                               const std::string& markerset, const std::string& skeleton_units,
                               SkeletonFitInputs* inputs);

// Runs the rounds. Errors name the marker file; `settings` are validated first.
Status FitSubjectToTake(const SkeletonFitInputs& inputs, const SkeletonFitSettings& settings,
                        const MarkerSolveOptions& solve_options, SkeletonFitResult* result,
                        const SkeletonFitCallback& callback = nullptr);

// Error when the checks failed and settings.check is "fail": the CLI's message.
Status SkeletonFitCheckStatus(const SkeletonFitInputs& inputs, const SkeletonFitSettings& settings,
                              const SkeletonFitResult& result);

// The console line of an event ("fit_skeleton: round 2/12: 41 markers, ..."), lengths in mm
// (skeleton units when `templ`'s unit is unknown); *to_stdout: the line is a result (a round's
// RMS), not progress. "" for kFrames (a progress bar's).
std::string SkeletonFitEventLine(const SkeletonFitEvent& event, const Skeleton& templ, bool* to_stdout);

// The console summary after the fit: the checks, the bone scales that changed, the RMS.
std::string SkeletonFitSummary(const SkeletonFitResult& result);

// The report (`--report`): frames, rounds, kept round, RMS, bone scales, checks, the label map,
// the held segments.
JsonObject SkeletonFitReportJson(const SkeletonFitInputs& inputs, const SkeletonFitResult& result);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_TASKS_FIT_SKELETON_TASK_H_
