// Fitting a subject to a take's markers alone (`mocapsolve fit_skeleton`, the Python
// module's fit_skeleton()): the round logic around FitSkeletonToMarkers
// (problems/marker_solve/skeleton_fit.h), so the command line and Python run one code path.
//
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
#ifndef MOCAPSOLVE_PIPELINE_SKELETON_FITTING_H_
#define MOCAPSOLVE_PIPELINE_SKELETON_FITTING_H_

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
#include "pipeline/template_label_maps.h"
#include "pipeline/template_labels.h"
#include "problems/marker_solve/marker_frame_solver.h"
#include "problems/marker_solve/skeleton_fit.h"
#include "problems/marker_solve/subject_checks.h"

namespace mocapsolve {

// The options as the user names them: one field per flag of `mocapsolve fit_skeleton`
// (same name, default and units), documented once in kSkeletonFitSettingHelp.
struct SkeletonFitSettings {
  int fit_iterations = -1;       // -1: 15 with a template subject, else 6.
  int attach_rounds = -1;        // -1: 12 with a template subject, else 0.
  int attach_iterations = 6;
  int fit_frame_step = 4;
  int fit_max_frames = 0;        // 0 = all frames.
  double max_skin_cm = 12.0;     // 0 = off.
  double min_bone_scale = 0.8;
  double max_bone_scale = 1.25;
  double offset_prior = 0.0;
  double fit_outlier_mm = 200.0;  // 0 = off.
  std::string check = "fail";    // fail | warn | off.
  // TEMPLATE:TAKE pairs or their file (template_labels.h); "auto": a shipped map that fits the
  // take (template_label_maps.h); "" or "none": none.
  std::string template_labels = kTemplateLabelsAuto;
};

struct SettingHelp {
  const char* name;
  const char* help;
};

// One line of help per setting, in the order of the struct: the gflags help of
// apps/fit_skeleton_command.cc and the Python docstring are both made from it.
inline constexpr SettingHelp kSkeletonFitSettingHelp[] = {
    {"fit_iterations", "Alternations of pose solve and length/offset fit on the template's markers; "
                       "-1: 15 with --template_subject, else 6."},
    {"attach_rounds", "Rounds of attaching every marker of the take to the fitted skeleton (auto: the joint it "
                      "moves least with, among joints whose bone is within --max_skin_cm) and fitting again "
                      "(stopping early when a round improves the marker RMS by less than 1 %); -1: 12 with "
                      "--template_subject, else 0."},
    {"attach_iterations", "Fit iterations in each attach round."},
    {"fit_frame_step", "Use every N-th frame in the length/offset fit."},
    {"fit_max_frames", "Fit on the first N frames only (0 = all)."},
    {"max_skin_cm", "Markers stay within this distance of their bone (fit and attach); 0: off."},
    {"min_bone_scale", "Bone lengths no shorter than this times the template's."},
    {"max_bone_scale", "Bone lengths no longer than this times the template's."},
    {"offset_prior", "Weight of the prior that keeps marker offsets near the template's in the first fit, per "
                     "frame, relative to a marker residual; 0: off."},
    {"fit_outlier_mm", "Leave out of every round's fit the samples of the template's markers farther than this, "
                       "and than 5 times their marker's median residual, from their marker in the first fit "
                       "(mislabels, ghosts); the fit RMS and the checks are then over the kept samples, and the "
                       "report counts the others; 0: fit every sample."},
    {"check", "The subject checks (marker within 15 cm of its bone, or within its template distance when "
              "larger, torso direction within 15 degrees of the markers', left/right within 5 %, marker RMS within 25 mm): fail (exit 1, nothing written but "
              "the report), warn, off."},
    {"template_labels", "Template markers that are the take's under other labels: TEMPLATE:TAKE pairs "
                        "(RFWT:RASI,LFWT:LASI) or a file of them (examples/ais_to_cmu_labels.txt); round 0 fits "
                        "them under the take's labels, which the fitted subject keeps. auto: the first shipped map "
                        "(examples/*_to_cmu_labels.txt) whose take labels are all in the take and whose template "
                        "labels are all in the template but none in the take; \"\" or none: labels as they are."},
};

// The help of `name` in a table like the one above ("" if absent).
template <size_t N>
const char* SettingHelpFor(const SettingHelp (&table)[N], const std::string& name) {
  for (const SettingHelp& entry : table) {
    if (name == entry.name) return entry.help;
  }
  return "";
}

inline constexpr char kSkeletonFitSettingNames[] =
    "fit_iterations,attach_rounds,attach_iterations,fit_frame_step,fit_max_frames,max_skin_cm,min_bone_scale,"
    "max_bone_scale,offset_prior,fit_outlier_mm,check,template_labels";

// The CLI's one-line messages ("--attach_rounds: -1..20").
Status ValidateSkeletonFitSettings(const SkeletonFitSettings& settings);

// What the fit reports while it runs, for a progress display.
struct SkeletonFitEvent {
  enum Kind {
    kTemplateLabels, // text: the label map applied (its file, "inline" or, for auto, the shipped file); markers: pairs.
    kAbsentMarkers,  // text: the template's labels the take lacks (left out).
    kRoundStart,     // round, rounds, markers, frames, iterations.
    kFrames,         // round, iteration (the pose solve's step: 0 before the first step, outlier passes included;
                     // k the solve of step k), frames_done of frames.
    kIteration,      // round, iteration, rms (skeleton units).
    kRoundDone,      // round, markers, rms_first, rms (skeleton units).
    kStopped,        // round: it did not improve (rms = 0) or by less than 1 % (rms: the kept one); the rounds stop.
    kKept,           // round (the kept one), rms: the last round was not the best.
  };
  Kind kind = kRoundStart;
  int round = 0, rounds = 0, markers = 0, frames = 0, iterations = 0, iteration = 0, frames_done = 0;
  double rms_first = 0.0, rms = 0.0;
  double seconds = 0.0;  // Since FitSubjectToTake started.
  std::string text;
};
using SkeletonFitCallback = std::function<void(const SkeletonFitEvent&)>;

struct SkeletonFitInputs {
  Subject templ;                    // Skeleton + marker set to start from.
  bool from_template_subject = true;  // Picks the -1 defaults (a subject file vs --skeleton/--markerset).
  std::string template_name;        // The template's file, for the report.
  std::string markers_path;         // The take's .c3d/.trc (named in errors).
  std::string axes = "x,y,z";       // Take's file -> skeleton axes.
  double marker_scale = 0.0;        // Take's units -> skeleton units; 0: from the units.
  double amc_fps = 120.0;           // Recorded in the subject.
};

struct SkeletonFitRound {
  int round = 0;
  int markers = 0;
  std::vector<double> rms;  // Before and after each iteration, skeleton units.
  int outlier_samples = 0;  // Left out of the round's fit (--fit_outlier_mm): round 0's, in every round.
};

struct SkeletonFitResult {
  Subject subject;          // The fitted subject (skeleton inline, marker set, axes, scale).
  Motion motion;            // The kept round's solved motion (frames fitted).
  SkeletonFitReport report; // The kept round's fit (rms by iteration, bone scales).
  SubjectChecks checks;
  std::vector<SkeletonFitRound> rounds;
  std::vector<std::string> absent;  // Template labels the take lacks.
  std::vector<TemplateLabel> template_labels;  // The map applied (settings.template_labels).
  std::string template_labels_map;  // Where it came from: its file, "inline", or "" (none applied).
  int frames = 0;           // Frames fitted.
  int attach_rounds = 0;    // Rounds asked for (after the -1 default).
  int kept_round = -1;
  int outlier_samples = 0;  // Samples of the template's markers left out (--fit_outlier_mm).
  double seconds = 0.0;
  double mm_per_unit = 1.0; // 1 when the skeleton's unit is unknown.
  bool unit_known = false;
};

// Runs the rounds. Errors name the marker file; `settings` are validated first.
Status FitSubjectToTake(const SkeletonFitInputs& inputs, const SkeletonFitSettings& settings,
                        const MarkerSolveOptions& solve_options, SkeletonFitResult* result,
                        const SkeletonFitCallback& callback = nullptr);

// Error when the checks failed and settings.check is "fail": the CLI's message.
Status SkeletonFitCheckStatus(const SkeletonFitInputs& inputs, const SkeletonFitSettings& settings,
                              const SkeletonFitResult& result);

// The report (`--report`): frames, rounds, kept round, RMS, bone scales, checks, the label map.
JsonObject SkeletonFitReportJson(const SkeletonFitInputs& inputs, const SkeletonFitResult& result);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PIPELINE_SKELETON_FITTING_H_
