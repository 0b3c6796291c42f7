// Subject files: one actor in one marker set, calibrated once and reused for every take.
//
// A subject holds what every command on that actor's takes needs and would otherwise
// take as flags (--skeleton, --skeleton_units, --markerset, --axes, --marker_scale):
//   - the skeleton, inline (io/skeleton_json.h), so the file can be copied anywhere; older
//     or hand-written files may name a skeleton file instead (ASF/BVH/glTF, a path
//     relative to the subject file), which is still read;
//   - the calibrated marker set, inline (io/marker_set_file.h's format);
//   - how marker files map onto the skeleton: axes (as --axes spells them), the marker
//     unit -> skeleton unit scale (0: from the files' declared units), and an optional
//     label prefix ("Subject1:") stripped from file labels;
//   - frame-rate assumptions (amc_fps for AMC motions, which do not store it).
//
// Format (version 1; unknown keys are errors, so typos surface):
//   {
//     "format": "mocapsolve.subject", "version": 1,
//     "name": "cmu02",                          optional
//     "skeleton": {"units": "in", ...},         an inline skeleton object (io/skeleton_json.h;
//                                               what WriteSubject writes), or a path relative
//                                               to this file ("../amc/02.asf"; read only)
//     "skeleton_units": "cm",                   optional, with a path: the unit of a file
//                                               that states none (BVH)
//     "markerset": {"format": "mocapsolve.markerset", ...},   inline, required
//     "marker_files": {"axes": "y,z,x", "scale": 0, "label_prefix": ""},   optional
//     "amc_fps": 120,                           optional
//     "mean_pose": {"lfemur": [w, x, y, z], ...}   optional: each joint's mean local
//                                               rotation over the take the subject was
//                                               fitted on (unit quaternions; a joint not
//                                               named: identity), the rest prior's
//                                               reference (MarkerSolveOptions::rest_rotations)
//   }
// Errors are one line naming the file, line:column and field, e.g.
//   S.json:7:5: markerset: markers[3]: 'RTOE': attachments[0].joint: unknown joint 'rtoes'
#ifndef MOCAPSOLVE_PIPELINE_SUBJECT_H_
#define MOCAPSOLVE_PIPELINE_SUBJECT_H_

#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinematics/marker_set.h"
#include "kinematics/marker_trajectories.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "problems/marker_repair/unlabelled_assignment.h"
#include "problems/marker_solve/marker_observations.h"

namespace mocapsolve {

struct Subject {
  std::string name;
  Skeleton skeleton;           // As loaded (the file's, or the inline one); unit known.
  std::string skeleton_path;   // The file it was read from (empty: inline); informational:
                               // WriteSubject always writes the skeleton inline.
  MarkerSet markers;
  std::string axes = "x,y,z";  // Marker file axes -> skeleton axes (ParseAxes).
  double marker_scale = 0.0;   // Marker file units -> skeleton units; 0: from the units.
  std::string label_prefix;    // Stripped from marker file labels ("" = none).
  double amc_fps = 120.0;      // Frame rate of AMC motions.
  // Each joint's mean local rotation in the fitted take (one per joint), or empty (none:
  // the rest prior pulls toward zero rotations).
  QuaternionVector mean_pose;
};

// What a subject path says instead of a file for a subject fitted from the take itself
// (`pipeline --subject=auto`, a batch manifest's "subject": "auto"; tasks/auto_subject_task.h).
inline constexpr char kAutoSubject[] = "auto";

// Reads and validates a subject file (skeleton file paths resolved against its folder).
Status ReadSubject(const std::string& path, Subject* subject);
// The same from a subject file's text; `name` stands for the file in errors (skeleton paths
// are resolved against the working directory).
Status ParseSubject(const std::string& text, const std::string& name, Subject* subject);
// A subject assembled from separate files, as the commands' --skeleton, --skeleton_units,
// --markerset, --axes, --marker_scale and --amc_fps (and the Python keywords) name them.
struct SubjectFiles {
  std::string skeleton_path;   // .asf / .bvh / .glb / .fbx.
  std::string skeleton_units;  // For a file that states none (BVH): mm, cm, m, in.
  std::string markerset_path;  // .json (io/marker_set_file.h).
  std::string axes = "x,y,z";
  double marker_scale = 0.0;
  double amc_fps = 120.0;
};
// Reads the skeleton (its unit must then be known) and the marker set.
Status LoadSubjectFromFiles(const SubjectFiles& files, Subject* subject);

// Writes atomically, the skeleton inline (whatever skeleton_path says).
Status WriteSubject(const std::string& path, const Subject& subject);
// The file text WriteSubject writes to `path`.
std::string FormatSubject(const std::string& path, const Subject& subject);

// A take of markers with its model.
struct MarkerTake {
  std::string name;  // The marker file's path (or what stands for it in messages).
  Skeleton skeleton;
  MarkerSet markers;
  QuaternionVector mean_pose;       // The subject's (empty if it has none).
  MarkerTrajectories trajectories;  // The file as read (labels as the file spells them).
  MarkerFileToModel transform;      // File to skeleton frame.
  std::vector<std::vector<Eigen::Vector3d>> observed;  // [frame][marker], skeleton units.
  // The file's unlabelled points (kinematics/unlabelled_label.h; columns the marker set
  // reads excluded) in the skeleton frame and units, and the file column of each track
  // (unlabelled_columns[k] for unlabelled.names[k]).
  UnlabelledPoints unlabelled;
  std::vector<int> unlabelled_columns;
};

// The mapping of a marker file onto the subject's skeleton: its axes, then its marker
// scale or (0) the file's and skeleton's units. Errors name `name` or the field.
Status SubjectFileTransform(const Subject& subject, const MarkerTrajectories& file, const std::string& name,
                            MarkerFileToModel* transform);

// Reads a marker file as every command does (DefaultMarkerReadOptions), and of a file of
// several subjects without --subject_prefix, the one with the subject's own label prefix.
Status ReadMarkerFileForSubject(const Subject& subject, const std::string& markers_path,
                                MarkerTrajectories* trajectories);
// Reads the marker file at markers_path and maps it onto the subject: the label prefix
// stripped, axes and scale applied, observed[f][m] gathered for every marker of the set
// (an error names the ones the file lacks), and the unlabelled points kept.
Status LoadTakeForSubject(const Subject& subject, const std::string& markers_path, MarkerTake* take);
// The same for markers already in memory (Python's Markers, a corrupted copy); `name`
// stands for the file in messages.
Status TakeForSubject(const Subject& subject, MarkerTrajectories trajectories, const std::string& name,
                      MarkerTake* take);
// Commands that compute on a take refuse one without data: RequireMarkerData
// (io/marker_file.h), and at least one sample of the marker set's markers ("<path>: no
// marker of the marker set is observed in any frame").
// Also refuses a take in which some segment is never observed (RequireObservableSegments).
Status RequireTakeData(const std::string& path, const MarkerTake& take);
// A segment (a joint the marker set puts markers on) none of whose markers, nor any on the
// joints below it, has a sample in any frame (seen[m]: marker m has one) leaves its joint
// unobservable for the whole take: the solve would hold it at the prior and the repair would
// invent its markers. The error names each such segment and its labels.
Status RequireObservableSegments(const std::string& path, const Skeleton& skeleton, const MarkerSet& markers,
                                 const std::vector<char>& seen);

// The inverse for outputs: the take's file as read, with every sample of the set's
// markers that differs from the observation (repaired[f][m], skeleton frame and units)
// mapped back to the file's axes and units; every other sample as it was read. A sample
// that is another marker's observation of the same frame (relabelled: a swap undone) is
// that marker's sample as read, bit for bit.
// *rewritten (optional) counts the samples replaced. The unlabelled points a repair
// assigned to markers (`assigned`, its report's list) are removed from their unlabelled
// columns (they now live under the marker's label); *unlabelled_removed counts them.
MarkerTrajectories WithRepairedSamples(const MarkerTake& take,
                                       const std::vector<std::vector<Eigen::Vector3d>>& repaired,
                                       int* rewritten = nullptr,
                                       const std::vector<UnlabelledAssignment>& assigned = {},
                                       int* unlabelled_removed = nullptr);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PIPELINE_SUBJECT_H_
