// Takes for the subject fitted on the fly (tasks/auto_subject_task.h, `pipeline
// --subject=auto`): the shipped template's own 41 markers (CMU subject 2) riding a
// synthetic walk on its skeleton, so a fit from the template can explain them exactly;
// and a cloud of random points that is no body.
#ifndef MOCAPSOLVE_TESTS_AUTO_SUBJECT_TAKES_H_
#define MOCAPSOLVE_TESTS_AUTO_SUBJECT_TAKES_H_

#include <string>
#include <vector>

#include "kinematics/marker_trajectories.h"

namespace mocapsolve::testing {

// `frames` frames at 60 fps of the shipped template walking (its mean pose with every limb
// swinging, the root moving forward), its markers in mm, written Z up (file (x, -z, y) of
// the skeleton's (x, y, z)). renamed: labels M0, M1, ... in a shuffled order (a protocol
// nobody mapped); else the template's own (CMU's LBWT, ...).
MarkerTrajectories TemplateWalkTake(int frames, bool renamed);

// TemplateWalkTake, but the right elbow (CMU's rradius) and wrist hold the mean pose until
// frame `bend_from`, and from there the elbow bends up to 70 degrees and straightens again:
// a take whose first part never bends a joint, so its forearm's markers move rigidly with
// the upper arm's there. One marker more, last: ROLC (renamed: M41) on the forearm just
// behind the elbow, nearer the upper arm's bone than the forearm's.
MarkerTrajectories TemplateWalkTakeBendingLate(int frames, int bend_from, bool renamed);

// `take` with only the markers named in `labels` (in that order), renamed to `renamed`
// when given (the same length): a sparse protocol's subset of a full-body take.
MarkerTrajectories KeepTakeMarkers(const MarkerTrajectories& take, const std::vector<std::string>& labels,
                                   const std::vector<std::string>& renamed = {});

// `points` points at random positions in a 2 m box, each moving at random, `frames` frames, mm.
MarkerTrajectories RandomPointsTake(int frames, int points);

}  // namespace mocapsolve::testing

#endif  // MOCAPSOLVE_TESTS_AUTO_SUBJECT_TAKES_H_
