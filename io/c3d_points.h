// Which points of a C3D file are markers, and under which labels: the vendor conventions
// the C3D reader (c3d_reader.h) applies after it has read the labels.
//
// Rules, in this order:
//   duplicates     a label used by several points (Motion Analysis/Cortex files do this)
//                  is kept for the first and numbered for the others: RKNE, RKNE#2,
//                  RKNE#3 (skipping names already taken). One warning lists them.
//   subjects       the subject prefixes are SUBJECTS:LABEL_PREFIXES (empty entries
//                  dropped) or, without it, the "Name:" parts of the labels (Vicon's
//                  convention); only prefixes some label carries count. With
//                  C3dReadOptions::subject_prefix the points of that subject are kept with
//                  the prefix stripped, those of the other subjects are dropped, and points
//                  without a prefix (unlabelled "*12", ...) are kept. Without it, a file of
//                  two or more subjects is read as the preferred subject (a subject file's
//                  own prefix, when the file has it) or else the one with the most points
//                  (an actor, not a prop), and a warning lists the others; one subject's
//                  labels are kept raw (FindMarker ignores the prefix).
//   model outputs  points that are not markers: those listed by POINT:ANGLES, FORCES,
//                  MOMENTS, POWERS, REACTIONS, SCALARS (Vicon Nexus, and BTK when it writes),
//                  each list may go on in ANGLES2, ANGLES3, ...; and by name (subject prefix
//                  ignored) the Plug-in Gait outputs Nexus does not always list: the virtual
//                  segment points <SEG>O/A/L/P (SEG = PEL, HED, TRX, [LR]CL, [LR]FE, [LR]TI,
//                  [LR]FO, [LR]TO, [LR]HU, [LR]RA, [LR]HN), CentreOfMass, CentreOfMassFloor,
//                  and names ending in Angles, Angle, Force, Moment, Power or GRF
//                  (LKneeAngles, LAbsAnkleAngle, LGroundReactionForce, LNormalisedGRF).
//                  They are left out of the markers (one warning with the count) unless
//                  C3dReadOptions::include_model_outputs; the reader keeps them in
//                  MarkerTrajectories::model_outputs for a rewrite.
// Labels are otherwise kept as the file spells them, blanks trimmed at both ends: case and
// inner spaces ("r should") are not changed, and matching them to a marker set is exact.
#ifndef MOCAPSOLVE_IO_C3D_POINTS_H_
#define MOCAPSOLVE_IO_C3D_POINTS_H_

#include <string>
#include <utility>
#include <vector>

#include "kinematics/status.h"

namespace mocapsolve {

// What the parameter section says about the points.
struct C3dPointLists {
  std::vector<std::string> labels;            // One per point; empty ones already "*<n>".
  std::vector<std::string> subject_prefixes;  // SUBJECTS:LABEL_PREFIXES, empty ones dropped.
  std::vector<std::string> subject_names;     // SUBJECTS:NAMES (may be empty).
  // ("ANGLES", its labels), ... for each model-output list the file has.
  std::vector<std::pair<std::string, std::vector<std::string>>> output_lists;
  // Where the labels come from, for messages ("marker labels" for a TRC's header line).
  std::string labels_field = "POINT:LABELS";
};

struct C3dPointSelection {
  enum class Role { kMarker, kModelOutput, kDropped };
  std::vector<Role> roles;                    // Per point.
  std::vector<std::string> labels;            // Per point: the label it is read under.
  std::vector<std::string> kinds;             // Per point: "ANGLES", ... or "" (model outputs).
  std::vector<std::string> subject_prefixes;  // For MarkerTrajectories::subject_prefixes.
  std::vector<std::string> warnings;          // One line each, without the file name.
  int num_model_outputs = 0;
  int num_dropped = 0;                        // Points of the subjects not chosen.
};

// The POINT parameters that list model outputs, in the order they are written.
const std::vector<std::string>& C3dModelOutputKinds();

// The Plug-in Gait output naming (see above) of a name without subject prefix; *kind is
// "ANGLES", "FORCES", "MOMENTS", "POWERS" or "" (virtual points, centre of mass).
bool IsPluginGaitOutputName(const std::string& name, std::string* kind = nullptr);

// Applies the rules above. An error (a choice that is not one of the file's subjects) is
// one line naming the parameter, without the file name.
// preferred_subject_prefix: the subject read from a file of several when subject_prefix
// is empty and the file has it.
Status SelectC3dPoints(const C3dPointLists& lists, const std::string& subject_prefix,
                       bool include_model_outputs, C3dPointSelection* selection,
                       const std::string& preferred_subject_prefix = "");

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_C3D_POINTS_H_
