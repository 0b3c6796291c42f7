// The protocols of `evaluate --method=leave_one_out` (settings: EvaluateSettings::protocol):
// which subject predicts which frames, so that no sample of a left-out marker on the scored
// frames is used anywhere (subject fit, offsets, mean pose, initialisation).
//   cross_take  the subject as given, every frame of the take scored. It must come from
//               another take of the actor (`calibrate --out_subject` or `fit_skeleton` on a
//               range-of-motion or first take): a subject fitted on the scored take holds every
//               marker's offset and mean pose from these very samples, and its figures are
//               optimistic by construction.
//   time_split  the take cut at half its frames; a subject fitted on the first half
//               (FitSubjectToTake, the given subject as the template, with the fit's
//               settings as `evaluate` reads them: fit_skeleton's options; its checks
//               reported, not enforced) and the second half scored.
// The leave-one-out itself (problems/marker_solve/leave_one_out.h) then solves the scored
// frames without the marker, so its own samples there reach neither the solve nor the
// per-take offset refinement.
#ifndef MOCAPSOLVE_TASKS_LEAVE_ONE_OUT_PROTOCOL_H_
#define MOCAPSOLVE_TASKS_LEAVE_ONE_OUT_PROTOCOL_H_

#include <string>

#include "io/json_writer.h"
#include "kinematics/status.h"
#include "pipeline/subject.h"
#include "settings/skeleton_fit_settings.h"
#include "settings/solver_settings.h"

namespace mocapsolve {

// *scored: the take whose frames are scored, with the subject that scores them; *report:
// the protocol's record ("protocol", "scored_frames", and for time_split the fit: frames,
// RMS in mm, checks). Errors: an unknown protocol, a take too short to split (fewer than 20
// frames), a fit that fails (naming take.name).
Status LeaveOneOutProtocolTake(const MarkerTake& take, const std::string& protocol, const SolverSettings& solver,
                               const SkeletonFitSettings& fit, MarkerTake* scored, JsonObject* report);

// The take of a time split read against a template subject it need not match (a template
// from another marker set, as fit_skeleton's --template_subject): `templ`'s axes and scale
// map the file; *take holds the template's skeleton, marker set and mean pose, the file and
// its transform, and no observations (the fit gathers its own). Errors: no marker of the
// template in the file (the fit's label map aside: it needs at least one to read the axes).
Status TemplateTakeForSubject(const Subject& templ, MarkerTrajectories trajectories, const std::string& name,
                              MarkerTake* take);

// TemplateTakeForSubject on the files: the subject at `subject_path` as the template, the
// markers at `markers_path`; `axes` and `marker_scale`, when not null, describe the take's
// file instead of the template's (a front end's given --axes, --marker_scale).
Status ReadTimeSplitTake(const std::string& subject_path, const std::string& markers_path, const std::string* axes,
                         const double* marker_scale, MarkerTake* take);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_TASKS_LEAVE_ONE_OUT_PROTOCOL_H_
