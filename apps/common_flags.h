// The options shared by commands (the files they read and write, how files are read,
// --quiet: settings/file_settings.h, file_read_settings.h, console_settings.h) and the
// helpers that read them, so every command loads motions and writes reports the same way.
#ifndef MOCAPSOLVE_APPS_COMMON_FLAGS_H_
#define MOCAPSOLVE_APPS_COMMON_FLAGS_H_

#include <string>
#include <vector>

#include <gflags/gflags.h>

#include "io/atomic_file.h"
#include "io/json_writer.h"
#include "io/marker_file.h"
#include "io/motion_file.h"
#include "kinematics/marker_set.h"
#include "kinematics/marker_trajectories.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "pipeline/subject.h"
#include "settings/console_settings.h"
#include "settings/file_read_settings.h"
#include "settings/file_settings.h"
#include "problems/marker_solve/marker_observations.h"


namespace mocapsolve {

// The shared options named in `names` (comma-separated; from FileSettingOptions,
// FileReadSettingOptions and ConsoleSettingOptions) as one group of a Command's options.
// A command that reads --markers also gets include_model_outputs and subject_prefix (every
// marker file is read the same way); --quiet is every command's (main.cc registers it).
std::vector<Option> SharedOptions(const std::string& names);

// This run's values of the shared options, as parsed (and set by --config): main.cc reads
// them after parsing the command line, ApplyConfigFile again after applying a config.
const FileSettings& Files();
const FileReadSettings& FileReading();
const ConsoleSettings& Console();
void ReadSharedOptions();
// Whether option `name` was given (on the command line or by --config), for the rule "a
// given option wins over what a subject file holds"; never to pick a default.
bool GivenOnCommandLine(const std::string& name);

// ReadMotionFile with --skeleton and --amc_fps, then --skeleton_units.
Status LoadMotion(const std::string& path, Skeleton* skeleton, Motion* motion);

// --skeleton_units for a skeleton whose file states no unit (a BVH); an error if the
// file states another.
Status ApplySkeletonUnits(Skeleton* skeleton);
// ReadSkeletonFile (.bvh/.asf) then ApplySkeletonUnits.
Status LoadSkeleton(const std::string& path, Skeleton* skeleton);

// The marker file at `path` in the skeleton's axes and units (--axes, --marker_scale or
// the files' units): observed[f][m] for each marker of the set, NaN where missing.
Status LoadObservations(const std::string& path, const Skeleton& skeleton, const MarkerSet& markers,
                        MarkerTrajectories* trajectories, MarkerFileToModel* transform,
                        std::vector<std::vector<Eigen::Vector3d>>* observed);

// The one place the take flags become a model: --subject=S.json (pipeline/subject.h),
// or a subject assembled from --skeleton (whose unit must be known: repair thresholds
// are in cm), --skeleton_units, --markerset, --axes, --marker_scale and --amc_fps.
// Giving --subject and any of those mapping flags is an error naming both.
Status LoadSubjectFromFlags(Subject* subject);
// Checks that the flags name a take (--markers and --subject, or --markers, --skeleton
// and --markerset) and lists its input files (for CheckNotAnInput).
Status MarkerTakeInputs(std::vector<std::string>* inputs);
// LoadSubjectFromFlags, then LoadTakeForSubject on --markers, then RequireMarkerData.
Status LoadMarkerTake(MarkerTake* take);

// Commands that compute on frames (every one but info and convert) refuse a take without
// any: RequireFrames (io/motion_file.h), RequireMarkerData (io/marker_file.h).

// Writes the report to --report if set (atomically), in the envelope every report shares
// (docs/schemas/report.schema.json).
Status WriteReport(const JsonObject& report);

// The flags the running command reads, with the values in force (the report's "options").
JsonObject OptionsInForce();

// What the running command is doing, named in its failure report's "stage": main.cc says
// "arguments" while it checks the flags, "run" when the command starts and "outputs" while
// it publishes them; a command names its own steps in between ("inputs", "solve", ...).
void SetStage(const std::string& stage);

// CheckNotAnInput (an output path must not name one of the inputs): io/atomic_file.h.

// Every given output (empty = not asked for) names none of the given inputs and no other
// output ("X: named by two output flags").
Status CheckOutputsApart(const std::vector<std::string>& outputs, const std::vector<std::string>& inputs);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_APPS_COMMON_FLAGS_H_
