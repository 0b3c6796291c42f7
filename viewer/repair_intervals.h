// The repaired intervals a page colours and draws as bars, from a repair's report: the
// intervals it detected (each with its reason: "missing", "outlier", "joint difference",
// "swap") and those it filled (with their fill method: "reference", "polynomial", ...).
// A filled interval takes the reason of the detected interval of its marker that overlaps
// it most, or "gap" when none does (a fill method is not a reason). A detected
// "unlabelled" interval (unlabelled points the repair gave the marker: observations, not
// fills) is drawn as itself, under the filled ones.
//
// The report file is the JSON `mocapsolve repair --report` and `pipeline` write:
//   {"detected": [{"marker": "LKNE", "first_frame": 10, "last_frame": 14, "what": "outlier"}, ...],
//    "filled": [ ...same fields... ], ...}
// frames 0-based and inclusive (indices into the take). Labels are matched to the take's
// exactly or after the take's subject prefix ("LKNE" is "TakeoMonday:LKNE").
#ifndef MOCAPSOLVE_VIEWER_REPAIR_INTERVALS_H_
#define MOCAPSOLVE_VIEWER_REPAIR_INTERVALS_H_

#include <string>
#include <vector>

#include "kinematics/status.h"
#include "viewer/view_scene.h"

namespace mocapsolve {

struct ReportedInterval {
  int marker = 0;               // Index into the take's labels.
  int first = 0, last = 0;      // Frames, inclusive.
  std::string what;
};

std::vector<ViewInterval> RepairedViewIntervals(const std::vector<ReportedInterval>& detected,
                                                const std::vector<ReportedInterval>& filled);

// Reads a repair report's "detected" and "filled" lists against the take's labels.
// Errors (one line) name the file and the field: a missing list, a marker the take does
// not have, a frame outside [0, num_frames) or last < first.
Status ReadRepairReport(const std::string& path, const std::vector<std::string>& labels, int num_frames,
                        std::vector<ReportedInterval>* detected, std::vector<ReportedInterval>* filled);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_VIEWER_REPAIR_INTERVALS_H_
