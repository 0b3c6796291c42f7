// A map from a template subject's marker labels to a take's (`fit_skeleton
// --template_labels`, the Python fit_skeleton(template_labels=...)): for a take recorded with
// another marker protocol, the template markers that sit on the same anatomical landmark as
// one of the take's markers under another name (CMU's RFWT, the right ASIS, is the AIS set's
// RASI). FitSubjectToTake renames those template markers to the take's labels before round 0,
// so round 0 fits them with the template's joints and offsets as a start, and the fitted
// subject holds the take's own labels (later commands on the take find them).
//
// Text: pairs TEMPLATE:TAKE separated by commas, spaces or newlines; '#' starts a comment
// that runs to the end of its line. The setting's value is that text, or the path of a file
// holding it (a value without ':' is a path). examples/ais_to_cmu_labels.txt is one; the
// shipped ones are also applied without a flag (template_label_maps.h).
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_TEMPLATE_LABELS_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_TEMPLATE_LABELS_H_

#include <string>
#include <vector>

#include "kinematics/marker_set.h"
#include "kinematics/marker_trajectories.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

struct TemplateLabel {
  std::string templ;  // The template marker set's label.
  std::string take;   // The take's label for the same landmark.
};

// Parses `value` (inline pairs, or a file's path) into pairs, in their order. Errors are one
// line and name "--template_labels" or the file and line: a pair that is not TEMPLATE:TAKE,
// a template or take label named twice, a file without pairs.
Status ReadTemplateLabels(const std::string& value, std::vector<TemplateLabel>* labels);

// The same for `text` itself: the pairs of the file `file` (named in errors with the line),
// or inline pairs when `file` is "".
Status ParseTemplateLabels(const std::string& text, const std::string& file, std::vector<TemplateLabel>* labels);

// `markers` (the template's set on `skeleton`) with each mapped marker renamed to its take
// label. Errors name the label: a template label the set lacks, a take label absent from
// `take` (the file `take_path`), a new label that another, unmapped template marker
// already holds.
Status RenameTemplateMarkers(const std::vector<TemplateLabel>& labels, const Skeleton& skeleton,
                             const MarkerTrajectories& take, const std::string& take_path, MarkerSet* markers);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_TEMPLATE_LABELS_H_
